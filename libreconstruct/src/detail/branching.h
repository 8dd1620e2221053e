// SPDX-License-Identifier: BSD-3-Clause
// Private: the mid-plane composite of Meyers, Skinner and Sloan (1992), for the topology changes left
// at the finest level of interpolation (or every one, with Branching::MidPlaneComposite).
#pragma once

#include "detail/correspondence.h"
#include "detail/tiling_types.h"

#include <cstddef>
#include <vector>

namespace contourmesh::detail {

/// Tiles the contours of one group between `lower` and `upper` (every contour of both levels belongs
/// to it; some correspond to several on the other side). Contours that correspond one to one get a
/// minimum-area band. Where a side has several, they are copied onto an intermediate plane (the
/// mid-plane; the thirds when both sides have several), each copy is joined to its contour by a
/// straight band, the copies are bridged into one composite contour between their nearest points, the
/// composite is tiled to the other side, and the gap under each bridge is closed by two faces (role
/// Bridge). With BandRefinement::Interpolated, the composites' bridges cross no contour, an opening hole
/// is bridged where the wall is open on the other side only when that bridge is short, and where a
/// composite crosses the ring on the other side in the plane, the band between them is the crossing band
/// (crossing_band.h) when that leaves less flat and sliver area than the least-area band.
/// A hole that opens to the outside joins its outer contour's composite; a hole that ends is capped
/// facing into the cavity (half the slab beyond its plane with EndCaps::HalfSpacing); an outer contour
/// with no partner is capped with its holes.
///
/// With `deferred`, the bands that join a composite contour to the other side (the costly part: rings of
/// all of a side's contours) are not solved but listed there; every other face is added. The faces
/// added so far then have the composite's bridge area and most of its flat and sliver area (the bands
/// add faces; a crossing band also splits some, so it is no lower bound), so that a caller can often
/// decide whether it needs the composite at all before finish_composite. `links`: the levels'
/// correspondence when the caller has it (restrict_correspondence), else it is computed.
struct DeferredBand {
  LevelContour lower, upper;
  double wl = 0.0, wu = 0.0;
  std::size_t position = 0;  ///< index among the mesh's faces where the band's faces belong
  bool lower_composite = false, upper_composite = false;  ///< which rings are composites
};
void tile_composite(const Level& lower, const Level& upper, const TilingOptions& options, SlabMesh& out,
                    std::vector<DeferredBand>* deferred = nullptr, const Correspondence* links = nullptr);

/// Solves the bands tile_composite deferred into `out` and inserts their faces where it would have
/// added them (a crossing band's faces are appended): the mesh is then the one tile_composite makes
/// without `deferred`.
void finish_composite(const std::vector<DeferredBand>& deferred, const TilingOptions& options, SlabMesh& out);

}  // namespace contourmesh::detail
