// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/shapes.h>

#include <gtest/gtest.h>

#include "smooth/test_meshes.h"

namespace contourmesh {
namespace {

TEST(Adjacency, ClosedCubeSatisfiesEulerAndHasNoBoundary) {
  const Mesh cube = make_cube(4);
  const MeshAdjacency adj = build_adjacency(cube);
  EXPECT_TRUE(adj.is_closed());
  // V - E + F = 2 for a sphere-like surface.
  EXPECT_EQ(static_cast<long>(cube.num_vertices()) - static_cast<long>(adj.num_edges()) + cube.num_faces(), 2);
  for (Index i = 0; i < cube.num_vertices(); ++i) {
    EXPECT_GE(adj.valence(i), 3);
    for (Index k = adj.neighbor_offsets[i]; k < adj.neighbor_offsets[i + 1]; ++k) EXPECT_EQ(adj.edge_face_count[k], 2);
    // Sorted, unique, no self loops.
    const auto ring = adj.ring(i);
    for (std::size_t a = 1; a < ring.size(); ++a) EXPECT_LT(ring[a - 1], ring[a]);
    for (Index j : ring) EXPECT_NE(j, i);
  }
}

TEST(Adjacency, FanCentreHasAllSixNeighboursAndRimIsBoundary) {
  const Mesh fan = test::hexagon_fan();
  const MeshAdjacency adj = build_adjacency(fan);
  EXPECT_EQ(adj.valence(0), 6);
  EXPECT_EQ(adj.incident_faces(0).size(), 6u);
  EXPECT_EQ(adj.is_boundary[0], 0);
  for (Index i = 1; i <= 6; ++i) {
    EXPECT_EQ(adj.is_boundary[i], 1) << i;
    EXPECT_EQ(adj.valence(i), 3);
    EXPECT_EQ(adj.incident_faces(i).size(), 2u);
  }
  EXPECT_FALSE(adj.is_closed());
}

TEST(Adjacency, RemovingOneFaceOpensExactlyItsThreeVertices) {
  Mesh sphere = make_icosphere(2);
  const Triangle removed = sphere.triangles.back();
  sphere.triangles.pop_back();
  const MeshAdjacency adj = build_adjacency(sphere);
  int boundary = 0;
  for (Index i = 0; i < sphere.num_vertices(); ++i) boundary += adj.is_boundary[i];
  EXPECT_EQ(boundary, 3);
  for (Index v : removed) EXPECT_EQ(adj.is_boundary[v], 1);
}

TEST(Adjacency, IndexOutOfRangeThrowsNamingTheTriangle) {
  Mesh m = test::tetrahedron();
  m.triangles[2][1] = 9;
  try {
    (void)build_adjacency(m);
    FAIL() << "expected InvalidInputError";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace contourmesh
