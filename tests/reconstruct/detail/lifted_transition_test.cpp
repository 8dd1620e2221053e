// SPDX-License-Identifier: BSD-3-Clause
// The lifted triangulation between levels whose contours do not cross.
#include "detail/lifted_transition.h"

#include "detail/caps.h"

#include <contourmesh/smooth/mesh_quality.h>
#include <contourmesh/smooth/metrics.h>

#include <gtest/gtest.h>

#include "reconstruct/detail/level_helpers.h"
#include "reconstruct/mesh_checks.h"

namespace contourmesh::detail {
namespace {

using test::circle_points;

TEST(LiftedTransition, AShrinkingDiscIsAWellShapedSlope) {
  // A disc of radius 10 below one of radius 2, 1 mm above: a nearly flat slope. The least-area band
  // would fan 60 points into 12; the lifted fill has no slivers and rises with the distance from the rim.
  test::TestStack stack;
  const Level lower{0.0, {stack.contour(circle_points(0, 0, 10, 60), 0.0)}};
  const Level upper{1.0, {stack.contour(circle_points(0, 0, 2, 12), 1.0)}};
  SlabMesh slope = stack.slab();
  ASSERT_TRUE(lifted_transition(lower, upper, slope));
  EXPECT_GT(slope.vertices.size(), 50u) << "interior vertices about a spacing apart";
  for (const Eigen::Vector3d& v : slope.vertices) {
    const double r = v.head<2>().norm();
    EXPECT_NEAR(v.z(), (10.0 - r) / 8.0, 0.15) << r;  // relative distance to the two circles
  }
  const TilingDefects d = measure_defects(slope);
  EXPECT_LT(d.sliver_area, 0.01 * d.area);
  // Closed by the two caps it is a sphere-like surface facing out.
  SlabMesh below = stack.slab(), above = stack.slab();
  cap_end(lower.contours[0], {}, 0.0, 0.0, false, TilingOptions{}, below);
  cap_end(upper.contours[0], {}, 1.0, 0.0, true, TilingOptions{}, above);
  const Mesh mesh = stack.assemble({&below, &slope, &above});
  const test::Topology t = test::topology_of(mesh);
  EXPECT_TRUE(t.closed && t.manifold) << t.problems;
  EXPECT_EQ(t.euler, 2);
  EXPECT_GT(enclosed_volume(mesh), 0.0);
}

TEST(LiftedTransition, SmallContoursInsideAnAnnulusFaceUpBetweenThem) {
  // A ring below, two small discs standing on its wall above.
  test::TestStack stack;
  const Level lower{
      0.0,
      {stack.contour(circle_points(0, 0, 12, 80), 0.0), stack.contour(circle_points(0, 0, 6, 40, true), 0.0, true, 0)}};
  const Level upper{
      1.0, {stack.contour(circle_points(9, 0, 1.5, 12), 1.0), stack.contour(circle_points(-9, 0, 1.5, 12), 1.0)}};
  SlabMesh fill = stack.slab();
  ASSERT_TRUE(lifted_transition(lower, upper, fill));
  for (const Triangle& t : fill.triangles) {
    const Eigen::Vector3d n =
        (fill.position(t[1]) - fill.position(t[0])).cross(fill.position(t[2]) - fill.position(t[0]));
    EXPECT_GT(n.z(), 0.0) << "material below, nothing above";
  }
}

TEST(LiftedTransition, FillsOnBothSidesOfALevelShareNoEdgeInItsPlane) {
  // A disc, two small discs side by side inside it, the disc again (fuzz_tiling's seed_one_to_two): the
  // fills below and above the middle level would both join the two small discs across their 0.4 mm gap,
  // the same edge in the middle plane used by four faces. Such edges are split off the plane.
  test::TestStack stack;
  const Level bottom{0.0, {stack.contour(circle_points(0, 0, 10, 12), 0.0)}};
  const Level middle{
      2.0, {stack.contour(circle_points(-3.75, 0, 3.5, 12), 2.0), stack.contour(circle_points(3.75, 0, 3.5, 12), 2.0)}};
  const Level top{4.0, {stack.contour(circle_points(0, 0, 10, 12), 4.0)}};
  SlabMesh below = stack.slab(), lower = stack.slab(), upper = stack.slab(), above = stack.slab();
  ASSERT_TRUE(lifted_transition(bottom, middle, lower));
  ASSERT_TRUE(lifted_transition(middle, top, upper));
  cap_end(bottom.contours[0], {}, 0.0, 0.0, false, TilingOptions{}, below);
  cap_end(top.contours[0], {}, 4.0, 0.0, true, TilingOptions{}, above);
  const test::Topology t = test::topology_of(stack.assemble({&below, &lower, &upper, &above}));
  EXPECT_TRUE(t.closed && t.manifold) << t.problems;
}

TEST(LiftedTransition, CrossingContoursOrAnEndAreLeftToTheOthers) {
  test::TestStack stack;
  const Level lower{0.0, {stack.contour(circle_points(0, 0, 5, 30), 0.0)}};
  const Level crossing{1.0, {stack.contour(circle_points(4, 0, 5, 30), 1.0)}};
  SlabMesh out = stack.slab();
  EXPECT_FALSE(lifted_transition(lower, crossing, out));
  // A second lower disc with nothing above it: its face is bounded by one level only.
  const Level two{0.0,
                  {stack.contour(circle_points(0, 0, 5, 30), 0.0), stack.contour(circle_points(20, 0, 5, 30), 0.0)}};
  const Level one{1.0, {stack.contour(circle_points(0, 0, 2, 12), 1.0)}};
  EXPECT_FALSE(lifted_transition(two, one, out));
  EXPECT_TRUE(out.triangles.empty());
  EXPECT_TRUE(out.vertices.empty());
}

}  // namespace
}  // namespace contourmesh::detail
