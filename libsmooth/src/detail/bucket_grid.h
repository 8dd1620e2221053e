// SPDX-License-Identifier: BSD-3-Clause
// A uniform grid of buckets over a box, shared by the triangle and point locators: the cell of a point,
// and a walk over the cells in growing shells (Chebyshev rings) around a query point.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace contourmesh::detail {

/// Squared distance from p to the axis-aligned box [lo, hi] (0 inside it).
[[nodiscard]] inline double squared_distance_to_box(const Eigen::Vector3d& p, const Eigen::Vector3d& lo,
                                                    const Eigen::Vector3d& hi) {
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double out = std::max({lo[a] - p[a], p[a] - hi[a], 0.0});
    d2 += out * out;
  }
  return d2;
}

struct BucketGrid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double cell = 1.0;
  std::array<std::int64_t, 3> dims{1, 1, 1};

  /// A grid over [lo, hi] with about `target_cells` cells (at least one along each axis, and cells
  /// at least `min_cell` wide).
  static BucketGrid over(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double target_cells, double min_cell) {
    BucketGrid g;
    const Eigen::Vector3d extent = (hi - lo).cwiseMax(1e-12);
    const double volume = extent.prod();
    double cell = std::cbrt(volume / std::max(1.0, target_cells));
    // A flat or thin box: base the cell on its two largest extents instead.
    const double largest = extent.maxCoeff();
    cell = std::max({cell, min_cell, largest / 2048.0});
    g.cell = cell;
    g.origin = lo;
    for (int a = 0; a < 3; ++a) {
      g.dims[static_cast<std::size_t>(a)] =
          std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(extent[a] / cell)));
    }
    return g;
  }

  [[nodiscard]] std::int64_t count() const { return dims[0] * dims[1] * dims[2]; }

  [[nodiscard]] std::int64_t coord(double x, int axis) const {
    const double c = std::floor((x - origin[axis]) / cell);
    const double hi = static_cast<double>(dims[static_cast<std::size_t>(axis)] - 1);
    return static_cast<std::int64_t>(std::clamp(c, 0.0, hi));
  }
  [[nodiscard]] std::array<std::int64_t, 3> cell_of(const Eigen::Vector3d& p) const {
    return {coord(p.x(), 0), coord(p.y(), 1), coord(p.z(), 2)};
  }
  [[nodiscard]] std::int64_t index(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return (z * dims[1] + y) * dims[0] + x;
  }
  /// Distance from p to the grid's box (0 inside).
  [[nodiscard]] double distance_to_box(const Eigen::Vector3d& p) const {
    Eigen::Vector3d hi = origin;
    for (int a = 0; a < 3; ++a) hi[a] += cell * static_cast<double>(dims[static_cast<std::size_t>(a)]);
    return std::sqrt(squared_distance_to_box(p, origin, hi));
  }
  /// Squared distance from p to cell (x, y, z) (0 inside it).
  [[nodiscard]] double distance2_to_cell(const Eigen::Vector3d& p, std::int64_t x, std::int64_t y,
                                         std::int64_t z) const {
    const Eigen::Vector3d lo = origin + cell * Eigen::Vector3d(static_cast<double>(x), static_cast<double>(y),
                                                               static_cast<double>(z));
    return squared_distance_to_box(p, lo, lo + Eigen::Vector3d::Constant(cell));
  }
  /// The largest shell radius that can hold a cell.
  [[nodiscard]] std::int64_t max_shell() const { return std::max({dims[0], dims[1], dims[2]}); }

  /// Calls visit(x, y, z) for every cell (x, y, z) at Chebyshev distance exactly r from `c`.
  template <typename Visit>
  void shell(const std::array<std::int64_t, 3>& c, std::int64_t r, Visit&& visit) const {
    const std::int64_t z0 = std::max<std::int64_t>(0, c[2] - r), z1 = std::min(dims[2] - 1, c[2] + r);
    const std::int64_t y0 = std::max<std::int64_t>(0, c[1] - r), y1 = std::min(dims[1] - 1, c[1] + r);
    const std::int64_t x0 = std::max<std::int64_t>(0, c[0] - r), x1 = std::min(dims[0] - 1, c[0] + r);
    for (std::int64_t z = z0; z <= z1; ++z) {
      const bool z_face = std::abs(z - c[2]) == r;
      for (std::int64_t y = y0; y <= y1; ++y) {
        const bool yz_face = z_face || std::abs(y - c[1]) == r;
        if (yz_face) {
          for (std::int64_t x = x0; x <= x1; ++x) visit(x, y, z);
        } else {
          if (c[0] - r >= 0) visit(c[0] - r, y, z);
          if (r > 0 && c[0] + r < dims[0]) visit(c[0] + r, y, z);
        }
      }
    }
  }
};

}  // namespace contourmesh::detail
