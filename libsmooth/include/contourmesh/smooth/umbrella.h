// SPDX-License-Identifier: BSD-3-Clause
// The umbrella operator of the paper (eq. 7): the discrete uniform Laplacian.
#pragma once

#include "contourmesh/smooth/adjacency.h"

#include <Eigen/Core>

namespace contourmesh {

/// U(v_i) = (1 / #N1(i)) * sum_{j in N1(i)} (v_j - v_i) for every vertex in one pass (paper eq. 7).
/// Returns 3 x n, in input units; an isolated vertex gets zero.
/// Preconditions: `positions.cols() == adjacency.num_vertices()`.
[[nodiscard]] Eigen::Matrix3Xd umbrella(const Eigen::Matrix3Xd& positions, const MeshAdjacency& adjacency);

/// Same as `umbrella`, writing into `out` (resized to 3 x n) so iterative callers reuse one buffer.
void umbrella(const Eigen::Matrix3Xd& positions, const MeshAdjacency& adjacency, Eigen::Matrix3Xd& out);

/// |U(v_i)| for every vertex ("the value of U" in the paper).
[[nodiscard]] Eigen::VectorXd umbrella_norms(const Eigen::Matrix3Xd& positions, const MeshAdjacency& adjacency);

/// |U(v_i) . n_i|, the normal component of the umbrella, with `normals` unit vertex normals (3 x n).
/// Offered as an option next to the paper's |U| because on contour meshes much of |U| is tangential.
[[nodiscard]] Eigen::VectorXd umbrella_normal_norms(const Eigen::Matrix3Xd& positions, const MeshAdjacency& adjacency,
                                                    const Eigen::Matrix3Xd& normals);

}  // namespace contourmesh
