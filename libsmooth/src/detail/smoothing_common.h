// SPDX-License-Identifier: BSD-3-Clause
// Private helpers shared by the smoother implementations.
#pragma once

#include "detail/ring_sum.h"
#include "contourmesh/smooth/adjacency.h"
#include "contourmesh/smooth/errors.h"
#include "contourmesh/smooth/smoothing.h"

#include <cstdint>
#include <vector>

namespace contourmesh::detail {

/// 1 for every vertex the smoother may move: not locked, not a fixed boundary vertex, not isolated.
inline std::vector<std::uint8_t> movable_mask(const MeshAdjacency& adj, const SmoothingOptions& options) {
  const Index n = adj.num_vertices();
  std::vector<std::uint8_t> movable(static_cast<std::size_t>(n), 1);
  for (Index i = 0; i < n; ++i) {
    if (!options.locked.empty() && options.locked[i] != 0) movable[i] = 0;
    if (options.boundary == BoundaryPolicy::Fixed && adj.is_boundary[i] != 0) movable[i] = 0;
    if (adj.valence(i) == 0) movable[i] = 0;
  }
  return movable;
}

/// Checks options and that the adjacency belongs to the mesh.
inline void check_inputs(const Mesh& mesh, const MeshAdjacency& adj, const SmoothingOptions& options) {
  if (adj.num_vertices() != mesh.num_vertices()) {
    throw InvalidInputError("smoothing: the adjacency has " + std::to_string(adj.num_vertices()) +
                            " vertices but the mesh has " + std::to_string(mesh.num_vertices()));
  }
  check_smoothing_options(options, mesh.num_vertices());
}

/// Reports the end of iteration `done` (1-based) of `total`; throws CancelledError on request.
inline void end_iteration(const SmoothingOptions& options, int done, int total, const Eigen::Matrix3Xd& positions) {
  if (options.on_iteration) options.on_iteration(done, positions);
  if (options.progress && !options.progress("smooth", static_cast<double>(done) / total)) {
    throw CancelledError("smoothing");
  }
}

/// out_i = in_i + factor * U(in)_i for movable vertices, in_i otherwise (one Jacobi umbrella step).
inline void umbrella_step(const Eigen::Matrix3Xd& in, Eigen::Matrix3Xd& out, const MeshAdjacency& adj, double factor,
                          const std::vector<std::uint8_t>& movable) {
  out.resize(3, adj.num_vertices());
  double* q = out.data();
  const std::uint8_t* mv = movable.data();
  for_each_ring_sum(in, adj, [=](Index i, const double* pi, double sx, double sy, double sz, Index count) {
    double* qi = q + 3 * static_cast<std::ptrdiff_t>(i);
    if (!mv[i]) {
      qi[0] = pi[0];
      qi[1] = pi[1];
      qi[2] = pi[2];
      return;
    }
    const double w = factor / static_cast<double>(count);  // movable vertices have count > 0
    qi[0] = pi[0] + (sx * w - factor * pi[0]);
    qi[1] = pi[1] + (sy * w - factor * pi[1]);
    qi[2] = pi[2] + (sz * w - factor * pi[2]);
  });
}

}  // namespace contourmesh::detail
