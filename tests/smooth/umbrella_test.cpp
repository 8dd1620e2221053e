// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/normals.h>
#include <contourmesh/smooth/shapes.h>
#include <contourmesh/smooth/umbrella.h>

#include <gtest/gtest.h>

#include "smooth/test_meshes.h"

namespace contourmesh {
namespace {

TEST(Umbrella, RegularPlanarFanCentreIsZero) {
  const Mesh fan = test::hexagon_fan(2.5);
  const Eigen::Matrix3Xd u = umbrella(fan.positions, build_adjacency(fan));
  EXPECT_LT(u.col(0).norm(), 1e-14);
  // A rim vertex's umbrella points into the fan.
  EXPECT_LT(u.col(1).dot(fan.positions.col(1)), 0.0);
}

TEST(Umbrella, IsTheMeanOfNeighbourOffsets) {
  Mesh fan = test::hexagon_fan();
  fan.positions(2, 0) = 0.3;  // lift the centre
  const Eigen::Matrix3Xd u = umbrella(fan.positions, build_adjacency(fan));
  EXPECT_NEAR(u(2, 0), -0.3, 1e-14);
  EXPECT_NEAR(u(0, 0), 0.0, 1e-14);
  // Vertex 1 has neighbours 0, 2 and 6.
  const Eigen::Vector3d expected =
      (fan.positions.col(0) + fan.positions.col(2) + fan.positions.col(6)) / 3.0 - fan.positions.col(1);
  EXPECT_LT((u.col(1) - expected).norm(), 1e-14);
}

TEST(Umbrella, PointsInwardOnASphereWithNormalComponentDominant) {
  const Mesh sphere = make_icosphere(3, 2.0);
  const MeshAdjacency adj = build_adjacency(sphere);
  const Eigen::Matrix3Xd u = umbrella(sphere.positions, adj);
  const Eigen::Matrix3Xd n = vertex_normals(sphere.positions, sphere.triangles);
  const Eigen::VectorXd norms = umbrella_norms(sphere.positions, adj);
  const Eigen::VectorXd normal_norms = umbrella_normal_norms(sphere.positions, adj, n);
  for (Index i = 0; i < sphere.num_vertices(); ++i) {
    EXPECT_LT(u.col(i).dot(n.col(i)), 0.0);
    EXPECT_LE(normal_norms[i], norms[i] + 1e-15);
    EXPECT_GT(normal_norms[i], 0.5 * norms[i]);  // icosphere rings are irregular near the 12 poles
  }
  EXPECT_GT(normal_norms.sum(), 0.75 * norms.sum());
}

}  // namespace
}  // namespace contourmesh
