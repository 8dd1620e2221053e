// SPDX-License-Identifier: BSD-3-Clause
// How far a surface is from drawn contours: the cross-section of a mesh with each slice plane compared
// with the contours drawn in that plane. See docs/contours.md.
#pragma once

#include "contourmesh/reconstruct/contours.h"

#include <contourmesh/smooth/mesh.h>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <vector>

namespace contourmesh {

/// One segment of a cross-section, in the stack's slice coordinates (u, v), mm. Oriented so that the
/// region inside the surface is on its left: an outer boundary runs counter-clockwise, seen from +w.
using SectionSegment = std::array<Eigen::Vector2d, 2>;

/// The cross-section of a triangle mesh with the plane w = `w` of `frame` (its origin and axes; the
/// slices are not used). A vertex exactly in the plane counts as above it (below it with
/// `just_above`), so a mesh whose vertices lie on the plane (a tiled mesh at its slice positions) is cut
/// once, along its edges in the plane, as if the plane were an infinitesimal step below (above).
[[nodiscard]] std::vector<SectionSegment> cross_section(const Mesh& mesh, const ContourStack& frame, double w,
                                                        bool just_above = false);

/// Area enclosed by a cross-section, mm^2 (outer boundaries count positive, holes negative).
[[nodiscard]] double section_area(const std::vector<SectionSegment>& section);

struct ContourDeviationOptions {
  /// Distances are measured from points this far apart (mm) along the section and along the contours,
  /// > 0; every vertex is measured too.
  double sample_step = 0.1;
};

/// Distances in the slice planes between a surface and the contours of a stack, mm.
struct ContourDeviation {
  /// Over both directions (section points to the nearest contour, contour points to the nearest
  /// section segment), weighted by arc length: the symmetric mean distance.
  double mean = 0.0;
  double rms = 0.0;
  double max = 0.0;  ///< the symmetric Hausdorff distance over the slices measured
  std::size_t slices = 0;  ///< slices with contours that were measured
  /// Slices with contours whose plane does not cut the mesh (a surface that shrank away from an end
  /// slice); not in the statistics above.
  std::size_t slices_without_section = 0;
  /// Per slice of the stack: the largest distance (0 for slices without contours, infinity for
  /// slices without a section).
  std::vector<double> slice_max;
};

/// Compares `mesh` with every slice of `contours` that holds contours: the mesh is cut with the slice
/// plane (cross_section) and distances are measured both ways in that plane. For a tiled mesh this
/// checks that tiling kept the contours; after smoothing it is the in-plane deviation from the drawn
/// contours. A slice whose plane cuts nothing just below is cut just above (a cap in the plane of the
/// lowest slice). Throws InvalidInputError for a sample step <= 0.
[[nodiscard]] ContourDeviation contour_deviation(const Mesh& mesh, const ContourStack& contours,
                                                 const ContourDeviationOptions& options = {});

}  // namespace contourmesh
