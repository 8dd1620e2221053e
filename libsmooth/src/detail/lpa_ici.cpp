// SPDX-License-Identifier: BSD-3-Clause
#include "detail/lpa_ici.h"

#include "detail/profile_kinks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

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

}  // namespace

void CircleSums::add(double x, double y, double x_unit) {
  const double yn = y / x_unit;
  const double w = x * x + yn * yn;
  s1 += 1.0;
  sx += x;
  sxx += x * x;
  sw += w;
  sxw += x * w;
  sww += w * w;
  ty += y;
  txy += x * y;
  twy += w * y;
  min_x = std::min(min_x, x);
  max_x = std::max(max_x, x);
  max_abs_yn = std::max(max_abs_yn, std::abs(yn));
  ++count;
}

CircleSums CircleSums::operator+(const CircleSums& o) const {
  CircleSums m = *this;
  m.s1 += o.s1;
  m.sx += o.sx;
  m.sxx += o.sxx;
  m.sw += o.sw;
  m.sxw += o.sxw;
  m.sww += o.sww;
  m.ty += o.ty;
  m.txy += o.txy;
  m.twy += o.twy;
  m.min_x = std::min(min_x, o.min_x);
  m.max_x = std::max(max_x, o.max_x);
  m.max_abs_yn = std::max(max_abs_yn, o.max_abs_yn);
  m.count += o.count;
  return m;
}

bool fit_circle(const CircleSums& m, double x_unit, double& value, double& variance) {
  if (m.count < 4 || !(x_unit > 0.0)) return false;
  // M = [[s1 sx sw] [sx sxx sxw] [sw sxw sww]], symmetric; its inverse from the cofactors.
  const double a = m.s1, b = m.sx, c = m.sw, d = m.sxx, e = m.sxw, f = m.sww;
  const double i00 = d * f - e * e, i01 = c * e - b * f, i02 = b * e - c * d;
  const double i11 = a * f - c * c, i12 = b * c - a * e, i22 = a * d - b * b;
  const double det = a * i00 + b * i01 + c * i02;
  const double scale = std::max({a * d * f, b * b * f, c * c * d, 1e-300});
  if (!(std::abs(det) > 1e-9 * scale)) return false;
  // Coefficients of y (in y's unit) = C0 + C1 x + C2 w; in units of x_unit, c_k = C_k / x_unit.
  const double c0 = (i00 * m.ty + i01 * m.txy + i02 * m.twy) / det / x_unit;
  const double c1 = (i01 * m.ty + i11 * m.txy + i12 * m.twy) / det / x_unit;
  const double c2 = (i02 * m.ty + i12 * m.txy + i22 * m.twy) / det / x_unit;
  const double disc = 1.0 - 4.0 * c0 * c2;
  if (!(disc >= 0.25)) return false;
  // Every sample on the near half of the circle (|yn| at most about the radius 1 / (2 |c2|)): a sample's
  // algebraic residual moves by 1 - 2 c2 yn per unit of its noise, which stays within [0, 2].
  if (2.0 * std::abs(c2) * m.max_abs_yn > 1.0) return false;
  // The circle must hold the window as a graph: its centre's abscissa -c1 / (2 c2) within its radius
  // sqrt(1 + c1^2 - 4 c0 c2) / (2 |c2|) of every sample's.
  if (c2 != 0.0) {
    const double root = std::sqrt(1.0 + c1 * c1 - 4.0 * c0 * c2);
    const double lo = -c1 - root, hi = -c1 + root;  // 2 c2 (centre -+ radius), ordered for c2 > 0
    const double x_lo = 2.0 * c2 * (c2 > 0.0 ? m.min_x : m.max_x), x_hi = 2.0 * c2 * (c2 > 0.0 ? m.max_x : m.min_x);
    if (x_lo < lo || x_hi > hi) return false;
  }
  const double yn0 = 2.0 * c0 / (1.0 + std::sqrt(disc));
  // Linearised: d yn0 = (d c0 + yn0^2 d c2) / (1 - 2 c2 yn0); in y's unit d y0 = d C0 + (yn0^2 / x_unit) d C2
  // over the same factor, with Var(C) = sigma^2 M^-1.
  const double g = 1.0 / (1.0 - 2.0 * c2 * yn0);
  const double j0 = g, j2 = g * yn0 * yn0 / x_unit;
  value = yn0 * x_unit;
  variance = (j0 * j0 * i00 + 2.0 * j0 * j2 * i02 + j2 * j2 * i22) / det;
  return std::isfinite(value) && std::isfinite(variance) && variance > 0.0;
}

