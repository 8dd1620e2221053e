// SPDX-License-Identifier: BSD-3-Clause
#include "detail/lpa_ici.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace contourmesh::detail {

void Profile::sort() {
  for (int i = 1; i < size; ++i) {
    const double xi = x[static_cast<std::size_t>(i)], yi = y[static_cast<std::size_t>(i)];
    int j = i - 1;
    while (j >= 0 && x[static_cast<std::size_t>(j)] > xi) {
      x[static_cast<std::size_t>(j) + 1] = x[static_cast<std::size_t>(j)];
      y[static_cast<std::size_t>(j) + 1] = y[static_cast<std::size_t>(j)];
      --j;
    }
    x[static_cast<std::size_t>(j + 1)] = xi;
    y[static_cast<std::size_t>(j + 1)] = yi;
  }
}

namespace {

// Running sums of one window: S_p = sum x^p (p <= 4), T_a = sum x^a y (a <= 2).
struct Moments {
  double s[5] = {0, 0, 0, 0, 0};
  double t[3] = {0, 0, 0};
  int distinct = 0;  // samples added (profiles hold distinct x)
  void add(double x, double y) {
    const double x2 = x * x;
    s[0] += 1.0;
    s[1] += x;
    s[2] += x2;
    s[3] += x2 * x;
    s[4] += x2 * x2;
    t[0] += y;
    t[1] += x * y;
    t[2] += x2 * y;
    ++distinct;
  }
  Moments operator+(const Moments& o) const {
    Moments m = *this;
    for (int k = 0; k < 5; ++k) m.s[k] += o.s[k];
    for (int k = 0; k < 3; ++k) m.t[k] += o.t[k];
    m.distinct += o.distinct;
    return m;
  }
};

// Least-squares parabola through the window, evaluated at 0: value and (M^-1)_00, the variance factor.
inline bool fit_parabola(const Moments& m, double& value, double& variance) {
  if (m.distinct < 3) return false;
  const double a = m.s[0], b = m.s[1], c = m.s[2], d = m.s[3], e = m.s[4];
  // M = [[a b c] [b c d] [c d e]]; cofactors of the first row give the first row of M^-1 * det.
  const double c00 = c * e - d * d, c01 = -(b * e - c * d), c02 = b * d - c * c;
  const double det = a * c00 + b * c01 + c * c02;
  const double scale = std::max({a * c * e, b * b * e, 1e-300});
  if (!(std::abs(det) > 1e-9 * scale)) return false;
  value = (c00 * m.t[0] + c01 * m.t[1] + c02 * m.t[2]) / det;
  variance = c00 / det;
  return std::isfinite(value) && variance > 0.0;
}

// Least-squares line through the window, evaluated at 0. On a window symmetric about 0 this is the mean
// (variance 1 / n), and unlike the mean it follows a sloped profile without bias.
bool fit_mean(const Moments& m, double& value, double& variance) {
  if (m.distinct < 1) return false;
  value = m.t[0] / m.s[0];
  variance = 1.0 / m.s[0];
  return true;
}

bool fit_line(const Moments& m, double& value, double& variance) {
  if (m.distinct < 2) return false;
  const double det = m.s[0] * m.s[2] - m.s[1] * m.s[1];
  if (!(det > 1e-9 * std::max(m.s[0] * m.s[2], 1e-300))) return false;
  value = (m.s[2] * m.t[0] - m.s[1] * m.t[1]) / det;
  variance = m.s[2] / det;
  return std::isfinite(value);
}

// The window kinds: below (x <= 0), above (x >= 0), and over both sides a parabola, a line, the mean.
enum Kind { kBelow = 0, kAbove = 1, kSymmetric = 2, kLine = 3, kMean = 4, kKinds = 5 };

// The ICI state of one window kind.
struct Grown {
  double value = 0.0, variance = -1.0;  // variance < 0: nothing fitted yet
  double lower = -std::numeric_limits<double>::infinity(), upper = std::numeric_limits<double>::infinity();
  int half_width = 0;
  bool stopped = false;

  // Offers the estimate of the window of half-width h; stops the kind when the intervals part.
  void offer(double value_h, double variance_h, int h, const LpaIciOptions& o) {
    const double s = o.sigma * std::sqrt(variance_h);
    const double lo = std::max(lower, value_h - o.gamma * s), hi = std::min(upper, value_h + o.gamma * s);
    if (lo > hi) {
      stopped = true;
      return;
    }
    lower = lo;
    upper = hi;
    value = value_h;
    variance = variance_h;
    half_width = h;
  }
};

}  // namespace

