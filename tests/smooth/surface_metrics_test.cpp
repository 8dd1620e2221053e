// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/surface_metrics.h"
#include "contourmesh/smooth/closest_point.h"
#include "contourmesh/smooth/errors.h"
#include "contourmesh/smooth/shapes.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <memory>
#include <numbers>

namespace contourmesh {
namespace {

using std::numbers::pi;

ScalarField sphere_sdf(double r) {
  return [r](const Eigen::Vector3d& p) { return p.norm() - r; };
}
VectorField radial() {
  return [](const Eigen::Vector3d& p) { return Eigen::Vector3d(p.normalized()); };
}

// An axis-aligned box of half size `half` whose edges and corners are rounded with radius `round`.
ScalarField rounded_box_sdf(double half, double round) {
  return [=](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q = p.cwiseAbs() - Eigen::Vector3d::Constant(half - round);
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0) - round;
  };
}
VectorField numeric_normal(const ScalarField& f) {
  return [f](const Eigen::Vector3d& p) {
    constexpr double h = 1e-5;
    Eigen::Vector3d g;
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(a);
      g[a] = (f(p + e) - f(p - e)) / (2 * h);
    }
    return Eigen::Vector3d(g.normalized());
  };
}

SurfaceTruth sphere_truth(double r) {
  SurfaceTruth t;
  t.distance = sphere_sdf(r);
  t.normal = radial();
  t.samples = sample_implicit_surface(
      t.distance, t.normal, Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-r - 1), Eigen::Vector3d::Constant(r + 1)),
      0.25);
  return t;
}

TEST(SurfaceSampling, MeshSamplesWeighTheFaceArea) {
  const Mesh cube = make_cube(3, 2.0);  // area 6 * 16 = 96
  const SurfaceSamples s = sample_mesh_surface(cube.positions, cube.triangles, 50.0, 1);
  EXPECT_NEAR(s.area(), 96.0, 96.0 * 0.02);
  for (Index k = 0; k < s.size(); ++k) EXPECT_LE(s.points.col(k).cwiseAbs().maxCoeff(), 2.0 + 1e-12);
}

TEST(SurfaceSampling, MeshSamplesAreReproducible) {
  const Mesh cube = make_cube(2, 1.0);
  const SurfaceSamples a = sample_mesh_surface(cube.positions, cube.triangles, 20.0, 5);
  const SurfaceSamples b = sample_mesh_surface(cube.positions, cube.triangles, 20.0, 5);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.points, b.points);
}

TEST(SurfaceSampling, ImplicitSamplesWeighTheSphereArea) {
  const SurfaceTruth t = sphere_truth(10.0);
  EXPECT_NEAR(t.samples.area(), 4.0 * pi * 100.0, 4.0 * pi * 100.0 * 0.01);
  for (Index k = 0; k < t.samples.size(); ++k) EXPECT_NEAR(t.samples.points.col(k).norm(), 10.0, 1e-6);
}

TEST(SurfaceSampling, BadDensityIsRefused) {
  const Mesh cube = make_cube(1, 1.0);
  EXPECT_THROW((void)sample_mesh_surface(cube.positions, cube.triangles, 0.0), InvalidInputError);
}

TEST(SurfaceAccuracy, OffsetSphereIsAtTheOffsetOnBothSides) {
  // A fine sphere of radius 10.5 against the true sphere of radius 10.
  const Mesh mesh = make_icosphere(6, 10.5);
  const SurfaceAccuracy a = surface_accuracy(mesh, sphere_truth(10.0));
  EXPECT_NEAR(a.all.mesh_to_truth_rms, 0.5, 0.01);
  EXPECT_NEAR(a.all.truth_to_mesh_rms, 0.5, 0.01);
  EXPECT_NEAR(a.all.rms, 0.5, 0.01);
  EXPECT_NEAR(a.all.hausdorff, 0.5, 0.01);
  EXPECT_NEAR(a.all.mean_signed, 0.5, 0.01);  // outside: positive
  EXPECT_LT(a.all.normal_error_degrees, 0.5);
  EXPECT_NEAR(a.vertex_rms, 0.5, 1e-9);  // icosphere vertices lie exactly on radius 10.5
}

TEST(SurfaceAccuracy, ChordsOfACoarseSphereShowOnlyBetweenTheVertices) {
  // The vertices of a coarse icosphere lie on the truth; its faces cut inside it.
  const Mesh mesh = make_icosphere(2, 10.0);
  const SurfaceAccuracy a = surface_accuracy(mesh, sphere_truth(10.0));
  EXPECT_NEAR(a.vertex_rms, 0.0, 1e-9);
  EXPECT_GT(a.all.rms, 0.1);
  EXPECT_LT(a.all.mean_signed, -0.1);  // chords lie inside
}

