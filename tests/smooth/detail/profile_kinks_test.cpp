// SPDX-License-Identifier: BSD-3-Clause
// White-box tests of the kink test of the cross-slice smoother's profiles
// (libsmooth/src/detail/profile_kinks.h) and of lpa_ici bounded by it: analytic hinges and parabolas,
// and the false-alarm rate at a known noise level.
#include "detail/lpa_ici.h"
#include "detail/profile_kinks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace contourmesh::detail {
namespace {

// A hinge: slope `left` up to x = `at`, slope `right` beyond it, continuous; sampled at integers
// -8..8 shifted so that the vertex (x = 0) sits at `vertex` on the hinge's own axis. The truth at
// x = 0 is hinge(vertex).
double hinge(double u, double at, double left, double right) {
  return u <= at ? left * u : left * at + right * (u - at);
}

Profile hinge_profile(double vertex, double at, double left, double right) {
  Profile p;
  for (int k = -8; k <= 8; ++k) p.push(k, hinge(vertex + k, at, left, right) - hinge(vertex, at, left, right));
  return p;
}

LpaIciOptions options(double sigma, bool kinks) {
  LpaIciOptions o;
  o.sigma = sigma;
  o.gamma = 2.0;
  o.max_half_width = 8;
  o.kinks = kinks;
  o.kink_false_rate = 0.01;
  return o;
}

TEST(Chi2Quantile, MatchesTables) {
  EXPECT_NEAR(chi2_1_upper_quantile(0.05), 3.841459, 1e-5);
  EXPECT_NEAR(chi2_1_upper_quantile(0.01), 6.634897, 1e-5);
  EXPECT_NEAR(chi2_1_upper_quantile(0.001), 10.827566, 1e-5);
}

TEST(FindKink, LocatesTheHingeOfANoiseFreeProfile) {
  // A concave junction (a shaft meeting a flare): slope 0.1 then 0.9 per slice, the break at x = 3.
  const Profile p = hinge_profile(0.0, 3.0, 0.1, 0.9);
  KinkTestOptions o;
  o.sigma = 0.4;
  const Kink kink = find_kink(p, o);
  ASSERT_TRUE(kink.found);
  EXPECT_DOUBLE_EQ(kink.x, 3.0);
  EXPECT_GT(kink.statistic, chi2_1_upper_quantile(o.false_rate / kink.candidates));
  EXPECT_LT(kink.p_value, o.false_rate);
  EXPECT_EQ(kink.candidates, 13);  // -6..6: two samples beyond each
}

TEST(FindKink, FindsNoKinkOnAParabola) {
  Profile p;
  for (int k = -8; k <= 8; ++k) p.push(k, 0.2 * k + 0.05 * k * k - 0.3);
  KinkTestOptions o;
  o.sigma = 0.4;
  const Kink kink = find_kink(p, o);
  EXPECT_FALSE(kink.found);
  EXPECT_LT(kink.statistic, 1e-12);
}

TEST(FindKink, NeverReportsWithoutNoise) {
  // sigma 0: the noise-free guarantee (nothing is estimated, nothing is cut).
  const Profile p = hinge_profile(0.0, 3.0, 0.1, 0.9);
  KinkTestOptions o;
  o.sigma = 0.0;
  EXPECT_FALSE(find_kink(p, o).found);
}

TEST(LpaIciKinks, RecoversBothSidesOfAHingeExactly) {
  // Every vertex position on either side of the hinge, and on it: the side holding the vertex is a line,
  // fitted without bias; without the kink test the two-sided windows reaching across it are biased.
  double worst_bounded = 0.0, worst_plain = 0.0;
  for (int vertex = -5; vertex <= 5; ++vertex) {
    const Profile p = hinge_profile(vertex, 0.0, -0.6, 0.6);
    const LpaIciResult bounded = lpa_ici(p, options(0.1, true));
    const LpaIciResult plain = lpa_ici(p, options(0.1, false));
    ASSERT_TRUE(bounded.valid);
    EXPECT_GE(bounded.kinks, 1) << "vertex " << vertex;
    EXPECT_NEAR(bounded.value, 0.0, 1e-9) << "vertex " << vertex;
    worst_bounded = std::max(worst_bounded, std::abs(bounded.value));
    worst_plain = std::max(worst_plain, std::abs(plain.value));
  }
  EXPECT_GT(worst_plain, 0.05);  // the bias the test removes
}

TEST(LpaIciKinks, LeavesASmoothProfileAsItWas) {
  Profile p;
  for (int k = -8; k <= 8; ++k) p.push(k, 0.2 * k + 0.05 * k * k);
  const LpaIciResult bounded = lpa_ici(p, options(0.4, true));
  const LpaIciResult plain = lpa_ici(p, options(0.4, false));
  EXPECT_EQ(bounded.kinks, 0);
  EXPECT_DOUBLE_EQ(bounded.value, plain.value);
  EXPECT_EQ(bounded.symmetric, plain.symmetric);
}

TEST(LpaIciKinks, BoundsAProfileAtAKinkOnEachSide) {
  // A flat bottom between two walls (slope 0.8 per slice below x = -3 and beyond x = 5), at height 0.05:
  // the first kink found bounds the profile, the second bounds what is left (in place), and the flat
  // middle is fitted exactly. Without the kink test the windows reach the walls and lift the estimate.
  Profile p;
  for (int k = -8; k <= 8; ++k) p.push(k, 0.05 + 0.8 * std::max({-3.0 - k, k - 5.0, 0.0}));
  const LpaIciResult bounded = lpa_ici(p, options(0.1, true));
  const LpaIciResult plain = lpa_ici(p, options(0.1, false));
  ASSERT_TRUE(bounded.valid);
  EXPECT_EQ(bounded.kinks, 2);
  EXPECT_NEAR(bounded.value, 0.05, 1e-9);
  EXPECT_GT(std::abs(plain.value - 0.05), 0.05);
}

LpaIciOptions side_lines(double sigma, bool lines) {
  LpaIciOptions o = options(sigma, true);
  o.kink_side_lines = lines;
  return o;
}

TEST(LpaIciKinkSides, LinesLowerTheErrorAtAStraightHinge) {
  // A hinge between two straight sides (1.2 mm per slice each way: found at 0.4 mm of noise). With the
  // vertex on it only the one-sided windows are fitted, and lines fit them without bias and with less
  // variance than parabolas: the root-mean-square error drops. Beside it (one or two slices) the two-sided
  // windows of the side holding the vertex dominate, and the lines must not make it worse.
  std::mt19937 rng(21);
  std::normal_distribution<double> noise(0.0, 0.4);
  for (const int vertex : {0, -1, 2}) {
    double sum2_lines = 0.0, sum2_curves = 0.0;
    int both_found = 0;
    constexpr int kTrials = 2000;
    for (int t = 0; t < kTrials; ++t) {
      Profile p = hinge_profile(vertex, 0.0, -1.2, 1.2);
      for (int k = 0; k < p.size; ++k) p.y[static_cast<std::size_t>(k)] += noise(rng);
      const LpaIciResult lines = lpa_ici(p, side_lines(0.4, true));
      const LpaIciResult curves = lpa_ici(p, side_lines(0.4, false));
      ASSERT_TRUE(lines.valid && curves.valid);
      both_found += lines.kinks > 0 && curves.kinks > 0 ? 1 : 0;
      sum2_lines += lines.value * lines.value;
      sum2_curves += curves.value * curves.value;
    }
    const double rms_lines = std::sqrt(sum2_lines / kTrials), rms_curves = std::sqrt(sum2_curves / kTrials);
    EXPECT_GT(both_found, kTrials * 9 / 10) << "vertex " << vertex;
    EXPECT_LT(rms_lines, (vertex == 0 ? 0.85 : 1.0) * rms_curves) << "vertex " << vertex;
  }
}

TEST(LpaIciKinkSides, CurvedSidesKeepTheirParabolas) {
  // Two sides of the same curvature (0.3 mm per slice squared) with a slope break of 2 mm per slice
  // between them: the hinge model is exact, and a line on either side disagrees with its parabola by far
  // more than the noise (0.02 mm) allows, so the parabolas stay and every estimate is exact.
  for (const int vertex : {-2, 0, 1, 3}) {
    Profile p;
    const auto side = [](double u) { return 0.3 * u * u + (u <= 0.0 ? -1.0 : 1.0) * u; };
    for (int k = -8; k <= 8; ++k) p.push(k, side(vertex + k) - side(vertex));
    const LpaIciResult lines = lpa_ici(p, side_lines(0.02, true));
    ASSERT_TRUE(lines.valid);
    EXPECT_GE(lines.kinks, 1) << "vertex " << vertex;
    EXPECT_NEAR(lines.value, 0.0, 1e-9) << "vertex " << vertex;
  }
}

TEST(LpaIciKinkSides, AProfileWithoutAKinkIsFittedAsBefore) {
  std::mt19937 rng(22);
  std::normal_distribution<double> noise(0.0, 0.4);
  for (int t = 0; t < 200; ++t) {
    Profile p;
    for (int k = -8; k <= 8; ++k) p.push(k, 0.2 * k + 0.02 * k * k + noise(rng));
    const LpaIciResult lines = lpa_ici(p, side_lines(0.4, true));
    const LpaIciResult curves = lpa_ici(p, side_lines(0.4, false));
    if (lines.kinks > 0) continue;  // a false alarm (rate 0.01): a bounded profile
    EXPECT_EQ(lines.value, curves.value);
    EXPECT_EQ(lines.below, curves.below);
    EXPECT_EQ(lines.above, curves.above);
  }
}

// The rate of kinks found on kink-free parabolas with Gaussian noise of sigma.
double false_kink_rate(int half_width, double sigma, double alpha, int trials, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  KinkTestOptions o;
  o.sigma = sigma;
  o.false_rate = alpha;
  int found = 0;
  for (int t = 0; t < trials; ++t) {
    Profile p;
    for (int k = -half_width; k <= half_width; ++k) p.push(k, 0.03 * k * k - 0.1 * k + noise(rng));
    found += find_kink(p, o).found ? 1 : 0;
  }
  return static_cast<double>(found) / trials;
}

TEST(FindKink, SingleCandidateFalseRateIsAlpha) {
  // Five samples: one candidate hinge (the middle), so the statistic is exactly chi-square with one
  // degree of freedom and the rate is alpha (binomial standard deviation of 4000 trials at 0.05: 0.0034).
  const double rate = false_kink_rate(2, 0.4, 0.05, 4000, 11);
  EXPECT_NEAR(rate, 0.05, 0.012);
}

TEST(FindKink, ScannedFalseRateIsBoundedByAlpha) {
  // Seventeen samples, thirteen candidates: the Bonferroni bound keeps the rate at most alpha; the
  // candidates are strongly correlated, so it is not far below either.
  const double rate = false_kink_rate(8, 0.4, 0.05, 4000, 12);
  EXPECT_LE(rate, 0.05 + 0.01);
  EXPECT_GE(rate, 0.01);
}

}  // namespace
}  // namespace contourmesh::detail
