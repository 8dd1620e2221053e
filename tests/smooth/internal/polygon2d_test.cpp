// SPDX-License-Identifier: BSD-3-Clause
// The shared 2-D polygon module against closed-form values.
#include "contourmesh/internal/polygon2d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace contourmesh::detail {
namespace {

// 4 x 2 rectangle, counter-clockwise, with a collinear extra vertex on the bottom edge.
const Polygon kRectangle = {{0, 0}, {2, 0}, {4, 0}, {4, 2}, {0, 2}};

TEST(Polygon2d, SignedAreaIsPositiveCounterClockwise) {
  EXPECT_DOUBLE_EQ(polygon_signed_area(kRectangle), 8.0);
  const Polygon reversed(kRectangle.rbegin(), kRectangle.rend());
  EXPECT_DOUBLE_EQ(polygon_signed_area(reversed), -8.0);
}

TEST(Polygon2d, ContainsByTheEvenOddRule) {
  EXPECT_TRUE(polygon_contains(kRectangle, {1, 1}));
  EXPECT_TRUE(polygon_contains(kRectangle, {2, 1}));  // the ray passes through no vertex's level
  EXPECT_FALSE(polygon_contains(kRectangle, {5, 1}));
  EXPECT_FALSE(polygon_contains(kRectangle, {1, 3}));
}

TEST(Polygon2d, SignedDistanceIsExactInsideAndOutside) {
  EXPECT_DOUBLE_EQ(polygon_signed_distance(kRectangle, {1, 1}), -1.0);
  EXPECT_DOUBLE_EQ(polygon_signed_distance(kRectangle, {3.5, 1}), -0.5);
  EXPECT_DOUBLE_EQ(polygon_signed_distance(kRectangle, {6, 1}), 2.0);
  EXPECT_DOUBLE_EQ(polygon_signed_distance(kRectangle, {7, 6}), 5.0);  // nearest: the corner (4, 2)
  const Polygon reversed(kRectangle.rbegin(), kRectangle.rend());
  EXPECT_DOUBLE_EQ(polygon_signed_distance(reversed, {1, 1}), -1.0);  // orientation does not matter
}

TEST(Polygon2d, EarClippingCoversTheAreaWithCounterClockwiseTriangles) {
  // An L shape (reflex corner at (2, 2)).
  const Polygon l = {{0, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 4}, {0, 4}};
  const auto triangles = triangulate_polygon(l);
  ASSERT_EQ(triangles.size(), l.size() - 2);
  double area = 0.0;
  for (const auto& t : triangles) {
    const double a = polygon_signed_area({l[t[0]], l[t[1]], l[t[2]]});
    EXPECT_GT(a, 0.0);
    area += a;
  }
  EXPECT_DOUBLE_EQ(area, polygon_signed_area(l));
}

TEST(Polygon2d, TriangulationWithAHoleLeavesTheHoleOut) {
  const Polygon outer = {{0, 0}, {6, 0}, {6, 6}, {0, 6}};
  const Polygon hole = {{2, 2}, {2, 4}, {4, 4}, {4, 2}};  // clockwise
  const auto triangles = triangulate_with_holes(outer, {hole});
  double area = 0.0;
  for (const auto& t : triangles) {
    Polygon corners;
    for (const PolygonVertex& v : t) corners.push_back(v.polygon == 0 ? outer[v.vertex] : hole[v.vertex]);
    area += polygon_signed_area(corners);
  }
  EXPECT_NEAR(area, 36.0 - 4.0, 1e-12);
}

// A jagged ring of 1 200 points (every other one reflex, as on a noisy segmentation) around two square
// holes: the ear tests look only at the nodes near each ear, so a large ring is where a missed blocker
// would show, as a triangle over another vertex or area counted twice.
TEST(Polygon2d, TriangulationOfALargeJaggedRingWithHolesIsExact) {
  Polygon outer;
  constexpr int kPoints = 1200;
  for (int k = 0; k < kPoints; ++k) {
    const double angle = 2.0 * M_PI * k / kPoints;
    const double radius = 50.0 + (k % 2 == 0 ? 1.5 : -1.5) + 4.0 * std::sin(5.0 * angle);
    outer.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
  }
  const Polygon left = {{-20, -5}, {-20, 5}, {-10, 5}, {-10, -5}};  // clockwise
  const Polygon right = {{10, -5}, {10, 5}, {20, 5}, {20, -5}};
  const std::vector<Polygon> holes = {left, right};
  const auto triangles = triangulate_with_holes(outer, holes);
  ASSERT_EQ(triangles.size(), outer.size() + left.size() + right.size() + 2 * holes.size() - 2);
  const auto point = [&](const PolygonVertex& v) {
    return v.polygon == 0 ? outer[v.vertex] : holes[v.polygon - 1][v.vertex];
  };
  std::vector<Eigen::Vector2d> all(outer.begin(), outer.end());
  for (const Polygon& hole : holes) all.insert(all.end(), hole.begin(), hole.end());
  double area = 0.0;
  for (const auto& t : triangles) {
    const Eigen::Vector2d a = point(t[0]), b = point(t[1]), c = point(t[2]);
    const double signed_area = polygon_signed_area({a, b, c});
    ASSERT_GT(signed_area, 0.0);
    area += signed_area;
    const auto side = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
      return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
    };
    for (const Eigen::Vector2d& p : all) {  // no vertex strictly inside a triangle
      ASSERT_FALSE(side(a, b, p) > 0.0 && side(b, c, p) > 0.0 && side(c, a, p) > 0.0);
    }
  }
  EXPECT_NEAR(area, polygon_signed_area(outer) - 200.0, 1e-9 * polygon_signed_area(outer));
}

TEST(Polygon2d, OverlapAreaOfTwoShiftedSquares) {
  const Polygon a = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  const Polygon b = {{1, 0}, {3, 0}, {3, 2}, {1, 2}};
  EXPECT_NEAR(overlap_area(a, b), 2.0, 2.0 / 128);
}

}  // namespace
}  // namespace contourmesh::detail
