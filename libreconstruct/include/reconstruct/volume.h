// CT volumes: the image type of libreconstruct and reading / writing it with ITK.
#pragma once

#include <itkImage.h>

#include <filesystem>

namespace contourmesh {

/// A CT volume: one float per voxel, in Hounsfield units for CT (raw scanner values for files that are
/// not calibrated). Spacing, origin and direction are in millimetres, LPS physical space as ITK reads
/// it. Index axis 2 is the slice axis.
using CtImage = itk::Image<float, 3>;

/// Working memory per voxel of a volume on its way through the reconstruction, in bytes: the float
/// image, a filtered copy, and the segmentation's dense values, mask and component labels. A volume
/// whose estimate exceeds the memory available is refused (LimitError) before it is read or rendered.
inline constexpr double kVolumeBytesPerVoxel = 17.0;

/// Reads a volume from a file (.mha/.mhd, .nrrd/.nhdr, .nii/.nii.gz) or from a directory holding one
/// DICOM series (slice order and spacing from Image Position (Patient), not from SliceThickness;
/// rescale slope/intercept applied, so values are HU). Throws InvalidInputError naming the path for a
/// missing or unreadable file, an image that is not 3-D (a single 2-D slice), an empty volume, a
/// directory without a DICOM series or with several series (their UIDs are listed); LimitError when the
/// volume's estimated working memory (kVolumeBytesPerVoxel) exceeds the memory available.
[[nodiscard]] CtImage::Pointer read_volume(const std::filesystem::path& path);

/// Writes a volume atomically (temporary file, then rename); format from the extension
/// (.mha, .nrrd, .nii, .nii.gz). Throws InvalidInputError naming the path on failure.
void write_volume(const CtImage* image, const std::filesystem::path& path);

}  // namespace contourmesh
