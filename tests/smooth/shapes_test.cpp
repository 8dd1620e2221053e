// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/metrics.h>
#include <contourmesh/smooth/shapes.h>
#include <contourmesh/smooth/validation.h>

#include <gtest/gtest.h>

#include <numbers>

namespace contourmesh {
namespace {

TEST(Shapes, IcosphereHasTheExpectedSizeAndLiesOnTheSphere) {
  const Eigen::Vector3d c(1, -2, 3);
  const Mesh s = make_icosphere(3, 2.5, c);
  EXPECT_EQ(s.num_vertices(), 10 * 64 + 2);
  EXPECT_EQ(s.num_faces(), 20 * 64);
  for (Index i = 0; i < s.num_vertices(); ++i) EXPECT_NEAR((s.positions.col(i) - c).norm(), 2.5, 1e-12);
  EXPECT_TRUE(find_mesh_problems(s).empty());
  EXPECT_GT(enclosed_volume(s), 0.0);
}

TEST(Shapes, CubeIsClosedOutwardAndOnItsFaces) {
  const Mesh c = make_cube(5, 2.0);
  EXPECT_EQ(c.num_vertices(), 6 * 25 + 2);
  EXPECT_TRUE(find_mesh_problems(c).empty());
  EXPECT_TRUE(build_adjacency(c).is_closed());
  for (Index i = 0; i < c.num_vertices(); ++i) EXPECT_NEAR(c.positions.col(i).cwiseAbs().maxCoeff(), 2.0, 1e-12);
}

TEST(Shapes, ContourStackIsAClosedOutwardPrismWithIds) {
  ContourStackSpec spec;
  spec.curve = ridge_circle_curve(10.0, 3.0, 0.5);
  spec.slices = 8;
  spec.points_per_contour = 200;
  spec.slice_spacing = 1.5;
  spec.end_caps = EndCaps::AtEndSlice;
  const Mesh m = make_contour_stack(spec);
  EXPECT_TRUE(find_mesh_problems(m).empty());
  EXPECT_TRUE(build_adjacency(m).is_closed());
  ASSERT_TRUE(m.has_contour_ids());
  EXPECT_EQ(m.num_vertices(), 8 * 200);
  for (Index i = 0; i < m.num_vertices(); ++i) {
    EXPECT_EQ(m.slice_ids[i], i / 200);
    EXPECT_DOUBLE_EQ(m.positions(2, i), 1.5 * (i / 200));
  }
  // Cap triangles join vertices of one slice; side triangles span two adjacent slices.
  for (const Triangle& t : m.triangles) {
    const int lo = std::min({m.slice_ids[t[0]], m.slice_ids[t[1]], m.slice_ids[t[2]]});
    const int hi = std::max({m.slice_ids[t[0]], m.slice_ids[t[1]], m.slice_ids[t[2]]});
    EXPECT_LE(hi - lo, 1);
  }
  // Volume = polygon area x height; the polygon is the sampled curve.
  double area = 0.0;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector2d a = spec.curve(i / 200.0), b = spec.curve((i + 1) / 200.0);
    area += 0.5 * (a.x() * b.y() - a.y() * b.x());
  }
  EXPECT_NEAR(enclosed_volume(m), area * 1.5 * 7, 1e-9 * area);
  // Half-spacing ends (the default): two copies, kNoId, and half a spacing more at each end.
  spec.end_caps = EndCaps::HalfSpacing;
  const Mesh h = make_contour_stack(spec);
  EXPECT_TRUE(find_mesh_problems(h).empty());
  EXPECT_TRUE(build_adjacency(h).is_closed());
  EXPECT_EQ(h.num_vertices(), 10 * 200);
  for (Index i = 8 * 200; i < h.num_vertices(); ++i) EXPECT_EQ(h.slice_ids[i], kNoId);
  EXPECT_NEAR(enclosed_volume(h), area * 1.5 * 8, 1e-9 * area);
}

TEST(Shapes, ContourStackSdfIsZeroOnTheSamplesAndSignedCorrectly) {
  ContourStackSpec spec;
  spec.curve = ridge_circle_curve(10.0, 3.0, 0.5);
  spec.slices = 5;
  spec.points_per_contour = 64;
  const Mesh m = make_contour_stack(spec);
  const ScalarField sdf = contour_stack_sdf(spec);
  for (Index i = 0; i < m.num_vertices(); ++i) EXPECT_NEAR(sdf(m.positions.col(i)), 0.0, 1e-3);
  // Slices at z = 0 .. 8; the sampled prism extends half a spacing further: z = -1 .. 9.
  EXPECT_NEAR(sdf({0, 0, 4}), -5.0, 1e-9);       // closest: the end caps
  EXPECT_NEAR(sdf({0, -10, 4}), 0.0, 1e-3);      // on the side
  EXPECT_NEAR(sdf({0, -12, 4}), 2.0, 1e-3);      // 2 outside the side
  EXPECT_NEAR(sdf({13, 0, 4}), 0.0, 1e-3);       // ridge tip
  EXPECT_NEAR(sdf({0, -12, 12}), std::hypot(2.0, 3.0), 1e-3);  // beyond an edge of the top cap
  spec.end_caps = EndCaps::AtEndSlice;
  EXPECT_NEAR(contour_stack_sdf(spec)({0, 0, 4}), -4.0, 1e-9);
}

TEST(Shapes, NoiseIsReproducibleAndInPlaneNoiseKeepsSlices) {
  ContourStackSpec spec;
  spec.curve = ridge_circle_curve(10.0, 3.0, 0.5);
  Mesh a = make_contour_stack(spec), b = make_contour_stack(spec);
  const Mesh clean = a;
  add_noise(a, {0.2, 42, NoiseDirection::InPlane});
  add_noise(b, {0.2, 42, NoiseDirection::InPlane});
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.positions.row(2), clean.positions.row(2));
  const double rms = std::sqrt((a.positions - clean.positions).squaredNorm() / a.num_vertices());
  EXPECT_NEAR(rms, 0.2 * std::sqrt(2.0), 0.02);
}

}  // namespace
}  // namespace contourmesh
