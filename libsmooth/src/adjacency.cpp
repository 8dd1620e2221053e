// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/adjacency.h"

#include "contourmesh/smooth/errors.h"

#include <algorithm>
#include <limits>
#include <string>

namespace contourmesh {

bool MeshAdjacency::is_closed() const {
  return std::none_of(is_boundary.begin(), is_boundary.end(), [](std::uint8_t b) { return b != 0; });
}

MeshAdjacency build_adjacency(const Mesh& mesh) {
  const Index n = mesh.num_vertices();
  const Index nf = mesh.num_faces();
  MeshAdjacency adj;

  // Vertex-to-face incidence by counting sort.
  adj.face_offsets.assign(static_cast<std::size_t>(n) + 1, 0);
  for (Index f = 0; f < nf; ++f) {
    for (Index v : mesh.triangles[f]) {
      if (v < 0 || v >= n) {
        throw InvalidInputError("triangle " + std::to_string(f) + " references vertex " + std::to_string(v) +
                                ", outside [0, " + std::to_string(n) + ")");
      }
      ++adj.face_offsets[v + 1];
    }
  }
  for (Index i = 0; i < n; ++i) adj.face_offsets[i + 1] += adj.face_offsets[i];
  adj.faces.resize(static_cast<std::size_t>(adj.face_offsets[n]));
  {
    std::vector<Index> fill(adj.face_offsets.begin(), adj.face_offsets.end() - 1);
    for (Index f = 0; f < nf; ++f) {
      for (Index v : mesh.triangles[f]) adj.faces[fill[v]++] = f;
    }
  }

  // 1-rings: gather the two other corners of every incident face, sort, and count multiplicities.
  // The multiplicity of j in i's gathered list is the number of faces sharing edge (i, j). Written
  // through raw pointers into arrays sized for a closed mesh (as many ring entries as face corners;
  // they grow for open meshes), without a branch per corner and with an insertion sort for the usual
  // dozen entries: the full method builds the adjacency of every mesh it touches.
  adj.neighbor_offsets.assign(static_cast<std::size_t>(n) + 1, 0);
  adj.is_boundary.assign(static_cast<std::size_t>(n), 0);
  adj.neighbors.resize(adj.faces.size());
  adj.edge_face_count.resize(adj.faces.size());
  Index* out_neighbors = adj.neighbors.data();
  std::uint8_t* out_counts = adj.edge_face_count.data();
  const Index* face_offsets = adj.face_offsets.data();
  const Index* faces = adj.faces.data();
  std::vector<Index> scratch;
  Index written = 0;
  for (Index i = 0; i < n; ++i) {
    const Index begin = face_offsets[i];
    const Index end = face_offsets[i + 1];
    // Up to two corners per face, plus room for the write of i itself that is not kept.
    const auto room = static_cast<std::size_t>(2 * (end - begin) + 3);
    if (scratch.size() < room) scratch.resize(std::max<std::size_t>(room, 64));
    Index* s = scratch.data();
    std::size_t count = 0;
    for (Index k = begin; k < end; ++k) {
      for (Index v : mesh.triangles[faces[k]]) {
        s[count] = v;
        count += v != i;
      }
    }
    if (count <= 24) {
      for (std::size_t a = 1; a < count; ++a) {
        const Index x = s[a];
        std::size_t b = a;
        for (; b > 0 && s[b - 1] > x; --b) s[b] = s[b - 1];
        s[b] = x;
      }
    } else {
      std::sort(s, s + count);
    }
    std::uint8_t boundary = 0;
    for (std::size_t a = 0; a < count;) {
      std::size_t b = a + 1;
      while (b < count && s[b] == s[a]) ++b;
      if (static_cast<std::size_t>(written) == adj.neighbors.size()) {  // an open mesh: more edges
        adj.neighbors.resize(2 * adj.neighbors.size() + 16);
        adj.edge_face_count.resize(adj.neighbors.size());
        out_neighbors = adj.neighbors.data();
        out_counts = adj.edge_face_count.data();
      }
      out_neighbors[written] = s[a];
      out_counts[written] = static_cast<std::uint8_t>(std::min<std::size_t>(b - a, 255));
      ++written;
      boundary |= static_cast<std::uint8_t>(b - a == 1);
      a = b;
    }
    adj.is_boundary[i] = boundary;
    adj.neighbor_offsets[i + 1] = written;
  }
  adj.neighbors.resize(static_cast<std::size_t>(written));
  adj.edge_face_count.resize(static_cast<std::size_t>(written));
  return adj;
}

}  // namespace contourmesh
