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
};

// Least-squares parabola through the window, evaluated at 0: value and (M^-1)_00, the variance factor.
bool fit_parabola(const Moments& m, double& value, double& variance) {
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

bool fit_mean(const Moments& m, double& value, double& variance) {
  if (m.distinct < 1) return false;
  value = m.t[0] / m.s[0];
  variance = 1.0 / m.s[0];
  return true;
}

// One window kind grown by ICI. `next_below` / `next_above` walk outwards from the centre.
struct Grown {
  double value = 0.0, variance = -1.0;  // variance < 0: nothing fitted
  double lower = -std::numeric_limits<double>::infinity(), upper = std::numeric_limits<double>::infinity();
  int half_width = 0;
};

template <typename Fit>
Grown grow(const Profile& p, int centre, bool down, bool up, const LpaIciOptions& o, Fit fit) {
  Grown g;
  Moments m;
  m.add(p.x[static_cast<std::size_t>(centre)], p.y[static_cast<std::size_t>(centre)]);
  int lo = centre - 1, hi = centre + 1;
  double lower = -std::numeric_limits<double>::infinity(), upper = std::numeric_limits<double>::infinity();
  for (int h = 1; h <= o.max_half_width; ++h) {
    const double reach = static_cast<double>(h) + 0.5;
    bool added = false;
    if (down) {
      while (lo >= 0 && p.x[static_cast<std::size_t>(lo)] >= -reach) {
        m.add(p.x[static_cast<std::size_t>(lo)], p.y[static_cast<std::size_t>(lo)]);
        --lo;
        added = true;
      }
    }
    if (up) {
      while (hi < p.size && p.x[static_cast<std::size_t>(hi)] <= reach) {
        m.add(p.x[static_cast<std::size_t>(hi)], p.y[static_cast<std::size_t>(hi)]);
        ++hi;
        added = true;
      }
    }
    if (!added) {
      if (!(down && lo >= 0) && !(up && hi < p.size)) break;  // the profile ends: the window cannot grow
      continue;
    }
    double value = 0.0, variance = 0.0;
    if (!fit(m, value, variance)) continue;
    const double s = o.sigma * std::sqrt(variance);
    lower = std::max(lower, value - o.gamma * s);
    upper = std::min(upper, value + o.gamma * s);
    if (lower > upper) break;
    g.value = value;
    g.variance = variance;
    g.lower = lower;
    g.upper = upper;
    g.half_width = h;
  }
  return g;
}

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
  const Grown below = grow(p, centre, true, false, o, fit_parabola);
  const Grown above = grow(p, centre, false, true, o, fit_parabola);
  Grown symmetric = grow(p, centre, true, true, o, fit_parabola);
  if (o.symmetric_mean && symmetric.variance > 0.0) {
    const Grown mean = grow(p, centre, true, true, o, fit_mean);
    if (mean.variance > 0.0 && mean.variance < symmetric.variance &&
        std::abs(mean.value - symmetric.value) <= o.gamma * o.sigma * std::sqrt(symmetric.variance)) {
      symmetric = mean;
    }
  }
  double num = 0.0, den = 0.0;
  for (const Grown* g : std::array<const Grown*, 3>{&below, &above, &symmetric}) {
    if (g->variance <= 0.0) continue;
    num += g->value / g->variance;
    den += 1.0 / g->variance;
  }
  r.below = below.half_width;
  r.above = above.half_width;
  r.symmetric = symmetric.half_width;
  if (den > 0.0) {
    r.value = num / den;
    r.variance = 1.0 / den;
    r.valid = true;
  }
  return r;
}

}  // namespace contourmesh::detail
