// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/divergence.h"

#include "contourmesh/smooth/errors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

namespace contourmesh {

DivergenceBounds DivergenceBounds::of(const Eigen::Matrix3Xd& reference) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (Eigen::Index i = 0; i < reference.cols(); ++i) {
    if (!reference.col(i).allFinite()) continue;
    lo = lo.cwiseMin(reference.col(i));
    hi = hi.cwiseMax(reference.col(i));
  }
  DivergenceBounds b;
  if (!(lo.array() <= hi.array()).all()) return b;  // nothing finite: every position fails the check
  b.centre = 0.5 * (lo + hi);
  const double diagonal = (hi - lo).norm();
  // A point-like input: allow a relative floor so that rounding alone never counts as divergence.
  b.radius = kDivergenceFactor * std::max(diagonal, 1e-9 * std::max(1.0, b.centre.cwiseAbs().maxCoeff()));
  return b;
}

void check_not_diverged(const Eigen::Matrix3Xd& positions, const DivergenceBounds& bounds, const std::string& stage,
                        int iteration) {
  const double r2 = bounds.radius * bounds.radius;
  for (Eigen::Index i = 0; i < positions.cols(); ++i) {
    const auto p = positions.col(i);
    const bool finite = p.allFinite();
    if (finite && (p - bounds.centre).squaredNorm() <= r2) continue;
    std::ostringstream msg;
    msg << stage << " diverged";
    if (iteration >= 0) msg << " at iteration " << iteration;
    msg << ": vertex " << i << " ";
    if (finite) {
      msg << "moved to (" << p.x() << ", " << p.y() << ", " << p.z() << "), more than " << kDivergenceFactor
          << " times the mesh's size from it";
    } else {
      msg << "has a non-finite coordinate (" << p.x() << ", " << p.y() << ", " << p.z() << ")";
    }
    msg << " (too many iterations, or too large a step, for this smoother)";
    throw DivergenceError(msg.str());
  }
}

IterationObserver divergence_guard(const Eigen::Matrix3Xd& reference, std::string stage, IterationObserver next) {
  const DivergenceBounds bounds = DivergenceBounds::of(reference);
  return [bounds, stage = std::move(stage), next = std::move(next)](int iteration, const Eigen::Matrix3Xd& p) {
    check_not_diverged(p, bounds, stage, iteration);
    if (next) next(iteration, p);
  };
}

}  // namespace contourmesh
