// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/reconstruct/contours.h>
#include <contourmesh/smooth/errors.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace contourmesh {
namespace {

std::vector<Eigen::Vector2d> square(double s) { return {{0, 0}, {s, 0}, {s, s}, {0, s}}; }

TEST(Contours, AreaPerimeterAndInside) {
  const auto sq = square(2.0);
  EXPECT_DOUBLE_EQ(signed_area(sq), 4.0);
  auto cw = sq;
  std::reverse(cw.begin(), cw.end());
  EXPECT_DOUBLE_EQ(signed_area(cw), -4.0);
  EXPECT_DOUBLE_EQ(perimeter(sq), 8.0);
  EXPECT_TRUE(point_in_polygon(sq, {1, 1}));
  EXPECT_FALSE(point_in_polygon(sq, {3, 1}));
}

TEST(Contours, ResamplingIsUniformAndKeepsTheShape) {
  std::vector<Eigen::Vector2d> circle;
  for (int k = 0; k < 500; ++k) {
    const double a = 2 * std::numbers::pi * k / 500;
    circle.emplace_back(10 * std::cos(a), 10 * std::sin(a));
  }
  const auto r = resample_closed(circle, 0.5);
  EXPECT_EQ(r.size(), static_cast<std::size_t>(std::round(perimeter(circle) / 0.5)));
  for (std::size_t i = 0; i < r.size(); ++i) {
    EXPECT_NEAR(r[i].norm(), 10.0, 2e-3);
    EXPECT_NEAR((r[(i + 1) % r.size()] - r[i]).norm(), 0.5, 0.01);
  }
  EXPECT_EQ(resample_closed(square(1.0), 10.0).size(), 3u);  // never fewer than 3 points
  EXPECT_THROW((void)resample_closed(square(1.0), 0.0), InvalidInputError);
}

TEST(Contours, SelfIntersectionsAreFoundWithTheirEdges) {
  EXPECT_FALSE(find_self_intersection(square(2.0)));
  // A figure of eight: edges 1 (2,0)-(0,2) and 3 (2,2)-(0,0) cross at (1, 1).
  const std::vector<Eigen::Vector2d> eight = {{0, 0}, {2, 0}, {0, 2}, {2, 2}};
  const auto x = find_self_intersection(eight);
  ASSERT_TRUE(x);
  EXPECT_EQ(x->first, 1u);
  EXPECT_EQ(x->second, 3u);
  EXPECT_TRUE(x->where.isApprox(Eigen::Vector2d(1, 1)));
  // A vertex touching a non-adjacent edge, and a repeated point.
  EXPECT_TRUE(find_self_intersection({{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}}));
  EXPECT_TRUE(find_self_intersection({{0, 0}, {4, 0}, {2, 2}, {4, 4}, {0, 4}, {2, 2}}));
  // A triangle cannot intersect itself; a thin spike that doubles back along itself does.
  EXPECT_FALSE(find_self_intersection({{0, 0}, {1, 0}, {0, 1}}));
  EXPECT_TRUE(find_self_intersection({{0, 0}, {4, 0}, {4, 1}, {1, 1}, {5, 1}, {5, 3}, {0, 3}}));
}

TEST(Contours, CrossingsBetweenPolygonsAreFoundWithTheirEdges) {
  auto shifted = [](std::vector<Eigen::Vector2d> p, double dx, double dy) {
    for (auto& v : p) v += Eigen::Vector2d(dx, dy);
    return p;
  };
  // Disjoint, and nested without touching: no crossing.
  EXPECT_FALSE(find_polygon_crossing({square(2.0), shifted(square(2.0), 5, 0)}));
  EXPECT_FALSE(find_polygon_crossing({square(4.0), shifted(square(1.0), 1, 1)}));
  // Overlapping squares: edge 0 (0,0)-(2,0) ... the first crossing in (polygon, edge) order is edge 1 of
  // the first, (2,0)-(2,2), with edge 0 of the second, (1,1)-(3,1), at (2, 1).
  const auto x = find_polygon_crossing({square(2.0), shifted(square(2.0), 1, 1)});
  ASSERT_TRUE(x);
  EXPECT_EQ(x->first, 0u);
  EXPECT_EQ(x->first_edge, 1u);
  EXPECT_EQ(x->second, 1u);
  EXPECT_EQ(x->second_edge, 0u);
  EXPECT_TRUE(x->where.isApprox(Eigen::Vector2d(2, 1)));
  // Touching at a corner counts; self-intersections of one polygon do not.
  EXPECT_TRUE(find_polygon_crossing({square(2.0), shifted(square(2.0), 2, 2)}));
  EXPECT_FALSE(find_polygon_crossing({{{0, 0}, {2, 0}, {0, 2}, {2, 2}}}));
  // The third polygon crosses the first: polygons are named by their index in the set.
  const auto y = find_polygon_crossing({square(2.0), shifted(square(2.0), 10, 0), shifted(square(2.0), -1, 0.5)});
  ASSERT_TRUE(y);
  EXPECT_EQ(y->first, 0u);
  EXPECT_EQ(y->second, 2u);
}

TEST(Contours, SelfIntersectionSearchIsFastOnLargeContours) {
  std::vector<Eigen::Vector2d> circle;
  const int n = 200'000;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * std::numbers::pi * k / n;
    circle.emplace_back(100 * std::cos(a), 100 * std::sin(a));
  }
  EXPECT_FALSE(find_self_intersection(circle));  // quadratic would take minutes
  std::swap(circle[1000], circle[1001]);          // a bow tie in a long contour
  const auto x = find_self_intersection(circle);
  ASSERT_TRUE(x);
  EXPECT_EQ(x->first, 999u);
  EXPECT_EQ(x->second, 1001u);
}

}  // namespace
}  // namespace contourmesh
