// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/vtk/vtk_image_convert.h"

#include <contourmesh/smooth/errors.h>

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSetGet.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

namespace contourmesh {

namespace {

template <typename T>
void copy_to_float(const T* source, float* target, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) target[i] = static_cast<float>(source[i]);
}

}  // namespace

CtImage::Pointer to_ct_image(vtkImageData* image, vtkDataArray* scalars) {
  if (image == nullptr) throw InvalidInputError("vtkImageData to CT image: no image");
  int extent[6];
  image->GetExtent(extent);
  const int dims[3] = {extent[1] - extent[0] + 1, extent[3] - extent[2] + 1, extent[5] - extent[4] + 1};
  if (dims[0] <= 0 || dims[1] <= 0 || dims[2] <= 0)
    throw InvalidInputError("vtkImageData to CT image: the image is empty");
  if (scalars == nullptr) scalars = image->GetPointData()->GetScalars();
  if (scalars == nullptr) throw InvalidInputError("vtkImageData to CT image: the image has no point scalars");
  const auto n =
      static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]) * static_cast<std::size_t>(dims[2]);
  const std::string name = scalars->GetName() != nullptr ? scalars->GetName() : "(unnamed)";
  if (scalars->GetNumberOfComponents() != 1) {
    throw InvalidInputError("vtkImageData to CT image: scalars '" + name + "' have " +
                            std::to_string(scalars->GetNumberOfComponents()) + " components, expected 1");
  }
  if (static_cast<std::size_t>(scalars->GetNumberOfTuples()) != n) {
    throw InvalidInputError("vtkImageData to CT image: scalars '" + name + "' hold " +
                            std::to_string(scalars->GetNumberOfTuples()) + " values for " + std::to_string(n) +
                            " voxels");
  }

  // Direction and spacing: VTK allows negative spacings, ITK does not, so flip the column instead.
  Eigen::Matrix3d direction = Eigen::Matrix3d::Identity();
  if (vtkMatrix3x3* m = image->GetDirectionMatrix()) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) direction(r, c) = m->GetElement(r, c);
    }
  }
  double vtk_spacing[3];
  image->GetSpacing(vtk_spacing);
  CtImage::SpacingType spacing;
  for (int c = 0; c < 3; ++c) {
    if (!(std::isfinite(vtk_spacing[c]) && vtk_spacing[c] != 0.0)) {
      throw InvalidInputError("vtkImageData to CT image: spacing " + std::to_string(c) + " is " +
                              std::to_string(vtk_spacing[c]) + ", expected a finite non-zero value");
    }
    spacing[c] = std::abs(vtk_spacing[c]);
    if (vtk_spacing[c] < 0.0) direction.col(c) = -direction.col(c);
  }
  if (!direction.allFinite() || !(direction.transpose() * direction).isIdentity(1e-6)) {
    throw InvalidInputError("vtkImageData to CT image: the direction matrix is not orthonormal");
  }
  double first[3];
  image->TransformIndexToPhysicalPoint(extent[0], extent[2], extent[4], first);

  auto out = CtImage::New();
  CtImage::RegionType region;
  CtImage::SizeType size;
  for (int c = 0; c < 3; ++c) size[c] = static_cast<CtImage::SizeValueType>(dims[c]);
  region.SetSize(size);  // index 0
  out->SetRegions(region);
  out->SetSpacing(spacing);
  CtImage::PointType origin;
  for (int c = 0; c < 3; ++c) origin[c] = first[c];
  out->SetOrigin(origin);
  CtImage::DirectionType itk_direction;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) itk_direction(r, c) = direction(r, c);
  }
  out->SetDirection(itk_direction);
  out->Allocate();

  // VTK and ITK both store x fastest, then y, then z.
  float* target = out->GetBufferPointer();
  if (scalars->HasStandardMemoryLayout()) {
    void* source = scalars->GetVoidPointer(0);
    switch (scalars->GetDataType()) {
      vtkTemplateMacro(copy_to_float(static_cast<const VTK_TT*>(source), target, n));
      default:
        for (std::size_t i = 0; i < n; ++i)
          target[i] = static_cast<float>(scalars->GetComponent(static_cast<vtkIdType>(i), 0));
    }
  } else {
    for (std::size_t i = 0; i < n; ++i)
      target[i] = static_cast<float>(scalars->GetComponent(static_cast<vtkIdType>(i), 0));
  }
  return out;
}

vtkSmartPointer<vtkImageData> to_image_data(const CtImage* image, const char* scalars_name) {
  if (image == nullptr) throw InvalidInputError("CT image to vtkImageData: no image");
  const auto region = image->GetLargestPossibleRegion();
  if (image->GetBufferedRegion() != region) {
    throw InvalidInputError("CT image to vtkImageData: only part of the image is in memory (run its pipeline first)");
  }
  const auto size = region.GetSize();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->SetDimensions(static_cast<int>(size[0]), static_cast<int>(size[1]), static_cast<int>(size[2]));
  const auto spacing = image->GetSpacing();
  out->SetSpacing(spacing[0], spacing[1], spacing[2]);
  // The CtImage may start at a non-zero index: place VTK's index 0 at that voxel.
  CtImage::PointType first;
  image->TransformIndexToPhysicalPoint(region.GetIndex(), first);
  out->SetOrigin(first[0], first[1], first[2]);
  const auto& d = image->GetDirection();
  out->SetDirectionMatrix(d(0, 0), d(0, 1), d(0, 2), d(1, 0), d(1, 1), d(1, 2), d(2, 0), d(2, 1), d(2, 2));

  vtkNew<vtkFloatArray> values;
  values->SetName(scalars_name);
  const auto n = static_cast<vtkIdType>(region.GetNumberOfPixels());
  values->SetNumberOfValues(n);
  const float* source = image->GetBufferPointer();
  std::copy(source, source + n, values->GetPointer(0));
  out->GetPointData()->SetScalars(values);
  return out;
}

}  // namespace contourmesh
