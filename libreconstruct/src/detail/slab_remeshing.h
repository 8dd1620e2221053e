// SPDX-License-Identifier: BSD-3-Clause
// Private: improving the shape of a slab's faces after it is tiled, without moving its boundary (the
// contours of the two slices, shared with the neighbouring slabs) or its vertices.
#pragma once

#include "detail/tiling_types.h"

#include <cstddef>

namespace contourmesh::detail {

/// What improve_slab_faces did.
struct SlabRemeshing {
  std::size_t flips = 0;
  std::size_t splits = 0;
  std::size_t insertions = 0;  ///< vertices put inside slivers that lie nearly in the slice planes
};

/// Removes slivers (faces whose smallest angle is under 10 degrees) from a slab's tiling, where bands
/// between very different contours (composites, intermediate contours, a contour and its copy) fan
/// long thin faces:
/// - edge flips that raise the smaller of the two faces' smallest angles (the max-min angle criterion
///   of Delaunay triangulations, applied on the surface), only where the four corners lie within
///   `max_deviation` (mm) of one plane, so that the surface moves by at most that much;
/// - for a sliver lying nearly in the slice planes (normal within 30 degrees of the slice axis), a new
///   vertex (without ids, on the surface) at the off-centre of its shortest edge (Ungor 2004; the
///   circumcentre when nearer), found by walking the faces in the (u, v) plane, followed by flips;
///   where that point lies beyond the level region, the edge the walk stopped at is split at its
///   midpoint (a composite's bridge edge included);
/// - splits of a sliver's longest edge at its midpoint (a vertex on the surface, without ids: the
///   surface does not move) while that edge is longer than `min_split_length` (mm), followed by flips.
/// Only faces that share a corner with a sliver take part, caps excepted (planar, and triangulated as
/// CapRefinement asks), and only edges between two such faces of the same role are flipped: the edges
/// on the slab's boundary (the slice contours) and their vertices, with their ids, stay as they are. A
/// flip never joins two contour vertices of one plane (a chord across a contour would lie in its
/// plane; two vertices without ids of one plane only where both faces lie nearly in the slice planes on
/// one side), never creates an edge that exists, never turns a face over against its old ones and
/// never adds a fold (a face nearly in the slice planes facing up next to one facing down); a chord in
/// a plane never adds area within 10 degrees of the slice planes. Does nothing when the slab has no
/// slivers. Faces keep their roles.
SlabRemeshing improve_slab_faces(SlabMesh& mesh, double max_deviation, double min_split_length);

}  // namespace contourmesh::detail
