// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/mesh_quality.h"

#include "contourmesh/smooth/errors.h"

#include "detail/edge_uses.h"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <numbers>
#include <string>

namespace contourmesh {

namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;

// Angle between two edge vectors leaving a corner, in degrees; atan2 keeps small angles accurate.
double corner_angle(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return kDegrees * std::atan2(u.cross(v).norm(), u.dot(v));
}

void check_triangles(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles, const char* what) {
  const Index n = static_cast<Index>(positions.cols());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    for (Index v : triangles[f]) {
      if (v < 0 || v >= n) {
        throw InvalidInputError(std::string(what) + ": triangle " + std::to_string(f) + " refers to vertex " +
                                std::to_string(v) + ", outside the " + std::to_string(n) + " positions");
      }
    }
  }
}

void check_angle(double degrees, double max, const char* what) {
  if (!(degrees >= 0.0 && degrees <= max)) {
    throw InvalidInputError(std::string(what) + ": the angle must be in [0, " + std::to_string(static_cast<int>(max)) +
                            "] degrees, got " + std::to_string(degrees));
  }
}

Eigen::Vector3d unit_axis(const Eigen::Vector3d& axis, const char* what) {
  const double norm = axis.norm();
  if (!(std::isfinite(norm) && norm > 0.0))
    throw InvalidInputError(std::string(what) + ": the axis must be finite and non-zero");
  return axis / norm;
}

void check_skip(std::span<const std::uint8_t> skip, std::size_t faces, const char* what) {
  if (!skip.empty() && skip.size() != faces) {
    throw InvalidInputError(std::string(what) + ": " + std::to_string(skip.size()) + " skip flags for " +
                            std::to_string(faces) + " faces");
  }
}

}  // namespace

double minimum_angle_degrees(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, bc = c - b, ca = a - c;
  if (ab.squaredNorm() == 0.0 || bc.squaredNorm() == 0.0 || ca.squaredNorm() == 0.0) return 0.0;
  const double at_a = corner_angle(ab, -ca);
  const double at_b = corner_angle(bc, -ab);
  const double at_c = 180.0 - at_a - at_b;
  return std::clamp(std::min({at_a, at_b, at_c}), 0.0, 60.0);
}

double sliver_area_share(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                         double min_angle_degrees) {
  check_angle(min_angle_degrees, 60.0, "sliver_area_share");
  check_triangles(positions, triangles, "sliver_area_share");
  double total = 0.0, slivers = 0.0;
  for (const Triangle& t : triangles) {
    const Eigen::Vector3d a = positions.col(t[0]), b = positions.col(t[1]), c = positions.col(t[2]);
    const double area = 0.5 * (b - a).cross(c - a).norm();
    total += area;
    if (contourmesh::minimum_angle_degrees(a, b, c) < min_angle_degrees) slivers += area;
  }
  return total > 0.0 ? slivers / total : 0.0;
}

double sliver_area_share(const Mesh& mesh, double min_angle_degrees) {
  return sliver_area_share(mesh.positions, mesh.triangles, min_angle_degrees);
}

double area_facing_axis(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                        const Eigen::Vector3d& axis, double max_angle_degrees, std::span<const std::uint8_t> skip) {
  check_angle(max_angle_degrees, 90.0, "area_facing_axis");
  check_skip(skip, triangles.size(), "area_facing_axis");
  check_triangles(positions, triangles, "area_facing_axis");
  const Eigen::Vector3d n_axis = unit_axis(axis, "area_facing_axis");
  const double min_cos = std::cos(max_angle_degrees / kDegrees);
  double area = 0.0;
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    if (!skip.empty() && skip[f]) continue;
    const Triangle& t = triangles[f];
    const Eigen::Vector3d cross =
        (positions.col(t[1]) - positions.col(t[0])).cross(positions.col(t[2]) - positions.col(t[0]));
    const double twice = cross.norm();
    if (twice > 0.0 && std::abs(cross.dot(n_axis)) >= min_cos * twice) area += 0.5 * twice;
  }
  return area;
}

double share_without_ids(const Mesh& mesh) {
  const Index n = mesh.num_vertices();
  if (n == 0) return 0.0;
  if (!mesh.has_contour_ids()) return 1.0;
  const auto none = std::count(mesh.slice_ids.begin(), mesh.slice_ids.end(), kNoId);
  return static_cast<double>(none) / static_cast<double>(n);
}

MeshQuality mesh_quality(const Mesh& mesh, const MeshQualityOptions& options, std::span<const std::uint8_t> skip) {
  check_angle(options.sliver_angle_degrees, 60.0, "mesh_quality");
  check_angle(options.shelf_angle_degrees, 90.0, "mesh_quality");
  check_skip(skip, mesh.triangles.size(), "mesh_quality");
  check_triangles(mesh.positions, mesh.triangles, "mesh_quality");
  const Eigen::Vector3d axis = unit_axis(options.slice_axis, "mesh_quality");
  const double min_cos = std::cos(options.shelf_angle_degrees / kDegrees);
  MeshQuality q;
  double slivers = 0.0;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    const Eigen::Vector3d a = mesh.positions.col(t[0]), b = mesh.positions.col(t[1]), c = mesh.positions.col(t[2]);
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const double twice = cross.norm();
    if (twice == 0.0) continue;
    const double area = 0.5 * twice;
    q.area += area;
    const double angle = minimum_angle_degrees(a, b, c);
    q.min_angle_degrees = std::min(q.min_angle_degrees, angle);
    if (angle < options.sliver_angle_degrees) slivers += area;
    if ((skip.empty() || !skip[f]) && std::abs(cross.dot(axis)) >= min_cos * twice) q.shelf_area += area;
  }
  if (q.area > 0.0) {
    q.sliver_area_share = slivers / q.area;
    q.shelf_area_share = q.shelf_area / q.area;
  }
  q.share_without_ids = share_without_ids(mesh);
  return q;
}

double fold_area_share(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                       double min_turn_degrees) {
  check_angle(min_turn_degrees, 180.0, "fold_area_share");
  check_triangles(positions, triangles, "fold_area_share");
  const std::size_t nf = triangles.size();
  std::vector<Eigen::Vector3d> normals(nf);
  std::vector<double> areas(nf);
  double total = 0.0;
  for (std::size_t f = 0; f < nf; ++f) {
    const Triangle& t = triangles[f];
    const Eigen::Vector3d n =
        (positions.col(t[1]) - positions.col(t[0])).cross(positions.col(t[2]) - positions.col(t[0]));
    areas[f] = 0.5 * n.norm();
    normals[f] = areas[f] > 0.0 ? Eigen::Vector3d(n / n.norm()) : Eigen::Vector3d::Zero();
    total += areas[f];
  }
  if (!(total > 0.0)) return 0.0;
  const double max_cosine = std::cos(min_turn_degrees / kDegrees);
  std::vector<std::uint8_t> folded(nf, 0);
  const std::vector<detail::EdgeUse> uses = detail::sorted_edge_uses(triangles);
  detail::for_each_edge(uses, [&](std::size_t k, std::size_t count) {
    if (count != 2) return;
    const auto f = static_cast<std::size_t>(uses[k].face), g = static_cast<std::size_t>(uses[k + 1].face);
    if (areas[f] > 0.0 && areas[g] > 0.0 && normals[f].dot(normals[g]) < max_cosine) folded[f] = folded[g] = 1;
  });
  double area = 0.0;
  for (std::size_t f = 0; f < nf; ++f) area += folded[f] ? areas[f] : 0.0;
  return area / total;
}

}  // namespace contourmesh
