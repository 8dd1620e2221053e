// CT volumes: the image type of libreconstruct and reading / writing it with ITK.
#pragma once

#include <itkImage.h>

#include <cstddef>
#include <filesystem>
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

/// How read_volume picks what to read.
struct VolumeReadOptions {
  /// For a DICOM directory: the Series Instance UID (0020,000E) of the series to read; empty: the
  /// directory must hold exactly one series. Must be empty for a file.
  std::string series_uid;
};

/// Reads a volume from a file (.mha/.mhd, .nrrd/.nhdr, .nii/.nii.gz) or from a directory holding
/// DICOM series: the one series, or `options.series_uid` (slice order and spacing from Image Position
/// (Patient), not from SliceThickness; rescale slope/intercept applied, so values are HU). Throws
/// InvalidInputError naming the path for a missing or unreadable file, an image that is not 3-D (a
/// single 2-D slice), an empty volume, a directory without a DICOM series, with several series and no
/// `series_uid` (their UIDs are listed), or without the series asked for; LimitError when the volume's
/// estimated working memory (kVolumeBytesPerVoxel) exceeds the memory available.
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

/// Writes a volume atomically (temporary file, then rename); format from the extension
/// (.mha, .nrrd, .nii, .nii.gz). Throws InvalidInputError naming the path on failure.
void write_volume(const CtImage* image, const std::filesystem::path& path);

}  // namespace contourmesh
