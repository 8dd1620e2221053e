// SPDX-License-Identifier: BSD-3-Clause
// White-box tests of the profile fits of the cross-slice smoother (libsmooth/src/detail/lpa_ici.h): the
// circle model against analytic arcs and lines, and its fallback to the parabola.
#include "detail/lpa_ici.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace contourmesh::detail {
namespace {

constexpr double kSpacing = 2.0;  // mm per x unit, as between CT slices

// The great circle of a sphere of `radius` (mm) through a vertex at height `z0` (mm) from the equator,
// as a cross-slice profile: x in slice spacings from the vertex, y the in-slice offset (mm) from the
// vertex, over up to `reach` slices each way inside the sphere. The truth at x = 0 is 0.
Profile sphere_profile(double radius, double z0, int reach) {
  Profile p;
  const double r0 = std::sqrt(radius * radius - z0 * z0);
  for (int k = -reach; k <= reach; ++k) {
    const double z = z0 + k * kSpacing;
    if (std::abs(z) >= radius - 0.5) continue;
    p.push(k, std::sqrt(radius * radius - z * z) - r0);
  }
  return p;
}

LpaIciOptions options(bool circle, double sigma) {
  LpaIciOptions o;
  o.sigma = sigma;
  o.gamma = 2.0;
  o.max_half_width = 8;
  o.circle = circle;
  o.x_unit = kSpacing;
  return o;
}

TEST(FitCircle, ReproducesAnExactArc) {
  // A circle of 13 mm centred off the axes, sampled at x = -5..5 (x in units of 2 mm): the fit is exact.
  const double cx = 1.3, cy = 12.2, radius = 13.0;
  CircleSums sums;
  for (int k = -5; k <= 5; ++k) {
    const double u = k * kSpacing;
    sums.add(k, cy - std::sqrt(radius * radius - (u - cx) * (u - cx)), kSpacing);
  }
  double value = 0.0, variance = 0.0;
  ASSERT_TRUE(fit_circle(sums, kSpacing, value, variance));
  EXPECT_NEAR(value, cy - std::sqrt(radius * radius - cx * cx), 1e-9);
  EXPECT_GT(variance, 0.0);
  EXPECT_LT(variance, 1.0);  // eleven samples: more precise than one
}

TEST(FitCircle, IsTheLineOnAStraightProfile) {
  CircleSums sums;
  for (int k = -4; k <= 4; ++k) sums.add(k, 0.7 - 0.3 * k, kSpacing);
  double value = 0.0, variance = 0.0;
  ASSERT_TRUE(fit_circle(sums, kSpacing, value, variance));
  EXPECT_NEAR(value, 0.7, 1e-12);
}

TEST(FitCircle, RefusesACircleThatDoesNotHoldTheWindow) {
  // Samples on a circle of 2 mm (one unit) far from x = 0: it neither reaches x = 0 nor holds the
  // window as a graph. The caller falls back to the parabola.
  CircleSums sums;
  for (const double t : {-1.2, -0.6, 0.0, 0.6, 1.2}) {
    sums.add(4.0 + std::sin(t), kSpacing * (1.0 - std::cos(t)), kSpacing);
  }
  double value = 0.0, variance = 0.0;
  EXPECT_FALSE(fit_circle(sums, kSpacing, value, variance));
}

TEST(FitCircle, RefusesTooFewOrRepeatedSamples) {
  CircleSums sums;
  sums.add(0.0, 0.0, kSpacing);
  sums.add(1.0, 0.5, kSpacing);
  double value = 0.0, variance = 0.0;
  EXPECT_FALSE(fit_circle(sums, kSpacing, value, variance));
  sums.add(1.0, 0.5, kSpacing);  // three samples, two distinct
  EXPECT_FALSE(fit_circle(sums, kSpacing, value, variance));
}

TEST(LpaIciCircle, ReproducesASphereProfile) {
  // The great circle of a 13 mm sphere (the femur's head), at the equator and at two latitudes whose
  // profiles slope by up to 0.5 (read as they are, not rotated): exact with every window.
  for (const double z0 : {0.0, 3.0, -5.0}) {
    const Profile p = sphere_profile(13.0, z0, 8);
    const LpaIciResult r = lpa_ici(p, options(true, 0.05));
    ASSERT_TRUE(r.valid);
    EXPECT_NEAR(r.value, 0.0, 1e-9) << "z0 " << z0;
    EXPECT_GE(r.symmetric, 5) << "z0 " << z0;  // nothing stops the symmetric window early
  }
}

TEST(LpaIciCircle, IsExactOnAStraightProfile) {
  Profile p;
  for (int k = -8; k <= 8; ++k) p.push(k, 0.25 * k);
  const LpaIciResult circle = lpa_ici(p, options(true, 0.3));
  const LpaIciResult parabola = lpa_ici(p, options(false, 0.3));
  ASSERT_TRUE(circle.valid);
  EXPECT_NEAR(circle.value, 0.0, 1e-12);
  EXPECT_NEAR(circle.value, parabola.value, 1e-12);
}

TEST(LpaIciCircle, FallsBackToTheParabolaWhereNoCircleFits) {
  // A sharp tent (a crease across the slices): every window's circle is refused or well posed; either
  // way the estimate stays within the samples' range, as the parabola's does.
  Profile p;
  for (int k = -8; k <= 8; ++k) p.push(k, -3.0 * std::abs(k));
  const LpaIciResult circle = lpa_ici(p, options(true, 0.3));
  const LpaIciResult parabola = lpa_ici(p, options(false, 0.3));
  ASSERT_TRUE(circle.valid);
  EXPECT_LE(std::abs(circle.value), std::max(std::abs(parabola.value), 1.0));
}

TEST(LpaIciCircle, NoisyStraightProfilesDoNotBlowUp) {
  // Near-straight noisy profiles: the circle degenerates to the line (c2 near 0), never to a huge
  // or tiny circle; its errors stay of the parabola's size.
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.4);
  double worst_circle = 0.0, worst_parabola = 0.0, sum2_circle = 0.0, sum2_parabola = 0.0;
  constexpr int kTrials = 2000;
  for (int trial = 0; trial < kTrials; ++trial) {
    Profile p;
    const double slope = 0.1 * (trial % 7 - 3);
    for (int k = -8; k <= 8; ++k) p.push(k, slope * k * kSpacing + noise(rng));
    const double truth = 0.0;
    const LpaIciResult c = lpa_ici(p, options(true, 0.4));
    const LpaIciResult q = lpa_ici(p, options(false, 0.4));
    ASSERT_TRUE(c.valid && std::isfinite(c.value));
    worst_circle = std::max(worst_circle, std::abs(c.value - truth));
    worst_parabola = std::max(worst_parabola, std::abs(q.value - truth));
    sum2_circle += (c.value - truth) * (c.value - truth);
    sum2_parabola += (q.value - truth) * (q.value - truth);
  }
  EXPECT_LT(worst_circle, 1.5 * worst_parabola);
  EXPECT_LT(std::sqrt(sum2_circle / kTrials), 1.2 * std::sqrt(sum2_parabola / kTrials));
}

TEST(LpaIciCircle, BiasOnANoiseFreeSphereDrops) {
  // Windows grown for 0.4 mm of contour noise on noise-free sphere profiles (radius 13-15 mm, latitudes
  // up to 5 mm): the parabola's bias is the limit the circle removes.
  double bias_parabola = 0.0, bias_circle = 0.0;
  for (const double radius : {13.0, 15.0}) {
    for (const double z0 : {-5.0, -2.0, 0.0, 1.0, 4.0}) {
      const Profile p = sphere_profile(radius, z0, 8);
      bias_parabola = std::max(bias_parabola, std::abs(lpa_ici(p, options(false, 0.4)).value));
      bias_circle = std::max(bias_circle, std::abs(lpa_ici(p, options(true, 0.4)).value));
    }
  }
  EXPECT_GT(bias_parabola, 0.05);
  EXPECT_LT(bias_circle, 0.25 * bias_parabola);
}

}  // namespace
}  // namespace contourmesh::detail
