// SPDX-License-Identifier: BSD-3-Clause
// One contour to one contour: the least-area band, its quality, and twisted bands.
#include "detail/band_tiling.h"

#include <contourmesh/reconstruct/contours.h>
#include <contourmesh/reconstruct/segmentation.h>
#include <contourmesh/smooth/errors.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <string>

#include "reconstruct/detail/level_helpers.h"
#include "reconstruct/partial_volume.h"

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

TEST(BandTiling, LargeContoursAreSolvedCoarseToFineWhateverTheirSize) {
  // 2000 x 2000 point pairs, over full_dp_limit: the full grid needs 36 MB, the band of +/- 15 % around
  // the diagonal 11 MB, the coarse-to-fine corridor about 1 MB, which is what fits in 5 MB.
  const Polygon lower = circle_points(0, 0, 100, 2000), upper = circle_points(0.5, 0, 98, 2000);
  TilingOptions o;
  o.full_dp_limit = 1'000'000;
  o.limits.max_memory_bytes = 5'000'000;
  const std::vector<BandTriangle> band = minimum_area_band(lower, 0.0, upper, 2.0, o);
  EXPECT_EQ(band.size(), 4000u);
  // The corridor's own memory is checked before it is allocated.
  o.limits.max_memory_bytes = 600'000;
  try {
    (void)minimum_area_band(lower, 0.0, upper, 2.0, o);
    FAIL() << "no LimitError";
  } catch (const LimitError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("tiling: contours of 2000 and 2000 points: needs about ", 0), 0u) << what;
  }
}

TEST(BandTiling, ASmallContourAgainstALargeOneUsesTheDiagonalBandAboveTheLimit) {
  // 24 x 3000 point pairs: too few points on one side for the coarse grid. The full grid needs about
  // 0.65 MB, the band of +/- 15 % of the points around the diagonal about 0.2 MB.
  const Polygon lower = circle_points(0, 0, 100, 24), upper = circle_points(0, 0, 100, 3000);
  TilingOptions o;
  o.limits.max_memory_bytes = 400'000;
  try {
    (void)minimum_area_band(lower, 0.0, upper, 2.0, o);  // the full grid, under the default limit
    FAIL() << "no LimitError";
  } catch (const LimitError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("tiling: contours of 24 and 3000 points: needs about 675 kB", 0), 0u) << what;
  }
  o.full_dp_limit = 1000;
  const std::vector<BandTriangle> band = minimum_area_band(lower, 0.0, upper, 2.0, o);
  EXPECT_EQ(band.size(), 3024u);
  // Each lower edge spans the upper points of its arc: the band follows the diagonal.
  for (const BandTriangle& t : band) {
    if (t[0].ring == 0 && t[1].ring == 0) {
      EXPECT_NEAR(std::abs(t[2].index - t[0].index * 125 - 62.5), 0.0, 64.0) << t[0].index << " " << t[2].index;
    }
  }
}

// The least-area band by the textbook recurrence over the whole grid, triangle areas from Eigen
// (0.5 |(b - a) x (c - a)|), from the start pair lower[r0], upper[q0], with the tiler's rules (the path
// leaves the start edge along the lower ring and returns along the upper one; moving along the lower
// ring wins ties) and its listing of the triangles (from the end of the path).
std::vector<BandTriangle> reference_band(const Polygon& lower, double wl, const Polygon& upper, double wu, int r0,
                                         int q0, double span_weight) {
  const int m = static_cast<int>(lower.size()), n = static_cast<int>(upper.size());
  auto P = [&](int i) {
    const Eigen::Vector2d& p = lower[static_cast<std::size_t>((r0 + i) % m)];
    return Eigen::Vector3d(p.x(), p.y(), wl);
  };
  auto Q = [&](int j) {
    const Eigen::Vector2d& q = upper[static_cast<std::size_t>((q0 + j) % n)];
    return Eigen::Vector3d(q.x(), q.y(), wu);
  };
  auto area = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    return 0.5 * (b - a).cross(c - a).norm();
  };
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<std::vector<double>> cost(m + 1, std::vector<double>(n + 1, inf));
  std::vector<std::vector<int>> along_lower(m + 1, std::vector<int>(n + 1, 0));
  cost[0][0] = 0.0;
  for (int i = 0; i <= m; ++i) {
    for (int j = 0; j <= n; ++j) {
      if ((i == 0) || (i == m && j == 0) || (j == n && i < m)) continue;
      double c = inf;
      if (cost[i - 1][j] < inf) {
        c = cost[i - 1][j] + area(P(i - 1), P(i), Q(j));
        along_lower[i][j] = 1;
      }
      if (j > 0 && cost[i][j - 1] < inf) {
        const double c2 = cost[i][j - 1] + area(P(i), Q(j), Q(j - 1));
        if (c2 < c) {
          c = c2;
          along_lower[i][j] = 0;
        }
      }
      cost[i][j] = c + (span_weight > 0.0 && c < inf ? span_weight * (P(i) - Q(j)).squaredNorm() : 0.0);
    }
  }
  std::vector<BandTriangle> band;
  auto L = [&](int k) { return BandCorner{0, (r0 + k) % m}; };
  auto U = [&](int k) { return BandCorner{1, (q0 + k) % n}; };
  for (int i = m, j = n; i > 0 || j > 0;) {
    if (along_lower[i][j]) {
      band.push_back({L(i - 1), L(i), U(j)});
      --i;
    } else {
      band.push_back({L(i), U(j), U(j - 1)});
      --j;
    }
  }
  return band;
}

