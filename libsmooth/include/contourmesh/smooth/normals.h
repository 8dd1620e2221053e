// SPDX-License-Identifier: BSD-3-Clause
// Face and vertex normals, face areas and edge-length statistics.
#pragma once

#include "contourmesh/smooth/adjacency.h"
#include "contourmesh/smooth/mesh.h"

#include <Eigen/Core>

namespace contourmesh {

/// Unit face normals (3 x F) of the triangles over `positions` (3 x n), right-hand rule, so outward
/// for counter-clockwise triangles. A zero-area triangle gets the zero vector.
[[nodiscard]] Eigen::Matrix3Xd face_normals(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles);

/// Face areas (F), in squared input units.
[[nodiscard]] Eigen::VectorXd face_areas(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles);

/// Unit vertex normals (3 x n): the area-weighted mean of incident face normals (the normal of the local frame of the
/// curvature fit, paper section 3.1). An isolated vertex or one whose faces cancel gets the zero vector.
[[nodiscard]] Eigen::Matrix3Xd vertex_normals(const Eigen::Matrix3Xd& positions,
                                              const std::vector<Triangle>& triangles);

/// The same normals, bit for bit, on every core: each vertex sums its incident faces (`adjacency`, built
/// from these triangles) in ascending face order, as the one-pass version adds them. Throws
/// InvalidInputError when the adjacency's vertex count is not the positions'.
[[nodiscard]] Eigen::Matrix3Xd vertex_normals(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                                              const MeshAdjacency& adjacency);

/// Mean length of the mesh's undirected edges (0 for a mesh without edges).
[[nodiscard]] double mean_edge_length(const Eigen::Matrix3Xd& positions, const MeshAdjacency& adjacency);

}  // namespace contourmesh