LpaIciResult lpa_ici(const Profile& p, const LpaIciOptions& o) {
  LpaIciResult r;
  int centre = -1;
  for (int k = 0; k < p.size; ++k) {
    if (std::abs(p.x[static_cast<std::size_t>(k)]) < 1e-9) {
      centre = k;
      break;
    }
  }
  if (centre < 0) return r;
  r.value = p.y[static_cast<std::size_t>(centre)];
  // All kinds grow together, one unit of x per step, from the same running moments of each side.
  Moments down, up;  // the samples below and above the centre taken so far
  Moments centre_only;
  centre_only.add(0.0, r.value);
  std::array<Grown, kKinds> g;
  int lo = centre - 1, hi = centre + 1;
  for (int h = 1; h <= o.max_half_width; ++h) {
    const double reach = static_cast<double>(h) + 0.5;
    bool added_down = false, added_up = false;
    while (lo >= 0 && p.x[static_cast<std::size_t>(lo)] >= -reach) {
      down.add(p.x[static_cast<std::size_t>(lo)], p.y[static_cast<std::size_t>(lo)]);
      --lo;
      added_down = true;
    }
    while (hi < p.size && p.x[static_cast<std::size_t>(hi)] <= reach) {
      up.add(p.x[static_cast<std::size_t>(hi)], p.y[static_cast<std::size_t>(hi)]);
      ++hi;
      added_up = true;
    }
    // Only the windows still growing are summed and fitted (stopped kinds keep their last estimate).
    const bool grow_below = added_down && !g[kBelow].stopped, grow_above = added_up && !g[kAbove].stopped;
    const bool grow_symmetric = !g[kSymmetric].stopped, grow_line = o.symmetric_mean && !g[kLine].stopped,
               grow_mean = o.symmetric_mean && !g[kMean].stopped;
    const bool grow_both = (added_down || added_up) && (grow_symmetric || grow_line || grow_mean);
    double value = 0.0, variance = 0.0;
    if (grow_below || grow_both) {
      const Moments below = centre_only + down;
      if (grow_below && fit_parabola(below, value, variance)) g[kBelow].offer(value, variance, h, o);
      if (grow_both) {
        const Moments both = below + up;
        if (grow_symmetric && fit_parabola(both, value, variance)) g[kSymmetric].offer(value, variance, h, o);
        if (grow_line && fit_line(both, value, variance)) g[kLine].offer(value, variance, h, o);
        if (grow_mean && fit_mean(both, value, variance)) g[kMean].offer(value, variance, h, o);
      }
    }
    if (grow_above && fit_parabola(centre_only + up, value, variance)) g[kAbove].offer(value, variance, h, o);
    const bool more = lo >= 0 || hi < p.size;
    if (!more) break;
    bool all_stopped = true;
    for (const Grown& k : g) all_stopped = all_stopped && k.stopped;
    if (all_stopped) break;
  }
  // The line or the mean (whichever is more precise) replaces the parabola where it agrees with it: a
  // straight profile, or a flat one seen from one side near a profile's end (lower variance than the
  // line on a lopsided window).
  Grown symmetric = g[kSymmetric];
  if (symmetric.variance > 0.0) {
    const double tolerance = o.gamma * o.sigma * std::sqrt(symmetric.variance);
    const Grown* best = nullptr;
    for (const Grown* simpler : std::array<const Grown*, 2>{&g[kLine], &g[kMean]}) {
      if (simpler->variance > 0.0 && simpler->variance < symmetric.variance &&
          std::abs(simpler->value - symmetric.value) <= tolerance &&
          (best == nullptr || simpler->variance < best->variance)) {
        best = simpler;
      }
    }
    if (best != nullptr) symmetric = *best;
  }
  double num = 0.0, den = 0.0;
  for (const Grown* k : std::array<const Grown*, 3>{&g[kBelow], &g[kAbove], &symmetric}) {
    if (k->variance <= 0.0) continue;
    num += k->value / k->variance;
    den += 1.0 / k->variance;
  }
  r.below = g[kBelow].half_width;
  r.above = g[kAbove].half_width;
  r.symmetric = symmetric.half_width;
  if (den > 0.0) {
    r.value = num / den;
    r.variance = 1.0 / den;
    r.valid = true;
  }
  return r;
}

}  // namespace contourmesh::detail
