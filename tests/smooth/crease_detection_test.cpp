// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/crease_detection.h"
#include "contourmesh/smooth/errors.h"
#include "contourmesh/smooth/shapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace contourmesh {
namespace {

// Distance from p to the nearest edge of the cube [-h, h]^3 (p on its surface).
double distance_to_cube_edges(const Eigen::Vector3d& p, double h) {
  const Eigen::Vector3d a = p.cwiseAbs();
  // On a face the nearest edge is the nearer of the face's two in-face coordinates' limits.
  std::array<double, 3> gaps{h - a.x(), h - a.y(), h - a.z()};
  std::sort(gaps.begin(), gaps.end());
  return gaps[1];  // gaps[0] is ~0 (the face the point lies on)
}

TEST(CreaseDetection, CubeEdgesAreFoundInABandAndFacesAreSmooth) {
  const double h = 10.0;
  const Mesh cube = make_cube(20, h);  // 1 mm grid
  const CreaseDetection d = detect_creases(cube, build_adjacency(cube));
  for (Index i = 0; i < cube.num_vertices(); ++i) {
    const double to_edge = distance_to_cube_edges(cube.positions.col(i), h);
    const VertexLabel l = d.labels[static_cast<std::size_t>(i)];
    if (to_edge < 0.5) {
      EXPECT_TRUE(l == VertexLabel::Edge || l == VertexLabel::Corner) << "vertex " << i << " at " << to_edge;
    }
    if (to_edge > 2.5) EXPECT_EQ(l, VertexLabel::Smooth) << "vertex " << i << " at " << to_edge;
  }
}

TEST(CreaseDetection, CubeCornersAreCorners) {
  const double h = 10.0;
  const Mesh cube = make_cube(20, h);
  const CreaseDetection d = detect_creases(cube, build_adjacency(cube));
  for (Index i = 0; i < cube.num_vertices(); ++i) {
    if ((cube.positions.col(i).cwiseAbs() - Eigen::Vector3d::Constant(h)).norm() < 1e-9) {
      EXPECT_EQ(d.labels[static_cast<std::size_t>(i)], VertexLabel::Corner);
    }
  }
  EXPECT_GT(d.corners, 0u);
}

TEST(CreaseDetection, SmoothSphereHasNoFeature) {
  const Mesh sphere = make_icosphere(4, 10.0);
  const CreaseDetection d = detect_creases(sphere, build_adjacency(sphere));
  EXPECT_EQ(d.edges + d.corners + d.noise, 0u);
}

TEST(CreaseDetection, AShortDentIsNoiseNotAFeature) {
  // One vertex of a fine sphere pushed in: a crease around it, but no line.
  Mesh sphere = make_icosphere(5, 10.0);
  sphere.positions.col(0) *= 0.93;
  const CreaseDetection d = detect_creases(sphere, build_adjacency(sphere));
  EXPECT_EQ(d.edges + d.corners, 0u);
  EXPECT_GT(d.noise, 0u);
}

TEST(CreaseDetection, BadOptionsAreRefused) {
  const Mesh cube = make_cube(2, 1.0);
  CreaseOptions o;
  o.radius = 0.0;
  EXPECT_THROW((void)detect_creases(cube, build_adjacency(cube), o), InvalidInputError);
}

}  // namespace
}  // namespace contourmesh
