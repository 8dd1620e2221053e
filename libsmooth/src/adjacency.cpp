#include "smooth/adjacency.h"

#include "smooth/errors.h"

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
  // The multiplicity of j in i's gathered list is the number of faces sharing edge (i, j).
  adj.neighbor_offsets.assign(static_cast<std::size_t>(n) + 1, 0);
  adj.is_boundary.assign(static_cast<std::size_t>(n), 0);
  adj.neighbors.reserve(adj.faces.size());
  adj.edge_face_count.reserve(adj.faces.size());
  std::vector<Index> scratch;
  for (Index i = 0; i < n; ++i) {
    scratch.clear();
    for (Index k = adj.face_offsets[i]; k < adj.face_offsets[i + 1]; ++k) {
      const Triangle& t = mesh.triangles[adj.faces[k]];
      for (Index v : t) {
        if (v != i) scratch.push_back(v);
      }
    }
    std::sort(scratch.begin(), scratch.end());
    for (std::size_t a = 0; a < scratch.size();) {
      std::size_t b = a;
      while (b < scratch.size() && scratch[b] == scratch[a]) ++b;
      const std::size_t count = b - a;
      adj.neighbors.push_back(scratch[a]);
      adj.edge_face_count.push_back(static_cast<std::uint8_t>(std::min<std::size_t>(count, 255)));
      if (count == 1) adj.is_boundary[i] = 1;
      a = b;
    }
    adj.neighbor_offsets[i + 1] = static_cast<Index>(adj.neighbors.size());
  }
  return adj;
}

}  // namespace contourmesh
