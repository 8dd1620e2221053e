// SPDX-License-Identifier: BSD-3-Clause
#include "vtk_methods.h"

#include "timing.h"

#include <contourmesh/vtk/vtk_convert.h>
#include <contourmesh/vtk/vtk_image_convert.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/metrics.h>

#include <vtkDiscreteFlyingEdges3D.h>
#include <vtkImageConnectivityFilter.h>
#include <vtkImageConstantPad.h>
#include <vtkImageData.h>
#include <vtkImageThreshold.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmoothPolyDataFilter.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <cmath>
#include <limits>

namespace contourmesh::compare_detail {

Eigen::Matrix3Xd positions_of(vtkPolyData* poly) {
  const auto n = static_cast<Index>(poly->GetNumberOfPoints());
  Eigen::Matrix3Xd p(3, n);
  for (Index i = 0; i < n; ++i) poly->GetPoint(i, p.col(i).data());
  return p;
}

// (vtkBinaryLabelmapToClosedSurfaceConversionRule in 3D Slicer.)
vtkSmartPointer<vtkPolyData> windowed_sinc(vtkPolyData* input, int iterations, double passband) {
  vtkNew<vtkWindowedSincPolyDataFilter> filter;
  filter->SetInputData(input);
  filter->SetNumberOfIterations(iterations);
  filter->SetPassBand(passband);
  filter->NormalizeCoordinatesOn();
  filter->BoundarySmoothingOff();
  filter->FeatureEdgeSmoothingOff();
  filter->NonManifoldSmoothingOn();
  filter->Update();
  return filter->GetOutput();
}

vtkSmartPointer<vtkPolyData> smooth_polydata(vtkPolyData* input, int iterations, double relaxation,
                                             double feature_angle, double edge_angle) {
  vtkNew<vtkSmoothPolyDataFilter> filter;
  filter->SetInputData(input);
  filter->SetNumberOfIterations(iterations);
  filter->SetRelaxationFactor(relaxation);
  filter->SetConvergence(0.0);  // run every iteration
  filter->FeatureEdgeSmoothingOn();
  filter->SetFeatureAngle(feature_angle);
  filter->SetEdgeAngle(edge_angle);
  filter->BoundarySmoothingOn();
  filter->Update();
  return filter->GetOutput();
}

namespace {

// Keeps the 6-connected regions of value 1 with at least `min_voxels` voxels, as 1; the rest becomes 0.
void keep_large_regions(vtkImageConnectivityFilter* filter, vtkIdType min_voxels) {
  filter->SetScalarRange(1.0, 1.0);
  filter->SetExtractionModeToAllRegions();
  filter->SetSizeRange(min_voxels, std::numeric_limits<vtkIdType>::max());
  filter->SetLabelModeToConstantValue();
  filter->SetLabelConstantValue(1);
  filter->SetLabelScalarTypeToUnsignedChar();
  filter->GenerateRegionExtentsOff();
}

// 0 -> 1 and 1 -> 0 on a binary unsigned char image.
void invert(vtkImageThreshold* filter) {
  filter->ThresholdByLower(0.5);
  filter->SetInValue(1);
  filter->SetOutValue(0);
  filter->ReplaceInOn();
  filter->ReplaceOutOn();
  filter->SetOutputScalarTypeToUnsignedChar();
}

}  // namespace

VoxelSurface voxel_route(const CtImage& image, double threshold, double min_voxels, int sinc_iterations,
                         double passband, int repeats, const ProgressCallback& progress, const std::string& stage) {
  const auto report = [&](double fraction) {
    if (progress && !progress(stage, fraction)) throw CancelledError(stage);
  };
  VoxelSurface v;
  // Work in index space scaled by the spacing (origin 0, identity direction) and map the points to
  // physical space afterwards, whatever the image's direction matrix.
  vtkSmartPointer<vtkImageData> vtk_image = to_image_data(&image);
  double first[3];
  vtk_image->GetOrigin(first);
  Eigen::Matrix3d direction;
  const auto& d = image.GetDirection();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) direction(r, c) = d(r, c);
  }
  vtk_image->SetOrigin(0.0, 0.0, 0.0);
  vtk_image->SetDirectionMatrix(1, 0, 0, 0, 1, 0, 0, 0, 1);
  int extent[6];
  vtk_image->GetExtent(extent);

  const auto min_speck_voxels = static_cast<vtkIdType>(std::ceil(min_voxels));
  vtkSmartPointer<vtkPolyData> raw_poly, smooth_poly;
  v.seconds = timed(repeats, [&](const StageRecorder& record) {
    auto t = Clock::now();
    vtkNew<vtkImageThreshold> binarize;
    binarize->SetInputData(vtk_image);
    binarize->ThresholdByUpper(threshold);
    binarize->SetInValue(1);
    binarize->SetOutValue(0);
    binarize->ReplaceInOn();
    binarize->ReplaceOutOn();
    binarize->SetOutputScalarTypeToUnsignedChar();
    vtkAlgorithm* binary = binarize;
    // Islands and holes below the contour route's speck size are removed and filled, as the contour
    // route drops such regions and holes per slice and such components after tiling; otherwise noise
    // voxels decide the voxel route's metrics.
    vtkNew<vtkImageConnectivityFilter> islands;
    vtkNew<vtkImageThreshold> background;
    vtkNew<vtkImageConnectivityFilter> large_background;
    vtkNew<vtkImageThreshold> filled;
    if (min_speck_voxels > 0) {
      islands->SetInputConnection(binarize->GetOutputPort());
      keep_large_regions(islands, min_speck_voxels);
      background->SetInputConnection(islands->GetOutputPort());
      invert(background);
      large_background->SetInputConnection(background->GetOutputPort());
      keep_large_regions(large_background, min_speck_voxels);
      filled->SetInputConnection(large_background->GetOutputPort());
      invert(filled);
      binary = filled;
    }
    vtkNew<vtkImageConstantPad> pad;
    pad->SetInputConnection(binary->GetOutputPort());
    pad->SetOutputWholeExtent(extent[0] - 1, extent[1] + 1, extent[2] - 1, extent[3] + 1, extent[4] - 1, extent[5] + 1);
    pad->SetConstant(0);
    pad->Update();
    record("threshold", seconds_since(t));
    report(0.3);

    t = Clock::now();
    vtkNew<vtkDiscreteFlyingEdges3D> surface;
    surface->SetInputConnection(pad->GetOutputPort());
    surface->SetValue(0, 1.0);
    surface->ComputeNormalsOff();
    surface->ComputeGradientsOff();
    surface->ComputeScalarsOff();
    surface->Update();
    raw_poly = surface->GetOutput();
    record("surface", seconds_since(t));
    report(0.6);

    t = Clock::now();
    smooth_poly = windowed_sinc(raw_poly, sinc_iterations, passband);
    record("smooth", seconds_since(t));
  });
  if (raw_poly->GetNumberOfPolys() == 0) {
    throw InvalidInputError("the voxel route found no surface at threshold " + std::to_string(threshold));
  }
  const Eigen::Vector3d origin(first[0], first[1], first[2]);
  const auto to_physical = [&](vtkPolyData* poly) {
    Mesh m = from_polydata(poly);
    m.positions = (direction * m.positions).colwise() + origin;
    return m;
  };
  v.raw = to_physical(raw_poly);
  v.smoothed = to_physical(smooth_poly);
  // Marching-cubes triangles may wind inwards; the volume's sign tells, and the metrics want outward.
  if (enclosed_volume(v.raw) < 0.0) {
    for (Triangle& t : v.raw.triangles) std::swap(t[1], t[2]);
    v.smoothed.triangles = v.raw.triangles;
  }
  return v;
}

}  // namespace contourmesh::compare_detail
