// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/normals.h"

#include "contourmesh/internal/huge_pages.h"
#include "detail/parallel.h"
#include "contourmesh/smooth/errors.h"

#include <string>

namespace contourmesh {

Eigen::Matrix3Xd face_normals(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles) {
  Eigen::Matrix3Xd normals(3, static_cast<Eigen::Index>(triangles.size()));
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    const Eigen::Vector3d c =
        (positions.col(t[1]) - positions.col(t[0])).cross(positions.col(t[2]) - positions.col(t[0]));
    const double len = c.norm();
    normals.col(static_cast<Eigen::Index>(f)) = len > 0.0 ? Eigen::Vector3d(c / len) : Eigen::Vector3d::Zero();
  }
  return normals;
}

Eigen::VectorXd face_areas(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles) {
  Eigen::VectorXd areas(static_cast<Eigen::Index>(triangles.size()));
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    areas[static_cast<Eigen::Index>(f)] =
        0.5 * (positions.col(t[1]) - positions.col(t[0])).cross(positions.col(t[2]) - positions.col(t[0])).norm();
  }
  return areas;
}

Eigen::Matrix3Xd vertex_normals(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles) {
  Eigen::Matrix3Xd normals = Eigen::Matrix3Xd::Zero(3, positions.cols());
  for (const Triangle& t : triangles) {
    // The unnormalised cross product is twice the area times the unit normal: area weighting for free.
    const Eigen::Vector3d c =
        (positions.col(t[1]) - positions.col(t[0])).cross(positions.col(t[2]) - positions.col(t[0]));
    for (Index v : t) normals.col(v) += c;
  }
  for (Eigen::Index i = 0; i < normals.cols(); ++i) {
    const double len = normals.col(i).norm();
    if (len > 0.0) normals.col(i) /= len;
  }
  return normals;
}

Eigen::Matrix3Xd vertex_normals(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                                const MeshAdjacency& adjacency) {
  if (adjacency.num_vertices() != static_cast<Index>(positions.cols())) {
    throw InvalidInputError("vertex normals: the adjacency has " + std::to_string(adjacency.num_vertices()) +
                            " vertices, the positions " + std::to_string(positions.cols()));
  }
  // The faces' unnormalised cross products first (each once), then every vertex's sum over its faces.
  auto cross = detail::huge_matrix<Eigen::Matrix3Xd>(3, static_cast<Eigen::Index>(triangles.size()));
  detail::parallel_chunks(triangles.size(), 16384, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t f = begin; f < end; ++f) {
      const Triangle& t = triangles[f];
      cross.col(static_cast<Eigen::Index>(f)) =
          (positions.col(t[1]) - positions.col(t[0])).cross(positions.col(t[2]) - positions.col(t[0]));
    }
  });
  auto normals = detail::huge_matrix<Eigen::Matrix3Xd>(3, positions.cols());
  const auto n = static_cast<std::size_t>(positions.cols());
  detail::parallel_chunks(n, 16384, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (auto i = static_cast<Index>(begin); i < static_cast<Index>(end); ++i) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (Index f : adjacency.incident_faces(i)) sum += cross.col(f);
      normals.col(i) = sum;
      const double len = normals.col(i).norm();
      if (len > 0.0) normals.col(i) /= len;
    }
  });
  return normals;
}

double mean_edge_length(const Eigen::Matrix3Xd& positions, const MeshAdjacency& adj) {
  double sum = 0.0;
  std::size_t count = 0;
  for (Index i = 0; i < adj.num_vertices(); ++i) {
    for (Index j : adj.ring(i)) {
      if (j > i) {
        sum += (positions.col(j) - positions.col(i)).norm();
        ++count;
      }
    }
  }
  return count ? sum / static_cast<double>(count) : 0.0;
}

}  // namespace contourmesh
