// SPDX-License-Identifier: BSD-3-Clause
// Topological summary of a triangle mesh: closedness, manifoldness, Euler characteristic, components.
#pragma once

#include "contourmesh/smooth/mesh.h"

#include <string>
#include <vector>

namespace contourmesh {

struct TopologySummary {
  bool closed = false;    ///< no boundary edge
  bool manifold = false;  ///< no degenerate, duplicate or non-manifold element (find_mesh_problems is empty)
  long euler_characteristic = 0;  ///< V - E + F, counting only vertices used by a triangle
  int components = 0;             ///< connected components of the triangles
  std::string first_problems;     ///< up to five problems, "; "-separated, when not manifold
};

/// Connected components of the triangles: one label per vertex in [0, count), -1 for a vertex used
/// by no triangle. Labels are numbered in order of their lowest vertex index.
struct ComponentLabels {
  std::vector<Index> of_vertex;
  int count = 0;
};
[[nodiscard]] ComponentLabels component_labels(const Mesh& mesh);

/// Computes the summary in O(V + F) plus validation. For a closed manifold mesh with c components of
/// genus g_k, euler_characteristic = sum_k (2 - 2 g_k).
[[nodiscard]] TopologySummary summarize_topology(const Mesh& mesh);

}  // namespace contourmesh
