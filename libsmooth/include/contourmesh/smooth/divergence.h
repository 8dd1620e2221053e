// SPDX-License-Identifier: BSD-3-Clause
// Guards against diverged results: an iterative smoother run for too many iterations or with too large
// a step grows high frequencies until the coordinates overflow. A result like that must be an error
// (DivergenceError), never a mesh written with exit status 0.
#pragma once

#include "contourmesh/smooth/mesh.h"
#include "contourmesh/smooth/smoothing.h"

#include <Eigen/Core>

#include <string>

namespace contourmesh {

/// A result counts as diverged when a vertex lies farther than this many times the input's
/// bounding-box diagonal from the input's bounding-box centre. Smoothing moves vertices towards their
/// neighbours: no converging smoother comes near it.
inline constexpr double kDivergenceFactor = 10.0;

/// The region a result must stay in: the input's bounding box grown by kDivergenceFactor.
struct DivergenceBounds {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0.0;  ///< kDivergenceFactor x the diagonal (a small floor for a point-like input)

  /// The bounds of `reference` (3 x n; non-finite columns ignored).
  [[nodiscard]] static DivergenceBounds of(const Eigen::Matrix3Xd& reference);
};

/// Throws DivergenceError when a column of `positions` is non-finite or outside `bounds`. The message
/// names `stage`, the iteration when `iteration` >= 0, the first such vertex and its position, and
/// suggests fewer iterations or a smaller step.
void check_not_diverged(const Eigen::Matrix3Xd& positions, const DivergenceBounds& bounds, const std::string& stage,
                        int iteration = -1);

/// An IterationObserver (SmoothingOptions::on_iteration, FeatureSmoothingOptions::on_iteration) that
/// runs check_not_diverged after every iteration, so a diverging run stops at once, then calls `next`.
/// Every column is checked against the bounds of `reference` (for the paper's method the adaptive mesh,
/// whose added vertices lie among the input's).
[[nodiscard]] IterationObserver divergence_guard(const Eigen::Matrix3Xd& reference, std::string stage,
                                                 IterationObserver next = {});

}  // namespace contourmesh
