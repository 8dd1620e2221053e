// SPDX-License-Identifier: BSD-3-Clause
// The split of each 1-ring by slice (the paper's notation, section 3; ids as in mesh.h): N1^c(i), N1^{c-1}(i),
// N1^{c+1}(i).
#pragma once

#include "contourmesh/smooth/adjacency.h"
#include "contourmesh/smooth/mesh.h"

#include <span>
#include <vector>

namespace contourmesh {

/// The 1-ring of every vertex reordered into four consecutive groups, CSR style:
/// same slice c(i) | slice below c(i)-1 | slice above c(i)+1 | other (no id, or a slice further away,
/// for example a cap centre or an inconsistent id). Within a group neighbours keep increasing index order.
struct SliceRings {
  std::vector<Index> offsets;  ///< n + 1 entries, as MeshAdjacency::neighbor_offsets
  std::vector<Index> neighbors;
  std::vector<Index> below_begin;  ///< absolute positions in `neighbors` where each group starts
  std::vector<Index> above_begin;
  std::vector<Index> other_begin;

  [[nodiscard]] std::span<const Index> same(Index i) const { return span(offsets[i], below_begin[i]); }
  [[nodiscard]] std::span<const Index> below(Index i) const { return span(below_begin[i], above_begin[i]); }
  [[nodiscard]] std::span<const Index> above(Index i) const { return span(above_begin[i], other_begin[i]); }
  [[nodiscard]] std::span<const Index> other(Index i) const { return span(other_begin[i], offsets[i + 1]); }

 private:
  [[nodiscard]] std::span<const Index> span(Index b, Index e) const {
    return {neighbors.data() + b, neighbors.data() + e};
  }
};

/// Splits every 1-ring by the slice ids of the mesh. Throws InvalidInputError if the mesh has no
/// contour ids or the adjacency does not match it. A vertex with slice id kNoId has all its neighbours
/// in the "other" group.
[[nodiscard]] SliceRings split_rings_by_slice(const Mesh& mesh, const MeshAdjacency& adjacency);

}  // namespace contourmesh
