// SPDX-License-Identifier: BSD-3-Clause
// Conversion between vtkImageData and the CT volume type of libreconstruct (itk::Image<float, 3>).
#pragma once

#include <contourmesh/reconstruct/volume.h>

#include <vtkSmartPointer.h>

class vtkDataArray;
class vtkImageData;

namespace contourmesh {

/// Copies a 3-D vtkImageData into a CtImage: the voxel values of `scalars` (one component, any numeric
/// type, converted to float; the image's active point scalars when null), the spacing, and the
/// physical position and direction of the first voxel. VTK places voxel (i, j, k) of the extent at
/// origin + D (i sx, j sy, k sz) with D the direction matrix (identity before VTK 9); the CtImage
/// starts at index 0 with origin = the position of the extent's first voxel, so every voxel keeps its
/// physical position. A negative VTK spacing is turned positive by flipping that direction column
/// (ITK spacings are positive). Throws InvalidInputError for a null or empty image, missing scalars,
/// scalars with more than one component or the wrong number of tuples, a zero spacing, or a direction
/// matrix that is not orthonormal.
[[nodiscard]] CtImage::Pointer to_ct_image(vtkImageData* image, vtkDataArray* scalars = nullptr);

/// The inverse: a vtkImageData with extent [0, size - 1], float point scalars named `scalars_name`,
/// and the CtImage's spacing, origin and direction matrix. Throws InvalidInputError for a null image.
[[nodiscard]] vtkSmartPointer<vtkImageData> to_image_data(const CtImage* image,
                                                          const char* scalars_name = "ImageScalars");

}  // namespace contourmesh
