// SPDX-License-Identifier: BSD-3-Clause
// Adaptive subdivision around feature vertices (Xu et al. 2006, section 4).
#pragma once

#include "contourmesh/smooth/feature_detection.h"
#include "contourmesh/smooth/limits.h"
#include "contourmesh/smooth/mesh.h"

#include <cstdint>
#include <span>
#include <vector>

namespace contourmesh {

struct SubdivisionOptions {
  /// Subdivide until the selected vertex's umbrella measure is below gamma, at most this many times.
  int max_levels = 3;
  /// Stop threshold on the umbrella measure (the detection's gamma), length units, >= 0.
  double gamma = 0.0;
  UmbrellaMeasure measure = UmbrellaMeasure::Length;
  /// Checked before each level allocates its midpoints: the vertices the level could reach (all
  /// incident edges bisected) and their estimated memory (mesh, adjacency and smoothing buffers).
  ResourceLimits limits;
};

/// The subdivided mesh. Vertices 0 .. original_vertices - 1 are the input's, unmoved and in order;
/// new vertices are appended, so resuming the original resolution is a slice of the position array.
struct AdaptiveMesh {
  Mesh mesh;
  Index original_vertices = 0;
  /// Input vertices subdivided at least once, and how many were subdivided at each level.
  std::vector<Index> subdivided;
  std::vector<std::size_t> per_level;
};

/// Spoke bisection: at each level every edge incident to a selected vertex whose umbrella measure
/// still exceeds gamma gets its midpoint, and each triangle is split by the pattern of its bisected
/// edges (one: 2 triangles, two: 3 with the shorter diagonal, three: 4). The 1-ring of a selected
/// vertex becomes the midpoints of its edges, so its umbrella is exactly halved per level; only its
/// 1-ring triangles change; the mesh stays conforming (no T-junctions) and manifold, and the geometry
/// is unchanged (midpoints lie on the old edges). A midpoint on an edge of one contour keeps that
/// contour's ids; others get kNoId. `selected` has one flag per vertex (non-zero: subdivide, e.g. the
/// edge and corner labels). Throws InvalidInputError for a mask of the wrong size or options out of
/// range, LimitError (before allocating) when a level would exceed `options.limits`.
[[nodiscard]] AdaptiveMesh subdivide_adaptively(const Mesh& mesh, std::span<const std::uint8_t> selected,
                                                const SubdivisionOptions& options);

}  // namespace contourmesh
