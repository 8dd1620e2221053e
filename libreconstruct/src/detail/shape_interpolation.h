// SPDX-License-Identifier: BSD-3-Clause
// Private: shape-based interpolation between the regions of two adjacent contour levels (Raya and
// Udupa 1990; Herman, Zheng and Bucholtz 1992). Each level's region (outer contours minus holes) is
// turned into a signed distance field on a common 2-D grid; the region between them at a fraction t is
// the set where (1 - t) d_lower + t d_upper < 0, and its boundary is extracted with marching squares.
#pragma once

#include "contourmesh/internal/polygon2d.h"

#include <cstddef>
#include <optional>
#include <vector>

namespace contourmesh::detail {

/// Signed distances (mm, negative inside) of two regions, sampled at the nodes of one grid:
/// node (i, j) is at origin + h (i, j), i < nx, j < ny, stored row by row (index j * nx + i).
struct DistancePair {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double h = 1.0;
  int nx = 0;
  int ny = 0;
  std::vector<double> lower;
  std::vector<double> upper;
};

/// Samples the signed distances of the regions bounded by `lower` and `upper` (each a set of closed,
/// disjoint, simple polygons, nested outer / hole / outer ...; even-odd inside) on a grid of spacing
/// `h` covering both with a margin of two cells. Distances are exact Euclidean distances to the nearest
/// polygon edge (nearest-edge propagation seeded next to every edge; errors only where the nearest
/// edge is not one of a neighbouring node's, a fraction of h at worst). The grid is coarsened when it
/// would exceed `max_nodes` nodes. Either set may be empty (its distances are then +infinity-like: a
/// large positive value).
[[nodiscard]] DistancePair signed_distance_pair(const std::vector<Polygon>& lower, const std::vector<Polygon>& upper,
                                                double h, std::size_t max_nodes = 4'000'000);

/// The level f = `level` of f = (1 - t) lower + t upper (by default its zero level) as closed polygons,
/// inside (f < level) on the left: outer boundaries counter-clockwise, holes clockwise. A positive
/// level grows the region but never beyond the union of the two regions, a negative one shrinks it but
/// never within their intersection (the zero level lies between the two by construction). Sub-cell
/// accurate (linear interpolation along the grid edges); a saddle cell is resolved by the mean of its
/// corners. The polygons are simple and disjoint. Nodes exactly on the level count as outside.
[[nodiscard]] std::vector<Polygon> zero_level(const DistancePair& fields, double t, double level = 0.0);

/// The area (mm^2) that zero_level(fields, t, level) encloses, outer areas minus hole areas, up to
/// rounding, in one pass over the grid's cells without building the polygons: each cell adds the part of
/// it that the marching squares put inside (corners and edge crossings, saddles as zero_level resolves
/// them). 0 for an empty grid.
[[nodiscard]] double level_area(const DistancePair& fields, double t, double level = 0.0);

/// The level (see zero_level) whose region encloses `target_area` (mm^2, outer areas minus hole areas),
/// within 0.1 % of it or a cell of the grid, or as near as the union or intersection of the regions
/// allows (a few passes of level_area over the grid). The zero level of averaged distances loses area
/// wherever the two regions differ in shape (a blob below an elongated contour: the elongated one's ends
/// are far from the blob, so the average is positive there and the level is short), which shrinks every
/// refined band and branching. Shifting the level restores the area asked (see docs/reconstruction.md,
/// "Tiling"). 0 when the zero level's area is already within a cell of the target or the grid is empty.
[[nodiscard]] double level_for_area(const DistancePair& fields, double t, double target_area);

/// One contour of an interpolated level.
struct InterpolatedContour {
  Polygon points;     ///< resampled to the requested spacing; outer counter-clockwise, hole clockwise
  bool is_hole = false;
  int parent = -1;    ///< for a hole, the index of the outer contour that encloses it
};

/// The contours of the interpolated level at t, ready for tiling: the level f = `iso` (zero_level), loops shorter than
/// three spacings dropped (with holes left without an enclosing outer), each resampled uniformly to
/// `spacing`, holes given their parents. When resampling makes contours cross or touch, the spacing is
/// halved (twice at most). nullopt when no valid level results.
[[nodiscard]] std::optional<std::vector<InterpolatedContour>> interpolate_contours(const DistancePair& fields, double t,
                                                                                   double spacing, double iso = 0.0);

}  // namespace contourmesh::detail
