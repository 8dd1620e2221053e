// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/metrics.h"

#include "contourmesh/smooth/errors.h"
#include "contourmesh/smooth/limits.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace contourmesh {

double enclosed_volume(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles) {
  // Subtracting a reference point keeps the sum well conditioned far from the origin.
  const Eigen::Vector3d ref = positions.cols() ? Eigen::Vector3d(positions.rowwise().mean()) : Eigen::Vector3d::Zero();
  double sum = 0.0;
  for (const Triangle& t : triangles) {
    const Eigen::Vector3d a = positions.col(t[0]) - ref;
    const Eigen::Vector3d b = positions.col(t[1]) - ref;
    const Eigen::Vector3d c = positions.col(t[2]) - ref;
    sum += a.dot(b.cross(c));
  }
  return sum / 6.0;
}

double enclosed_volume(const Mesh& mesh) { return enclosed_volume(mesh.positions, mesh.triangles); }

double surface_area(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles) {
  double sum = 0.0;
  for (const Triangle& t : triangles) {
    sum += (positions.col(t[1]) - positions.col(t[0])).cross(positions.col(t[2]) - positions.col(t[0])).norm();
  }
  return 0.5 * sum;
}

double surface_area(const Mesh& mesh) { return surface_area(mesh.positions, mesh.triangles); }

double volume_shrinking_rate(double original_volume, double smoothed_volume) {
  if (!(std::isfinite(original_volume) && original_volume != 0.0)) {
    throw InvalidInputError("volume shrinking rate: the original volume is " + std::to_string(original_volume));
  }
  return (original_volume - smoothed_volume) / original_volume;
}

std::vector<double> volume_shrinking_curve(const Mesh& mesh, const SmoothingOptions& options) {
  // One value per iteration: the iteration count is bounded by the memory it would take.
  check_allocation("volume curve of " + std::to_string(options.iterations) + " iterations", 0.0,
                   8.0 * (std::max(options.iterations, 0) + 1.0), ResourceLimits{});
  const double v0 = enclosed_volume(mesh);
  std::vector<double> curve{0.0};
  if (options.method == SmoothingMethod::None) {
    curve.resize(static_cast<std::size_t>(std::max(options.iterations, 0)) + 1, 0.0);
    return curve;
  }
  SmoothingOptions observed = options;
  observed.on_iteration = [&](int iteration, const Eigen::Matrix3Xd& positions) {
    curve.push_back(volume_shrinking_rate(v0, enclosed_volume(positions, mesh.triangles)));
    if (options.on_iteration) options.on_iteration(iteration, positions);
  };
  (void)smooth(mesh, observed);
  return curve;
}

namespace {

template <typename IndexRange>
DistanceStats distance_stats(const Eigen::Matrix3Xd& positions, const ScalarField& sdf, const IndexRange& indices) {
  DistanceStats s;
  double sum = 0.0, sum_sq = 0.0;
  for (Index i : indices) {
    if (i < 0 || i >= positions.cols()) {
      throw InvalidInputError("distance_to_surface: vertex index " + std::to_string(i) + " out of range");
    }
    const double d = std::abs(sdf(positions.col(i)));
    sum += d;
    sum_sq += d * d;
    s.max = std::max(s.max, d);
    ++s.count;
  }
  if (s.count) {
    s.mean = sum / static_cast<double>(s.count);
    s.rms = std::sqrt(sum_sq / static_cast<double>(s.count));
  }
  return s;
}

struct IotaRange {
  Index n;
  struct It {
    Index i;
    Index operator*() const { return i; }
    It& operator++() { ++i; return *this; }
    bool operator!=(const It& o) const { return i != o.i; }
  };
  [[nodiscard]] It begin() const { return {0}; }
  [[nodiscard]] It end() const { return {n}; }
};

template <typename IndexRange>
AngleStats angle_stats(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                       const VectorField& normal, const IndexRange& faces) {
  AngleStats s;
  double sum = 0.0;
  for (Index f : faces) {
    if (f < 0 || static_cast<std::size_t>(f) >= triangles.size()) {
      throw InvalidInputError("normal_angular_error: face index " + std::to_string(f) + " out of range");
    }
    const Triangle& t = triangles[f];
    const Eigen::Vector3d c =
        (positions.col(t[1]) - positions.col(t[0])).cross(positions.col(t[2]) - positions.col(t[0]));
    const double len = c.norm();
    if (!(len > 0.0)) continue;
    const Eigen::Vector3d centroid = (positions.col(t[0]) + positions.col(t[1]) + positions.col(t[2])) / 3.0;
    const Eigen::Vector3d truth = normal(centroid).normalized();
    const double cosine = std::clamp(c.dot(truth) / len, -1.0, 1.0);
    const double degrees = std::acos(cosine) * 180.0 / std::numbers::pi;
    sum += degrees;
    s.max_degrees = std::max(s.max_degrees, degrees);
    ++s.count;
  }
  if (s.count) s.mean_degrees = sum / static_cast<double>(s.count);
  return s;
}

}  // namespace

DistanceStats distance_to_surface(const Eigen::Matrix3Xd& positions, const ScalarField& sdf) {
  return distance_stats(positions, sdf, IotaRange{static_cast<Index>(positions.cols())});
}

DistanceStats distance_to_surface(const Eigen::Matrix3Xd& positions, const ScalarField& sdf,
                                  std::span<const Index> vertices) {
  return distance_stats(positions, sdf, vertices);
}

AngleStats normal_angular_error(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                                const VectorField& normal) {
  return angle_stats(positions, triangles, normal, IotaRange{static_cast<Index>(triangles.size())});
}

AngleStats normal_angular_error(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                                const VectorField& normal, std::span<const Index> faces) {
  return angle_stats(positions, triangles, normal, faces);
}

}  // namespace contourmesh
