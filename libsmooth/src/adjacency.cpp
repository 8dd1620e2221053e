// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/adjacency.h"

#include "contourmesh/internal/huge_pages.h"
#include "detail/parallel.h"
#include "contourmesh/smooth/errors.h"

#include <algorithm>
#include <limits>
#include <string>
#include <utility>

namespace contourmesh {

bool MeshAdjacency::is_closed() const {
  return std::none_of(is_boundary.begin(), is_boundary.end(), [](std::uint8_t b) { return b != 0; });
}

namespace {

// The rings of one chunk of vertices, as Part says.
struct Part {
  bool spilled = false;  // written to `neighbors` and `counts` below instead of in place
  std::size_t written = 0;
  std::vector<Index> neighbors;
  std::vector<std::uint8_t> counts;
};

// Writes the rings of vertices [first, last) (sorted, with each neighbour's face count) in place, from
// face_offsets[first] on, or into `part` when they do not fit there; sets their ring sizes in
// neighbor_offsets[i + 1] and their boundary flags.
void write_rings(const Mesh& mesh, std::size_t first, std::size_t last, MeshAdjacency& adj, Part& part) {
  const Index* face_offsets = adj.face_offsets.data();
  const Index* faces = adj.faces.data();
  const auto base = static_cast<std::size_t>(face_offsets[first]);
  std::size_t room = static_cast<std::size_t>(face_offsets[last]) - base;
  Index* out_neighbors = adj.neighbors.data() + base;
  std::uint8_t* out_counts = adj.edge_face_count.data() + base;
  std::vector<Index> scratch;
  std::size_t written = 0;
  for (auto i = static_cast<Index>(first); i < static_cast<Index>(last); ++i) {
    const Index begin = face_offsets[i];
    const Index end = face_offsets[i + 1];
    // Up to two corners per face, plus room for the write of i itself that is not kept.
    const auto need = static_cast<std::size_t>(2 * (end - begin) + 3);
    if (scratch.size() < need) scratch.resize(std::max<std::size_t>(need, 64));
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
    std::size_t distinct = count > 0 ? 1 : 0;  // the ring's size: the gathered corners come in pairs
    for (std::size_t a = 1; a < count; ++a) distinct += static_cast<std::size_t>(s[a] != s[a - 1]);
    if (written + distinct > room) {  // an open mesh: more edges than face corners
      if (!part.spilled) {
        part.neighbors.assign(out_neighbors, out_neighbors + written);
        part.counts.assign(out_counts, out_counts + written);
        part.spilled = true;
      }
      room = 2 * (written + distinct) + 16;
      part.neighbors.resize(room);
      part.counts.resize(room);
      out_neighbors = part.neighbors.data();
      out_counts = part.counts.data();
    }
    std::uint8_t boundary = 0;
    const std::size_t ring_start = written;
    for (std::size_t a = 0; a < count;) {
      std::size_t b = a + 1;
      while (b < count && s[b] == s[a]) ++b;
      out_neighbors[written] = s[a];
      out_counts[written] = static_cast<std::uint8_t>(std::min<std::size_t>(b - a, 255));
      ++written;
      boundary |= static_cast<std::uint8_t>(b - a == 1);
      a = b;
    }
    adj.is_boundary[static_cast<std::size_t>(i)] = boundary;
    adj.neighbor_offsets[static_cast<std::size_t>(i) + 1] = static_cast<Index>(written - ring_start);
  }
  part.written = written;
}

}  // namespace

MeshAdjacency build_adjacency(const Mesh& mesh) {
  const Index n = mesh.num_vertices();
  const Index nf = mesh.num_faces();
  MeshAdjacency adj;

  // Vertex-to-face incidence by counting sort.
  detail::assign_huge(adj.face_offsets, static_cast<std::size_t>(n) + 1, Index{0});
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
  detail::resize_huge(adj.faces, static_cast<std::size_t>(adj.face_offsets[n]));
  {
    std::vector<Index> fill(adj.face_offsets.begin(), adj.face_offsets.end() - 1);
    for (Index f = 0; f < nf; ++f) {
      for (Index v : mesh.triangles[f]) adj.faces[fill[v]++] = f;
    }
  }

  // 1-rings: gather the two other corners of every incident face, sort, and count multiplicities.
  // The multiplicity of j in i's gathered list is the number of faces sharing edge (i, j). Fixed chunks
  // of vertices on every core, with an insertion sort for the usual dozen entries: the full method
  // builds the adjacency of every mesh it touches. A closed mesh has as many ring entries per vertex as
  // faces, so each chunk writes in place, where its vertices' faces are listed; a chunk whose rings do
  // not fit there (an open mesh) writes into its own arrays, and the chunks are then joined in order.
  // Either way the arrays do not depend on the number of threads.
  detail::assign_huge(adj.neighbor_offsets, static_cast<std::size_t>(n) + 1, Index{0});
  detail::assign_huge(adj.is_boundary, static_cast<std::size_t>(n), std::uint8_t{0});
  detail::resize_huge(adj.neighbors, adj.faces.size());
  detail::resize_huge(adj.edge_face_count, adj.faces.size());
  constexpr std::size_t kChunk = 16384;
  std::vector<Part> parts((static_cast<std::size_t>(n) + kChunk - 1) / kChunk);
  const Index* face_offsets = adj.face_offsets.data();
  detail::parallel_chunks(static_cast<std::size_t>(n), kChunk,
                          [&](std::size_t chunk, std::size_t first, std::size_t last) {
                            write_rings(mesh, first, last, adj, parts[chunk]);
                          });
  for (Index i = 0; i < n; ++i) adj.neighbor_offsets[i + 1] += adj.neighbor_offsets[i];
  const bool in_place = std::all_of(parts.begin(), parts.end(), [&](const Part& part) {
    const std::size_t chunk = static_cast<std::size_t>(&part - parts.data());
    const std::size_t first = chunk * kChunk, last = std::min(static_cast<std::size_t>(n), first + kChunk);
    return !part.spilled && part.written == static_cast<std::size_t>(face_offsets[last] - face_offsets[first]);
  });
  if (!in_place) {
    std::vector<Index> neighbors(static_cast<std::size_t>(adj.neighbor_offsets[n]));
    std::vector<std::uint8_t> counts(neighbors.size());
    for (std::size_t chunk = 0; chunk < parts.size(); ++chunk) {
      const Part& part = parts[chunk];
      const auto base = static_cast<std::ptrdiff_t>(face_offsets[chunk * kChunk]);
      const auto to = static_cast<std::ptrdiff_t>(adj.neighbor_offsets[chunk * kChunk]);
      const auto size = static_cast<std::ptrdiff_t>(part.written);
      const Index* from_neighbors = part.spilled ? part.neighbors.data() : adj.neighbors.data() + base;
      const std::uint8_t* from_counts = part.spilled ? part.counts.data() : adj.edge_face_count.data() + base;
      std::copy(from_neighbors, from_neighbors + size, neighbors.begin() + to);
      std::copy(from_counts, from_counts + size, counts.begin() + to);
    }
    adj.neighbors = std::move(neighbors);
    adj.edge_face_count = std::move(counts);
  }
  return adj;
}

}  // namespace contourmesh
