// Topology checks shared by the reconstruction tests.
#pragma once

#include <smooth/adjacency.h>
#include <smooth/mesh.h>
#include <smooth/validation.h>

#include <numeric>
#include <string>
#include <vector>

namespace contourmesh::test {

struct Topology {
  bool closed = false;
  bool manifold = false;  // no degenerate, duplicate or non-manifold elements
  long euler = 0;          // V - E + F over vertices used by triangles
  int components = 0;      // connected components of the triangle set
  std::string problems;
};

inline Topology topology_of(const Mesh& mesh) {
  Topology t;
  const MeshAdjacency adj = build_adjacency(mesh);
  t.closed = adj.is_closed();
  const auto problems = find_mesh_problems(mesh);
  t.manifold = problems.empty();
  for (std::size_t k = 0; k < std::min<std::size_t>(problems.size(), 5); ++k) t.problems += describe(problems[k]) + "; ";
  long used = 0;
  for (Index i = 0; i < mesh.num_vertices(); ++i) used += adj.valence(i) > 0;
  t.euler = used - static_cast<long>(adj.num_edges()) + mesh.num_faces();
  std::vector<Index> parent(static_cast<std::size_t>(mesh.num_vertices()));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](Index x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const Triangle& tri : mesh.triangles) {
    parent[find(tri[0])] = find(tri[1]);
    parent[find(tri[1])] = find(tri[2]);
  }
  for (Index i = 0; i < mesh.num_vertices(); ++i) t.components += (adj.valence(i) > 0 && find(i) == i) ? 1 : 0;
  return t;
}

}  // namespace contourmesh::test
