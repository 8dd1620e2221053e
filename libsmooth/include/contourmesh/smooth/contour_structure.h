// SPDX-License-Identifier: BSD-3-Clause
// The contour structure of a tiled mesh (the ids of mesh.h), recovered from its vertex ids and connectivity:
// each vertex's two neighbours along its own contour, windows of consecutive contour vertices, and
// the slice axis.
#pragma once

#include "contourmesh/smooth/adjacency.h"
#include "contourmesh/smooth/mesh.h"

#include <Eigen/Core>

#include <array>
#include <string>
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

/// Recovers slice and contour ids for a contour-stack mesh saved without them (ids as in mesh.h): vertices are
/// binned by their coordinate along `axis` (values closer than `tolerance`, default 1e-4 of the extent
/// along the axis, share a slice plane; planes are numbered in increasing order), and within a plane
/// the connected components of that plane's edges are the contours. Returns false and leaves the
/// mesh untouched when the vertices do not lie on planes (less than 90% of them on planes holding at
/// least three vertices, e.g. a marching-cubes mesh). Throws InvalidInputError for a zero axis.
bool assign_ids_by_slice_planes(Mesh& mesh, const MeshAdjacency& adjacency, const Eigen::Vector3d& axis,
                                double tolerance = 0.0);

/// Renumbers the slice ids in use consecutively from the lowest one, in their order, closing gaps (ids
/// between the lowest and the highest that no vertex uses, as when a file's ids jump by 2). kNoId
/// stays. Returns the number of gaps closed; the mesh is unchanged when there were none or when it has
/// no ids.
std::size_t compact_slice_ids(Mesh& mesh);

/// The first inconsistency between a mesh's contour ids and its connectivity and geometry, as one line
/// naming the vertices involved, or an empty string when the ids are consistent (or absent):
/// - an id below kNoId, or a vertex with exactly one of its two ids kNoId;
/// - an edge joining slices whose ids differ by more than one (tiling joins adjacent slices only);
/// - slice planes out of order along the slice axis, or the ids not spanning planes at all;
/// - a vertex nearer to the plane of another slice than to its own (off by more than half the gap to
///   the adjacent slice), e.g. a same-slice edge between two slice planes.
/// The slice-axis estimate ignores copies off the slices (kNoId). Use after compact_slice_ids.
[[nodiscard]] std::string find_contour_id_problem(const Mesh& mesh, const MeshAdjacency& adjacency);

/// Repairs inconsistent ids of a contour-stack mesh: recovers them from the slice planes along `axis`
/// (assign_ids_by_slice_planes), then gives each recovered plane the slice id most of its vertices had
/// in `mesh` (kNoId for planes of copies off the slices), so that only the wrong ids change; contour
/// ids are the recovered ones. Returns false and leaves the mesh untouched when the mesh has no ids,
/// its vertices do not lie on planes normal to `axis`, a plane has no majority id or two planes claim
/// the same slice (planes that are not the file's slices), or the result is still inconsistent.
bool repair_contour_ids(Mesh& mesh, const MeshAdjacency& adjacency, const Eigen::Vector3d& axis);

}  // namespace contourmesh
