#include "smooth/topology.h"

#include "smooth/adjacency.h"
#include "smooth/validation.h"

#include <algorithm>
#include <numeric>
#include <vector>

namespace contourmesh {

TopologySummary summarize_topology(const Mesh& mesh) {
  TopologySummary t;
  const auto problems = find_mesh_problems(mesh);
  t.manifold = problems.empty();
  for (std::size_t k = 0; k < std::min<std::size_t>(problems.size(), 5); ++k) {
    t.first_problems += (k ? "; " : "") + describe(problems[k]);
  }
  for (const MeshProblem& p : problems) {
    if (p.kind == MeshProblemKind::IndexOutOfRange) return t;  // nothing else is meaningful
  }
  const MeshAdjacency adj = build_adjacency(mesh);
  t.closed = adj.is_closed();
  long used = 0;
  for (Index i = 0; i < mesh.num_vertices(); ++i) used += adj.valence(i) > 0 ? 1 : 0;
  t.euler_characteristic = used - static_cast<long>(adj.num_edges()) + mesh.num_faces();
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

}  // namespace contourmesh