// A random star-shaped ring, counter-clockwise: concave where the wave is deep.
Polygon random_ring(std::mt19937& rng, int points) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double cx = 4.0 * u(rng) - 2.0, cy = 4.0 * u(rng) - 2.0, r = 10.0 + 10.0 * u(rng);
  const double depth = 0.5 * u(rng), lobes = std::floor(1.0 + 6.0 * u(rng)), phase = 6.0 * u(rng);
  Polygon ring;
  for (int k = 0; k < points; ++k) {
    const double t = 2.0 * std::numbers::pi * (k + 0.3 * u(rng)) / points;
    const double rr = r * (1.0 + depth * std::sin(lobes * t + phase) + 0.02 * u(rng));
    ring.emplace_back(cx + rr * std::cos(t), cy + rr * std::sin(t));
  }
  return ring;
}

TEST(BandTiling, TheProgrammeFindsTheBandOfTheTextbookRecurrence) {
  // The programme computes its triangle areas from the rings' planes (no call, constants per row);
  // the band must be the one the plain recurrence gives, triangle for triangle, on convex and
  // concave rings of every size the whole grid is solved for, with and without the span weight.
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> size(3, 250);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 60; ++trial) {
    const Polygon lower = random_ring(rng, size(rng)), upper = random_ring(rng, size(rng));
    const double wl = 4.0 * u(rng) - 2.0, wu = wl + 0.3 + 3.0 * u(rng);
    const int start = static_cast<int>(u(rng) * static_cast<double>(lower.size()));
    const double span_weight = trial % 3 == 0 ? 1.0 : 0.0;
    const std::vector<BandTriangle> band = minimum_area_band(lower, wl, upper, wu, TilingOptions{}, start, span_weight);
    ASSERT_FALSE(band.empty());
    // The start pair: the corners of the start edge in the first triangle listed.
    const bool first_along_lower = band[0][1].ring == 0;
    const int r0 = first_along_lower ? band[0][1].index : band[0][0].index;
    const int q0 = first_along_lower ? band[0][2].index : band[0][1].index;
    EXPECT_EQ(r0, start);
    const std::vector<BandTriangle> expected = reference_band(lower, wl, upper, wu, r0, q0, span_weight);
    ASSERT_EQ(band.size(), expected.size()) << "trial " << trial;
    for (std::size_t t = 0; t < band.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(band[t][k].ring, expected[t][k].ring) << "trial " << trial << " triangle " << t;
        ASSERT_EQ(band[t][k].index, expected[t][k].index) << "trial " << trial << " triangle " << t;
      }
    }
  }
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

TEST(BandTiling, CongruentContoursAreJoinedStraightAcross) {
  // A cylinder's contour as segmentation traces it through 0.5 mm pixels (353 points, with straight
  // stretches along the pixel rows and diagonals), and the same contour on the next slice. Along such
  // stretches many ways across have the least area to rounding; the band must not drift along the ring
  // into fans of slivers (which sent such a slab to be halved: a cavity's floor then ended nearly a slice
  // spacing low instead of half of one).
  const auto image = test::partial_volume({130, 130, 3}, {0.5, 0.5, 1.5}, [](const Eigen::Vector3d& p) {
    return std::hypot(p.x() - 32.0, p.y() - 32.0) - 28.0;
  });
  SegmentationOptions so;
  so.threshold = 500.0;
  const Polygon ring = segment_contours(*image, so).stack.slices[1].contours[0].points;
  ASSERT_GT(ring.size(), 300u);
  double longest = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i)
    longest = std::max(longest, (ring[(i + 1) % ring.size()] - ring[i]).norm());
  const double spacing = perimeter(ring) / static_cast<double>(ring.size());
  const std::vector<BandTriangle> band = untwisted_band(ring, 0.0, ring, 1.5, TilingOptions{}, spacing);
  const BandQuality q = band_quality(ring, 0.0, ring, 1.5, band);
  EXPECT_EQ(q.sliver_share(), 0.0);
  EXPECT_LE(q.longest_cross_edge, std::hypot(longest, 1.5) + 1e-9) << "an edge across skips one point at most";
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
