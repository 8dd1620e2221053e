// SPDX-License-Identifier: BSD-3-Clause
// The signed distance fields and the marching-squares levels of shape-based interpolation.
#include "detail/shape_interpolation.h"

#include <contourmesh/reconstruct/contours.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "reconstruct/detail/level_helpers.h"

namespace contourmesh::detail {
namespace {

using test::arc_points;
using test::circle_points;

TEST(ShapeInterpolation, DistancesOfASquareAreExactAndSigned) {
  const Polygon square = {{-5, -5}, {5, -5}, {5, 5}, {-5, 5}};
  const DistancePair g = signed_distance_pair({square}, {}, 0.25);
  ASSERT_GT(g.nx, 40);
  ASSERT_GT(g.ny, 40);
  for (int j = 0; j < g.ny; j += 3) {
    for (int i = 0; i < g.nx; i += 3) {
      const Eigen::Vector2d p = g.origin + g.h * Eigen::Vector2d(i, j);
      const Eigen::Vector2d q = p.cwiseAbs() - Eigen::Vector2d(5, 5);
      const double truth = q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);  // box distance
      EXPECT_NEAR(g.lower[static_cast<std::size_t>(j) * g.nx + i], truth, 1e-9) << p.transpose();
    }
  }
  // An empty region is far outside everywhere.
  EXPECT_GT(*std::min_element(g.upper.begin(), g.upper.end()), 1e6);
}

TEST(ShapeInterpolation, ConcentricCirclesGiveTheCircleInBetween) {
  // d_lower = |x| - 10, d_upper = |x| - 4: the level at t is the circle of radius 10 - 6 t.
  const DistancePair g = signed_distance_pair({circle_points(0, 0, 10, 200)}, {circle_points(0, 0, 4, 80)}, 0.25);
  for (const double t : {0.25, 0.5, 0.75}) {
    const std::vector<Polygon> loops = zero_level(g, t);
    ASSERT_EQ(loops.size(), 1u) << t;
    EXPECT_GT(signed_area(loops[0]), 0.0) << "outer boundaries run counter-clockwise";
    for (const Eigen::Vector2d& p : loops[0]) EXPECT_NEAR(p.norm(), 10.0 - 6.0 * t, 0.02) << t;
  }
}

TEST(ShapeInterpolation, AHoleClosesWhereTheBlendTurnsNegative) {
  // Lower: annulus 5 < |x| < 10; upper: the full disc of radius 10. In the hole, d_lower = 5 - |x| and
  // d_upper = |x| - 10: the hole's radius at t is (5 - 15 t) / (1 - 2 t), while positive.
  const DistancePair g = signed_distance_pair({circle_points(0, 0, 10, 200), circle_points(0, 0, 5, 100, true)},
                                              {circle_points(0, 0, 10, 200)}, 0.2);
  const auto level = interpolate_contours(g, 0.2, 0.5);
  ASSERT_TRUE(level);
  ASSERT_EQ(level->size(), 2u);
  const InterpolatedContour& hole = (*level)[0].is_hole ? (*level)[0] : (*level)[1];
  const InterpolatedContour& outer = (*level)[0].is_hole ? (*level)[1] : (*level)[0];
  EXPECT_TRUE(hole.is_hole);
  EXPECT_EQ(hole.parent, &outer - level->data());
  EXPECT_LT(signed_area(hole.points), 0.0) << "holes run clockwise";
  const double radius = (5.0 - 15.0 * 0.2) / (1.0 - 2.0 * 0.2);
  for (const Eigen::Vector2d& p : hole.points) EXPECT_NEAR(p.norm(), radius, 0.05);
  // At t = 0.4 the blend is negative everywhere inside the outer circle: the hole has closed.
  const auto closed = interpolate_contours(g, 0.4, 0.5);
  ASSERT_TRUE(closed);
  EXPECT_EQ(closed->size(), 1u);
}

TEST(ShapeInterpolation, OneDiscSplitsIntoTwoBetweenTheSlices) {
  const DistancePair g = signed_distance_pair({circle_points(0, 0, 10, 200)},
                                              {circle_points(-7, 0, 4, 80), circle_points(7, 0, 4, 80)}, 0.25);
  EXPECT_EQ(zero_level(g, 0.2).size(), 1u);
  EXPECT_EQ(zero_level(g, 0.9).size(), 2u);
  // Every level is a set of simple, disjoint polygons, resampled to the spacing asked.
  for (int k = 1; k < 10; ++k) {
    const auto level = interpolate_contours(g, k / 10.0, 0.7);
    ASSERT_TRUE(level) << k;
    std::vector<Polygon> polygons;
    for (const InterpolatedContour& c : *level) {
      EXPECT_FALSE(find_self_intersection(c.points));
      EXPECT_NEAR(perimeter(c.points) / static_cast<double>(c.points.size()), 0.7, 0.05);
      polygons.push_back(c.points);
    }
    EXPECT_FALSE(find_polygon_crossing(polygons));
  }
}

TEST(ShapeInterpolation, AWindowInAWallClosesGradually) {
  // Two arcs with windows between them below a full annulus (the orbits of a skull): the window at the
  // middle of the wall closes before the slice that has none, and the closed level is an annulus.
  const DistancePair g = signed_distance_pair(
      {arc_points(0.3, 3.14159 - 0.3, 8, 12, 40), arc_points(3.14159 + 0.3, 2 * 3.14159 - 0.3, 8, 12, 40)},
      {circle_points(0, 0, 12, 120), circle_points(0, 0, 8, 80, true)}, 0.2);
  EXPECT_EQ(zero_level(g, 0.1).size(), 2u);
  const auto closed = interpolate_contours(g, 0.95, 0.7);
  ASSERT_TRUE(closed);
  ASSERT_EQ(closed->size(), 2u);
  EXPECT_NE((*closed)[0].is_hole, (*closed)[1].is_hole);
}

TEST(ShapeInterpolation, LoopsShorterThanThreeSpacingsAreDropped) {
  // A disc shrinking from radius 2 to 0.5: its level at t has radius 2 - 1.5 t.
  const DistancePair g = signed_distance_pair({circle_points(0, 0, 2, 30)}, {circle_points(0, 0, 0.5, 12)}, 0.05);
  const auto early = interpolate_contours(g, 0.1, 2.0);  // perimeter 11.6 mm: kept
  ASSERT_TRUE(early);
  EXPECT_EQ(early->size(), 1u);
  const auto late = interpolate_contours(g, 0.9, 2.0);  // perimeter 4.1 mm: dropped
  ASSERT_TRUE(late);
  EXPECT_TRUE(late->empty());
  EXPECT_TRUE(zero_level(DistancePair{}, 0.5).empty());
}

// A small blob below an elongated contour (the end of a drawn scar): the zero level of the averaged
// distances is short, since the elongated contour's ends are far from the blob, and loses a quarter of
// the area between the slices; the level of level_for_area has the area asked.
TEST(ShapeInterpolation, TheLevelForAnAreaRestoresTheAreaBetweenDifferentShapes) {
  Polygon ellipse;
  for (int k = 0; k < 120; ++k) {
    const double a = 2.0 * 3.14159265358979 * k / 120.0;
    ellipse.emplace_back(2.0 * std::cos(a), 7.0 * std::sin(a));
  }
  const Polygon blob = circle_points(0, 0, 1.7, 40);
  const DistancePair g = signed_distance_pair({blob}, {ellipse}, 0.1);
  const double target = 0.5 * (signed_area(blob) + signed_area(ellipse));
  auto area_of = [&](const std::vector<Polygon>& loops) {
    double a = 0.0;
    for (const Polygon& p : loops) a += signed_area(p);
    return a;
  };
  EXPECT_LT(area_of(zero_level(g, 0.5)), 0.85 * target) << "the zero level loses area";
  const double iso = level_for_area(g, 0.5, target);
  EXPECT_GT(iso, 0.0);
  EXPECT_NEAR(area_of(zero_level(g, 0.5, iso)), target, 1e-3 * target);
  const auto level = interpolate_contours(g, 0.5, 0.5, iso);
  ASSERT_TRUE(level);
  ASSERT_EQ(level->size(), 1u);
  EXPECT_NEAR(signed_area((*level)[0].points), target, 0.02 * target);
  // Concentric circles: the zero level at t has radius 10 - 6 t; the level for a smaller area lies
  // inside it, with the area asked.
  const DistancePair c = signed_distance_pair({circle_points(0, 0, 10, 200)}, {circle_points(0, 0, 4, 80)}, 0.25);
  const double small = 0.8 * 3.14159265358979 * 7.0 * 7.0;
  const double inside = level_for_area(c, 0.5, small);
  EXPECT_LT(inside, 0.0);
  EXPECT_NEAR(area_of(zero_level(c, 0.5, inside)), small, 1e-3 * small);
  EXPECT_EQ(level_for_area(DistancePair{}, 0.5, 1.0), 0.0);
}

// level_area reads the area of zero_level's polygons off the cells without building them. Random fields
// on a small grid make many saddle cells (both ways) and loops with holes; every level must agree with the
// polygons' own area, whatever its sign.
TEST(ShapeInterpolation, TheLevelAreaIsTheAreaOfTheLevelsPolygons) {
  DistancePair g;
  g.origin = Eigen::Vector2d(-3.0, 2.0);
  g.h = 0.7;
  g.nx = 23;
  g.ny = 17;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const std::size_t count = static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny);
  for (std::size_t k = 0; k < count; ++k) {
    const int i = static_cast<int>(k % static_cast<std::size_t>(g.nx)), j = static_cast<int>(k / g.nx);
    const bool border = i < 2 || j < 2 || i >= g.nx - 2 || j >= g.ny - 2;  // outside, as a real grid's margin
    g.lower.push_back(border ? 5.0 : value(rng));
    g.upper.push_back(border ? 5.0 : value(rng) + 0.2);
  }
  int saddles = 0;
  for (std::size_t k = 0; k + g.nx + 1 < count; ++k) {
    const double a = g.lower[k], b = g.lower[k + 1], c = g.lower[k + g.nx + 1], d = g.lower[k + g.nx];
    saddles += ((a < 0) == (c < 0)) && ((b < 0) == (d < 0)) && ((a < 0) != (b < 0));
  }
  ASSERT_GT(saddles, 20) << "the field must hold saddle cells";
  for (const double t : {0.0, 0.3, 0.5, 1.0}) {
    for (const double level : {-0.4, -0.1, 0.0, 0.15, 0.5}) {
      double polygons = 0.0;
      for (const Polygon& p : zero_level(g, t, level)) polygons += signed_area(p);
      EXPECT_NEAR(level_area(g, t, level), polygons, 1e-9 * (1.0 + std::abs(polygons))) << t << " " << level;
    }
  }
  EXPECT_EQ(level_area(DistancePair{}, 0.5), 0.0);
}

}  // namespace
}  // namespace contourmesh::detail
