// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/normals.h>
#include <contourmesh/smooth/shapes.h>

#include <gtest/gtest.h>

#include <random>

#include "detail/parallel.h"

namespace contourmesh {
namespace {

// The vertex normals from the adjacency (each vertex sums its faces in ascending order, on every core) are
// the one-pass scatter's, bit for bit, on one thread and on several, over many chunks.
TEST(VertexNormals, FromTheAdjacencyEqualTheScatteredOnesBitForBit) {
  Mesh mesh = make_icosphere(6, 10.0);  // 40 962 vertices: several chunks
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    for (int a = 0; a < 3; ++a) mesh.positions(a, i) += noise(rng);
  }
  const MeshAdjacency adjacency = build_adjacency(mesh);
  const Eigen::Matrix3Xd scattered = vertex_normals(mesh.positions, mesh.triangles);
  for (unsigned threads : {1u, 3u}) {
    const detail::ScopedWorkerCount count(threads);
    EXPECT_TRUE(vertex_normals(mesh.positions, mesh.triangles, adjacency) == scattered) << threads << " threads";
  }
}

TEST(VertexNormals, AnAdjacencyOfAnotherMeshIsRefused) {
  const Mesh small = make_icosphere(1), large = make_icosphere(2);
  EXPECT_THROW((void)vertex_normals(large.positions, large.triangles, build_adjacency(small)), InvalidInputError);
}

}  // namespace
}  // namespace contourmesh
