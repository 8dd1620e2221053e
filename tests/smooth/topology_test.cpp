// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/shapes.h>
#include <contourmesh/smooth/topology.h>

#include <gtest/gtest.h>

#include "smooth/test_meshes.h"

namespace contourmesh {
namespace {

TEST(Topology, SphereCubeAndTwoComponents) {
  const TopologySummary s = summarize_topology(make_icosphere(2));
  EXPECT_TRUE(s.closed);
  EXPECT_TRUE(s.manifold);
  EXPECT_EQ(s.euler_characteristic, 2);
  EXPECT_EQ(s.components, 1);
  Mesh two = make_cube(2);
  const Mesh other = make_icosphere(1, 1.0, {5, 0, 0});
  const Index offset = two.num_vertices();
  two.positions.conservativeResize(3, offset + other.num_vertices());
  two.positions.rightCols(other.num_vertices()) = other.positions;
  for (Triangle t : other.triangles) two.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  const TopologySummary t = summarize_topology(two);
  EXPECT_EQ(t.components, 2);
  EXPECT_EQ(t.euler_characteristic, 4);
}

TEST(Topology, OpenFanAndNonManifoldFin) {
  const TopologySummary fan = summarize_topology(test::hexagon_fan());
  EXPECT_FALSE(fan.closed);
  EXPECT_EQ(fan.euler_characteristic, 1);  // a disc
  Mesh fin = test::tetrahedron();
  fin.positions.conservativeResize(3, 5);
  fin.positions.col(4) << 0.5, -1.0, 0.5;
  fin.triangles.push_back({0, 1, 4});
  const TopologySummary f = summarize_topology(fin);
  EXPECT_FALSE(f.manifold);
  EXPECT_NE(f.first_problems.find("non-manifold edge"), std::string::npos);
}

}  // namespace
}  // namespace contourmesh
