// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/closest_point.h"
#include "contourmesh/smooth/errors.h"
#include "contourmesh/smooth/shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace contourmesh {
namespace {

// Brute force: the nearest point over every face.
double brute_force(const Mesh& mesh, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Triangle& t : mesh.triangles) {
    const Eigen::Vector3d q =
        closest_point_on_triangle(p, mesh.positions.col(t[0]), mesh.positions.col(t[1]), mesh.positions.col(t[2]));
    best = std::min(best, (q - p).norm());
  }
  return best;
}

TEST(ClosestPoint, TriangleRegionsAreExact) {
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  EXPECT_TRUE(closest_point_on_triangle({0.5, 0.5, 3.0}, a, b, c).isApprox(Eigen::Vector3d(0.5, 0.5, 0)));  // face
  EXPECT_TRUE(closest_point_on_triangle({-1, -1, 0}, a, b, c).isApprox(a));                                 // vertex
  EXPECT_TRUE(closest_point_on_triangle({1, -2, 1}, a, b, c).isApprox(Eigen::Vector3d(1, 0, 0)));           // edge
  EXPECT_TRUE(closest_point_on_triangle({2, 2, 0}, a, b, c).isApprox(Eigen::Vector3d(1, 1, 0)));  // hypotenuse
}

TEST(ClosestPoint, DegenerateTriangleGivesTheNearestEdgePoint) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(2, 0, 0);
  EXPECT_NEAR((closest_point_on_triangle({1.5, 1.0, 0.0}, a, b, c) - Eigen::Vector3d(1.5, 0, 0)).norm(), 0.0, 1e-12);
}

TEST(ClosestPoint, LocatorAgreesWithBruteForceNearAndFar) {
  const Mesh sphere = make_icosphere(3, 5.0);
  const TriangleLocator locator(sphere.positions, sphere.triangles);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (int k = 0; k < 300; ++k) {
    Eigen::Vector3d dir(gauss(rng), gauss(rng), gauss(rng));
    dir.normalize();
    const double radius = k < 200 ? 5.0 + 0.3 * gauss(rng) : 5.0 + 40.0 * std::abs(gauss(rng));  // near, then far
    const Eigen::Vector3d p = radius * dir;
    const ClosestPoint q = locator.closest(p);
    EXPECT_NEAR(q.distance, brute_force(sphere, p), 1e-9) << "query " << k;
    EXPECT_NEAR((q.point - p).norm(), q.distance, 1e-9);
  }
}

TEST(ClosestPoint, EmptyMeshIsInfinitelyFar) {
  const TriangleLocator locator(Eigen::Matrix3Xd(3, 0), {});
  EXPECT_TRUE(std::isinf(locator.closest(Eigen::Vector3d::Zero()).distance));
  EXPECT_EQ(locator.closest(Eigen::Vector3d::Zero()).face, -1);
}

TEST(ClosestPoint, FaceOutOfRangeIsRefused) {
  EXPECT_THROW(TriangleLocator(Eigen::Matrix3Xd::Zero(3, 3), {{0, 1, 3}}), InvalidInputError);
}

TEST(ClosestPoint, PointLocatorAgreesWithBruteForce) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  Eigen::Matrix3Xd points(3, 500);
  for (Index i = 0; i < points.cols(); ++i) points.col(i) = Eigen::Vector3d(u(rng), u(rng), 0.1 * u(rng));
  const PointLocator locator(points);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d p(2 * u(rng), 2 * u(rng), u(rng));
    const double brute = (points.colwise() - p).colwise().norm().minCoeff();
    EXPECT_NEAR(locator.distance(p), brute, 1e-12);
  }
  EXPECT_TRUE(std::isinf(PointLocator(Eigen::Matrix3Xd(3, 0)).distance(Eigen::Vector3d::Zero())));
}

}  // namespace
}  // namespace contourmesh
