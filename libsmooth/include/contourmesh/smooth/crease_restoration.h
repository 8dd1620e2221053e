// SPDX-License-Identifier: BSD-3-Clause
// Creases that the image's blur rounded, made sharp again (docs/smoothing.md, "Creases rounded by the
// image's blur"). Thresholding a blurred image rounds a convex crease inwards and fills a concave one:
// for a right angle and a Gaussian blur of sigma, the iso-level passes 0.77 sigma inside the corner.
// Where crease detection labelled an edge, this step refines the mesh there and moves the vertices near
// the crease onto the two planes that meet in it.
//
// 1. Subdivision: `levels` spoke bisections around the vertices labelled Edge whose ball (step 2, on the
//    input mesh) fits two planes with the mesh rounded inside them (`min_rounding`)
//    (subdivide_adaptively, the paper's adaptive subdivision): new vertices come after the input's, which
//    keep their order. Labels without two planes (gentle or noisy folds, corners: most of a real scan's)
//    or where the mesh is already sharp leave the mesh as it is.
// 2. For each such input vertex and each new vertex, its ball on the refined mesh: the vertices within
//    `radius` connected to it through such vertices. Their normals are split in two by 2-means, seeded
//    with the extremes along the middle eigenvector of the ball's normal tensor, and each side's normal
//    is the mode of its normals: the mean of those within `mode_angle_degrees` of it, four rounds (a
//    plain mean is pulled towards the other side by the rounded part).
// 3. Each side's plane passes through the area-weighted mean offset of its vertices within
//    `mode_angle_degrees` of its normal and within `slab` of the vertex along the crease (a longer
//    stretch of a curved wall would put the plane inside it by the arc's sagitta).
// 4. A vertex moves only where the planes meet at `min_angle_degrees` or more, no third plane holds more
//    than `max_third_share` of the ball (a corner), each fits its vertices to
//    `max_residual` RMS, and the vertex lies within `max_line_distance` of their line. With signed
//    distances d0, d1 to the planes, a convex crease's surface is max(d0, d1) = 0 and a concave one's
//    min(d0, d1) = 0: a vertex inside both planes of a convex crease moves onto the nearer one, or onto
//    their line where it lies about as deep below both (`line_ratio`); one outside both onto their
//    line (mirrored for a concave crease). Vertices with contour ids move within
//    their slice plane only (along the chosen plane's in-plane normal); no move exceeds `max_move`.
// Every vertex's move is computed from the subdivided mesh's positions before any moves (Jacobi), so
// the result does not depend on the order or on the number of threads.
#pragma once

#include "contourmesh/smooth/feature_detection.h"
#include "contourmesh/smooth/mesh.h"

#include <cstddef>
#include <vector>

namespace contourmesh {

/// Whether cross-slice smoothing restores the creases of its result (CrossSliceOptions).
enum class CreaseRestoration {
  None,       ///< the result keeps the input's connectivity (the default)
  Subdivide,  ///< restore_creases on the result and its edge labels: more vertices, the input's first
};

struct CreaseRestorationOptions {
  int levels = 1;                    ///< spoke bisections around the edge vertices, in [0, 3]
  double radius = 2.5;               ///< mm, the ball of the plane fits, > 0
  double mode_angle_degrees = 12.0;  ///< a side's normals within this of its mode fit its plane, (0, 45]
  double slab = 0.8;                 ///< mm along the crease that a plane's offset is fitted over, > 0
  double min_angle_degrees = 40.0;   ///< least angle between the two planes' normals, (0, 180)
  double max_residual = 0.1;         ///< mm, the largest RMS distance of a side's vertices to its plane, > 0
  double max_line_distance = 1.0;    ///< mm, the farthest a moving vertex lies from the planes' line, > 0
  double max_move = 0.6;             ///< mm, the longest move, > 0
  /// A ball where normals more than 30 degrees out of the plane of the two sides' normals hold more
  /// than this share of the area is a corner (three planes): no move there, in [0, 1].
  double max_third_share = 0.05;
  /// mm: an edge vertex whose ball fits two planes is refined and moved only where it or a vertex of its
  /// 1-ring lies inside both planes (a convex crease; outside both, a concave one) by more than this:
  /// elsewhere the mesh is already sharp and new vertices would not move. >= 0. Default 0.03: on the
  /// phantoms 2-35 % fewer vertices than without the test, the same accuracy (docs/smoothing.md).
  double min_rounding = 0.03;
  /// A vertex inside both planes of a convex crease (outside both, concave), at depths a <= b below
  /// them, moves onto their line where a >= line_ratio b (near the bisector), else onto the nearer
  /// plane; in [0, 1]. Default 0.4: feature RMS up to 4 % lower than with 1 (which puts every such
  /// vertex on a plane), within 0.3 % on femur, two-objects and cavity (docs/smoothing.md).
  double line_ratio = 0.4;
};

struct RestoredCreases {
  /// The subdivided mesh with the vertices near the creases moved: the input's vertices first, in order,
  /// then the new ones (ids kNoId, or the contour's where a new vertex halves an edge of one contour).
  Mesh mesh;
  Index original_vertices = 0;
  std::size_t moved = 0;  ///< vertices moved
};

/// Restores the creases of `mesh` at its vertices labelled VertexLabel::Edge (`labels`: one per vertex,
/// e.g. CrossSliceResult::labels). Meshes with contour ids keep their contour vertices on their slice
/// planes (the slice axis from estimate_slice_axis; without ids, or where it cannot be estimated, every
/// vertex moves freely). Throws InvalidInputError for labels of the wrong size or options out of range.
[[nodiscard]] RestoredCreases restore_creases(const Mesh& mesh, const std::vector<VertexLabel>& labels,
                                              const CreaseRestorationOptions& options = {});

}  // namespace contourmesh
