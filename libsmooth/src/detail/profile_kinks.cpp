// SPDX-License-Identifier: BSD-3-Clause
#include "detail/profile_kinks.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace contourmesh::detail {

double chi2_1_upper_quantile(double p) {
  // P(chi2_1 > z^2) = P(|N(0,1)| > z) = erfc(z / sqrt 2): bisection on z (erfc is decreasing).
  p = std::clamp(p, 1e-300, 1.0);
  double lo = 0.0, hi = 40.0;
  for (int it = 0; it < 200 && hi - lo > 1e-12 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::sqrt(2.0)) > p ? lo : hi) = mid;
  }
  const double z = 0.5 * (lo + hi);
  return z * z;
}

Kink find_kink(const Profile& p, const KinkTestOptions& o) {
  Kink kink;
  if (!(o.sigma > 0.0) || !(o.false_rate > 0.0 && o.false_rate < 1.0)) return kink;
  const int min_side = std::max(o.min_side, 2);
  // The samples taking part: a contiguous run of the sorted profile.
  int first = 0, last = p.size - 1;
  while (first < p.size && p.x[static_cast<std::size_t>(first)] < -o.max_abs_x) ++first;
  while (last >= 0 && p.x[static_cast<std::size_t>(last)] > o.max_abs_x) --last;
  const int n = last - first + 1;
  const int k_begin = first + min_side, k_end = last - min_side;  // candidate hinges, inclusive
  if (n < 5 || k_begin > k_end) return kink;
  // The null model: one parabola. Its normal matrix, inverse and residuals.
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (int j = first; j <= last; ++j) {
    const double x = p.x[static_cast<std::size_t>(j)], y = p.y[static_cast<std::size_t>(j)];
    const Eigen::Vector3d row(1.0, x, x * x);
    normal += row * row.transpose();
    rhs += y * row;
  }
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(normal);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 1e-9 * ldlt.vectorD().maxCoeff())) return kink;
  const Eigen::Vector3d beta = ldlt.solve(rhs);
  double residual[kMaxProfile];
  for (int j = first; j <= last; ++j) {
    const double x = p.x[static_cast<std::size_t>(j)];
    residual[j] = p.y[static_cast<std::size_t>(j)] - (beta[0] + beta[1] * x + beta[2] * x * x);
  }
  // Each hinge h = (x - x_k)_+: with the null residuals r orthogonal to the parabola's columns, adding h
  // lowers the residual sum of squares by (h . r)^2 / |h - P h|^2, |h - P h|^2 = h . h - (X^T h)^T M^-1 X^T h.
  const double sigma2 = o.sigma * o.sigma;
  double best = 0.0;
  for (int k = k_begin; k <= k_end; ++k) {
    const double xk = p.x[static_cast<std::size_t>(k)];
    Eigen::Vector3d xh = Eigen::Vector3d::Zero();
    double hh = 0.0, hr = 0.0;
    for (int j = k + 1; j <= last; ++j) {
      const double x = p.x[static_cast<std::size_t>(j)], h = x - xk;
      xh += h * Eigen::Vector3d(1.0, x, x * x);
      hh += h * h;
      hr += h * residual[j];
    }
    ++kink.candidates;
    const double orthogonal = hh - xh.dot(ldlt.solve(xh));
    if (!(orthogonal > 1e-9 * hh)) continue;
    const double drop = hr * hr / orthogonal / sigma2;
    if (drop > best) {
      best = drop;
      kink.index = k;
      kink.x = xk;
    }
  }
  if (kink.candidates == 0) return kink;
  kink.statistic = best;
  kink.threshold = chi2_1_upper_quantile(o.false_rate / kink.candidates);
  kink.found = kink.index >= 0 && best > kink.threshold;
  return kink;
}

}  // namespace contourmesh::detail
