// SPDX-License-Identifier: BSD-3-Clause
// Private: tiling one contour to one contour of an adjacent level (a band), and judging the band.
#pragma once

#include "detail/tiling_types.h"

#include <array>
#include <cstdint>
#include <vector>

namespace contourmesh::detail {

/// A corner of a band triangle: point `index` of the lower (ring 0) or upper (ring 1) contour.
struct BandCorner {
  std::uint8_t ring = 0;
  int index = 0;
};
using BandTriangle = std::array<BandCorner, 3>;

/// Fuchs-Kedem-Uselton: the band of least total triangle area between `lower` (on plane wl) and `upper`
/// (on plane wu > wl), both with the same orientation, by dynamic programming over the m x n grid of
/// point pairs, starting at lower[lower_start] and its nearest upper point where the upper contour runs
/// the same way. With `span_weight` > 0, each edge across adds span_weight times its squared length
/// to the cost. Over 90 000 pairs with both rings of 32 points or more: coarse to fine (the programme on
/// every k-th point, then the full rings in a corridor around its path); otherwise the full grid while
/// m * n is at most options.full_dp_limit, else a band of +/- options.band_fraction of the points around
/// the arc-length diagonal. The path leaves the start edge along one ring and returns along the other, so the start
/// edge is the only one used twice and the band is an annulus. Triangles are oriented so that, for
/// counter-clockwise rings, normals point away from the enclosed region. Throws LimitError when the
/// programme would exceed options.limits' memory budget.
[[nodiscard]] std::vector<BandTriangle> minimum_area_band(const Polygon& lower, double wl, const Polygon& upper,
                                                          double wu, const TilingOptions& options,
                                                          int lower_start = 0, double span_weight = 0.0);

/// The least-area band (where it has slivers between contours less than the gap apart, nearly congruent,
/// its ties broken by the shorter edges across: span weight 1e-4); when it is twisted (band_is_twisted),
/// also from starts a quarter, half and three quarters round (ties broken the same way) and with
/// span_weight 1: the untwisted one of least area, else the one with the shortest longest edge across
/// (`twisted` then says so).
[[nodiscard]] std::vector<BandTriangle> untwisted_band(const Polygon& lower, double wl, const Polygon& upper,
                                                       double wu, const TilingOptions& options, double spacing,
                                                       bool* twisted = nullptr);

/// How well shaped a band is.
struct BandQuality {
  double area = 0.0;
  double sliver_area = 0.0;        ///< area of triangles whose smallest angle is under 10 degrees
  double longest_cross_edge = 0.0;  ///< longest edge joining the two contours (3-D, mm)
  [[nodiscard]] double sliver_share() const { return area > 0.0 ? sliver_area / area : 0.0; }
};
/// `shear`: the band is judged at (u, v) + shear * w (SlabMesh::shear).
[[nodiscard]] BandQuality band_quality(const Polygon& lower, double wl, const Polygon& upper, double wu,
                                       const std::vector<BandTriangle>& band,
                                       const Eigen::Vector2d& shear = Eigen::Vector2d::Zero());

/// Hausdorff distance between the point sets of two contours (2-D, mm): how far apart the curves are
/// at worst. Exact for the points, with the early break of Taha and Hanbury (2015).
[[nodiscard]] double contour_distance(const Polygon& a, const Polygon& b);

/// True when the band joins its contours across far more than they are apart: its longest edge across
/// is over twice the 3-D distance the curves are apart (contour_distance and the planes' gap) plus two
/// contour spacings. Two slits of a thin wall at different places, for example, make the least-area band
/// cross the wall's inside. Such a pair is a change of topology in disguise (a hole closes and opens
/// again).
[[nodiscard]] bool band_is_twisted(const Polygon& lower, double wl, const Polygon& upper, double wu,
                                   const BandQuality& quality, double spacing);

/// Adds the band's triangles between two level contours to `out` (role Band).
void emit_band(const LevelContour& lower, const LevelContour& upper, const std::vector<BandTriangle>& band,
               SlabMesh& out);

/// A straight band between a contour and its copy on another plane (same points, same order): two
/// triangles per edge. `lower` lies below `upper`.
void emit_copy_band(const std::vector<VertexRef>& lower, const std::vector<VertexRef>& upper, SlabMesh& out);

/// A copy of `c` on plane w: the same points, new local vertices.
[[nodiscard]] LevelContour copy_contour(const LevelContour& c, double w, SlabMesh& out);

}  // namespace contourmesh::detail
