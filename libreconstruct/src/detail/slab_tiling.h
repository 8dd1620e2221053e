// SPDX-License-Identifier: BSD-3-Clause
// Private: tiling the slab between two levels: correspondence, then for each group a band, a cap, or
// intermediate contours by shape-based interpolation (docs/reconstruction.md, "Tiling").
#pragma once

#include "detail/tiling_types.h"

namespace contourmesh::detail {

/// Tiles the slab between `lower` and `upper` (upper.w > lower.w) into `out`:
/// - groups with no contour on one side are capped (half the slab beyond with EndCaps::HalfSpacing);
/// - one-to-one groups get minimum-area bands; when a band holds slivers (more than
///   options.max_band_sliver_share of its area in faces under 10 degrees), the group is tiled again
///   through intermediate contours of the shape-based interpolation, at most
///   options.max_band_aspect contour spacings apart across the band (BandRefinement::Interpolated);
/// - groups whose topology changes get the interpolated contours of the mid-plane, and each half is
///   tiled the same way, options.max_branching_depth levels deep at most (Branching::Interpolated);
///   what still changes topology at the finest level, or where interpolation fails, is joined by a
///   mid-plane composite (tile_composite).
/// Vertices of intermediate contours have no ids. `out.stats` counts one-to-one pairs, branchings and
/// refined groups of this slab (not of the halves), every intermediate contour, composite and cap.
void tile_slab(const Level& lower, const Level& upper, const TilingOptions& options, SlabMesh& out);

/// tile_contours, with the faces of each slab judged as they will be once slice s is moved in its plane
/// by judged_offsets[s] (one per slice of `stack`, or none: as tiled), the mesh sheared linearly between
/// the slices (the drift alignment, docs/contours.md): the slab between slices s and s + 1 is judged with
/// SlabMesh::shear = (judged_offsets[s + 1] - judged_offsets[s]) / its gap, so that a band which stands
/// straight as tiled but leans once sheared back is refined through intermediate contours.
[[nodiscard]] TilingResult tile_contours_judged(const ContourStack& stack, const TilingOptions& options,
                                                const ProgressCallback& progress,
                                                const std::vector<Eigen::Vector2d>& judged_offsets);

}  // namespace contourmesh::detail
