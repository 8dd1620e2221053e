// SPDX-License-Identifier: BSD-3-Clause
#include "detail/smoothing_common.h"

namespace contourmesh {

Eigen::Matrix3Xd laplacian_smooth(const Mesh& mesh, const MeshAdjacency& adj, const SmoothingOptions& options) {
  detail::check_inputs(mesh, adj, options);
  const double lambda = options.lambda.value_or(default_lambda(SmoothingMethod::Laplacian));
  const std::vector<std::uint8_t> movable = detail::movable_mask(adj, options);
  Eigen::Matrix3Xd current = mesh.positions;
  Eigen::Matrix3Xd next(3, mesh.num_vertices());
  for (int it = 0; it < options.iterations; ++it) {
    detail::umbrella_step(current, next, adj, lambda, movable);
    current.swap(next);
    detail::end_iteration(options, it + 1, options.iterations, current);
  }
  return current;
}

Eigen::Matrix3Xd taubin_smooth(const Mesh& mesh, const MeshAdjacency& adj, const SmoothingOptions& options) {
  detail::check_inputs(mesh, adj, options);
  const double lambda = options.lambda.value_or(default_lambda(SmoothingMethod::Taubin));
  const std::vector<std::uint8_t> movable = detail::movable_mask(adj, options);
  Eigen::Matrix3Xd current = mesh.positions;
  Eigen::Matrix3Xd next(3, mesh.num_vertices());
  for (int it = 0; it < options.iterations; ++it) {
    detail::umbrella_step(current, next, adj, lambda, movable);
    detail::umbrella_step(next, current, adj, options.mu, movable);
    detail::end_iteration(options, it + 1, options.iterations, current);
  }
  return current;
}

}  // namespace contourmesh
