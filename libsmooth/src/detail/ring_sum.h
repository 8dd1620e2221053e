// SPDX-License-Identifier: BSD-3-Clause
// The one hot loop behind the umbrella operator and the umbrella smoothing steps.
#pragma once

#include "contourmesh/smooth/adjacency.h"

#include <Eigen/Core>

#include <cstddef>

namespace contourmesh::detail {

/// For every vertex i, sums its 1-ring positions and calls
/// `visit(i, const double* p_i, double sx, double sy, double sz, Index count)`.
/// Streams the CSR arrays and the 3 x n position block without temporaries.
template <typename Visit>
inline void for_each_ring_sum(const Eigen::Matrix3Xd& positions, const MeshAdjacency& adj, Visit&& visit) {
  const Index n = adj.num_vertices();
  const Index* offsets = adj.neighbor_offsets.data();
  const Index* nbrs = adj.neighbors.data();
  const double* p = positions.data();
  for (Index i = 0; i < n; ++i) {
    const Index begin = offsets[i];
    const Index end = offsets[i + 1];
    double sx = 0.0, sy = 0.0, sz = 0.0;
    Index k = begin;
    // The first four neighbours (every vertex of a closed mesh has at least three) without loop
    // branches, added in the same order as the loop: fewer mispredicted exits at valence 5-7.
    if (end - begin >= 4) {
      const double* q0 = p + 3 * static_cast<std::ptrdiff_t>(nbrs[k]);
      const double* q1 = p + 3 * static_cast<std::ptrdiff_t>(nbrs[k + 1]);
      const double* q2 = p + 3 * static_cast<std::ptrdiff_t>(nbrs[k + 2]);
      const double* q3 = p + 3 * static_cast<std::ptrdiff_t>(nbrs[k + 3]);
      sx = sx + q0[0] + q1[0] + q2[0] + q3[0];
      sy = sy + q0[1] + q1[1] + q2[1] + q3[1];
      sz = sz + q0[2] + q1[2] + q2[2] + q3[2];
      k += 4;
    }
    for (; k < end; ++k) {
      const double* q = p + 3 * static_cast<std::ptrdiff_t>(nbrs[k]);
      sx += q[0];
      sy += q[1];
      sz += q[2];
    }
    visit(i, p + 3 * static_cast<std::ptrdiff_t>(i), sx, sy, sz, end - begin);
  }
}

}  // namespace contourmesh::detail
