// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/slice_neighbors.h"

#include "contourmesh/smooth/errors.h"

namespace contourmesh {

SliceRings split_rings_by_slice(const Mesh& mesh, const MeshAdjacency& adj) {
  if (!mesh.has_contour_ids()) throw InvalidInputError("split_rings_by_slice: the mesh has no contour ids");
  const Index n = mesh.num_vertices();
  if (adj.num_vertices() != n) throw InvalidInputError("split_rings_by_slice: adjacency does not match the mesh");

  SliceRings rings;
  rings.offsets = adj.neighbor_offsets;
  rings.neighbors.resize(adj.neighbors.size());
  rings.below_begin.resize(static_cast<std::size_t>(n));
  rings.above_begin.resize(static_cast<std::size_t>(n));
  rings.other_begin.resize(static_cast<std::size_t>(n));
  const auto& s = mesh.slice_ids;
  for (Index i = 0; i < n; ++i) {
    const auto ring = adj.ring(i);
    auto group = [&](Index j) {
      if (s[i] == kNoId || s[j] == kNoId) return 3;
      const int d = s[j] - s[i];
      return d == 0 ? 0 : d == -1 ? 1 : d == 1 ? 2 : 3;
    };
    Index out = rings.offsets[i];
    for (int g = 0; g < 4; ++g) {
      if (g == 1) rings.below_begin[i] = out;
      if (g == 2) rings.above_begin[i] = out;
      if (g == 3) rings.other_begin[i] = out;
      for (Index j : ring) {
        if (group(j) == g) rings.neighbors[out++] = j;
      }
    }
  }
  return rings;
}

}  // namespace contourmesh
