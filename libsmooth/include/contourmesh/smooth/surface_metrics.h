// SPDX-License-Identifier: BSD-3-Clause
// Accuracy measured over surfaces, not at vertices (docs/reconstruction.md, "Judging a tiling"):
// uniform samples on a mesh (their distance to the true surface) and on the true surface (their
// distance to the mesh), two-sided RMS and Hausdorff distance, area-weighted normal error, each split
// into a feature region (near the truth's sharp edges and corners) and the smooth rest.
//
// A contour mesh's vertices lie on the contours by construction, so its error sits inside the faces
// (chords between slices, slivers, caps): distances at vertices flatter it. These metrics do not.
#pragma once

#include "contourmesh/smooth/mesh.h"
#include "contourmesh/smooth/metrics.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <limits>
#include <vector>

namespace contourmesh {

/// Points on a surface, each standing for a patch of the surface of area `weights[k]` (mm^2).
struct SurfaceSamples {
  Eigen::Matrix3Xd points;
  std::vector<double> weights;
  /// For samples of a mesh: the face each point lies on; empty for samples of an implicit surface.
  std::vector<Index> faces;

  [[nodiscard]] Index size() const { return static_cast<Index>(points.cols()); }
  /// Sum of the weights: the area the samples stand for.
  [[nodiscard]] double area() const;
};

/// Uniform random samples on a triangle mesh: each face gets floor(area * density) samples plus one
/// more with probability equal to the remainder, placed uniformly in the face; every sample weighs
/// 1 / density. Reproducible for a seed. Throws InvalidInputError for density <= 0, a face index out
/// of range, or more than `max_samples` samples.
[[nodiscard]] SurfaceSamples sample_mesh_surface(const Eigen::Matrix3Xd& positions,
                                                 const std::vector<Triangle>& triangles, double density,
                                                 std::uint64_t seed = 1, std::size_t max_samples = 50'000'000);

/// Samples of the zero set of a signed distance function inside `box`: the crossings of the edges of a
/// grid of `spacing` (found in a narrow band only: blocks where |sdf| rules out the surface are skipped,
/// so `sdf` must be 1-Lipschitz, as an exact distance or a lower bound of it is), each moved onto the
/// surface by one Newton step along `normal` and weighted spacing^2 / (|n_x| + |n_y| + |n_z|), which
/// makes the weights sum to the surface area (an edge of axis a crosses a patch dA about
/// dA |n_a| / spacing^2 times). Throws InvalidInputError for spacing <= 0, an empty box or one of more
/// than 2^36 grid nodes.
[[nodiscard]] SurfaceSamples sample_implicit_surface(const ScalarField& sdf, const VectorField& normal,
                                                     const Eigen::AlignedBox3d& box, double spacing);

/// The truth a mesh is measured against.
struct SurfaceTruth {
  /// Distance to the true surface: signed (negative inside; then the mean signed distance is reported)
  /// or unsigned. Required.
  ScalarField distance;
  /// Unit outward normal of the true surface near a point (for normal errors); may be empty.
  VectorField normal;
  /// Samples of the true surface (from sample_implicit_surface, or sample_mesh_surface of a reference
  /// mesh). Required.
  SurfaceSamples samples;
  /// Distance to the nearest sharp edge or corner of the truth; empty when it has none known (then
  /// everything is "smooth").
  ScalarField feature_distance;
  /// True when `distance` is signed.
  bool signed_distance = true;
};

struct SurfaceMetricsOptions {
  double density = 4.0;        ///< samples per mm^2 on the measured mesh, > 0
  std::uint64_t seed = 1;      ///< for the mesh's samples
  double feature_radius = 1.5; ///< mm: samples closer than this to a true feature form the feature region
};

/// Accuracy over one region. NaN where the region holds no samples.
struct RegionAccuracy {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  /// Two-sided RMS distance, sqrt((mesh_to_truth_rms^2 + truth_to_mesh_rms^2) / 2), mm.
  double rms = kNaN;
  /// Two-sided Hausdorff distance: the larger of the two one-sided maxima, mm.
  double hausdorff = kNaN;
  double mesh_to_truth_rms = kNaN, truth_to_mesh_rms = kNaN;
  double mesh_to_truth_max = kNaN, truth_to_mesh_max = kNaN;
  /// Area-weighted mean signed distance of the mesh to the truth (positive: the mesh lies outside,
  /// e.g. swelling), mm; NaN for an unsigned truth.
  double mean_signed = kNaN;
  /// Area-weighted mean angle between the mesh's face normals and the true normal, degrees.
  double normal_error_degrees = kNaN;
  double mesh_area = 0.0, truth_area = 0.0;  ///< mm^2 of each surface in the region
};

struct SurfaceAccuracy {
  RegionAccuracy all, feature, smooth;
  /// Secondary: RMS of the distance of the vertices to the truth, each weighted by its vertex area
  /// (a third of its faces' area), mm; and the same over the feature region's vertices.
  double vertex_rms = RegionAccuracy::kNaN;
  double feature_vertex_rms = RegionAccuracy::kNaN;
};

/// Measures a mesh against a truth. Runs on every core. Throws InvalidInputError when the truth has
/// no distance or no samples, for options out of range, or a mesh whose faces name missing vertices.
[[nodiscard]] SurfaceAccuracy surface_accuracy(const Eigen::Matrix3Xd& positions,
                                               const std::vector<Triangle>& triangles, const SurfaceTruth& truth,
                                               const SurfaceMetricsOptions& options = {});
[[nodiscard]] SurfaceAccuracy surface_accuracy(const Mesh& mesh, const SurfaceTruth& truth,
                                               const SurfaceMetricsOptions& options = {});

}  // namespace contourmesh
