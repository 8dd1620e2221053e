// SPDX-License-Identifier: BSD-3-Clause
#include "detail/smoothing_common.h"
#include "contourmesh/smooth/normals.h"

namespace contourmesh {

Eigen::Matrix3Xd min_dist_flow(const Mesh& mesh, const MeshAdjacency& adj, const SmoothingOptions& options) {
  detail::check_inputs(mesh, adj, options);
  const double lambda = options.lambda.value_or(default_lambda(SmoothingMethod::MinDistFlow));
  const std::vector<std::uint8_t> movable = detail::movable_mask(adj, options);
  const Index n = mesh.num_vertices();
  const Index nf = mesh.num_faces();
  const double cos_limit = 1.0 - options.beta;

  Eigen::Matrix3Xd current = mesh.positions;
  Eigen::Matrix3Xd averaged(3, nf);
  Eigen::Matrix3Xd centroids(3, nf);
  std::vector<Index> stamp(static_cast<std::size_t>(nf), -1);
  for (int it = 0; it < options.iterations; ++it) {
    const Eigen::Matrix3Xd normals = face_normals(current, mesh.triangles);
    const Eigen::VectorXd areas = face_areas(current, mesh.triangles);
    for (Index f = 0; f < nf; ++f) {
      const Triangle& t = mesh.triangles[f];
      centroids.col(f) = (current.col(t[0]) + current.col(t[1]) + current.col(t[2])) / 3.0;
      // Average the normals of the faces around f that lie on the same side of every crease.
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (Index v : t) {
        for (Index g : adj.incident_faces(v)) {
          if (stamp[g] == f) continue;
          stamp[g] = f;
          if (normals.col(f).dot(normals.col(g)) >= cos_limit) sum += areas[g] * normals.col(g);
        }
      }
      const double len = sum.norm();
      averaged.col(f) = len > 0.0 ? Eigen::Vector3d(sum / len) : Eigen::Vector3d(normals.col(f));
    }
    Eigen::Matrix3Xd next = current;
    for (Index i = 0; i < n; ++i) {
      if (!movable[i]) continue;
      Eigen::Vector3d move = Eigen::Vector3d::Zero();
      double weight = 0.0;
      for (Index f : adj.incident_faces(i)) {
        const Eigen::Vector3d m = averaged.col(f);
        move += areas[f] * m * m.dot(centroids.col(f) - current.col(i));
        weight += areas[f];
      }
      if (weight > 0.0) next.col(i) += lambda * move / weight;
    }
    current.swap(next);
    // The stamps hold face indices; reset so the next iteration's "f" values do not collide.
    std::fill(stamp.begin(), stamp.end(), -1);
    detail::end_iteration(options, it + 1, options.iterations, current);
  }
  return current;
}

}  // namespace contourmesh
