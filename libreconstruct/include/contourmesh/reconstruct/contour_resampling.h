// SPDX-License-Identifier: BSD-3-Clause
// Resampling of drawn contours: evenly spaced points that keep the drawn shape within a tolerance.
// See docs/contours.md.
#pragma once

#include "contourmesh/reconstruct/contours.h"

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace contourmesh {

/// Resamples a drawn closed polygon (at least 3 points) to points about `spacing` mm apart while keeping
/// its shape within `tolerance` mm: runs of points that stay within `tolerance` of the chord joining
/// their ends (chords at most `spacing` long) are replaced by the chord, then chords longer than
/// `spacing` are split evenly. Drawn corners are kept; every output point lies on the input polygon.
/// Hand-drawn contours mix points 0.1 mm and 10 mm apart; the tiler's triangles, its refined caps and
/// the smoothing's umbrella operator want them about evenly spaced. `spacing` > 0, `tolerance` >= 0.
[[nodiscard]] std::vector<Eigen::Vector2d> resample_drawn(const std::vector<Eigen::Vector2d>& polygon, double spacing,
                                                          double tolerance);

/// What resample_drawn_stack did.
struct ResamplingReport {
  std::size_t points_before = 0;
  std::size_t points_after = 0;
  std::size_t exact_fallbacks = 0;  ///< contours only subdivided (simplifying them made contours meet)
};

/// resample_drawn on every contour of a normalised stack, then edges longer than 1.4 times the mean
/// edge of their outer contour split further, so that an outer contour and its holes are about evenly
/// sampled (the tiler's refined caps place interior vertices one mean edge apart). A contour whose
/// simplification would make it, or its slice, intersect is subdivided only (its points all kept).
/// Orientation, holes and parents are unchanged.
ResamplingReport resample_drawn_stack(ContourStack& stack, double spacing, double tolerance);

}  // namespace contourmesh
