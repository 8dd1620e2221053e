// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/slice_neighbors.h"

#include "contourmesh/internal/huge_pages.h"
#include "detail/parallel.h"
#include "contourmesh/smooth/errors.h"

#include <array>
#include <cstdint>
#include <vector>

namespace contourmesh {

SliceRings split_rings_by_slice(const Mesh& mesh, const MeshAdjacency& adj) {
  if (!mesh.has_contour_ids()) throw InvalidInputError("split_rings_by_slice: the mesh has no contour ids");
  const Index n = mesh.num_vertices();
  if (adj.num_vertices() != n) throw InvalidInputError("split_rings_by_slice: adjacency does not match the mesh");

  SliceRings rings;
  detail::reserve_huge(rings.offsets, adj.neighbor_offsets.size());
  rings.offsets = adj.neighbor_offsets;
  detail::resize_huge(rings.neighbors, adj.neighbors.size());
  detail::resize_huge(rings.below_begin, static_cast<std::size_t>(n));
  detail::resize_huge(rings.above_begin, static_cast<std::size_t>(n));
  detail::resize_huge(rings.other_begin, static_cast<std::size_t>(n));
  const auto& s = mesh.slice_ids;
  // Per neighbour its group (same slice, below, above, other), then a stable counting sort of the ring
  // by group: one pass over the ring instead of one per group.
  // Each vertex's ring is sorted on its own: fixed chunks on every core, each with its scratch.
  detail::parallel_chunks(
      static_cast<std::size_t>(n), 8192, [&](std::size_t, std::size_t chunk_begin, std::size_t chunk_end) {
        std::array<std::uint8_t, 64> small_groups{};
        std::vector<std::uint8_t> large_groups;
        for (auto i = static_cast<Index>(chunk_begin); i < static_cast<Index>(chunk_end); ++i) {
          const auto ring = adj.ring(i);
          const std::size_t size = ring.size();
          std::uint8_t* group = small_groups.data();
          if (size > small_groups.size()) {
            large_groups.resize(size);
            group = large_groups.data();
          }
          std::array<Index, 4> count{0, 0, 0, 0};
          for (std::size_t k = 0; k < size; ++k) {
            const Index j = ring[k];
            int g = 3;
            if (s[i] != kNoId && s[j] != kNoId) {
              const int d = s[j] - s[i];
              g = d == 0 ? 0 : d == -1 ? 1 : d == 1 ? 2 : 3;
            }
            group[k] = static_cast<std::uint8_t>(g);
            ++count[static_cast<std::size_t>(g)];
          }
          const Index begin = rings.offsets[i];
          rings.below_begin[i] = begin + count[0];
          rings.above_begin[i] = rings.below_begin[i] + count[1];
          rings.other_begin[i] = rings.above_begin[i] + count[2];
          std::array<Index, 4> out{begin, rings.below_begin[i], rings.above_begin[i], rings.other_begin[i]};
          for (std::size_t k = 0; k < size; ++k) rings.neighbors[out[group[k]]++] = ring[k];
        }
      });
  return rings;
}

}  // namespace contourmesh
