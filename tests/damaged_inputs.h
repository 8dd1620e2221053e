// SPDX-License-Identifier: BSD-3-Clause
// The "damaged inputs" fixture generator: small volumes, DICOM series and files broken the way real
// ones break (cut short, a corrupt stream, a sheared or singular direction, a duplicated or missing
// slice, NaN voxels ...), written at test time into a scratch directory. docs/robustness.md lists what
// the tools do with each.
#pragma once

#include <contourmesh/reconstruct/volume.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace contourmesh::test {

namespace fs = std::filesystem;

/// A small CT-like float volume (28 x 24 x 12 voxels, 1 x 1 x 2 mm): soft tissue (40 HU) with a box of
/// bone (1000 HU) well inside.
[[nodiscard]] CtImage::Pointer small_volume();

/// Writes `image` with ITK's writers directly (the format from the extension), optionally compressed:
/// the fixtures must be able to hold what ContourMesh's own writer refuses to write.
void write_raw_volume(const CtImage& image, const fs::path& path, bool compressed = false);

/// Keeps the first `keep` bytes of a file.
void cut_file(const fs::path& path, std::uintmax_t keep);
/// Keeps the given fraction of a file's bytes.
void cut_file_fraction(const fs::path& path, double fraction);
/// Replaces the first occurrence of `from` in a file by `to` (text headers); false when absent.
bool replace_in_file(const fs::path& path, const std::string& from, const std::string& to);
/// Overwrites the 32-bit little-endian floats at byte `offset` (a NIfTI-1 header field).
void patch_floats(const fs::path& path, std::size_t offset, const std::vector<float>& values);
/// Sets voxels (x fastest) `first` .. `first + count - 1` of a LOCAL MET_FLOAT MetaImage to `value`.
void set_mha_voxels(const fs::path& path, std::size_t first, std::size_t count, float value);

/// The real head-and-neck DICOM series of ../shared/data (CONTOURMESH_SHARED_DATA).
[[nodiscard]] fs::path headneck_series();
/// Copies `count` consecutive slices (files in name order, from `first`) of the head-and-neck series into
/// `dir` (created), writable, and returns their paths.
std::vector<fs::path> copy_headneck_slices(const fs::path& dir, int first, int count);
/// Sets a DICOM element of a file to a text value (DS, US written as text for IS/DS; binary for US tags
/// 0028,xxxx is handled by `set_dicom_us`).
void set_dicom_text(const fs::path& file, std::uint16_t group, std::uint16_t element, const std::string& value);
void set_dicom_us(const fs::path& file, std::uint16_t group, std::uint16_t element, std::uint16_t value);
/// The Image Position (Patient) of a DICOM file, as text ("x\y\z").
[[nodiscard]] std::string dicom_text(const fs::path& file, std::uint16_t group, std::uint16_t element);

}  // namespace contourmesh::test
