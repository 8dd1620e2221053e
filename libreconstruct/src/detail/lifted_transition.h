// SPDX-License-Identifier: BSD-3-Clause
// Private: joining two levels whose contours do not cross in the plane by a triangulated, lifted fill
// of the region where exactly one of them has material.
#pragma once

#include "detail/tiling_types.h"

namespace contourmesh::detail {

/// Where no contour of `lower` crosses or touches a contour of `upper` (seen along the slice axis), the
/// surface between the levels is, face by face of the plane arrangement of all their contours, the
/// region where exactly one level has material. Each such face is triangulated as a cap with holes
/// would be (a refined constrained Delaunay triangulation, interior vertices about a contour spacing
/// apart) and its interior vertices are lifted between the planes by their relative distance to the
/// face's lower and upper contours, w = w_lower + (w_upper - w_lower) d_lower / (d_lower + d_upper): the
/// surface that shape-based interpolation describes, where the least-area band would fan slivers
/// across a nearly flat region (a contour shrinking to a speck, small contours inside a large one).
/// Faces facing up where the lower level alone has material, down where the upper alone has it; role
/// Band. Returns false, adding nothing, when contours cross, or when a face is bounded by contours of
/// one level only (an end: it is capped, not lifted).
bool lifted_transition(const Level& lower, const Level& upper, SlabMesh& out);

}  // namespace contourmesh::detail
