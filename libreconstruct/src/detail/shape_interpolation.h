// Private: shape-based interpolation between the regions of two adjacent contour levels (Raya and
// Udupa 1990; Herman, Zheng and Bucholtz 1992). Each level's region (outer contours minus holes) is
// turned into a signed distance field on a common 2-D grid; the region between them at a fraction t is
// the set where (1 - t) d_lower + t d_upper < 0, and its boundary is extracted with marching squares.
#pragma once

#include "detail/polygon.h"

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

/// The zero level of f = (1 - t) lower + t upper as closed polygons, inside (f < 0) on the left: outer
/// boundaries counter-clockwise, holes clockwise. Sub-cell accurate (linear interpolation along the
/// grid edges); a saddle cell is resolved by the mean of its corners. The polygons are simple and
/// disjoint. Nodes where f is exactly 0 count as outside.
[[nodiscard]] std::vector<Polygon> zero_level(const DistancePair& fields, double t);

/// One contour of an interpolated level.
struct InterpolatedContour {
  Polygon points;     ///< resampled to the requested spacing; outer counter-clockwise, hole clockwise
  bool is_hole = false;
  int parent = -1;    ///< for a hole, the index of the outer contour that encloses it
};

/// The contours of the interpolated level at t, ready for tiling: the zero level, loops shorter than
/// three spacings dropped (with holes left without an enclosing outer), each resampled uniformly to
/// `spacing`, holes given their parents. When resampling makes contours cross or touch, the spacing is
/// halved (twice at most). nullopt when no valid level results.
[[nodiscard]] std::optional<std::vector<InterpolatedContour>> interpolate_contours(const DistancePair& fields, double t,
                                                                                   double spacing);

}  // namespace contourmesh::detail
