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

}  // namespace contourmesh
