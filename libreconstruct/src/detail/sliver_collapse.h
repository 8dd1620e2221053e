// SPDX-License-Identifier: BSD-3-Clause
// Private: removing slivers from a slab's tiling by collapsing one of their corners onto a neighbour
// (docs/reconstruction.md, "Tiling", face quality).
#pragma once

#include "detail/tiling_types.h"

#include <cstddef>

namespace contourmesh::detail {

/// Removes slivers (smallest angle under 10 degrees) by edge collapses, sharpest first. Thin bands
/// between two levels of an interpolation that nearly coincide (sub-slabs a fraction of a millimetre
/// thick, where a halved slab runs along a wall) are rows of slivers that no flip or split can mend.
///
/// Only the faces around the slivers take part (those that touch a vertex within one edge of a sliver's
/// corner). The corner that goes is a vertex the slab added itself (no ids: an intermediate contour, a copy, a
/// split's midpoint), never on the slab's boundary and never a corner of a cap; it moves onto one of its
/// neighbours at most `max_length` (mm) away, which stays where it is. Of the collapses a sliver
/// allows, the one that leaves the best smallest angle is made, and a collapse is allowed only when:
/// - the surface stays an edge-manifold (the two ends share no neighbour but the third corners of the
///   edge's two faces), and no new edge joins two contour vertices of one slice (a chord in its plane,
///   which the next slab may hold too);
/// - the neighbour lies within `max_deviation` (mm) of the plane of every face around the vertex that
///   goes, and that vertex within `max_deviation` of the plane of every face it leaves behind, so the
///   surface moves by about that much at most;
/// - no face turns by more than 45 degrees or to zero area, and the faces lying within 10 degrees of the
///   slice planes (shelves) do not grow in area;
/// - the smallest angle of the faces around the vertex that goes rises.
/// The slab's contour vertices and their ids, its boundary and its caps stay as they are; the local
/// vertices that remain are renumbered in order. `mesh` is a whole slab's mesh, not a scratch mesh (its
/// local vertices are numbered from 0). Returns how many edges were collapsed.
std::size_t collapse_slivers(SlabMesh& mesh, double max_length, double max_deviation);

}  // namespace contourmesh::detail
