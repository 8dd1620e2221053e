// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/umbrella.h"

#include "detail/ring_sum.h"
#include "contourmesh/smooth/errors.h"

namespace contourmesh {

void umbrella(const Eigen::Matrix3Xd& positions, const MeshAdjacency& adj, Eigen::Matrix3Xd& out) {
  const Index n = adj.num_vertices();
  if (positions.cols() != n) {
    throw InvalidInputError("umbrella: " + std::to_string(positions.cols()) + " positions for an adjacency of " +
                            std::to_string(n) + " vertices");
  }
  out.resize(3, n);
  double* u = out.data();
  using detail::for_each_ring_sum;
  for_each_ring_sum(positions, adj, [u](Index i, const double* pi, double sx, double sy, double sz, Index count) {
    double* ui = u + 3 * static_cast<std::ptrdiff_t>(i);
    if (count == 0) {
      ui[0] = ui[1] = ui[2] = 0.0;
      return;
    }
    const double inv = 1.0 / static_cast<double>(count);
    ui[0] = sx * inv - pi[0];
    ui[1] = sy * inv - pi[1];
    ui[2] = sz * inv - pi[2];
  });
}

Eigen::Matrix3Xd umbrella(const Eigen::Matrix3Xd& positions, const MeshAdjacency& adj) {
  Eigen::Matrix3Xd out;
  umbrella(positions, adj, out);
  return out;
}

Eigen::VectorXd umbrella_norms(const Eigen::Matrix3Xd& positions, const MeshAdjacency& adj) {
  return umbrella(positions, adj).colwise().norm().transpose();
}

Eigen::VectorXd umbrella_normal_norms(const Eigen::Matrix3Xd& positions, const MeshAdjacency& adj,
                                      const Eigen::Matrix3Xd& normals) {
  if (normals.cols() != positions.cols()) {
    throw InvalidInputError("umbrella_normal_norms: one normal per vertex expected");
  }
  const Eigen::Matrix3Xd u = umbrella(positions, adj);
  return u.cwiseProduct(normals).colwise().sum().cwiseAbs().transpose();
}

}  // namespace contourmesh
