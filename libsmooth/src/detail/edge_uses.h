// SPDX-License-Identifier: BSD-3-Clause
// Private: the triangles' directed edges sorted by undirected edge, so that the triangles of an edge are
// adjacent (orientation checks, fold measures).
#pragma once

#include "contourmesh/smooth/mesh.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <vector>

namespace contourmesh::detail {

/// One triangle's use of an edge.
struct EdgeUse {
  std::uint64_t key;  ///< (min << 32) | max of the edge's vertex ids
  Index face;
  bool forward;  ///< traversed from the smaller to the larger index
};

/// Every edge use of `triangles`, sorted by edge, then by face.
inline std::vector<EdgeUse> sorted_edge_uses(const std::vector<Triangle>& triangles) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    for (int k = 0; k < 3; ++k) {
      const Index a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      const auto lo = static_cast<std::uint64_t>(std::min(a, b)), hi = static_cast<std::uint64_t>(std::max(a, b));
      uses.push_back({(lo << 32) | hi, static_cast<Index>(f), a < b});
    }
  }
  std::sort(uses.begin(), uses.end(),
            [](const EdgeUse& x, const EdgeUse& y) { return std::tie(x.key, x.face) < std::tie(y.key, y.face); });
  return uses;
}

/// Calls visit(first, count) for each run of uses of one edge.
template <typename Visit>
void for_each_edge(const std::vector<EdgeUse>& uses, Visit visit) {
  for (std::size_t k = 0; k < uses.size();) {
    std::size_t e = k + 1;
    while (e < uses.size() && uses[e].key == uses[k].key) ++e;
    visit(k, e - k);
    k = e;
  }
}

}  // namespace contourmesh::detail
