// SPDX-License-Identifier: BSD-3-Clause
// Private: the mid-plane composite of Meyers, Skinner and Sloan (1992), for the topology changes left
// at the finest level of interpolation (or every one, with Branching::MidPlaneComposite).
#pragma once

#include "detail/tiling_types.h"

namespace contourmesh::detail {

/// Tiles the contours of one group between `lower` and `upper` (every contour of both levels belongs
/// to it; some correspond to several on the other side). Contours that correspond one to one get a
/// minimum-area band. Where a side has several, they are copied onto an intermediate plane (the
/// mid-plane; the thirds when both sides have several), each copy is joined to its contour by a
/// straight band, the copies are bridged into one composite contour between their nearest points, the
/// composite is tiled to the other side, and the gap under each bridge is closed by two faces (role
/// Bridge). A hole that opens to the outside joins its outer contour's composite; a hole that ends is
/// capped facing into the cavity (half the slab beyond its plane with EndCaps::HalfSpacing); an outer
/// contour with no partner is capped with its holes.
void tile_composite(const Level& lower, const Level& upper, const TilingOptions& options, SlabMesh& out);

}  // namespace contourmesh::detail
