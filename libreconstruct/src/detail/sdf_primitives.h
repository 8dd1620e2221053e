// SPDX-License-Identifier: BSD-3-Clause
// Private: exact signed distance functions of the primitives the phantoms are built from (negative
// inside, millimetres).
#pragma once

#include "contourmesh/internal/polygon2d.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

namespace contourmesh::detail {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

inline constexpr double kPi = std::numbers::pi;

/// sqrt(x^2 + y^2) without std::hypot's overflow care (slow, and not needed at millimetre scales).
inline double length2(double x, double y) { return std::sqrt(x * x + y * y); }

inline double sd_sphere(const Vec3& p, const Vec3& centre, double radius) { return (p - centre).norm() - radius; }

/// The segment ab thickened by `radius`.
inline double sd_capsule(const Vec3& p, const Vec3& a, const Vec3& b, double radius) {
  const Vec3 ab = b - a;
  const Vec3 ap = p - a;
  const double h = std::clamp(ap.dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (ap - h * ab).norm() - radius;
}

/// A 2-D signed distance `d2` extruded along an axis: `w` is the axial coordinate from the middle, the
/// solid spans |w| <= half_height. Exact when d2 is.
inline double sd_extrude(double d2, double w, double half_height) {
  const double qx = d2;
  const double qy = std::abs(w) - half_height;
  return std::min(std::max(qx, qy), 0.0) + length2(std::max(qx, 0.0), std::max(qy, 0.0));
}

// Polygons (sections of prisms and solids of revolution): polygon_signed_distance and
// polygon_signed_area of contourmesh/internal/polygon2d.h.

/// An axis-aligned ellipse in a plane, with its exact signed distance (Eberly's closest point).
struct Ellipse {
  Vec2 centre;
  Vec2 axes;  ///< semi-axes along the two plane axes

  [[nodiscard]] double signed_distance(const Vec2& p) const;
};

/// An axis-aligned ellipsoid with its exact signed distance (Eberly's closest point).
struct Ellipsoid {
  Vec3 centre;
  Vec3 axes;                          ///< semi-axes along x, y, z
  std::array<int, 3> order{0, 1, 2};  ///< axes sorted by decreasing length

  Ellipsoid(const Vec3& c, const Vec3& a);

  [[nodiscard]] double signed_distance(const Vec3& p) const;

  /// Cheap bounds of signed_distance(p): with k = |(p - c) / axes|, the distance lies between
  /// e_min |k - 1| and e_max |k - 1| (scaling by 1/axes is Lipschitz with constant 1/e_min, and p / k is on
  /// the surface), with the sign of k - 1.
  [[nodiscard]] std::pair<double, double> distance_bounds(const Vec3& p) const;
};

}  // namespace contourmesh::detail
