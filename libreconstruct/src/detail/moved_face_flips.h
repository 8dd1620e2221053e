// SPDX-License-Identifier: BSD-3-Clause
// Private: edge flips that undo the slivers the off-slice heights make, after the slabs are assembled.
#pragma once

#include "contourmesh/reconstruct/tiling.h"

#include <contourmesh/smooth/mesh.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace contourmesh::detail {

/// Flips edges of the assembled mesh around its slivers (faces whose smallest angle is under 10
/// degrees) where that raises the smaller of the two faces' smallest angles (the max-min angle rule of
/// Delaunay triangulations, on the surface). Off-slice heights move the vertices without ids between the
/// slices, which turns some faces the slabs' face-quality pass left well shaped into slivers; these
/// flips mend them without moving a vertex or changing an id. The same limits as the slabs' pass hold:
/// the four corners lie within `max_deviation` (mm) of one plane; both faces are of one role and not
/// caps; an edge between two vertices of one slice contour (a contour edge or a chord across it) is
/// never flipped and never made; no new face turns over against either old one, no flip adds a fold (a
/// face within 30 degrees of the slice planes facing up next to one facing down) or area within 10
/// degrees of the slice planes (`axis`, unit). `roles` has one entry per face and stays valid (faces keep
/// their roles). Does nothing to a mesh without contour ids. Returns the number of flips.
std::size_t flip_moved_slivers(Mesh& mesh, const std::vector<FaceRole>& roles, const Eigen::Vector3d& axis,
                               double max_deviation);

}  // namespace contourmesh::detail
