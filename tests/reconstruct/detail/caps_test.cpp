// SPDX-License-Identifier: BSD-3-Clause
// Caps on ending contours.
#include "detail/caps.h"

#include <contourmesh/smooth/mesh_quality.h>

#include <gtest/gtest.h>

#include <numbers>

#include "reconstruct/detail/level_helpers.h"

namespace contourmesh::detail {
namespace {

using test::circle_points;

double faces_area(const SlabMesh& m, FaceRole role, double* z_min = nullptr, double* z_max = nullptr) {
  double area = 0.0;
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    if (m.roles[f] != role) continue;
    const Triangle& t = m.triangles[f];
    const Eigen::Vector3d a = m.position(t[0]), b = m.position(t[1]), c = m.position(t[2]);
    area += 0.5 * (b - a).cross(c - a).norm();
    for (const Eigen::Vector3d* p : {&a, &b, &c}) {
      if (z_min) *z_min = std::min(*z_min, p->z());
      if (z_max) *z_max = std::max(*z_max, p->z());
    }
  }
  return area;
}

TEST(Caps, AnEndIsExtendedAndCappedWithItsHoles) {
  test::TestStack stack;
  const LevelContour outer = stack.contour(circle_points(0, 0, 20, 180), 4.0);
  const LevelContour hole = stack.contour(circle_points(6, 0, 5, 45, true), 4.0, true, 0);
  SlabMesh out = stack.slab();
  cap_end(outer, {&hole}, 4.0, 1.0, true, TilingOptions{}, out);
  EXPECT_EQ(out.stats.caps, 1u);
  double lo = 1e9, hi = -1e9;
  const double cap = faces_area(out, FaceRole::Cap, &lo, &hi);
  EXPECT_DOUBLE_EQ(lo, 5.0);  // half a spacing (given: 1 mm) above the slice
  EXPECT_DOUBLE_EQ(hi, 5.0);
  const double polygon =
      0.5 * 180 * 400 * std::sin(2 * std::numbers::pi / 180) - 0.5 * 45 * 25 * std::sin(2 * std::numbers::pi / 45);
  EXPECT_NEAR(cap, polygon, 1e-6 * polygon);
  for (std::size_t f = 0; f < out.triangles.size(); ++f) {
    const Triangle& t = out.triangles[f];
    const Eigen::Vector3d a = out.position(t[0]), b = out.position(t[1]), c = out.position(t[2]);
    if (out.roles[f] == FaceRole::Cap) {
      EXPECT_GT((b - a).cross(c - a).z(), 0.0) << "an upward end faces up";
      EXPECT_GT(minimum_angle_degrees(a, b, c), 15.0) << "refined: no slivers";
    }
  }
}

TEST(Caps, AHoleEndFacesIntoTheCavity) {
  test::TestStack stack;
  const LevelContour hole = stack.contour(circle_points(0, 0, 5, 40, true), 2.0, true, 0);
  SlabMesh out = stack.slab();
  cap_hole_end(hole, 2.0, 0.0, true, TilingOptions{}, out);  // the cavity ends going up: its roof
  ASSERT_FALSE(out.triangles.empty());
  for (const Triangle& t : out.triangles) {
    const Eigen::Vector3d n = (out.position(t[1]) - out.position(t[0])).cross(out.position(t[2]) - out.position(t[0]));
    EXPECT_LT(n.z(), 0.0) << "the roof faces down, into the cavity";
  }
}

TEST(Caps, PlanarFillsTakeTheirRole) {
  test::TestStack stack;
  const LevelContour outer = stack.contour(circle_points(0, 0, 10, 60), 0.0);
  SlabMesh out = stack.slab();
  fill_planar(outer, {}, 0.0, false, FaceRole::Bridge, TilingOptions{}, out);
  EXPECT_EQ(out.stats.caps, 0u);
  EXPECT_GT(faces_area(out, FaceRole::Bridge), 0.0);
  EXPECT_EQ(faces_area(out, FaceRole::Cap), 0.0);
}

}  // namespace
}  // namespace contourmesh::detail
