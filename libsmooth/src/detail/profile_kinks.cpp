// SPDX-License-Identifier: BSD-3-Clause
#include "detail/profile_kinks.h"

#include <Eigen/Core>

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
  // The null model: one parabola. Its normal matrix (Moments), its inverse from the cofactors (the matrix
  // is symmetric, and so is the inverse) and the coefficients.
  Moments m;
  for (int j = first; j <= last; ++j) m.add(p.x[static_cast<std::size_t>(j)], p.y[static_cast<std::size_t>(j)]);
  const double a = m.s[0], b = m.s[1], c = m.s[2], d = m.s[3], e = m.s[4];
  const double i00 = c * e - d * d, i01 = c * d - b * e, i02 = b * d - c * c;
  const double i11 = a * e - c * c, i12 = b * c - a * d, i22 = a * c - b * b;
  const double det = a * i00 + b * i01 + c * i02;
  // Three distinct abscissae at least (n >= 5 distinct samples here): a well-posed parabola.
  if (!(det > 1e-9 * std::max({a * c * e, b * b * e, 1e-300}))) return kink;
  const double inv_det = 1.0 / det;
  const Eigen::Matrix3d inverse =
      (Eigen::Matrix3d() << i00, i01, i02, i01, i11, i12, i02, i12, i22).finished() * inv_det;
  const Eigen::Vector3d beta = inverse * Eigen::Vector3d(m.t[0], m.t[1], m.t[2]);
  // Each hinge h = (x - x_k)_+: with the null residuals r orthogonal to the parabola's columns, adding h
  // lowers the residual sum of squares by (h . r)^2 / |h - P h|^2, |h - P h|^2 = h . h - (X^T h)^T M^-1 X^T h.
  // All three from sums over the samples beyond x_k of x^p (p <= 3), r and x r, grown from the last sample
  // down: (X^T h)_p = S_{p+1} - x_k S_p, h . h = S_2 - 2 x_k S_1 + x_k^2 S_0, h . r = R_1 - x_k R_0.
  const double sigma2 = o.sigma * o.sigma;
  double best = 0.0;
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0, r0 = 0, r1 = 0;
  for (int j = last; j > k_end; --j) {
    const double x = p.x[static_cast<std::size_t>(j)];
    const double r = p.y[static_cast<std::size_t>(j)] - (beta[0] + beta[1] * x + beta[2] * x * x);
    s0 += 1.0, s1 += x, s2 += x * x, s3 += x * x * x, r0 += r, r1 += x * r;
  }
  for (int k = k_end; k >= k_begin; --k) {
    const double xk = p.x[static_cast<std::size_t>(k)];
    const Eigen::Vector3d xh(s1 - xk * s0, s2 - xk * s1, s3 - xk * s2);
    const double hh = s2 - 2.0 * xk * s1 + xk * xk * s0;
    const double hr = r1 - xk * r0;
    ++kink.candidates;
    const double orthogonal = hh - xh.dot(inverse * xh);
    if (orthogonal > 1e-9 * hh) {
      // Compared before the division by sigma^2, which is monotone: one division on the loop's critical
      // path instead of two (the loop is bound by their latency).
      const double drop = hr * hr / orthogonal;
      if (drop > best) {
        best = drop;
        kink.index = k;
        kink.x = xk;
      }
    }
    // Sample k joins the sums for the next hinge down.
    const double r = p.y[static_cast<std::size_t>(k)] - (beta[0] + beta[1] * xk + beta[2] * xk * xk);
    s0 += 1.0, s1 += xk, s2 += xk * xk, s3 += xk * xk * xk, r0 += r, r1 += xk * r;
  }
  if (kink.candidates == 0) return kink;
  best /= sigma2;
  kink.statistic = best;
  // P(chi2_1 > t) = erfc(sqrt(t / 2)), times the candidates (Bonferroni): one erfc, no quantile.
  kink.p_value = std::min(1.0, kink.candidates * std::erfc(std::sqrt(0.5 * best)));
  kink.found = kink.index >= 0 && kink.p_value < o.false_rate;
  return kink;
}

}  // namespace contourmesh::detail