TEST(SurfaceAccuracy, CubeAgainstRoundedCubeHasTheCornerGapAsHausdorff) {
  // A sharp cube of half size 10 against the same cube rounded with radius 1: the farthest mesh
  // point is a corner, sqrt(3) - 1 from the rounded corner; the farthest truth point is the middle of
  // a rounded corner, 1 - 1/sqrt(3) from the cube's faces.
  const double half = 10.0, round = 1.0;
  const Mesh mesh = make_cube(20, half);
  SurfaceTruth t;
  t.distance = rounded_box_sdf(half, round);
  t.normal = numeric_normal(t.distance);
  t.samples = sample_implicit_surface(
      t.distance, t.normal, Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-11), Eigen::Vector3d::Constant(11)), 0.2);
  const SurfaceAccuracy a = surface_accuracy(mesh, t, {.density = 20.0});
  EXPECT_NEAR(a.all.mesh_to_truth_max, (std::sqrt(3.0) - 1.0) * round, 0.01);
  // The truth's maximum is found among its samples (0.2 mm grid): from below, within a few hundredths.
  EXPECT_NEAR(a.all.truth_to_mesh_max, (1.0 - 1.0 / std::sqrt(3.0)) * round, 0.04);
  EXPECT_LE(a.all.truth_to_mesh_max, (1.0 - 1.0 / std::sqrt(3.0)) * round + 1e-6);
  EXPECT_NEAR(a.all.hausdorff, (std::sqrt(3.0) - 1.0) * round, 0.01);
  // Along an edge, away from the corners, the mesh side integrates (sqrt(u^2 + 1) - 1)^2 over u in
  // [0, 1] on each of the edge's two faces: about 0.0294 per unit of edge length and face.
  EXPECT_GT(a.all.rms, 0.03);
  EXPECT_LT(a.all.rms, 0.2);
}

TEST(SurfaceAccuracy, FeatureRegionIsTheBandAlongTheFeatures) {
  // The truth's features: the 12 edges of a cube of half size 10, sampled densely. Within 1.5 mm of
  // them lies a band of area 6 * (20^2 - 17^2) on the cube.
  const double half = 10.0;
  const Mesh mesh = make_cube(10, half);
  std::vector<Eigen::Vector3d> feature;
  for (int axis = 0; axis < 3; ++axis) {
    for (double s : {-half, half}) {
      for (double t : {-half, half}) {
        for (double u = -half; u <= half + 1e-9; u += 0.05) {
          Eigen::Vector3d p;
          p[axis] = u;
          p[(axis + 1) % 3] = s;
          p[(axis + 2) % 3] = t;
          feature.push_back(p);
        }
      }
    }
  }
  Eigen::Matrix3Xd points(3, static_cast<Index>(feature.size()));
  for (std::size_t k = 0; k < feature.size(); ++k) points.col(static_cast<Index>(k)) = feature[k];
  auto locator = std::make_shared<PointLocator>(points);
  SurfaceTruth t;
  t.distance = [half](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q = p.cwiseAbs() - Eigen::Vector3d::Constant(half);
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
  };
  t.normal = numeric_normal(t.distance);
  t.samples = sample_mesh_surface(mesh.positions, mesh.triangles, 10.0, 99);
  t.feature_distance = [locator](const Eigen::Vector3d& p) { return locator->distance(p); };
  const SurfaceAccuracy a = surface_accuracy(mesh, t, {.density = 10.0, .seed = 1, .feature_radius = 1.5});
  const double band = 6.0 * (400.0 - 289.0);
  EXPECT_NEAR(a.feature.mesh_area, band, band * 0.03);
  EXPECT_NEAR(a.smooth.mesh_area, 6.0 * 289.0, 6.0 * 289.0 * 0.03);
  EXPECT_NEAR(a.all.rms, 0.0, 1e-9);
}

TEST(SurfaceAccuracy, NormalErrorIsAreaWeightedAngle) {
  // The truth's normal field is the sphere's turned by 5 degrees about x: a normal at angle theta from
  // the x axis turns by about 5 sin(theta) degrees, whose mean over the sphere is 5 pi / 4.
  const Mesh mesh = make_icosphere(5, 10.0);
  SurfaceTruth t = sphere_truth(10.0);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(5.0 * pi / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  t.normal = [turn](const Eigen::Vector3d& p) { return Eigen::Vector3d(turn * p.normalized()); };
  const SurfaceAccuracy a = surface_accuracy(mesh, t);
  EXPECT_NEAR(a.all.normal_error_degrees, 5.0 * pi / 4.0, 0.1);
}

TEST(SurfaceAccuracy, TruthWithoutSamplesIsRefused) {
  SurfaceTruth t;
  t.distance = sphere_sdf(1.0);
  EXPECT_THROW((void)surface_accuracy(make_icosphere(1), t), InvalidInputError);
}

}  // namespace
}  // namespace contourmesh
