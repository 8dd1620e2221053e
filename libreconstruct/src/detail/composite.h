// SPDX-License-Identifier: BSD-3-Clause
// Private: the mid-plane composite of Meyers, Skinner and Sloan (1992): several contours of one level
// copied onto an intermediate plane and joined by bridges into one contour (docs/reconstruction.md,
// "Tiling", the bridge rules).
#pragma once

#include "detail/tiling_types.h"

#include <vector>

namespace contourmesh::detail {

/// The contours `members` of `level` copied onto plane w, each joined to its original by a straight band
/// (`below`: the originals lie below the plane), and the copies joined into one composite contour by
/// bridges, whose gaps are closed by two faces each (role Bridge); returns the composite. With
/// `clear_bridges` (BandRefinement::Interpolated) a bridge crosses no contour and goes where `other` (the
/// other level) joins what it joins; with `guide` (the one contour of the other level the composite is
/// tiled to) as well, a bridge that would give the composite another order of its pieces than the guide's
/// goes where the guide passes from piece to piece. Adds one to out.stats.composites.
[[nodiscard]] LevelContour composite_of(const Level& level, const std::vector<int>& members, const Level& other,
                                        double w, bool below, bool clear_bridges, SlabMesh& out,
                                        const Polygon* guide = nullptr);

}  // namespace contourmesh::detail
