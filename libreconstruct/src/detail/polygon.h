// Private 2-D polygon helpers for tiling: region overlap and triangulation of polygons with holes.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <vector>

namespace contourmesh::detail {

using Polygon = std::vector<Eigen::Vector2d>;

/// Area of the intersection of the regions enclosed by two simple polygons (even-odd rule), by exact
/// interval intersection on `rows` horizontal scanlines over the common bounding box (error about
/// 1 / rows of the smaller region's height). Orientation does not matter.
[[nodiscard]] double overlap_area(const Polygon& a, const Polygon& b, int rows = 128);

/// Triangulates the region inside `outer` (counter-clockwise) minus the `holes` (clockwise, strictly
/// inside `outer`, disjoint) by ear clipping after joining each hole to the outer boundary with a
/// bridge (the hole-elimination step of Eberly's "Triangulation by ear clipping"). Returns triangles
/// as (polygon, vertex) pairs: polygon 0 is the outer, polygon k + 1 is hole k. All triangles are
/// counter-clockwise. Never throws on degenerate input; it falls back to clipping convex corners.
struct PolygonVertex {
  int polygon;
  int vertex;
};
[[nodiscard]] std::vector<std::array<PolygonVertex, 3>> triangulate_with_holes(const Polygon& outer,
                                                                               const std::vector<Polygon>& holes);

}  // namespace contourmesh::detail
