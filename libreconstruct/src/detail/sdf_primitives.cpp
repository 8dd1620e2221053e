// SPDX-License-Identifier: BSD-3-Clause
#include "detail/sdf_primitives.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace contourmesh::detail {

namespace {

// Root of G(s) = sum_i (r_i z_i / (s + r_i))^2 - 1 for Eberly's normalised closest-point problem on an
// ellipse (N = 2) or ellipsoid (N = 3), with r_{N-1} = 1 and z_{N-1} > 0. G is convex and decreasing on
// s > -1; the root is bracketed by [z_{N-1} - 1, 0] inside and [0, |r z| - 1] outside. Safeguarded
// Newton (monotone from the left), with bisection steps when it is slow.
template <std::size_t N>
double ellipsoid_root(const std::array<double, N>& r, const std::array<double, N>& z, double g) {
  std::array<double, N> n{};
  double scale = 0.0;
  for (std::size_t i = 0; i < N; ++i) {
    n[i] = r[i] * z[i];
    scale = std::max(scale, std::abs(n[i]));
  }
  double lo = z[N - 1] - 1.0;
  double hi = 0.0;
  if (g > 0.0) {
    double sum = 0.0;
    for (std::size_t i = 0; i < N; ++i) sum += (n[i] / scale) * (n[i] / scale);
    hi = scale * std::sqrt(sum) - 1.0;
  }
  double s = std::clamp(0.0, lo, hi);
  for (int iteration = 0; iteration < 200; ++iteration) {
    double value = -1.0;
    double slope = 0.0;
    for (std::size_t i = 0; i < N; ++i) {
      const double q = n[i] / (s + r[i]);
      value += q * q;
      slope -= 2.0 * q * q / (s + r[i]);
    }
    if (std::abs(value) <= 1e-15) return s;
    if (value > 0.0) {
      lo = s;
    } else {
      hi = s;
    }
    double next = s - value / slope;
    if (!(next > lo && next < hi) || (iteration >= 8 && iteration % 2 == 1)) next = 0.5 * (lo + hi);
    const double tolerance = 1e-15 * (1.0 + std::abs(s));
    if (std::abs(next - s) <= tolerance || hi - lo <= tolerance) return next;
    s = next;
  }
  return s;
}

// Distance from (y0, y1), y >= 0, to the ellipse with semi-axes e0 >= e1 > 0 (Eberly).
double ellipse_distance_sorted(double e0, double e1, double y0, double y1) {
  if (y1 > 0.0) {
    if (y0 > 0.0) {
      const double z0 = y0 / e0;
      const double z1 = y1 / e1;
      const double g = z0 * z0 + z1 * z1 - 1.0;
      if (g == 0.0) return 0.0;
      const double r0 = (e0 / e1) * (e0 / e1);
      const double s = ellipsoid_root<2>({r0, 1.0}, {z0, z1}, g);
      const double x0 = r0 * y0 / (s + r0);
      const double x1 = y1 / (s + 1.0);
      return length2(x0 - y0, x1 - y1);
    }
    return std::abs(y1 - e1);
  }
  const double numer0 = e0 * y0;
  const double denom0 = e0 * e0 - e1 * e1;
  if (numer0 < denom0) {
    const double xde0 = numer0 / denom0;
    const double x0 = e0 * xde0;
    const double x1 = e1 * std::sqrt(std::max(0.0, 1.0 - xde0 * xde0));
    return length2(x0 - y0, x1);
  }
  return std::abs(y0 - e0);
}

// Distance from y >= 0 to the ellipsoid with semi-axes e0 >= e1 >= e2 > 0 (Eberly).
double ellipsoid_distance_sorted(double e0, double e1, double e2, double y0, double y1, double y2) {
  if (y2 > 0.0) {
    if (y1 > 0.0) {
      if (y0 > 0.0) {
        const double z0 = y0 / e0;
        const double z1 = y1 / e1;
        const double z2 = y2 / e2;
        const double g = z0 * z0 + z1 * z1 + z2 * z2 - 1.0;
        if (g == 0.0) return 0.0;
        const double r0 = (e0 / e2) * (e0 / e2);
        const double r1 = (e1 / e2) * (e1 / e2);
        const double s = ellipsoid_root<3>({r0, r1, 1.0}, {z0, z1, z2}, g);
        const double x0 = r0 * y0 / (s + r0);
        const double x1 = r1 * y1 / (s + r1);
        const double x2 = y2 / (s + 1.0);
        return std::sqrt((x0 - y0) * (x0 - y0) + (x1 - y1) * (x1 - y1) + (x2 - y2) * (x2 - y2));
      }
      return ellipse_distance_sorted(e1, e2, y1, y2);
    }
    if (y0 > 0.0) return ellipse_distance_sorted(e0, e2, y0, y2);
    return std::abs(y2 - e2);
  }
  const double denom0 = e0 * e0 - e2 * e2;
  const double denom1 = e1 * e1 - e2 * e2;
  const double numer0 = e0 * y0;
  const double numer1 = e1 * y1;
  if (numer0 < denom0 && numer1 < denom1) {
    const double xde0 = numer0 / denom0;
    const double xde1 = numer1 / denom1;
    const double discr = 1.0 - xde0 * xde0 - xde1 * xde1;
    if (discr > 0.0) {
      const double x0 = e0 * xde0;
      const double x1 = e1 * xde1;
      const double x2 = e2 * std::sqrt(discr);
      return std::sqrt((x0 - y0) * (x0 - y0) + (x1 - y1) * (x1 - y1) + x2 * x2);
    }
  }
  return ellipse_distance_sorted(e0, e1, y0, y1);
}

}  // namespace

double Ellipse::signed_distance(const Vec2& p) const {
  const double y0 = std::abs(p.x() - centre.x());
  const double y1 = std::abs(p.y() - centre.y());
  const double d = axes.x() >= axes.y() ? ellipse_distance_sorted(axes.x(), axes.y(), y0, y1)
                                        : ellipse_distance_sorted(axes.y(), axes.x(), y1, y0);
  const double u = y0 / axes.x();
  const double v = y1 / axes.y();
  return u * u + v * v < 1.0 ? -d : d;
}

Ellipsoid::Ellipsoid(const Vec3& c, const Vec3& a) : centre(c), axes(a) {
  std::sort(order.begin(), order.end(), [&](int i, int j) { return axes[i] > axes[j]; });
}

double Ellipsoid::signed_distance(const Vec3& p) const {
  const Vec3 y = (p - centre).cwiseAbs();
  const double d =
      ellipsoid_distance_sorted(axes[order[0]], axes[order[1]], axes[order[2]], y[order[0]], y[order[1]], y[order[2]]);
  return y.cwiseQuotient(axes).squaredNorm() < 1.0 ? -d : d;
}

std::pair<double, double> Ellipsoid::distance_bounds(const Vec3& p) const {
  const double k = (p - centre).cwiseQuotient(axes).norm();
  const double e_min = axes[order[2]], e_max = axes[order[0]];
  return k >= 1.0 ? std::pair{e_min * (k - 1.0), e_max * (k - 1.0)} : std::pair{e_max * (k - 1.0), e_min * (k - 1.0)};
}

}  // namespace contourmesh::detail
