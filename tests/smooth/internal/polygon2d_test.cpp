// SPDX-License-Identifier: BSD-3-Clause
// The shared 2-D polygon module against closed-form values.
#include "contourmesh/internal/polygon2d.h"

#include <gtest/gtest.h>

#include <cmath>

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

TEST(Polygon2d, OverlapAreaOfTwoShiftedSquares) {
  const Polygon a = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  const Polygon b = {{1, 0}, {3, 0}, {3, 2}, {1, 2}};
  EXPECT_NEAR(overlap_area(a, b), 2.0, 2.0 / 128);
}

}  // namespace
}  // namespace contourmesh::detail
