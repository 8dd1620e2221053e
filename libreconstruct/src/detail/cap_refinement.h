// SPDX-License-Identifier: BSD-3-Clause
// Private: well-shaped cap triangulations. Ear clipping alone fans long thin triangles across a cap;
// umbrella-based smoothing then drags the cap's rim towards its middle and rounds the object's ends.
#pragma once

#include "contourmesh/internal/polygon2d.h"

#include <array>
#include <vector>

namespace contourmesh::detail {

/// A triangulated cap: boundary vertices are (polygon, vertex) pairs as in triangulate_with_holes;
/// interior vertices added by refinement have polygon == -1 and vertex = index into `interior`.
struct RefinedCap {
  std::vector<Eigen::Vector2d> interior;
  std::vector<std::array<PolygonVertex, 3>> triangles;  ///< counter-clockwise
};

/// Ear clipping with holes, then constrained Delaunay refinement: Lawson flips of non-boundary edges,
/// insertion of triangle centroids while a triangle has an edge longer than 1.5 * `target_edge`, and a
/// two rounds of moving interior vertices to the mean of their neighbours (each followed by flips).
/// The boundary is never changed. target_edge <= 0 returns the ear-clipped triangulation unchanged.
[[nodiscard]] RefinedCap triangulate_refined(const Polygon& outer, const std::vector<Polygon>& holes,
                                             double target_edge);

}  // namespace contourmesh::detail
