// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/metrics.h>
#include <contourmesh/smooth/shapes.h>
#include <contourmesh/smooth/smoothing.h>

#include <gtest/gtest.h>

#include <numbers>

#include "smooth/test_meshes.h"

namespace contourmesh {
namespace {

const ScalarField unit_sphere_sdf = [](const Eigen::Vector3d& p) { return p.norm() - 1.0; };

SmoothingOptions options_for(SmoothingMethod method, int iterations = 20) {
  SmoothingOptions o;
  o.method = method;
  o.iterations = iterations;
  return o;
}

TEST(Smoothing, DefaultsAreThePaperSettings) {
  const SmoothingOptions o;
  EXPECT_EQ(o.iterations, 20);
  EXPECT_EQ(o.mu, -0.6732);
  EXPECT_EQ(o.beta, 0.03);
  EXPECT_EQ(o.boundary, BoundaryPolicy::Fixed);
  EXPECT_EQ(default_lambda(SmoothingMethod::Laplacian), 0.3);
  EXPECT_EQ(default_lambda(SmoothingMethod::Taubin), 0.6307);
  EXPECT_EQ(default_lambda(SmoothingMethod::MeanCurvatureFlow), 0.3);
  EXPECT_EQ(default_lambda(SmoothingMethod::MinDistFlow), 0.5);
}

TEST(Smoothing, MethodNamesRoundTrip) {
  for (SmoothingMethod m : all_smoothing_methods()) EXPECT_EQ(parse_smoothing_method(to_string(m)), m);
  EXPECT_EQ(all_smoothing_methods().size(), 7u);
  EXPECT_EQ(to_string(SmoothingMethod::FeaturePreserving), "paper");
  EXPECT_EQ(to_string(SmoothingMethod::CrossSlice), "cross-slice");
  EXPECT_THROW((void)parse_smoothing_method("bilateral"), InvalidInputError);
}

TEST(Smoothing, TheBaselineEntryPointRefusesTheOtherMethods) {
  const Mesh s = make_icosphere(1);
  for (SmoothingMethod m : {SmoothingMethod::FeaturePreserving, SmoothingMethod::CrossSlice}) {
    EXPECT_FALSE(is_baseline(m));
    EXPECT_THROW((void)smooth(s, options_for(m)), InvalidInputError) << to_string(m);
  }
}

TEST(Smoothing, LaplacianShrinksAnIcosphereMonotonically) {
  const Mesh s = make_icosphere(3);
  SmoothingOptions o = options_for(SmoothingMethod::Laplacian);
  std::vector<double> volumes{enclosed_volume(s)};
  o.on_iteration = [&](int, const Eigen::Matrix3Xd& p) { volumes.push_back(enclosed_volume(p, s.triangles)); };
  const Eigen::Matrix3Xd out = laplacian_smooth(s, build_adjacency(s), o);
  ASSERT_EQ(volumes.size(), 21u);
  for (std::size_t k = 1; k < volumes.size(); ++k) EXPECT_LT(volumes[k], volumes[k - 1]) << "iteration " << k;
  EXPECT_DOUBLE_EQ(volumes.back(), enclosed_volume(out, s.triangles));
  EXPECT_LT(volumes.back(), 0.99 * volumes.front());
}

TEST(Smoothing, TaubinKeepsVolumeWithinOnePercentWhileRemovingNoise) {
  Mesh s = make_icosphere(4);
  const double clean_volume = enclosed_volume(s);
  add_noise(s, {0.01, 3, NoiseDirection::Normal});
  const double noisy_volume = enclosed_volume(s);
  const DistanceStats before = distance_to_surface(s.positions, unit_sphere_sdf);
  const Eigen::Matrix3Xd out = taubin_smooth(s, build_adjacency(s), options_for(SmoothingMethod::Taubin));
  const DistanceStats after = distance_to_surface(out, unit_sphere_sdf);
  const double v = enclosed_volume(out, s.triangles);
  EXPECT_LT(std::abs(v - noisy_volume) / noisy_volume, 0.01);
  EXPECT_LT(std::abs(v - clean_volume) / clean_volume, 0.01);
  EXPECT_LT(after.rms, 0.5 * before.rms);
  // Laplacian with the same budget shrinks far more: the comparison that motivates Taubin.
  const Eigen::Matrix3Xd lap = laplacian_smooth(s, build_adjacency(s), options_for(SmoothingMethod::Laplacian));
  EXPECT_GT(std::abs(enclosed_volume(lap, s.triangles) - noisy_volume), 3.0 * std::abs(v - noisy_volume));
}

TEST(Smoothing, MeanCurvatureFlowShrinksASphereAtTheAnalyticRate) {
  // dv/dt = -2H n on a sphere: r(t)^2 = r0^2 - 4t.
  const Mesh s = make_icosphere(4, 1.0);
  SmoothingOptions o = options_for(SmoothingMethod::MeanCurvatureFlow, 250);
  o.time_step = TimeStep::Absolute;
  o.lambda = 2e-4;  // t = 0.05 after 250 steps
  std::vector<double> r2;
  o.on_iteration = [&](int, const Eigen::Matrix3Xd& p) { r2.push_back(p.colwise().squaredNorm().mean()); };
  (void)mean_curvature_flow(s, build_adjacency(s), o);
  ASSERT_EQ(r2.size(), 250u);
  for (int k : {49, 124, 249}) {
    const double t = (k + 1) * 2e-4;
    EXPECT_NEAR(r2[k], 1.0 - 4.0 * t, 0.01 * (1.0 - 4.0 * t)) << "at t = " << t;
  }
}

TEST(Smoothing, MeanCurvatureFlowRelativeStepMatchesLaplacianOnARegularFan) {
  Mesh fan = test::hexagon_fan(1.0);
  fan.positions(2, 0) = 0.05;
  const MeshAdjacency adj = build_adjacency(fan);
  SmoothingOptions o = options_for(SmoothingMethod::MeanCurvatureFlow, 1);
  const Eigen::Matrix3Xd mcf = mean_curvature_flow(fan, adj, o);
  o.method = SmoothingMethod::Laplacian;
  const Eigen::Matrix3Xd lap = laplacian_smooth(fan, adj, o);
  // Nearly planar, nearly equilateral: the two steps agree to first order.
  EXPECT_NEAR(mcf(2, 0), lap(2, 0), 0.05 * std::abs(0.05 - lap(2, 0)));
}

TEST(Smoothing, MinDistFlowLeavesAnExactCubeInItsPlanes) {
  const Mesh c = make_cube(6);
  const Eigen::Matrix3Xd out = min_dist_flow(c, build_adjacency(c), options_for(SmoothingMethod::MinDistFlow));
  for (Index i = 0; i < c.num_vertices(); ++i) {
    EXPECT_NEAR(out.col(i).cwiseAbs().maxCoeff(), 1.0, 1e-12) << "vertex " << i << " left the cube surface";
  }
}

TEST(Smoothing, MinDistFlowDenoisesACubeAndKeepsItsEdges) {
  Mesh c = make_cube(12);
  const Mesh clean = c;
  add_noise(c, {0.01, 5, NoiseDirection::Normal});
  const ScalarField cube_sdf = [](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q = p.cwiseAbs() - Eigen::Vector3d::Ones();
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
  };
  const DistanceStats before = distance_to_surface(c.positions, cube_sdf);
  const Eigen::Matrix3Xd md = min_dist_flow(c, build_adjacency(c), options_for(SmoothingMethod::MinDistFlow));
  const Eigen::Matrix3Xd tb = taubin_smooth(c, build_adjacency(c), options_for(SmoothingMethod::Taubin));
  const DistanceStats after = distance_to_surface(md, cube_sdf);
  EXPECT_LT(after.rms, 0.6 * before.rms);
  EXPECT_LT(after.rms, distance_to_surface(tb, cube_sdf).rms);  // Taubin rounds the edges and corners
}

TEST(Smoothing, LockedVerticesAndFixedBoundaryDoNotMove) {
  Mesh s = make_icosphere(2);
  add_noise(s, {0.05, 1, NoiseDirection::Isotropic});
  std::vector<std::uint8_t> locked(static_cast<std::size_t>(s.num_vertices()), 0);
  locked[0] = locked[7] = 1;
  for (auto method : {SmoothingMethod::Laplacian, SmoothingMethod::Taubin, SmoothingMethod::MeanCurvatureFlow,
                      SmoothingMethod::MinDistFlow}) {
    SmoothingOptions o = options_for(method);
    o.locked = locked;
    const Eigen::Matrix3Xd out = smooth(s, o);
    EXPECT_EQ(out.col(0), s.positions.col(0)) << to_string(method);
    EXPECT_EQ(out.col(7), s.positions.col(7)) << to_string(method);
    EXPECT_NE(out.col(1), s.positions.col(1)) << to_string(method);
  }
  Mesh fan = test::hexagon_fan();
  fan.positions(2, 0) = 0.4;
  for (auto method : {SmoothingMethod::Laplacian, SmoothingMethod::Taubin, SmoothingMethod::MeanCurvatureFlow,
                      SmoothingMethod::MinDistFlow}) {
    const Eigen::Matrix3Xd fixed = smooth(fan, options_for(method));
    for (Index i = 1; i <= 6; ++i) EXPECT_EQ(fixed.col(i), fan.positions.col(i)) << to_string(method);
    SmoothingOptions o = options_for(method);
    o.boundary = BoundaryPolicy::Free;
    const Eigen::Matrix3Xd free = smooth(fan, o);
    if (method == SmoothingMethod::Laplacian || method == SmoothingMethod::Taubin) {
      EXPECT_NE(free.col(1), fan.positions.col(1)) << to_string(method);
    }
  }
}

TEST(Smoothing, ProgressIsReportedAndCanCancel) {
  const Mesh s = make_icosphere(2);
  SmoothingOptions o = options_for(SmoothingMethod::Taubin, 10);
  std::vector<double> fractions;
  o.progress = [&](std::string_view stage, double f) {
    EXPECT_EQ(stage, "smooth");
    fractions.push_back(f);
    return true;
  };
  (void)smooth(s, o);
  ASSERT_EQ(fractions.size(), 10u);
  EXPECT_DOUBLE_EQ(fractions.back(), 1.0);
  for (auto method : {SmoothingMethod::Laplacian, SmoothingMethod::Taubin, SmoothingMethod::MeanCurvatureFlow,
                      SmoothingMethod::MinDistFlow}) {
    int calls = 0;
    o.method = method;
    o.progress = [&](std::string_view, double) { return ++calls < 3; };
    EXPECT_THROW((void)smooth(s, o), CancelledError) << to_string(method);
    EXPECT_EQ(calls, 3);
  }
}

TEST(Smoothing, OptionsOutOfRangeAreRejected) {
  const Mesh s = make_icosphere(1);
  auto rejects = [&](auto mutate) {
    SmoothingOptions o;
    mutate(o);
    EXPECT_THROW((void)smooth(s, o), InvalidInputError);
  };
  rejects([](SmoothingOptions& o) { o.iterations = -1; });
  rejects([](SmoothingOptions& o) { o.lambda = 1.5; });
  rejects([](SmoothingOptions& o) { o.lambda = 0.0; });
  rejects([](SmoothingOptions& o) { o.lambda = std::numeric_limits<double>::quiet_NaN(); });
  rejects([](SmoothingOptions& o) { o.mu = 0.2; });
  rejects([](SmoothingOptions& o) { o.beta = -1; });
  std::vector<std::uint8_t> short_mask(3, 0);
  rejects([&](SmoothingOptions& o) { o.locked = short_mask; });
}

TEST(Smoothing, NoneAndZeroIterationsReturnTheInput) {
  const Mesh s = make_icosphere(1);
  EXPECT_EQ(smooth(s, options_for(SmoothingMethod::None)), s.positions);
  EXPECT_EQ(smooth(s, options_for(SmoothingMethod::MinDistFlow, 0)), s.positions);
}

}  // namespace
}  // namespace contourmesh
