// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/shapes.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "detail/parallel.h"

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

// The rings from a plain map of each vertex's faces' corners: neighbour -> number of faces with that edge.
std::vector<std::map<Index, int>> reference_rings(const Mesh& mesh) {
  std::vector<std::map<Index, int>> rings(static_cast<std::size_t>(mesh.num_vertices()));
  for (const Triangle& t : mesh.triangles) {
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        if (t[a] != t[b]) ++rings[static_cast<std::size_t>(t[a])][t[b]];
      }
    }
  }
  return rings;
}

void expect_rings(const MeshAdjacency& adj, const std::vector<std::map<Index, int>>& reference) {
  ASSERT_EQ(adj.num_vertices(), static_cast<Index>(reference.size()));
  for (Index i = 0; i < adj.num_vertices(); ++i) {
    const auto& want = reference[static_cast<std::size_t>(i)];
    ASSERT_EQ(adj.valence(i), static_cast<Index>(want.size())) << "vertex " << i;
    Index k = adj.neighbor_offsets[i];
    bool boundary = false;
    for (const auto& [j, faces] : want) {
      EXPECT_EQ(adj.neighbors[k], j) << "vertex " << i;
      EXPECT_EQ(adj.edge_face_count[k], faces) << "vertex " << i;
      boundary = boundary || faces == 1;
      ++k;
    }
    EXPECT_EQ(adj.is_boundary[i] != 0, boundary) << "vertex " << i;
  }
}

// The rings are built in chunks of vertices on every core: in place for a closed mesh, through per-chunk
// arrays for an open one (a boundary vertex has one neighbour more than faces). Both give the plain
// rings, on one thread and on several, over many chunks.
TEST(Adjacency, ChunkedRingsMatchAPlainBuildClosedAndOpen) {
  ContourStackSpec spec;
  spec.curve = [](double t) { return Eigen::Vector2d(20.0 * std::cos(2 * M_PI * t), 20.0 * std::sin(2 * M_PI * t)); };
  spec.slices = 120;
  spec.points_per_contour = 400;
  const Mesh closed = make_contour_stack(spec);
  Mesh open_mesh = closed;
  // Without the caps (the faces touching a vertex without ids): both end contours become boundaries.
  std::erase_if(open_mesh.triangles, [&](const Triangle& t) {
    return std::any_of(t.begin(), t.end(),
                       [&](Index v) { return open_mesh.slice_ids[static_cast<std::size_t>(v)] < 0; });
  });
  ASSERT_GT(closed.num_vertices(), 2 * 16384);
  const Mesh& open = open_mesh;
  for (const Mesh* mesh : {&closed, &open}) {
    const auto reference = reference_rings(*mesh);
    for (unsigned threads : {1u, 3u}) {
      const detail::ScopedWorkerCount count(threads);
      const MeshAdjacency adj = build_adjacency(*mesh);
      EXPECT_EQ(adj.is_closed(), mesh == &closed);
      expect_rings(adj, reference);
    }
  }
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
