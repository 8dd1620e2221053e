// SPDX-License-Identifier: BSD-3-Clause
// Nearest-point queries on a triangle mesh's surface and on a point set, through a uniform grid of
// buckets. Used by the surface metrics (surface_metrics.h) and wherever a
// point must be compared with a surface.
#pragma once

#include "contourmesh/smooth/mesh.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace contourmesh {

/// The point of a surface nearest to a query point.
struct ClosestPoint {
  double distance = 0.0;  ///< Euclidean distance, input units
  Index face = -1;        ///< the triangle the point lies on (-1 for an empty mesh)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

/// The point of triangle (a, b, c) nearest to p (exact; degenerate triangles allowed).
[[nodiscard]] Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// A bucket grid over a triangle mesh's faces (copied: the locator owns its data). Building is
/// linear in the number of faces; a query visits the buckets around the query point in growing
/// shells until no closer face can exist, and skips a bucket, or a face, whose box is no nearer than
/// the best face so far, so queries near the surface cost a few exact triangle tests.
/// Queries are const and may run concurrently.
class TriangleLocator {
 public:
  /// Throws InvalidInputError for a face index out of range or a non-finite position of a face.
  TriangleLocator(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles);

  /// The nearest surface point; distance +infinity and face -1 when the mesh has no faces.
  [[nodiscard]] ClosestPoint closest(const Eigen::Vector3d& p) const;

  [[nodiscard]] Index num_faces() const { return static_cast<Index>(corners_.size() / 9); }

 private:
  std::vector<double> corners_;  // 9 per face: a, b, c
  std::vector<double> boxes_;    // 6 per face: the corners' min, then their max
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double cell_ = 1.0;
  std::array<std::int64_t, 3> dims_{1, 1, 1};
  std::vector<std::int64_t> start_;  // CSR over cells
  std::vector<Index> faces_;
};

/// A bucket grid over a set of points, for the distance to the nearest of them (e.g. a phantom's
/// densely sampled feature lines). Queries are const and may run concurrently.
class PointLocator {
 public:
  /// `points` is 3 x n; throws InvalidInputError for a non-finite point.
  explicit PointLocator(const Eigen::Matrix3Xd& points);

  /// Distance to the nearest point; +infinity for an empty set.
  [[nodiscard]] double distance(const Eigen::Vector3d& p) const;

 private:
  Eigen::Matrix3Xd points_;  // in cell order
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double cell_ = 1.0;
  std::array<std::int64_t, 3> dims_{1, 1, 1};
  std::vector<std::int64_t> start_;
};

}  // namespace contourmesh