namespace {

// The window kinds: below (x <= 0), above (x >= 0), over both sides a parabola, a line, the mean, and
// lines below and above (options.one_sided_lines).
enum Kind { kBelow = 0, kAbove = 1, kSymmetric = 2, kLine = 3, kMean = 4, kBelowLine = 5, kAboveLine = 6, kKinds = 7 };

// The ICI state of one window kind.
struct Grown {
  double value = 0.0, variance = -1.0;  // variance < 0: nothing fitted yet
  double lower = -std::numeric_limits<double>::infinity(), upper = std::numeric_limits<double>::infinity();
  int half_width = 0;
  bool stopped = false;

  // Offers the estimate of the window of half-width h; stops the kind when the intervals part. Inlined by
  // request: called five times a step in the hottest loop of the smoothing, where the compiler's own choice
  // varied with the rest of the unity build (out of line it cost lpa_ici 12 % more instructions).
  [[gnu::always_inline]] void offer(double value_h, double variance_h, int h, const LpaIciOptions& o) {
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

// A one-sided line replaces its side's curve where it agrees with it within gamma of the curve's
// deviation and is more precise. A side too short for a curve gets no line either: a line through the
// vertex and one more sample is the vertex itself, already counted by the other windows.
void prefer_line(const Grown& line, const LpaIciOptions& o, Grown& curve) {
  if (line.variance > 0.0 && curve.variance > 0.0 && line.variance < curve.variance &&
      std::abs(line.value - curve.value) <= o.gamma * o.sigma * std::sqrt(curve.variance)) {
    curve = line;
  }
}

}  // namespace

namespace {

// The estimator, with the circle model compiled in or out: the parabola-only instantiation is the code
// it was before the circle model existed (the default's cost and output unchanged).
template <bool kCircle>
LpaIciResult lpa_ici_impl(const Profile& p, const LpaIciOptions& o) {
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
  CircleSums circle_down, circle_up, circle_centre;  // the same for the circle model (kCircle only)
  if constexpr (kCircle) circle_centre.add(0.0, r.value, o.x_unit);
  std::array<Grown, kKinds> g;
  if (!o.two_sided) g[kSymmetric].stopped = g[kLine].stopped = g[kMean].stopped = true;
  if (!o.one_sided_lines) g[kBelowLine].stopped = g[kAboveLine].stopped = true;
  int lo = centre - 1, hi = centre + 1;
  for (int h = 1; h <= o.max_half_width; ++h) {
    const double reach = static_cast<double>(h) + 0.5;
    bool added_down = false, added_up = false;
    while (lo >= 0 && p.x[static_cast<std::size_t>(lo)] >= -reach) {
      const double xs = p.x[static_cast<std::size_t>(lo)], ys = p.y[static_cast<std::size_t>(lo)];
      down.add(xs, ys);
      if constexpr (kCircle) circle_down.add(xs, ys, o.x_unit);
      --lo;
      added_down = true;
    }
    while (hi < p.size && p.x[static_cast<std::size_t>(hi)] <= reach) {
      const double xs = p.x[static_cast<std::size_t>(hi)], ys = p.y[static_cast<std::size_t>(hi)];
      up.add(xs, ys);
      if constexpr (kCircle) circle_up.add(xs, ys, o.x_unit);
      ++hi;
      added_up = true;
    }
    // Only the windows still growing are summed and fitted (stopped kinds keep their last estimate).
    const bool grow_below = added_down && !g[kBelow].stopped, grow_above = added_up && !g[kAbove].stopped;
    const bool grow_symmetric = !g[kSymmetric].stopped, grow_line = o.symmetric_mean && !g[kLine].stopped,
               grow_mean = o.symmetric_mean && !g[kMean].stopped;
    const bool grow_both = (added_down || added_up) && (grow_symmetric || grow_line || grow_mean);
    double value = 0.0, variance = 0.0;
    if (added_down && !g[kBelowLine].stopped && fit_line(centre_only + down, value, variance)) {
      g[kBelowLine].offer(value, variance, h, o);
    }
    if (added_up && !g[kAboveLine].stopped && fit_line(centre_only + up, value, variance)) {
      g[kAboveLine].offer(value, variance, h, o);
    }
    // The curved model of a window: its circle where that is well posed (o.circle), else its parabola.
    // (Without kCircle the sums are never read and the calls reduce to fit_parabola.)
    const auto fit_curve = [&](const Moments& m, const CircleSums& c) {
      if (!fit_parabola(m, value, variance)) return false;
      double circle_value = 0.0, circle_variance = 0.0;
      if (kCircle && fit_circle(c, o.x_unit, circle_value, circle_variance)) {
        // The circle's linearised variance leaves out the noise inside w; where that matters it is
        // below the truth, so the parabola's variance on the same window (equal to first order in
        // c2 yn: the same design with x^2 for w) is its floor.
        value = circle_value;
        variance = std::max(variance, circle_variance);
      }
      return true;
    };
    if (grow_below || grow_both) {
      const Moments below = centre_only + down;
      const CircleSums circle_below = kCircle ? circle_centre + circle_down : circle_centre;
      if (grow_below && fit_curve(below, circle_below)) g[kBelow].offer(value, variance, h, o);
      if (grow_both) {
        const Moments both = below + up;
        const CircleSums circle_both = kCircle ? circle_below + circle_up : circle_centre;
        if (grow_symmetric && fit_curve(both, circle_both)) g[kSymmetric].offer(value, variance, h, o);
        if (grow_line && fit_line(both, value, variance)) g[kLine].offer(value, variance, h, o);
        if (grow_mean && fit_mean(both, value, variance)) g[kMean].offer(value, variance, h, o);
      }
    }
    if (grow_above && fit_curve(centre_only + up, kCircle ? circle_centre + circle_up : circle_centre)) {
      g[kAbove].offer(value, variance, h, o);
    }
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
  if (o.one_sided_lines) {
    prefer_line(g[kBelowLine], o, g[kBelow]);
    prefer_line(g[kAboveLine], o, g[kAbove]);
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

}  // namespace

LpaIciResult lpa_ici(const Profile& p, const LpaIciOptions& o) {
  const auto fit = [&](const Profile& q, const LpaIciOptions& oq) {
    return oq.circle ? lpa_ici_impl<true>(q, oq) : lpa_ici_impl<false>(q, oq);
  };
  if (!o.kinks || !(o.sigma > 0.0)) return fit(p, o);
  KinkTestOptions test;
  test.sigma = o.sigma;
  test.false_rate = o.kink_false_rate;
  test.max_abs_x = static_cast<double>(o.max_half_width) + 0.5;
  // The profile is copied only where a kink bounds it (most profiles have none).
  std::optional<Profile> bounded;
  const Profile* current = &p;
  LpaIciOptions local = o;
  int found = 0;
  for (; found < 3; ++found) {
    const Kink kink = find_kink(*current, test);
    if (!kink.found) break;
    if (std::abs(kink.x) < 1e-9) {  // the vertex is the kink: each side extrapolates to it
      local.two_sided = false;
      ++found;
      break;
    }
    // Keep the side holding x = 0, up to and with the hinge's sample: a contiguous run of the sorted
    // profile, moved to the front of the bounded copy (in place from the second kink on: the run starts
    // at or after the front, so copying forward reads each sample before it is overwritten).
    const int begin = kink.x > 0.0 ? 0 : kink.index, end = kink.x > 0.0 ? kink.index + 1 : current->size;
    if (!bounded) bounded.emplace();
    Profile& side = *bounded;
    for (int k = begin; k < end; ++k) {
      side.x[static_cast<std::size_t>(k - begin)] = current->x[static_cast<std::size_t>(k)];
      side.y[static_cast<std::size_t>(k - begin)] = current->y[static_cast<std::size_t>(k)];
    }
    side.size = end - begin;
    current = &side;
  }
  local.one_sided_lines = o.one_sided_lines || (o.kink_side_lines && found > 0);
  LpaIciResult r = fit(*current, local);
  r.kinks = found;
  return r;
}

}  // namespace contourmesh::detail
