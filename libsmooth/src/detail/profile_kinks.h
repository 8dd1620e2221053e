// SPDX-License-Identifier: BSD-3-Clause
// Change points in a profile (for the cross-slice smoother, docs/smoothing.md, "Kinks in the profiles"):
// a slope break, where two parts of a surface meet at a concave or convex junction, which no smooth
// local model fits and which biases every window reaching across it.
//
// The test pools the whole profile: one parabola y = a + b x + c x^2 against the same parabola plus a
// hinge d (x - x_k)_+ joined at sample k (continuous, with a slope break d), scanned over the samples
// with at least `min_side` samples strictly beyond the hinge on each side. With the noise's standard
// deviation sigma known, the drop of the residual sum of squares at a fixed k, divided by sigma^2, is
// chi-square with one degree of freedom where there is no kink; the maximum over the m candidates is
// compared with the (1 - alpha / m) quantile (a Bonferroni bound), so a kink-free profile with Gaussian
// noise reports a kink with probability at most alpha.
#pragma once

#include "detail/lpa_ici.h"

namespace contourmesh::detail {

struct KinkTestOptions {
  double sigma = 0.0;            ///< noise standard deviation of y; <= 0: no kink is ever reported
  double false_rate = 0.01;      ///< alpha, the largest probability of a kink on a kink-free profile, in (0, 1)
  int min_side = 2;              ///< samples needed strictly on each side of a candidate hinge, >= 2
  double max_abs_x = 8.5;        ///< only samples with |x| <= this take part
};

struct Kink {
  bool found = false;
  int index = -1;          ///< the hinge's sample index in the profile
  double x = 0.0;          ///< its abscissa
  double statistic = 0.0;  ///< the largest drop of the residual sum of squares over sigma^2
  double p_value = 1.0;    ///< its probability on a kink-free profile, times the candidates (Bonferroni)
  int candidates = 0;      ///< hinges scanned
};

/// The (1 - p) quantile of chi-square with one degree of freedom, p in (0, 1): the statistic a kink
/// needs among m candidates at false rate alpha is chi2_1_upper_quantile(alpha / m).
[[nodiscard]] double chi2_1_upper_quantile(double p);

/// The most significant slope break of `profile` (sorted by x), or found = false.
[[nodiscard]] Kink find_kink(const Profile& profile, const KinkTestOptions& options);

}  // namespace contourmesh::detail
