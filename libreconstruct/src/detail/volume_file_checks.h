// SPDX-License-Identifier: BSD-3-Clause
// Private: a volume file checked against what its header promises, before ITK reads it. ITK reads a
// MetaImage whose data are shorter than DimSize (MetaIO only prints a message), a cut zlib stream, a
// .nii.gz cut partway (the missing slices become zeros) and a NIfTI whose sform is sheared (it
// orthogonalises it silently): each gave a plausible mesh of the wrong shape with exit status 0.
#pragma once

#include <filesystem>
#include <string>

namespace contourmesh::detail {

/// Checks, by format (from the name: .mha/.mhd MetaImage, .nii/.nii.gz NIfTI-1 and -2, .nrrd/.nhdr
/// NRRD; others are left to ITK): that the data hold at least the bytes the header promises (voxels x
/// components x type size), that compressed data decompress completely (a zlib or gzip stream that
/// ends early or is corrupt is an error), and for NIfTI that an sform in use (sform_code > 0) has
/// orthogonal axes. Throws InvalidInputError whose message starts with `shown` and says what was
/// promised and what was found. Formats or variants it cannot check (data in a list of files, ASCII
/// or bzip2 encodings) pass.
void check_volume_file(const std::filesystem::path& path, const std::string& shown);

}  // namespace contourmesh::detail
