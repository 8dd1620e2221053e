#include <reconstruct/contours.h>
#include <smooth/errors.h>

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

}  // namespace
}  // namespace contourmesh
