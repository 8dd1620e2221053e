// Cross-slice smoothing: the project's default smoothing of contour meshes (docs/smoothing.md,
// "Cross-slice smoothing"). It follows the paper's observation (Xu et al. 2006, section 3) that
// segmentation errors perturb single contours while true shape continues from contour to contour:
// every contour vertex is corrected from the profile that the surface traces across the neighbouring
// slices, not from its umbrella.
//
// 1. Profiles: the plane through a contour vertex perpendicular to its contour's tangent cuts the
//    corresponding contours of up to `reach` slices above and below; the in-plane offsets of those
//    cuts along the vertex's in-plane normal, against their height along the slice axis, form the
//    profile a(z).
// 2. Fit: a weighted (tricube over the reach) least-squares polynomial of a(z); the vertex moves by the
//    fit's value at its own slice, along its in-plane normal, so that contour vertices stay in their
//    slice planes.
// 3. Vertices off the slices (caps, branchings) follow: their displacement is the harmonic extension of
//    the contour vertices' displacements.
#pragma once

#include "smooth/feature_detection.h"
#include "smooth/mesh.h"
#include "smooth/progress.h"

#include <vector>

namespace contourmesh {

struct CrossSliceOptions {
  /// Slices on each side of a vertex that its profile may use, >= 1.
  int reach = 6;
  /// Degree of the profile polynomial: 1 (a line: strongest denoising, biased where profiles curve)
  /// or 2 (default).
  int degree = 2;
  /// Jacobi iterations of the harmonic extension to vertices off the slices, >= 0.
  int extension_iterations = 30;
  /// Feature labels reported with the result (DetectionOptions of the paper's Algorithm 2).
  DetectionOptions detection;
  /// Stages "detect" and "smooth"; return false to cancel (CancelledError).
  ProgressCallback progress;
};

struct CrossSliceResult {
  Mesh mesh;                   ///< smoothed, same connectivity and ids
  FeatureDetection detection;  ///< labels of the input vertices
  std::size_t profiles = 0;    ///< contour vertices corrected from a profile
  double seconds_detect = 0.0, seconds_smooth = 0.0, seconds_total = 0.0;
};

/// Smooths a contour mesh. Needs contour ids (InvalidInputError otherwise; recover them with
/// assign_ids_by_slice_planes); throws InvalidInputError for options out of range and CancelledError
/// on request.
[[nodiscard]] CrossSliceResult cross_slice_smooth(const Mesh& mesh, const CrossSliceOptions& options = {});

}  // namespace contourmesh
