// SPDX-License-Identifier: BSD-3-Clause
// Ordered planar contours per slice: the output of segmentation and the input of tiling.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <optional>
#include <vector>

namespace contourmesh {

/// One closed contour in its slice plane. Points are in the slice's own 2-D frame (u, v) in mm, closed
/// implicitly (the last point connects to the first, which is not repeated). Outer contours run
/// counter-clockwise, holes clockwise, seen from +w (the slice axis).
struct Contour {
  std::vector<Eigen::Vector2d> points;
  bool is_hole = false;
  /// For a hole: index (in the same slice) of the outer contour that encloses it; -1 otherwise.
  int parent = -1;
};

/// The contours of one slice plane.
struct SliceContours {
  double w = 0.0;  ///< position of the slice plane along the slice axis, mm
  std::vector<Contour> contours;
};

/// A stack of slices with the frame that maps slice coordinates to physical space:
/// physical = origin + u * axis_u + v * axis_v + w * axis_w (orthonormal, right-handed axes).
/// Slices are ordered by increasing w; their index in `slices` is the slice id c(i) of mesh.h.
struct ContourStack {
  std::vector<SliceContours> slices;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis_u = Eigen::Vector3d::UnitX();
  Eigen::Vector3d axis_v = Eigen::Vector3d::UnitY();
  Eigen::Vector3d axis_w = Eigen::Vector3d::UnitZ();

  [[nodiscard]] Eigen::Vector3d to_physical(const Eigen::Vector2d& uv, double w) const {
    return origin + uv.x() * axis_u + uv.y() * axis_v + w * axis_w;
  }
  [[nodiscard]] std::size_t num_contours() const {
    std::size_t n = 0;
    for (const auto& s : slices) n += s.contours.size();
    return n;
  }
};

/// Signed area of a closed polygon (positive when counter-clockwise), mm^2.
[[nodiscard]] double signed_area(const std::vector<Eigen::Vector2d>& polygon);

/// Perimeter of a closed polygon, mm.
[[nodiscard]] double perimeter(const std::vector<Eigen::Vector2d>& polygon);

/// Even-odd point-in-polygon test.
[[nodiscard]] bool point_in_polygon(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p);

/// Two edges of a closed polygon that cross or touch although they are not neighbours along it. Edge k
/// runs from point k to point k + 1 (mod n); `first` < `second`.
struct SelfIntersection {
  std::size_t first = 0;
  std::size_t second = 0;
  Eigen::Vector2d where = Eigen::Vector2d::Zero();  ///< a point both edges share
};

/// The first self-intersection of a closed polygon, if any: a crossing, a vertex on a non-adjacent edge,
/// or a repeated point. Exact orientation tests on a uniform grid of the edges' bounding boxes, about
/// linear time for contours with evenly spaced points.
[[nodiscard]] std::optional<SelfIntersection> find_self_intersection(const std::vector<Eigen::Vector2d>& polygon);

/// Two closed polygons of a set whose edges cross or touch: edge `first_edge` of polygon `first` and edge
/// `second_edge` of polygon `second`, `first` < `second`.
struct PolygonCrossing {
  std::size_t first = 0;
  std::size_t first_edge = 0;
  std::size_t second = 0;
  std::size_t second_edge = 0;
  Eigen::Vector2d where = Eigen::Vector2d::Zero();  ///< a point both edges share
};

/// The first crossing, in (polygon, edge) order, between two different polygons of the set (the
/// contours of one slice must not meet); each polygon's own self-intersections are not looked for (see
/// find_self_intersection). The same grid search: about linear time in the total number of points.
/// nullopt also when a point is not finite.
[[nodiscard]] std::optional<PolygonCrossing> find_polygon_crossing(
    const std::vector<std::vector<Eigen::Vector2d>>& polygons);

/// Resamples a closed polygon uniformly by arc length to round(perimeter / spacing) points (at least
/// 3), starting at its first point. Throws InvalidInputError for spacing <= 0 or < 3 input points.
[[nodiscard]] std::vector<Eigen::Vector2d> resample_closed(const std::vector<Eigen::Vector2d>& polygon, double spacing);

}  // namespace contourmesh
