// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/metrics.h>
#include <contourmesh/smooth/shapes.h>

#include <gtest/gtest.h>

#include <numbers>

namespace contourmesh {
namespace {

TEST(Metrics, IcosphereVolumeAndAreaWithinPointOnePercent) {
  const double r = 3.0;
  const Mesh s = make_icosphere(6, r, {5, 5, 5});  // off the origin on purpose
  EXPECT_NEAR(enclosed_volume(s) / (4.0 / 3.0 * std::numbers::pi * r * r * r), 1.0, 1e-3);
  EXPECT_NEAR(surface_area(s) / (4.0 * std::numbers::pi * r * r), 1.0, 1e-3);
}

TEST(Metrics, CubeVolumeAndAreaAreExact) {
  const Mesh c = make_cube(3, 1.5);
  EXPECT_NEAR(enclosed_volume(c), 27.0, 27.0 * 1e-12);
  EXPECT_NEAR(surface_area(c), 6 * 9.0, 1e-12);
}

TEST(Metrics, ReversedOrientationGivesNegativeVolume) {
  Mesh c = make_cube(2);
  for (Triangle& t : c.triangles) std::swap(t[1], t[2]);
  EXPECT_NEAR(enclosed_volume(c), -8.0, 1e-12);
}

TEST(Metrics, VolumeShrinkingRateDefinition) {
  EXPECT_DOUBLE_EQ(volume_shrinking_rate(10.0, 9.0), 0.1);
  EXPECT_DOUBLE_EQ(volume_shrinking_rate(10.0, 11.0), -0.1);
  EXPECT_THROW((void)volume_shrinking_rate(0.0, 1.0), InvalidInputError);
}

TEST(Metrics, LaplacianShrinkingCurveStartsAtZeroAndGrows) {
  const Mesh s = make_icosphere(3);
  SmoothingOptions o;
  o.method = SmoothingMethod::Laplacian;
  o.iterations = 10;
  int observed = 0;
  o.on_iteration = [&](int, const Eigen::Matrix3Xd&) { ++observed; };
  const std::vector<double> curve = volume_shrinking_curve(s, o);
  ASSERT_EQ(curve.size(), 11u);
  EXPECT_EQ(curve[0], 0.0);
  EXPECT_EQ(observed, 10);  // the caller's observer still runs
  for (std::size_t k = 1; k < curve.size(); ++k) EXPECT_GT(curve[k], curve[k - 1]);
  o.method = SmoothingMethod::None;
  const auto flat = volume_shrinking_curve(s, o);
  ASSERT_EQ(flat.size(), 11u);
  for (double v : flat) EXPECT_EQ(v, 0.0);
}

TEST(Metrics, DistanceToSurfaceOverAllAndASubset) {
  Mesh s = make_icosphere(2, 1.0);
  const ScalarField sdf = [](const Eigen::Vector3d& p) { return p.norm() - 1.0; };
  const DistanceStats exact = distance_to_surface(s.positions, sdf);
  EXPECT_LT(exact.max, 1e-12);
  EXPECT_EQ(exact.count, static_cast<std::size_t>(s.num_vertices()));
  s.positions.col(0) *= 1.3;  // 0.3 out
  s.positions.col(1) *= 0.6;  // 0.4 in
  const DistanceStats all = distance_to_surface(s.positions, sdf);
  EXPECT_NEAR(all.max, 0.4, 1e-12);
  EXPECT_NEAR(all.mean, 0.7 / s.num_vertices(), 1e-12);
  EXPECT_NEAR(all.rms, std::sqrt(0.25 / s.num_vertices()), 1e-12);
  const std::vector<Index> subset = {0, 1};
  const DistanceStats two = distance_to_surface(s.positions, sdf, subset);
  EXPECT_EQ(two.count, 2u);
  EXPECT_NEAR(two.mean, 0.35, 1e-12);
  EXPECT_NEAR(two.rms, std::sqrt((0.09 + 0.16) / 2), 1e-12);
  const std::vector<Index> bad = {s.num_vertices()};
  EXPECT_THROW((void)distance_to_surface(s.positions, sdf, bad), InvalidInputError);
}

TEST(Metrics, NormalAngularErrorAgainstAnalyticNormals) {
  const Mesh c = make_cube(4);
  const VectorField cube_normal = [](const Eigen::Vector3d& p) {
    Eigen::Index axis;
    p.cwiseAbs().maxCoeff(&axis);
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    n[axis] = p[axis] > 0 ? 1.0 : -1.0;
    return n;
  };
  const AngleStats cube = normal_angular_error(c.positions, c.triangles, cube_normal);
  EXPECT_LT(cube.max_degrees, 1e-6);
  EXPECT_EQ(cube.count, static_cast<std::size_t>(c.num_faces()));

  const Mesh s = make_icosphere(4);
  const VectorField radial = [](const Eigen::Vector3d& p) { return Eigen::Vector3d(p.normalized()); };
  const AngleStats sphere = normal_angular_error(s.positions, s.triangles, radial);
  EXPECT_LT(sphere.mean_degrees, 1.0);
  // Flipped normals are 180 degrees off.
  const VectorField inward = [](const Eigen::Vector3d& p) { return Eigen::Vector3d(-p.normalized()); };
  const std::vector<Index> first = {0, 1, 2};
  EXPECT_GT(normal_angular_error(s.positions, s.triangles, inward, first).mean_degrees, 179.0);
}

}  // namespace
}  // namespace contourmesh
