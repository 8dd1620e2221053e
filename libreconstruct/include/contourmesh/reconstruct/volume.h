// SPDX-License-Identifier: BSD-3-Clause
// CT volumes: the image type of libreconstruct and reading / writing it with ITK.
#pragma once

#include <itkImage.h>

#include <contourmesh/smooth/progress.h>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace contourmesh {

/// A CT volume: one float per voxel, in Hounsfield units for CT (raw scanner values for files that are
/// not calibrated). Spacing, origin and direction are in millimetres, LPS physical space as ITK reads
/// it. Index axis 2 is the slice axis.
using CtImage = itk::Image<float, 3>;

/// Working memory per voxel of a volume on its way through the reconstruction, in bytes: the float
/// image, a filtered copy, and the segmentation's dense values, mask and component labels. A volume
/// whose estimate exceeds the memory available is refused (LimitError) before it is read or rendered.
inline constexpr double kVolumeBytesPerVoxel = 17.0;

/// A DICOM series whose slices are not evenly spaced (a missing slice, a varying slice distance).
enum class UnevenSlices {
  Refuse,    ///< InvalidInputError naming the two files around the widest gap (default)
  Resample,  ///< interpolated linearly along the slice normal onto an even grid at the typical
             ///< (median) slice distance, with a warning
};

/// Voxels that are NaN or infinite (float and double files).
enum class NonFiniteVoxels {
  Refuse,  ///< InvalidInputError giving their number and the first one's index (default)
  AsAir,   ///< read as the lowest finite value of the volume (air, or below it), with a warning
};

/// The messages ITK, GDCM, MetaIO and the NIfTI library print on their own during a read or write.
enum class LibraryMessages {
  Capture,      ///< kept off the terminal: problems are reported in the library's own words (default)
  PassThrough,  ///< printed as the libraries print them (the CLI's --verbose)
};

struct VolumeReadOptions {
  /// For a DICOM directory: the Series Instance UID (0020,000E) of the series to read; empty: the
  /// directory must hold exactly one series. Must be empty for a file.
  std::string series_uid;
  UnevenSlices uneven_slices = UnevenSlices::Refuse;
  NonFiniteVoxels non_finite = NonFiniteVoxels::Refuse;
  LibraryMessages library_messages = LibraryMessages::Capture;
  /// Receives one line per thing repaired or worth knowing, starting with the path ("scan: uneven
  /// slice spacing ...: resampled ..."). Unset: warnings are dropped.
  std::function<void(const std::string&)> on_warning;
};

/// Reads a volume from a file (.mha/.mhd, .nrrd/.nhdr, .nii/.nii.gz) or from a directory holding one
/// DICOM series (slice order and spacing from Image Position (Patient), not from SliceThickness;
/// rescale slope/intercept applied, so values are HU), and checks it against what it promised.
/// Throws InvalidInputError naming the path (one line) for:
/// - a missing, empty or unreadable file, an image that is not 3-D (a single 2-D slice), an empty
///   volume, a directory without a DICOM series, with several and no `series_uid`, or without the one
///   asked for (their UIDs are listed), a `series_uid` given for a file;
/// - data shorter than the header promises, a compressed stream that is cut or corrupt (MetaImage,
///   NIfTI .nii.gz, NRRD gzip), a spacing that is zero, negative or not finite, an origin that is not
///   finite, a direction matrix that is singular or not orthonormal (a sheared grid, e.g. a gantry
///   tilt: refused rather than silently orthogonalised, which misplaces every slice), a NIfTI sform
///   that is sheared;
/// - a DICOM series whose files do not decode or are cut, differ in size, spacing or orientation,
///   share a position, drift sideways, or are unevenly spaced (see UnevenSlices);
/// - non-finite voxels (see NonFiniteVoxels);
/// LimitError when the volume's estimated working memory (kVolumeBytesPerVoxel) exceeds the memory
/// available.
[[nodiscard]] CtImage::Pointer read_volume(const std::filesystem::path& path, const VolumeReadOptions& options = {});

/// One DICOM series of a directory.
struct DicomSeries {
  std::string uid;          ///< Series Instance UID (0020,000E)
  std::string number;       ///< Series Number (0020,0011), as stored; may be empty
  std::string modality;     ///< Modality (0008,0060): "CT", "MR", ...
  std::string description;  ///< Series Description (0008,103E); may be empty
  std::size_t files = 0;    ///< files (slices) of the series
};

/// The DICOM series of a directory (files directly in it), in the order of their UIDs, with the tags of
/// each series' first file. Throws InvalidInputError naming the path when it is not a directory or
/// cannot be scanned; an empty list when it holds no DICOM file.
[[nodiscard]] std::vector<DicomSeries> list_dicom_series(const std::filesystem::path& directory);

/// Checks a volume's values: NaN and infinite voxels are refused or replaced per `policy` (the warning,
/// if any, goes to `on_warning`, starting with `name`). Called by read_volume; for images from
/// elsewhere (a VTK pipeline). Throws InvalidInputError starting with `name`.
void check_voxel_values(CtImage& image, const std::string& name, NonFiniteVoxels policy,
                        const std::function<void(const std::string&)>& on_warning = {});

/// Checks a volume's geometry: spacing finite and > 0, origin finite, direction finite and orthonormal
/// (singular and sheared matrices are named as such). Throws InvalidInputError starting with `name`.
void check_volume_geometry(const CtImage& image, const std::string& name);

/// Writes a volume atomically (contourmesh/smooth/atomic_file.h: a temporary flushed to disk and renamed; only a
/// regular file is replaced, symbolic links are written through); format from the extension (.mha,
/// .nrrd, .nii, .nii.gz). The written file is checked against its header (every byte there, the
/// compressed stream complete) before it replaces anything, since ITK's writers do not check their
/// writes. `progress` is called with ("write", 1) before the rename: false cancels (CancelledError).
/// Throws InvalidInputError naming the path on failure (a full disk or a file size limit included).
void write_volume(const CtImage* image, const std::filesystem::path& path, const ProgressCallback& progress = {});

}  // namespace contourmesh
