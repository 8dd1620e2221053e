#include "smooth/umbrella.h"

#include "smooth/errors.h"

namespace contourmesh {

void umbrella(const Eigen::Matrix3Xd& positions, const MeshAdjacency& adj, Eigen::Matrix3Xd& out) {
  const Index n = adj.num_vertices();
  if (positions.cols() != n) {
    throw InvalidInputError("umbrella: " + std::to_string(positions.cols()) + " positions for an adjacency of " +
                            std::to_string(n) + " vertices");
  }
  out.resize(3, n);
  const Index* offsets = adj.neighbor_offsets.data();
  const Index* nbrs = adj.neighbors.data();
  const double* p = positions.data();
  double* u = out.data();
  for (Index i = 0; i < n; ++i) {
    const Index begin = offsets[i];
    const Index end = offsets[i + 1];
    double sx = 0.0, sy = 0.0, sz = 0.0;
    for (Index k = begin; k < end; ++k) {
      const double* q = p + 3 * static_cast<std::ptrdiff_t>(nbrs[k]);
      sx += q[0];
      sy += q[1];
      sz += q[2];
    }
    const double* pi = p + 3 * static_cast<std::ptrdiff_t>(i);
    double* ui = u + 3 * static_cast<std::ptrdiff_t>(i);
    if (end > begin) {
      const double inv = 1.0 / static_cast<double>(end - begin);
      ui[0] = sx * inv - pi[0];
      ui[1] = sy * inv - pi[1];
      ui[2] = sz * inv - pi[2];
    } else {
      ui[0] = ui[1] = ui[2] = 0.0;
    }
  }
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
  if (normals.cols() != positions.cols()) throw InvalidInputError("umbrella_normal_norms: one normal per vertex expected");
  const Eigen::Matrix3Xd u = umbrella(positions, adj);
  return u.cwiseProduct(normals).colwise().sum().cwiseAbs().transpose();
}

}  // namespace contourmesh
