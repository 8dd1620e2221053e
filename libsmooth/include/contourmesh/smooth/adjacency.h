// SPDX-License-Identifier: BSD-3-Clause
// Compact (CSR) connectivity of a triangle mesh: vertex 1-rings, vertex-to-face incidence and
// boundary flags. Built once, read by every hot loop.
#pragma once

#include "contourmesh/smooth/mesh.h"

#include <cstdint>
#include <span>
#include <vector>

namespace contourmesh {

/// CSR adjacency. For vertex i:
/// - its 1-ring N1(i) is `neighbors[neighbor_offsets[i] .. neighbor_offsets[i+1])`, sorted by index;
/// - the triangles that use it are `faces[face_offsets[i] .. face_offsets[i+1])`, in increasing order;
/// - `is_boundary[i]` is 1 when one of its edges belongs to exactly one triangle.
/// `edge_face_count[k]` is the number of triangles using the edge (i, neighbors[k]): 1 on a boundary,
/// 2 inside a manifold mesh, more on a non-manifold edge.
struct MeshAdjacency {
  std::vector<Index> neighbor_offsets;
  std::vector<Index> neighbors;
  std::vector<std::uint8_t> edge_face_count;
  std::vector<Index> face_offsets;
  std::vector<Index> faces;
  std::vector<std::uint8_t> is_boundary;

  [[nodiscard]] Index num_vertices() const {
    return neighbor_offsets.empty() ? 0 : static_cast<Index>(neighbor_offsets.size() - 1);
  }
  [[nodiscard]] std::span<const Index> ring(Index i) const {
    return {neighbors.data() + neighbor_offsets[i], neighbors.data() + neighbor_offsets[i + 1]};
  }
  [[nodiscard]] std::span<const Index> incident_faces(Index i) const {
    return {faces.data() + face_offsets[i], faces.data() + face_offsets[i + 1]};
  }
  [[nodiscard]] Index valence(Index i) const { return neighbor_offsets[i + 1] - neighbor_offsets[i]; }
  /// Number of undirected edges.
  [[nodiscard]] std::size_t num_edges() const { return neighbors.size() / 2; }
  /// True when no vertex is on a boundary.
  [[nodiscard]] bool is_closed() const;
};

/// Builds the adjacency in O(V + F). Preconditions: triangle indices are in [0, num_vertices)
/// (throws InvalidInputError naming the first triangle that is not). Degenerate or non-manifold
/// meshes are accepted here; `validate_mesh` reports them.
[[nodiscard]] MeshAdjacency build_adjacency(const Mesh& mesh);

}  // namespace contourmesh
