// The contour structure of a tiled mesh (SPEC 2), recovered from its vertex ids and connectivity:
// each vertex's two neighbours along its own contour, windows of consecutive contour vertices, and
// the slice axis.
#pragma once

#include "smooth/adjacency.h"
#include "smooth/mesh.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace contourmesh {

/// For every vertex, its two neighbours along its own contour (unordered), or -1 where it has not
/// exactly two: a vertex off the slices (kNoId), or a damaged contour. A same-slice, same-contour edge
/// is a contour edge unless both its triangles lie in that slice plane (a chord of a cap).
struct ContourNeighbours {
  std::vector<std::array<Index, 2>> of;

  /// Up to `size` consecutive vertices of i's contour centred on i (i itself in the middle; fewer near
  /// a damaged contour, never repeating a vertex), in contour order.
  [[nodiscard]] std::vector<Index> window(Index i, int size) const;
};

/// Requires contour ids (throws InvalidInputError otherwise).
[[nodiscard]] ContourNeighbours contour_neighbours(const Mesh& mesh, const MeshAdjacency& adjacency);

/// Unit normal of the slice planes, pointing towards increasing slice ids: the direction of least
/// spread of the vertices about their slice centroids. Requires ids and at least one slice with three
/// non-collinear vertices (throws InvalidInputError otherwise).
[[nodiscard]] Eigen::Vector3d estimate_slice_axis(const Mesh& mesh);

/// Recovers slice and contour ids for a contour-stack mesh saved without them (SPEC 2): vertices are
/// binned by their coordinate along `axis` (values closer than `tolerance`, default 1e-4 of the extent
/// along the axis, share a slice plane; planes are numbered in increasing order), and within a plane
/// the connected components of that plane's edges are the contours. Returns false and leaves the
/// mesh untouched when the vertices do not lie on planes (less than 90% of them on planes holding at
/// least three vertices, e.g. a marching-cubes mesh). Throws InvalidInputError for a zero axis.
bool assign_ids_by_slice_planes(Mesh& mesh, const MeshAdjacency& adjacency, const Eigen::Vector3d& axis,
                                double tolerance = 0.0);

}  // namespace contourmesh
