// SPDX-License-Identifier: BSD-3-Clause
// Private to ContourMesh (not installed): the 2-D polygon geometry that libsmooth (contour-stack
// shapes) and libreconstruct (contours, tiling, phantoms) share. Compiled into libsmooth
// (src/detail/polygon2d.cpp). A polygon is its vertices in order, closed implicitly (last -> first).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <vector>

namespace contourmesh::detail {

using Polygon = std::vector<Eigen::Vector2d>;

/// Twice the signed area of the triangle (a, b, c): > 0 when it turns counter-clockwise, 0 when the
/// points are collinear. The orientation predicate of segment crossings and point location.
[[nodiscard]] inline double orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

/// Signed area (shoelace formula): positive when the polygon runs counter-clockwise. 0 for fewer than
/// three vertices' worth of area; an empty polygon is not allowed.
[[nodiscard]] double polygon_signed_area(const Polygon& polygon);

/// Whether the edge a -> b crosses the ray from p towards +x: the step of the even-odd rule (an edge
/// counts once at the endpoint strictly above p.y, so a ray through a vertex is counted right).
[[nodiscard]] inline bool crosses_ray(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  return (a.y() > p.y()) != (b.y() > p.y()) && p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
}

/// Even-odd point-in-polygon test. Points on the boundary may go either way.
[[nodiscard]] bool polygon_contains(const Polygon& polygon, const Eigen::Vector2d& p);

/// Exact signed distance from p to the boundary of a simple polygon of any orientation: negative
/// inside (winding of the edges around p, after Inigo Quilez's 2-D polygon distance). Repeated
/// vertices are harmless.
[[nodiscard]] double polygon_signed_distance(const Polygon& polygon, const Eigen::Vector2d& p);

/// Area of the intersection of the regions enclosed by two simple polygons (even-odd rule), by exact
/// interval intersection on `rows` horizontal scanlines over the common bounding box (error about
/// 1 / rows of the smaller region's height). Orientation does not matter.
[[nodiscard]] double overlap_area(const Polygon& a, const Polygon& b, int rows = 128);

/// A corner of a triangle from triangulate_with_holes: polygon 0 is the outer, polygon k + 1 is hole k.
struct PolygonVertex {
  int polygon;
  int vertex;
};

/// Triangulates the region inside `outer` (counter-clockwise) minus the `holes` (clockwise, strictly
/// inside `outer`, disjoint) by ear clipping after joining each hole to the outer boundary with a
/// bridge (the hole-elimination step of Eberly's "Triangulation by ear clipping"). All triangles are
/// counter-clockwise; a simple polygon of n vertices without holes gives n - 2. Never throws on
/// degenerate input; it falls back to clipping the most convex corner.
[[nodiscard]] std::vector<std::array<PolygonVertex, 3>> triangulate_with_holes(const Polygon& outer,
                                                                               const std::vector<Polygon>& holes);

/// triangulate_with_holes without holes, as indices into `polygon`.
[[nodiscard]] std::vector<std::array<int, 3>> triangulate_polygon(const Polygon& polygon);

}  // namespace contourmesh::detail
