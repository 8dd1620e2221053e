// SPDX-License-Identifier: BSD-3-Clause
// One contour to one contour: the least-area band, its quality, and twisted bands.
#include "detail/band_tiling.h"

#include <contourmesh/reconstruct/contours.h>

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "reconstruct/detail/level_helpers.h"

namespace contourmesh::detail {
namespace {

using test::arc_points;
using test::circle_points;

Eigen::Vector3d corner(const Polygon& lower, double wl, const Polygon& upper, double wu, const BandCorner& c) {
  const Eigen::Vector2d& p =
      c.ring == 0 ? lower[static_cast<std::size_t>(c.index)] : upper[static_cast<std::size_t>(c.index)];
  return {p.x(), p.y(), c.ring == 0 ? wl : wu};
}

TEST(BandTiling, ABandUsesEveryContourEdgeOnceAndFacesOutward) {
  const Polygon lower = circle_points(0, 0, 10, 60), upper = circle_points(1, 0.5, 8, 45);
  const std::vector<BandTriangle> band = minimum_area_band(lower, 0.0, upper, 2.0, TilingOptions{});
  EXPECT_EQ(band.size(), 60u + 45u);
  std::map<std::pair<int, int>, int> edges;  // (ring, first point) of each contour edge used
  for (const BandTriangle& t : band) {
    for (int k = 0; k < 3; ++k) {
      const BandCorner& a = t[k];
      const BandCorner& b = t[(k + 1) % 3];
      if (a.ring == b.ring) ++edges[{a.ring, a.ring == 0 ? a.index : b.index}];
    }
    const Eigen::Vector3d p = corner(lower, 0, upper, 2, t[0]), q = corner(lower, 0, upper, 2, t[1]),
                          r = corner(lower, 0, upper, 2, t[2]);
    const Eigen::Vector3d normal = (q - p).cross(r - p);
    const Eigen::Vector3d centre = (p + q + r) / 3.0;
    EXPECT_GT(normal.head<2>().dot(centre.head<2>() - Eigen::Vector2d(0.5, 0.25)), 0.0) << "outward";
  }
  EXPECT_EQ(edges.size(), 60u + 45u);
  for (const auto& [edge, count] : edges) EXPECT_EQ(count, 1) << edge.first << " " << edge.second;
}

TEST(BandTiling, LargeContoursSolvedCoarseToFineKeepTheLeastArea) {
  // 600 x 540 point pairs: solved on every 3rd point first, then in a corridor. The band between two
  // coaxial circles is the frustum's side: its area is pi (r1 + r2) slant, less the chords' deficit.
  const Polygon lower = circle_points(0, 0, 50, 600), upper = circle_points(0, 0, 45, 540);
  const std::vector<BandTriangle> band = minimum_area_band(lower, 0.0, upper, 2.0, TilingOptions{});
  const BandQuality q = band_quality(lower, 0.0, upper, 2.0, band);
  const double frustum = std::numbers::pi * (50.0 + 45.0) * std::hypot(5.0, 2.0);
  EXPECT_NEAR(q.area / frustum, 1.0, 2e-3);
  EXPECT_EQ(band.size(), 600u + 540u);
}

TEST(BandTiling, QualityCountsSliversOfAFlatBand) {
  // Concentric circles 6 mm apart in the plane and 0.5 mm apart across: long thin faces.
  const Polygon lower = circle_points(0, 0, 16, 140), upper = circle_points(0, 0, 10, 90);
  const BandQuality flat =
      band_quality(lower, 0.0, upper, 0.5, minimum_area_band(lower, 0.0, upper, 0.5, TilingOptions{}));
  EXPECT_GT(flat.sliver_share(), 0.3);
  EXPECT_NEAR(flat.longest_cross_edge, std::hypot(6.0, 0.5), 0.5);
  // A cylinder's band has no slivers.
  const Polygon ring = circle_points(0, 0, 10, 90);
  const BandQuality steep =
      band_quality(ring, 0.0, ring, 1.0, minimum_area_band(ring, 0.0, ring, 1.0, TilingOptions{}));
  EXPECT_EQ(steep.sliver_share(), 0.0);
}

TEST(BandTiling, ContourDistanceIsTheHausdorffDistanceOfThePoints) {
  EXPECT_NEAR(contour_distance(circle_points(0, 0, 10, 360), circle_points(0, 0, 7, 360)), 3.0, 1e-9);
  EXPECT_NEAR(contour_distance(circle_points(0, 0, 10, 360), circle_points(2, 0, 10, 360)), 2.0, 0.01);
}

TEST(BandTiling, SlitsAtDifferentPlacesOfAThinWallTwistTheBand) {
  // A ring wall with a narrow slit, the slit a quarter turn on in the next slice: both are one outer
  // contour, but every band between them crosses the wall's inside.
  const Polygon a = arc_points(0.05, 2 * std::numbers::pi - 0.05, 18, 20, 120);
  const Polygon b =
      arc_points(std::numbers::pi / 2 + 0.05, std::numbers::pi / 2 + 2 * std::numbers::pi - 0.05, 18, 20, 120);
  const double spacing = perimeter(a) / static_cast<double>(a.size());
  const BandQuality q = band_quality(a, 0.0, b, 1.0, minimum_area_band(a, 0.0, b, 1.0, TilingOptions{}));
  EXPECT_TRUE(band_is_twisted(a, 0.0, b, 1.0, q, spacing)) << q.longest_cross_edge;
  bool twisted = false;
  (void)untwisted_band(a, 0.0, b, 1.0, TilingOptions{}, spacing, &twisted);
  EXPECT_TRUE(twisted) << "no start untwists it: it is a change of topology";
  // The same slit in both slices is an ordinary band.
  const BandQuality same = band_quality(a, 0.0, a, 1.0, minimum_area_band(a, 0.0, a, 1.0, TilingOptions{}));
  EXPECT_FALSE(band_is_twisted(a, 0.0, a, 1.0, same, spacing));
}

TEST(BandTiling, ACrackNarrowerThanTheSpacingIsTiledSideBySide) {
  // A closed crack whose two sides are 0.2 mm apart, points 1 mm apart: the least area alone cannot tell
  // the sides apart (fanning across the crack costs nothing) and may join one side of the lower crack
  // to the far side of the upper one, 40 mm away. The retries find the band along the crack.
  auto crack = [](double shift) {
    Polygon p;
    for (int k = 0; k <= 40; ++k) p.emplace_back(k, shift);        // one side, left to right
    for (int k = 40; k >= 0; --k) p.emplace_back(k, shift + 0.2);  // the other side, back
    return p;
  };
  const Polygon lower = crack(0.0), upper = crack(0.15);
  bool twisted = true;
  const std::vector<BandTriangle> band = untwisted_band(lower, 0.0, upper, 1.0, TilingOptions{}, 1.0, &twisted);
  EXPECT_FALSE(twisted);
  EXPECT_LT(band_quality(lower, 0.0, upper, 1.0, band).longest_cross_edge, 2.0);
}

TEST(BandTiling, CopyBandsJoinAContourToItsCopy) {
  test::TestStack stack;
  const LevelContour c = stack.contour(circle_points(0, 0, 5, 20), 0.0);
  SlabMesh out = stack.slab();
  const LevelContour copy = copy_contour(c, 1.0, out);
  EXPECT_EQ(out.vertices.size(), 20u);
  EXPECT_TRUE(is_local(copy.ids[0]));
  emit_copy_band(c.ids, copy.ids, out);
  EXPECT_EQ(out.triangles.size(), 40u);
  for (const Triangle& t : out.triangles) {
    const Eigen::Vector3d n = (out.position(t[1]) - out.position(t[0])).cross(out.position(t[2]) - out.position(t[0]));
    EXPECT_NEAR(n.z(), 0.0, 1e-12);  // vertical
  }
}

}  // namespace
}  // namespace contourmesh::detail
