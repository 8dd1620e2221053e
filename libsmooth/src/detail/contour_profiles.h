// SPDX-License-Identifier: BSD-3-Clause
// Profiles of a contour mesh's surface through a contour vertex (for the cross-slice smoother): across
// the slices, where the plane through the vertex perpendicular to its contour cuts the corresponding
// contours above and below; and along the vertex's own contour.
#pragma once

#include "detail/lpa_ici.h"
#include "detail/slice_edge_grid.h"
#include "contourmesh/smooth/adjacency.h"
#include "contourmesh/smooth/contour_structure.h"
#include "contourmesh/smooth/mesh.h"
#include "contourmesh/smooth/slice_neighbors.h"

#include <Eigen/Core>

#include <vector>

namespace contourmesh::detail {

/// The contour structure a profile walks on.
struct ContourFrame {
  const Mesh* mesh = nullptr;
  MeshAdjacency adjacency;
  ContourNeighbours contour;
  SliceRings rings;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< slice axis, towards increasing slice ids
  double slice_spacing = 1.0;                       ///< median height of the edges between slices
  double point_spacing = 1.0;                       ///< mean length of the contour edges
  std::vector<std::uint8_t> on_contour;             ///< 1: a slice id and two contour neighbours
  /// Per contour vertex, the contour vertex of the slice above (below) joined to it that is nearest
  /// in the slice plane, or -1: where a profile starts looking for its next cut.
  std::vector<Index> above, below;
  /// The contour edges of every slice, for cuts where the connectivity does not lead to the next slice.
  SliceEdgeGrid edges;

  [[nodiscard]] bool is_contour_vertex(Index i) const { return on_contour[static_cast<std::size_t>(i)] != 0; }
};

/// Builds the frame; throws InvalidInputError for a mesh without ids or whose slices do not span planes.
[[nodiscard]] ContourFrame make_contour_frame(const Mesh& mesh);

/// The in-slice unit normal of contour vertex i (its surface normal with the axial part removed), or
/// false when the surface there is within a few degrees of the slice plane.
[[nodiscard]] bool in_slice_normal(const ContourFrame& frame, const Eigen::Vector3d& surface_normal,
                                   Eigen::Vector3d& m);

/// The profile across the slices of contour vertex i on `positions` (with vertex normals `normals`):
/// samples (height along the axis in slice spacings, offset along m), up to `reach` slices each way,
/// through the plane at v_i with normal axis x m. Each cut is looked for along the mesh from the
/// previous one, and where the mesh does not lead there (a branching, a cap), among the next slice's
/// contour edges facing the same way within three slice spacings. Stops at a slice without such a cut.
void cross_slice_profile(const ContourFrame& frame, const Eigen::Matrix3Xd& positions, const Eigen::Matrix3Xd& normals,
                         Index i, const Eigen::Vector3d& m, int reach, Profile& out);

/// A point on a contour edge: x_a + t (x_b - x_a).
struct EdgePoint {
  Index a = -1, b = -1;
  double t = 0.0;
  [[nodiscard]] bool valid() const { return a >= 0; }
  [[nodiscard]] Eigen::Vector3d on(const Eigen::Matrix3Xd& x) const { return x.col(a) + t * (x.col(b) - x.col(a)); }
};

/// For every contour vertex, where its profile plane (through it, normal axis x m with m its in-slice
/// normal) cuts the corresponding contour of the next slice above and below: the first step of every
/// cross-slice profile, found once (along the mesh, or among the next slice's edges as
/// cross_slice_profile does).
struct NextCuts {
  std::vector<EdgePoint> up, down;
};
[[nodiscard]] NextCuts next_cuts(const ContourFrame& frame, const Eigen::Matrix3Xd& positions,
                                 const Eigen::Matrix3Xd& normals);

/// The profile across the slices of contour vertex i, chained from the next cuts: the cut above the
/// vertex, then above that cut the interpolation of the cuts above its edge's ends, and so on; samples
/// as in cross_slice_profile (offsets along the vertex's own m). The chain follows the surface from
/// slice to slice as the cuts of each contour's own planes lead, at two cuts per vertex in all instead
/// of two per sample.
void chained_profile(const ContourFrame& frame, const Eigen::Matrix3Xd& positions, const NextCuts& cuts, Index i,
                     const Eigen::Vector3d& m, int reach, Profile& out);

/// The profile along contour vertex i's own contour: samples (signed arc length in point spacings,
/// offset along m) of up to `reach` vertices each way (fewer on short contours).
void along_contour_profile(const ContourFrame& frame, const Eigen::Matrix3Xd& positions, Index i,
                           const Eigen::Vector3d& m, int reach, Profile& out);

/// A noise estimate and the data behind it.
struct NoiseEstimate {
  double sigma = 0.0;         ///< mm; 0 when no profile qualifies
  std::size_t profiles = 0;   ///< regular five-sample profiles the estimate is the median over
  std::size_t sampled = 0;    ///< contour vertices looked at (every `stride`-th)
  /// profiles / sampled (0 when nothing was sampled).
  [[nodiscard]] double share() const {
    return sampled > 0 ? static_cast<double>(profiles) / static_cast<double>(sampled) : 0.0;
  }
};

/// Noise standard deviation of profile offsets, from the fourth differences of five-sample profiles
/// (blind to quadratic shape): 1.4826 median |d4| / sqrt(70). `across` picks cross-slice or
/// along-contour profiles; every `stride`-th contour vertex is sampled.
[[nodiscard]] NoiseEstimate profile_noise(const ContourFrame& frame, const Eigen::Matrix3Xd& positions,
                                          const Eigen::Matrix3Xd& normals, bool across, Index stride = 2);

}  // namespace contourmesh::detail
