// SPDX-License-Identifier: BSD-3-Clause
#include "detail/smoothing_common.h"
#include "contourmesh/smooth/normals.h"

namespace contourmesh {

Eigen::Matrix3Xd mean_curvature_flow(const Mesh& mesh, const MeshAdjacency& adj, const SmoothingOptions& options) {
  detail::check_inputs(mesh, adj, options);
  const double lambda = options.lambda.value_or(default_lambda(SmoothingMethod::MeanCurvatureFlow));
  const std::vector<std::uint8_t> movable = detail::movable_mask(adj, options);
  double dt = lambda;
  if (options.time_step == TimeStep::RelativeToMeanEdge) {
    const double h = mean_edge_length(mesh.positions, adj);
    dt = lambda * h * h / 4.0;
  }
  const Index n = mesh.num_vertices();
  Eigen::Matrix3Xd current = mesh.positions;
  Eigen::Matrix3Xd lap(3, n);
  Eigen::VectorXd area(n);
  for (int it = 0; it < options.iterations; ++it) {
    lap.setZero();
    area.setZero();
    for (const Triangle& t : mesh.triangles) {
      const Eigen::Vector3d p[3] = {current.col(t[0]), current.col(t[1]), current.col(t[2])};
      const double twice_area = (p[1] - p[0]).cross(p[2] - p[0]).norm();
      if (!(twice_area > 0.0)) continue;  // a collapsed triangle contributes nothing
      for (int c = 0; c < 3; ++c) {
        // Corner c is opposite the edge (a, b); its cotangent weighs that edge.
        const int a = (c + 1) % 3;
        const int b = (c + 2) % 3;
        const Eigen::Vector3d ea = p[a] - p[c];
        const Eigen::Vector3d eb = p[b] - p[c];
        const double cot = ea.dot(eb) / twice_area;  // |ea x eb| == twice_area
        const Eigen::Vector3d d = p[b] - p[a];
        lap.col(t[a]) += cot * d;
        lap.col(t[b]) -= cot * d;
        area[t[c]] += twice_area / 6.0;  // one third of the triangle area
      }
    }
    for (Index i = 0; i < n; ++i) {
      if (movable[i] && area[i] > 0.0) current.col(i) += dt * lap.col(i) / (2.0 * area[i]);
    }
    detail::end_iteration(options, it + 1, options.iterations, current);
  }
  return current;
}

}  // namespace contourmesh
