// SPDX-License-Identifier: BSD-3-Clause
// Private to the comparison: VTK's smoothing filters as a VTK or 3D Slicer user configures them, and
// 3D Slicer's voxel route (threshold, islands, flying edges, windowed sinc) on a CT volume.
#pragma once

#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/mesh.h>
#include <contourmesh/smooth/progress.h>

#include <vtkSmartPointer.h>

#include <string>
#include <utility>
#include <vector>

class vtkPolyData;

namespace contourmesh::compare_detail {

/// The points of a polydata as a 3 x n matrix.
[[nodiscard]] Eigen::Matrix3Xd positions_of(vtkPolyData* poly);

/// vtkWindowedSincPolyDataFilter as 3D Slicer configures it for closed surfaces: normalized
/// coordinates, no boundary or feature-edge smoothing, non-manifold smoothing on.
[[nodiscard]] vtkSmartPointer<vtkPolyData> windowed_sinc(vtkPolyData* input, int iterations, double passband);

/// vtkSmoothPolyDataFilter with feature-edge smoothing, every iteration run (convergence 0).
[[nodiscard]] vtkSmartPointer<vtkPolyData> smooth_polydata(vtkPolyData* input, int iterations, double relaxation,
                                                           double feature_angle, double edge_angle);

/// The flying-edges surface of the thresholded volume (physical coordinates, outward), unsmoothed and
/// smoothed with windowed sinc, with the seconds of "threshold" (with the island and hole clean-up),
/// "surface" and "smooth", the fastest of `repeats` runs.
struct VoxelSurface {
  Mesh raw, smoothed;
  std::vector<std::pair<std::string, double>> seconds;
};

/// Islands and holes under `min_voxels` voxels are removed and filled (3D Slicer's Islands effect and a
/// hole fill); one voxel of background pads the volume so that bone touching the border gives a closed
/// surface. Throws InvalidInputError when no surface is found. `progress` reports under `stage`.
[[nodiscard]] VoxelSurface voxel_route(const CtImage& image, double threshold, double min_voxels, int sinc_iterations,
                                       double passband, int repeats, const ProgressCallback& progress,
                                       const std::string& stage);

}  // namespace contourmesh::compare_detail
