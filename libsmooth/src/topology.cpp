// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/topology.h"

#include "contourmesh/smooth/adjacency.h"
#include "contourmesh/smooth/validation.h"

#include "contourmesh/internal/union_find.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace contourmesh {

ComponentLabels component_labels(const Mesh& mesh) {
  const Index n = mesh.num_vertices();
  detail::UnionFind<Index> components(static_cast<std::size_t>(n));
  std::vector<std::uint8_t> used(static_cast<std::size_t>(n), 0);
  for (const Triangle& tri : mesh.triangles) {
    components.unite(tri[0], tri[1]);
    components.unite(tri[1], tri[2]);
    used[tri[0]] = used[tri[1]] = used[tri[2]] = 1;
  }
  ComponentLabels labels;
  labels.of_vertex.assign(static_cast<std::size_t>(n), -1);
  std::vector<Index> label_of_root(static_cast<std::size_t>(n), -1);
  for (Index i = 0; i < n; ++i) {
    if (!used[i]) continue;
    Index& l = label_of_root[components.find(i)];
    if (l < 0) l = labels.count++;
    labels.of_vertex[i] = l;
  }
  return labels;
}

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
  t.components = component_labels(mesh).count;
  return t;
}

}  // namespace contourmesh
