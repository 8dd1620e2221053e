#include "reconstruct/phantom.h"

#include "reconstruct/volume.h"

#include <smooth/errors.h>
#include <smooth/limits.h>

#include <itkDiscreteGaussianImageFilter.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <unordered_map>
#include <utility>

namespace contourmesh {

namespace {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;
using Box3 = Eigen::AlignedBox3d;

constexpr double kPi = std::numbers::pi;

// sqrt(x^2 + y^2) without std::hypot's overflow care (slow, and not needed at millimetre scales).
double length2(double x, double y) { return std::sqrt(x * x + y * y); }

// ---------------------------------------------------------------------------------------------------
// Exact signed distances of the primitives (negative inside).

double sd_sphere(const Vec3& p, const Vec3& centre, double radius) { return (p - centre).norm() - radius; }

double sd_capsule(const Vec3& p, const Vec3& a, const Vec3& b, double radius) {
  const Vec3 ab = b - a;
  const Vec3 ap = p - a;
  const double h = std::clamp(ap.dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (ap - h * ab).norm() - radius;
}

// A 2-D signed distance `d2` extruded along an axis: `w` is the axial coordinate from the middle, the
// solid spans |w| <= half_height. Exact when d2 is.
double sd_extrude(double d2, double w, double half_height) {
  const double qx = d2;
  const double qy = std::abs(w) - half_height;
  return std::min(std::max(qx, qy), 0.0) + length2(std::max(qx, 0.0), std::max(qy, 0.0));
}

// Exact signed distance to a simple polygon (any orientation), after Inigo Quilez.
double sd_polygon(const Vec2& p, const std::vector<Vec2>& v) {
  double d = (p - v[0]).squaredNorm();
  double s = 1.0;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i, ++i) {
    const Vec2 e = v[j] - v[i];
    const Vec2 w = p - v[i];
    const Vec2 b = w - e * std::clamp(w.dot(e) / e.squaredNorm(), 0.0, 1.0);
    d = std::min(d, b.squaredNorm());
    const bool c0 = p.y() >= v[i].y();
    const bool c1 = p.y() < v[j].y();
    const bool c2 = e.x() * w.y() > e.y() * w.x();
    if ((c0 && c1 && c2) || (!c0 && !c1 && !c2)) s = -s;
  }
  return s * std::sqrt(d);
}

double polygon_area(const std::vector<Vec2>& v) {
  double a = 0.0;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i, ++i) a += v[j].x() * v[i].y() - v[i].x() * v[j].y();
  return 0.5 * a;
}

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

// An axis-aligned ellipse in a plane, with its exact signed distance.
struct Ellipse {
  Vec2 centre;
  Vec2 axes;  // semi-axes along the two plane axes

  [[nodiscard]] double signed_distance(const Vec2& p) const {
    const double y0 = std::abs(p.x() - centre.x());
    const double y1 = std::abs(p.y() - centre.y());
    const double d = axes.x() >= axes.y() ? ellipse_distance_sorted(axes.x(), axes.y(), y0, y1)
                                          : ellipse_distance_sorted(axes.y(), axes.x(), y1, y0);
    const double u = y0 / axes.x();
    const double v = y1 / axes.y();
    return u * u + v * v < 1.0 ? -d : d;
  }
};

// An axis-aligned ellipsoid with its exact signed distance.
struct Ellipsoid {
  Vec3 centre;
  Vec3 axes;                          // semi-axes along x, y, z
  std::array<int, 3> order{0, 1, 2};  // axes sorted by decreasing length

  Ellipsoid(const Vec3& c, const Vec3& a) : centre(c), axes(a) {
    std::sort(order.begin(), order.end(), [&](int i, int j) { return axes[i] > axes[j]; });
  }

  [[nodiscard]] double signed_distance(const Vec3& p) const {
    const Vec3 y = (p - centre).cwiseAbs();
    const double d = ellipsoid_distance_sorted(axes[order[0]], axes[order[1]], axes[order[2]], y[order[0]], y[order[1]],
                                               y[order[2]]);
    return y.cwiseQuotient(axes).squaredNorm() < 1.0 ? -d : d;
  }

  // Cheap bounds of signed_distance(p): with k = |(p - c) / axes|, the distance lies between
  // e_min |k - 1| and e_max |k - 1| (scaling by 1/axes is Lipschitz with constant 1/e_min, and p / k is on
  // the surface), with the sign of k - 1.
  [[nodiscard]] std::pair<double, double> distance_bounds(const Vec3& p) const {
    const double k = (p - centre).cwiseQuotient(axes).norm();
    const double e_min = axes[order[2]], e_max = axes[order[0]];
    return k >= 1.0 ? std::pair{e_min * (k - 1.0), e_max * (k - 1.0)} : std::pair{e_max * (k - 1.0), e_min * (k - 1.0)};
  }
};

// ---------------------------------------------------------------------------------------------------
// Numerical tools on signed distance fields.

Vec3 numeric_gradient(const ScalarField& f, const Vec3& p, double h) {
  Vec3 g;
  for (int i = 0; i < 3; ++i) {
    Vec3 e = Vec3::Zero();
    e[i] = h;
    g[i] = (f(p + e) - f(p - e)) / (2.0 * h);
  }
  return g;
}

VectorField normal_field(const ScalarField& sdf) {
  return [sdf](const Vec3& p) -> Vec3 {
    const Vec3 g = numeric_gradient(sdf, p, 1e-4);
    const double n = g.norm();
    if (!(n > 1e-12) || !std::isfinite(n)) return Vec3::UnitZ();
    return g / n;
  };
}

// Volume of {sdf < 0} inside `box` by an adaptive octree: |sdf| is a lower bound of the distance to the
// surface, so a cell whose centre is farther than its half-diagonal is wholly inside or outside. Cells
// straddling the surface are refined down to cubes of side <= `leaf`, whose inside fraction is estimated
// from the signed distance at the centre (exact for a plane normal to an axis, unbiased otherwise). With
// leaf = 0.5 mm the error on the shapes with an analytic volume is below 2e-4 (it falls as leaf^2).
double integrate_volume(const ScalarField& sdf, const Box3& box, double leaf) {
  const Vec3 centre = box.center();
  double side = box.sizes().maxCoeff();
  int levels = 0;
  while (side > leaf) {
    side *= 0.5;
    ++levels;
  }
  // A top cube of side leaf * 2^levels around the box.
  const double top_half = 0.5 * side * std::pow(2.0, levels);

  struct Integrator {
    const ScalarField& f;
    double cell(const Vec3& c, double half, int level) const {
      const double d = f(c);
      const double half_diagonal = half * std::sqrt(3.0);
      const double volume = 8.0 * half * half * half;
      if (d >= half_diagonal) return 0.0;
      if (d <= -half_diagonal) return volume;
      if (level == 0) return volume * std::clamp(0.5 - d / (2.0 * half), 0.0, 1.0);
      const double q = 0.5 * half;
      double sum = 0.0;
      for (int k = 0; k < 8; ++k) {
        const Vec3 offset((k & 1) ? q : -q, (k & 2) ? q : -q, (k & 4) ? q : -q);
        sum += cell(c + offset, q, level - 1);
      }
      return sum;
    }
  };
  const Integrator integrator{sdf};
  // The eight top children run in parallel when threads are available.
  std::array<double, 8> parts{};
  const double q = 0.5 * top_half;
  auto run = [&](int k) {
    const Vec3 offset((k & 1) ? q : -q, (k & 2) ? q : -q, (k & 4) ? q : -q);
    parts[static_cast<std::size_t>(k)] = levels > 0 ? integrator.cell(centre + offset, q, levels - 1) : 0.0;
  };
  if (levels == 0) return integrator.cell(centre, top_half, 0);
  const unsigned threads = std::clamp(std::thread::hardware_concurrency(), 1u, 8u);
  if (threads <= 1) {
    for (int k = 0; k < 8; ++k) run(k);
  } else {
    std::atomic<int> next{0};
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) {
      pool.emplace_back([&] {
        for (int k = next++; k < 8; k = next++) run(k);
      });
    }
    for (std::thread& t : pool) t.join();
  }
  double total = 0.0;
  for (double v : parts) total += v;
  return total;
}

// Projects `p` onto the curve {f = 0, g = 0} by Gauss-Newton with the minimum-norm step. Fails when
// the surfaces are nearly tangent or the iteration does not converge.
std::optional<Vec3> project_to_curve(const ScalarField& f, const ScalarField& g, Vec3 p) {
  for (int iteration = 0; iteration < 30; ++iteration) {
    const double fv = f(p);
    const double gv = g(p);
    if (std::abs(fv) < 1e-10 && std::abs(gv) < 1e-10) return p;
    Eigen::Matrix<double, 2, 3> jacobian;
    jacobian.row(0) = numeric_gradient(f, p, 1e-6).transpose();
    jacobian.row(1) = numeric_gradient(g, p, 1e-6).transpose();
    const Eigen::Matrix2d normal_matrix = jacobian * jacobian.transpose();
    if (normal_matrix.determinant() < 1e-4) return std::nullopt;
    const Vec3 step = jacobian.transpose() * normal_matrix.inverse() * Vec2(fv, gv);
    if (!(step.norm() < 2.0)) return std::nullopt;
    p -= step;
  }
  return std::nullopt;
}

// Samples the intersection curves of the zero sets of `f` and `g` that lie on the surface of `whole`,
// searching `box` with an octree down to cells of side ~0.25 mm and projecting their centres.
void intersection_curves(const ScalarField& f, const ScalarField& g, const ScalarField& whole, const Box3& box,
                         std::vector<Vec3>& out) {
  if (box.isEmpty()) return;
  constexpr double kLeafHalf = 0.125;
  struct Search {
    const ScalarField& f;
    const ScalarField& g;
    const ScalarField& whole;
    std::vector<Vec3>& out;
    void cell(const Vec3& c, const Vec3& half) const {
      const double half_diagonal = half.norm();
      if (std::abs(f(c)) > half_diagonal || std::abs(g(c)) > half_diagonal || std::abs(whole(c)) > half_diagonal) {
        return;
      }
      if (half.maxCoeff() <= kLeafHalf) {
        const auto p = project_to_curve(f, g, c);
        if (p && (*p - c).norm() < 2.0 * half_diagonal && std::abs(whole(*p)) < 1e-8) out.push_back(*p);
        return;
      }
      const Vec3 q = 0.5 * half;
      for (int k = 0; k < 8; ++k) {
        const Vec3 offset((k & 1) ? q.x() : -q.x(), (k & 2) ? q.y() : -q.y(), (k & 4) ? q.z() : -q.z());
        cell(c + offset, q);
      }
    }
  };
  const Search search{f, g, whole, out};
  search.cell(box.center(), 0.5 * box.sizes());
}

// Greedy thinning: keeps a point unless a kept point lies within `radius`. On a densely sampled curve
// consecutive kept points are at most 2 * radius apart.
std::vector<Vec3> thin_points(const std::vector<Vec3>& points, double radius) {
  auto key = [radius](const Vec3& p) {
    const auto c = (p / radius).array().floor().cast<std::int64_t>();
    return std::array<std::int64_t, 3>{c[0], c[1], c[2]};
  };
  auto hash = [](const std::array<std::int64_t, 3>& k) {
    const auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
    return static_cast<std::size_t>((u(k[0]) * 73856093u) ^ (u(k[1]) * 19349663u) ^ (u(k[2]) * 83492791u));
  };
  std::unordered_map<std::array<std::int64_t, 3>, std::vector<std::size_t>, decltype(hash)> grid(points.size() + 1,
                                                                                                 hash);
  std::vector<Vec3> kept;
  const double r2 = radius * radius;
  for (const Vec3& p : points) {
    const auto k = key(p);
    bool near = false;
    for (int dx = -1; dx <= 1 && !near; ++dx) {
      for (int dy = -1; dy <= 1 && !near; ++dy) {
        for (int dz = -1; dz <= 1 && !near; ++dz) {
          const auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == grid.end()) continue;
          for (std::size_t idx : it->second) {
            if ((kept[idx] - p).squaredNorm() < r2) {
              near = true;
              break;
            }
          }
        }
      }
    }
    if (near) continue;
    grid[k].push_back(kept.size());
    kept.push_back(p);
  }
  return kept;
}

// ---------------------------------------------------------------------------------------------------
// Feature sampling.

constexpr double kFeatureSpacing = 0.4;  // mm between consecutive samples of an analytic feature curve

// Samples the curve `c(t)`, t in [0, 1], finely (`fine` steps), keeping a point whenever it is at least
// kFeatureSpacing from the last kept one and on the surface of `whole`.
template <typename Curve>
void sample_curve(const Curve& c, int fine, const ScalarField& whole, std::vector<Vec3>& out) {
  bool have_last = false;
  Vec3 last = Vec3::Zero();
  for (int i = 0; i <= fine; ++i) {
    const Vec3 p = c(static_cast<double>(i) / fine);
    if (std::abs(whole(p)) > 1e-8) {
      have_last = false;
      continue;
    }
    if (have_last && (p - last).norm() < kFeatureSpacing && i != fine) continue;
    out.push_back(p);
    last = p;
    have_last = true;
  }
}

void sample_segment(const Vec3& a, const Vec3& b, const ScalarField& whole, std::vector<Vec3>& out) {
  const int fine = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.02)));
  sample_curve([&](double t) { return Vec3(a + t * (b - a)); }, fine, whole, out);
}

// A closed curve given by an angle parameter; `speed` bounds |dc/dtheta| (mm per radian).
template <typename Curve>
void sample_closed_curve(const Curve& c, double speed, const ScalarField& whole, std::vector<Vec3>& out) {
  const int fine = std::max(64, static_cast<int>(std::ceil(2.0 * kPi * speed / 0.02)));
  sample_curve([&](double t) { return c(2.0 * kPi * t); }, fine, whole, out);
}

// ---------------------------------------------------------------------------------------------------
// Shapes. Each builder fills the sdf, bounds, topology, features and (when known) the analytic volume.

struct Primitive {
  ScalarField sdf;
  Box3 bounds;
};

Box3 box_of(const Vec3& lo, const Vec3& hi) { return Box3(lo, hi); }

Box3 capsule_box(const Vec3& a, const Vec3& b, double r) {
  Box3 box(a.cwiseMin(b), a.cwiseMax(b));
  box.min().array() -= r;
  box.max().array() += r;
  return box;
}

ScalarField union_of(const std::vector<Primitive>& parts) {
  return [parts](const Vec3& p) {
    double d = std::numeric_limits<double>::infinity();
    for (const Primitive& part : parts) d = std::min(d, part.sdf(p));
    return d;
  };
}

// Concave creases of a union: every pairwise intersection curve on the combined surface.
void union_creases(const std::vector<Primitive>& parts, const ScalarField& whole, std::vector<Vec3>& out) {
  for (std::size_t i = 0; i < parts.size(); ++i) {
    for (std::size_t j = i + 1; j < parts.size(); ++j) {
      Box3 overlap = parts[i].bounds.intersection(parts[j].bounds);
      if (overlap.isEmpty()) continue;
      overlap.min().array() -= 0.5;
      overlap.max().array() += 0.5;
      intersection_curves(parts[i].sdf, parts[j].sdf, whole, overlap, out);
    }
  }
}

struct ShapeBuild {
  ScalarField sdf;
  Box3 bounds;
  std::optional<double> volume;
  int surface_components = 1;
  int euler_characteristic = 2;
  std::vector<Vec3> features;
};

ShapeBuild build_ridge_box() {
  // Pentagonal prism: the block [-20,20] x [-15,15] under the roof y + 0.6|x| <= 15, z in [-25, 25].
  const std::vector<Vec2> section = {{-20.0, -15.0}, {20.0, -15.0}, {20.0, 3.0}, {0.0, 15.0}, {-20.0, 3.0}};
  constexpr double kHalfLength = 25.0;
  ShapeBuild s;
  s.sdf = [section](const Vec3& p) { return sd_extrude(sd_polygon(p.head<2>(), section), p.z(), kHalfLength); };
  s.bounds = box_of({-20.0, -15.0, -kHalfLength}, {20.0, 15.0, kHalfLength});
  s.volume = polygon_area(section) * 2.0 * kHalfLength;  // 960 * 50 = 48000 mm^3
  for (std::size_t i = 0, j = section.size() - 1; i < section.size(); j = i, ++i) {
    const Vec3 a(section[i].x(), section[i].y(), 0.0);
    const Vec3 b(section[j].x(), section[j].y(), 0.0);
    sample_segment(a - kHalfLength * Vec3::UnitZ(), a + kHalfLength * Vec3::UnitZ(), s.sdf, s.features);
    for (double z : {-kHalfLength, kHalfLength}) {
      sample_segment(a + z * Vec3::UnitZ(), b + z * Vec3::UnitZ(), s.sdf, s.features);
    }
  }
  return s;
}

ShapeBuild build_femur() {
  std::vector<Primitive> parts;
  // Shaft: a capsule along z, radius 12, z in [-46, 46].
  const Vec3 shaft_a(0.0, 0.0, -34.0), shaft_b(0.0, 0.0, 34.0);
  parts.push_back(
      {[=](const Vec3& p) { return sd_capsule(p, shaft_a, shaft_b, 12.0); }, capsule_box(shaft_a, shaft_b, 12.0)});
  // Posterior ridge (linea aspera): a triangular prism along z whose apex stands 4 mm off the shaft.
  const std::vector<Vec2> ridge = {{-3.5, 9.0}, {3.5, 9.0}, {0.0, 16.0}};
  constexpr double kRidgeHalf = 25.0;
  parts.push_back({[ridge](const Vec3& p) { return sd_extrude(sd_polygon(p.head<2>(), ridge), p.z(), kRidgeHalf); },
                   box_of({-3.5, 9.0, -kRidgeHalf}, {3.5, 16.0, kRidgeHalf})});
  // Neck (capsule, radius 8, about 126 degrees to the shaft) and spherical head (radius 15).
  const Vec3 neck_a(0.0, 0.0, 28.0), head_centre(-28.0, 0.0, 48.0);
  parts.push_back(
      {[=](const Vec3& p) { return sd_capsule(p, neck_a, head_centre, 8.0); }, capsule_box(neck_a, head_centre, 8.0)});
  parts.push_back(
      {[=](const Vec3& p) { return sd_sphere(p, head_centre, 15.0); }, capsule_box(head_centre, head_centre, 15.0)});
  // Two condyles (spheres, radius 13) at the bottom, 5 mm apart.
  for (double x : {-15.5, 15.5}) {
    const Vec3 c(x, 3.0, -44.0);
    parts.push_back({[=](const Vec3& p) { return sd_sphere(p, c, 13.0); }, capsule_box(c, c, 13.0)});
  }
  ShapeBuild s;
  s.sdf = union_of(parts);
  for (const Primitive& part : parts) s.bounds.extend(part.bounds);
  union_creases(parts, s.sdf, s.features);
  // The ridge's own edges: the apex line and the end triangles (the parts outside the shaft).
  for (std::size_t i = 0, j = ridge.size() - 1; i < ridge.size(); j = i, ++i) {
    const Vec3 a(ridge[i].x(), ridge[i].y(), 0.0);
    const Vec3 b(ridge[j].x(), ridge[j].y(), 0.0);
    sample_segment(a - kRidgeHalf * Vec3::UnitZ(), a + kRidgeHalf * Vec3::UnitZ(), s.sdf, s.features);
    for (double z : {-kRidgeHalf, kRidgeHalf}) {
      sample_segment(a + z * Vec3::UnitZ(), b + z * Vec3::UnitZ(), s.sdf, s.features);
    }
  }
  return s;
}

ShapeBuild build_pelvis() {
  // Cross-section in (r, z) with a sharp crest at (41, 15); revolved about the ring axis, which is
  // tilted by 22 degrees about x.
  const std::vector<Vec2> section = {{32.0, -9.0}, {44.0, -9.0}, {47.0, 0.0}, {41.0, 15.0}, {33.0, 3.0}};
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(22.0 * kPi / 180.0, Vec3::UnitX()).toRotationMatrix();
  ShapeBuild s;
  s.sdf = [section, rotation](const Vec3& p) {
    const Vec3 q = rotation.transpose() * p;
    return sd_polygon(Vec2(length2(q.x(), q.y()), q.z()), section);
  };
  // Pappus: volume = area * 2 pi * (r of the centroid).
  double moment = 0.0;  // integral of r over the section
  for (std::size_t i = 0, j = section.size() - 1; i < section.size(); j = i, ++i) {
    const double cross = section[j].x() * section[i].y() - section[i].x() * section[j].y();
    moment += (section[j].x() + section[i].x()) * cross / 6.0;
  }
  s.volume = 2.0 * kPi * std::abs(moment);
  s.surface_components = 1;
  s.euler_characteristic = 0;
  const Vec3 axis = rotation * Vec3::UnitZ();
  for (const Vec2& v : section) {
    const Vec3 centre = rotation * Vec3(0.0, 0.0, v.y());
    // The bounding box of a circle: centre +- r sqrt(1 - axis_k^2) along each axis k.
    const Vec3 extent = v.x() * (Vec3::Ones() - axis.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt();
    s.bounds.extend(centre - extent);
    s.bounds.extend(centre + extent);
    sample_closed_curve(
        [&](double t) { return Vec3(rotation * Vec3(v.x() * std::cos(t), v.x() * std::sin(t), v.y())); }, v.x(), s.sdf,
        s.features);
  }
  return s;
}

ShapeBuild build_skull() {
  // A 6 mm ellipsoidal shell, cut open by the plane z = -35, with two orbits drilled through the front
  // (-y): cylinders of radius 9 along y that end inside the cranial cavity.
  const Ellipsoid outer(Vec3(0.0, 0.0, -15.0), Vec3(54.0, 60.0, 56.0));
  const Ellipsoid inner(Vec3(0.0, 0.0, -15.0), Vec3(48.0, 54.0, 50.0));
  constexpr double kCut = -35.0;
  constexpr double kOrbitRadius = 9.0, kOrbitZ = -5.0, kOrbitX = 22.0;
  constexpr double kOrbitYMid = -47.5, kOrbitHalf = 27.5;  // y in [-75, -20]
  auto orbit = [=](const Vec3& p, double x) {
    return sd_extrude(length2(p.x() - x, p.z() - kOrbitZ) - kOrbitRadius, p.y() - kOrbitYMid, kOrbitHalf);
  };
  ShapeBuild s;
  s.sdf = [=](const Vec3& p) {
    // max(outer, -inner, cut, -orbits); an ellipsoid term is computed exactly only when its cheap upper
    // bound does not rule it out of the maximum (the result is the same, at half the cost).
    double d = std::max({kCut - p.z(), -orbit(p, kOrbitX), -orbit(p, -kOrbitX)});
    const auto [outer_lo, outer_hi] = outer.distance_bounds(p);
    const auto [inner_lo, inner_hi] = inner.distance_bounds(p);
    const double floor = std::max({d, outer_lo, -inner_hi});
    if (outer_hi >= floor) d = std::max(d, outer.signed_distance(p));
    if (-inner_lo >= floor) d = std::max(d, -inner.signed_distance(p));
    return d;
  };
  s.bounds = box_of({-54.0, -60.0, kCut}, {54.0, 60.0, -15.0 + 56.0});
  s.surface_components = 1;
  s.euler_characteristic = -2;
  // The rim: the two ellipses where the cut plane meets the outer and inner ellipsoids.
  for (const Ellipsoid* e : {&outer, &inner}) {
    const double t = (kCut - e->centre.z()) / e->axes.z();
    const double k = std::sqrt(1.0 - t * t);
    const double a = e->axes.x() * k, b = e->axes.y() * k;
    sample_closed_curve([&](double u) { return Vec3(a * std::cos(u), b * std::sin(u), kCut); }, std::max(a, b), s.sdf,
                        s.features);
  }
  // The orbit rims: each cylinder against each ellipsoid, on the front (y < 0).
  for (double x : {-kOrbitX, kOrbitX}) {
    for (const Ellipsoid* e : {&outer, &inner}) {
      auto rim = [&, x](double u) {
        const double px = x + kOrbitRadius * std::cos(u);
        const double pz = kOrbitZ + kOrbitRadius * std::sin(u);
        const double rx = (px - e->centre.x()) / e->axes.x();
        const double rz = (pz - e->centre.z()) / e->axes.z();
        return Vec3(px, e->centre.y() - e->axes.y() * std::sqrt(std::max(0.0, 1.0 - rx * rx - rz * rz)), pz);
      };
      sample_closed_curve(rim, 3.0 * kOrbitRadius, s.sdf, s.features);
    }
  }
  return s;
}

ShapeBuild build_branch() {
  std::vector<Primitive> parts;
  // Trunk: radius 10, flat bottom at z = -45, rounded top centred at z = -5.
  const Vec3 trunk_a(0.0, 0.0, -60.0), trunk_b(0.0, 0.0, -5.0);
  constexpr double kBottom = -45.0;
  parts.push_back({[=](const Vec3& p) { return std::max(sd_capsule(p, trunk_a, trunk_b, 10.0), kBottom - p.z()); },
                   box_of({-10.0, -10.0, kBottom}, {10.0, 10.0, 5.0})});
  // Two limbs (capsules, radius 8) from the top of the trunk up and out to rounded tips.
  for (double x : {-22.0, 22.0}) {
    const Vec3 tip(x, 0.0, 40.0);
    parts.push_back({[=](const Vec3& p) { return sd_capsule(p, trunk_b, tip, 8.0); }, capsule_box(trunk_b, tip, 8.0)});
  }
  ShapeBuild s;
  s.sdf = union_of(parts);
  s.bounds = box_of({-10.0, -10.0, kBottom}, {10.0, 10.0, 5.0});
  s.bounds.extend(parts[1].bounds);
  s.bounds.extend(parts[2].bounds);
  union_creases(parts, s.sdf, s.features);
  sample_closed_curve([&](double u) { return Vec3(10.0 * std::cos(u), 10.0 * std::sin(u), kBottom); }, 10.0, s.sdf,
                      s.features);
  return s;
}

ShapeBuild build_two_objects() {
  // A circular cylinder (radius 14, z in [-30, 30]) and an elliptic prism (semi-axes 10 x 16,
  // z in [-25, 25]), 18 mm apart.
  const Vec2 cylinder_centre(-22.0, 0.0);
  constexpr double kRadius = 14.0, kCylinderHalf = 30.0;
  const Ellipse ellipse{Vec2(20.0, 0.0), Vec2(10.0, 16.0)};
  constexpr double kPrismHalf = 25.0;
  ShapeBuild s;
  s.sdf = [=](const Vec3& p) {
    const double a = sd_extrude((p.head<2>() - cylinder_centre).norm() - kRadius, p.z(), kCylinderHalf);
    const double b = sd_extrude(ellipse.signed_distance(p.head<2>()), p.z(), kPrismHalf);
    return std::min(a, b);
  };
  s.bounds = box_of({-36.0, -16.0, -kCylinderHalf}, {30.0, 16.0, kCylinderHalf});
  s.volume = kPi * kRadius * kRadius * 2.0 * kCylinderHalf + kPi * ellipse.axes.prod() * 2.0 * kPrismHalf;
  s.surface_components = 2;
  s.euler_characteristic = 4;
  for (double z : {-kCylinderHalf, kCylinderHalf}) {
    sample_closed_curve(
        [&](double u) { return Vec3(cylinder_centre.x() + kRadius * std::cos(u), kRadius * std::sin(u), z); }, kRadius,
        s.sdf, s.features);
  }
  for (double z : {-kPrismHalf, kPrismHalf}) {
    sample_closed_curve(
        [&](double u) {
          return Vec3(ellipse.centre.x() + ellipse.axes.x() * std::cos(u), ellipse.axes.y() * std::sin(u), z);
        },
        ellipse.axes.maxCoeff(), s.sdf, s.features);
  }
  return s;
}

ShapeBuild build_cavity() {
  // A capped cylinder (radius 28, z in [-30, 30]) with a closed spherical cavity (radius 12) inside.
  constexpr double kRadius = 28.0, kHalf = 30.0, kCavityRadius = 12.0;
  const Vec3 cavity_centre(4.0, -3.0, 2.0);
  ShapeBuild s;
  s.sdf = [=](const Vec3& p) {
    const double solid = sd_extrude(p.head<2>().norm() - kRadius, p.z(), kHalf);
    return std::max(solid, -sd_sphere(p, cavity_centre, kCavityRadius));
  };
  s.bounds = box_of({-kRadius, -kRadius, -kHalf}, {kRadius, kRadius, kHalf});
  s.volume = kPi * kRadius * kRadius * 2.0 * kHalf - 4.0 / 3.0 * kPi * std::pow(kCavityRadius, 3);
  s.surface_components = 2;
  s.euler_characteristic = 4;
  for (double z : {-kHalf, kHalf}) {
    sample_closed_curve([&](double u) { return Vec3(kRadius * std::cos(u), kRadius * std::sin(u), z); }, kRadius, s.sdf,
                        s.features);
  }
  return s;
}

constexpr std::array<std::pair<PhantomShape, std::string_view>, 7> kShapeNames = {{
    {PhantomShape::RidgeBox, "ridge-box"},
    {PhantomShape::Femur, "femur"},
    {PhantomShape::Pelvis, "pelvis"},
    {PhantomShape::Skull, "skull"},
    {PhantomShape::Branch, "branch"},
    {PhantomShape::TwoObjects, "two-objects"},
    {PhantomShape::Cavity, "cavity"},
}};

// ---------------------------------------------------------------------------------------------------
// Rendering.

struct Renderer {
  const ScalarField& sdf;
  Vec3 origin;  // centre of voxel (0, 0, 0)
  Vec3 spacing;
  std::array<std::int64_t, 3> size;
  std::array<int, 3> samples;  // supersamples per voxel along each axis
  float* buffer;
  float bone;
  float tissue;

  using Range = std::array<std::int64_t, 6>;  // [x0, x1) [y0, y1) [z0, z1)

  // Splits `r` in halves along every axis that has more than one element and is at least half as
  // long (physically, with cell size `cell`) as the longest such axis.
  static int split(const Range& r, const Vec3& cell, std::array<Range, 8>& out) {
    double longest = 0.0;
    for (int a = 0; a < 3; ++a) {
      if (r[2 * a + 1] - r[2 * a] > 1) longest = std::max(longest, (r[2 * a + 1] - r[2 * a]) * cell[a]);
    }
    int count = 1;
    out[0] = r;
    for (int a = 0; a < 3; ++a) {
      const std::int64_t n = r[2 * a + 1] - r[2 * a];
      if (n <= 1 || n * cell[a] < 0.5 * longest) continue;
      const std::int64_t mid = r[2 * a] + n / 2;
      for (int i = 0; i < count; ++i) {
        out[count + i] = out[i];
        out[i][2 * a + 1] = mid;
        out[count + i][2 * a] = mid;
      }
      count *= 2;
    }
    return count;
  }

  // Number of supersamples inside the solid among those of `r` (sample indices of the voxel whose
  // lower corner is `corner`); `d` is the sdf at the centre of the range.
  int count_inside(const Vec3& corner, const Vec3& step, const Range& r, double d) const {
    const Vec3 lo(r[0], r[2], r[4]);
    const Vec3 hi(r[1], r[3], r[5]);
    const int count = static_cast<int>((r[1] - r[0]) * (r[3] - r[2]) * (r[5] - r[4]));
    if (count == 1) return d < 0.0 ? 1 : 0;
    const double half_diagonal = 0.5 * (hi - lo).cwiseProduct(step).norm();
    if (d >= half_diagonal) return 0;
    if (d <= -half_diagonal) return count;
    std::array<Range, 8> parts;
    const int n = split(r, step, parts);
    int inside = 0;
    for (int i = 0; i < n; ++i) {
      const Range& q = parts[static_cast<std::size_t>(i)];
      const Vec3 centre = corner + 0.5 * Vec3(q[0] + q[1], q[2] + q[3], q[4] + q[5]).cwiseProduct(step);
      inside += count_inside(corner, step, q, sdf(centre));
    }
    return inside;
  }

  void fill(const Range& r, float value) const {
    for (std::int64_t z = r[4]; z < r[5]; ++z) {
      for (std::int64_t y = r[2]; y < r[3]; ++y) {
        float* row = buffer + (z * size[1] + y) * size[0];
        std::fill(row + r[0], row + r[1], value);
      }
    }
  }

  // Renders the voxels of `r`.
  void block(const Range& r) const {
    const Vec3 lo(r[0], r[2], r[4]);
    const Vec3 hi(r[1], r[3], r[5]);
    const Vec3 centre = origin + (0.5 * (lo + hi) - Vec3::Constant(0.5)).cwiseProduct(spacing);
    const double half_diagonal = 0.5 * (hi - lo).cwiseProduct(spacing).norm();
    const double d = sdf(centre);
    if (d >= half_diagonal) return fill(r, tissue);
    if (d <= -half_diagonal) return fill(r, bone);
    if (r[1] - r[0] == 1 && r[3] - r[2] == 1 && r[5] - r[4] == 1) {
      const Vec3 step = spacing.cwiseQuotient(Vec3(samples[0], samples[1], samples[2]));
      const Vec3 corner = centre - 0.5 * spacing;
      const Range all{0, samples[0], 0, samples[1], 0, samples[2]};
      const int total = samples[0] * samples[1] * samples[2];
      const double fraction = static_cast<double>(count_inside(corner, step, all, d)) / total;
      buffer[(r[4] * size[1] + r[2]) * size[0] + r[0]] =
          static_cast<float>(tissue + (static_cast<double>(bone) - tissue) * fraction);
      return;
    }
    std::array<Range, 8> parts;
    const int n = split(r, spacing, parts);
    for (int i = 0; i < n; ++i) block(parts[static_cast<std::size_t>(i)]);
  }
};

void check_option(bool ok, const std::string& message) {
  if (!ok) throw InvalidInputError("render_phantom: " + message);
}

}  // namespace

std::string_view to_string(PhantomShape shape) {
  for (const auto& [s, name] : kShapeNames) {
    if (s == shape) return name;
  }
  return "unknown";
}

PhantomShape parse_phantom_shape(std::string_view name) {
  std::string valid;
  for (const auto& [s, n] : kShapeNames) {
    if (n == name) return s;
    valid += (valid.empty() ? "" : ", ") + std::string(n);
  }
  throw InvalidInputError("unknown phantom shape '" + std::string(name) + "'; valid shapes: " + valid);
}

std::vector<PhantomShape> all_phantom_shapes() {
  std::vector<PhantomShape> shapes;
  for (const auto& entry : kShapeNames) shapes.push_back(entry.first);
  return shapes;
}

Phantom make_phantom(PhantomShape shape) {
  ShapeBuild s;
  switch (shape) {
    case PhantomShape::RidgeBox:
      s = build_ridge_box();
      break;
    case PhantomShape::Femur:
      s = build_femur();
      break;
    case PhantomShape::Pelvis:
      s = build_pelvis();
      break;
    case PhantomShape::Skull:
      s = build_skull();
      break;
    case PhantomShape::Branch:
      s = build_branch();
      break;
    case PhantomShape::TwoObjects:
      s = build_two_objects();
      break;
    case PhantomShape::Cavity:
      s = build_cavity();
      break;
    default:
      throw InvalidInputError("make_phantom: unknown shape " + std::to_string(static_cast<int>(shape)));
  }
  Phantom p;
  p.shape = shape;
  p.sdf = s.sdf;
  p.normal = normal_field(s.sdf);
  p.bounds = s.bounds;
  if (s.volume) {
    p.volume = *s.volume;
  } else {
    Box3 box = s.bounds;
    box.min().array() -= 0.5;
    box.max().array() += 0.5;
    p.volume = integrate_volume(s.sdf, box, 0.5);
  }
  p.surface_components = s.surface_components;
  p.euler_characteristic = s.euler_characteristic;
  p.feature_points = thin_points(s.features, 0.2);
  return p;
}

double distance_to_features(const Phantom& phantom, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& q : phantom.feature_points) best = std::min(best, (q - p).squaredNorm());
  return std::sqrt(best);
}

CtImage::Pointer render_phantom(const Phantom& phantom, const PhantomVolumeOptions& options) {
  check_option(static_cast<bool>(phantom.sdf), "the phantom has no signed distance function");
  check_option(!phantom.bounds.isEmpty() && phantom.bounds.min().allFinite() && phantom.bounds.max().allFinite(),
               "the phantom has an empty or infinite bounding box");
  for (int a = 0; a < 3; ++a) {
    check_option(std::isfinite(options.spacing[a]) && options.spacing[a] > 0.0,
                 "spacing must be three finite numbers > 0 mm");
  }
  check_option(std::isfinite(options.margin) && options.margin >= 0.0, "margin must be a finite number >= 0 mm");
  check_option(std::isfinite(options.blur) && options.blur >= 0.0, "blur must be a finite sigma >= 0 mm");
  check_option(std::isfinite(options.noise) && options.noise >= 0.0, "noise must be a finite sigma >= 0 HU");
  check_option(std::isfinite(options.bone_hu) && std::isfinite(options.tissue_hu), "bone and tissue HU must be finite");

  const Vec3 lo = phantom.bounds.min() - Vec3::Constant(options.margin);
  const Vec3 hi = phantom.bounds.max() + Vec3::Constant(options.margin);
  std::array<std::int64_t, 3> size{};
  double voxels = 1.0;
  for (int a = 0; a < 3; ++a) {
    const double n = std::max(1.0, std::ceil((hi[a] - lo[a]) / options.spacing[a] - 1e-9));
    voxels *= n;
    check_option(voxels <= 2147483648.0, "the volume would have over 2^31 voxels; use a coarser spacing");
    size[static_cast<std::size_t>(a)] = static_cast<std::int64_t>(n);
  }
  // The image, the blur's output and the segmentation's copies of it (values, mask, labels).
  check_allocation("render_phantom: a volume of " + std::to_string(size[0]) + " x " + std::to_string(size[1]) + " x " +
                       std::to_string(size[2]) + " voxels",
                   0.0, voxels * kVolumeBytesPerVoxel, ResourceLimits{});
  // Voxel centres symmetric about the centre of the box.
  Vec3 origin;
  for (int a = 0; a < 3; ++a) {
    origin[a] =
        0.5 * (lo[a] + hi[a]) - 0.5 * static_cast<double>(size[static_cast<std::size_t>(a)] - 1) * options.spacing[a];
  }

  auto image = CtImage::New();
  CtImage::RegionType region;
  CtImage::SizeType itk_size;
  CtImage::SpacingType itk_spacing;
  CtImage::PointType itk_origin;
  for (unsigned a = 0; a < 3; ++a) {
    itk_size[a] = static_cast<itk::SizeValueType>(size[a]);
    itk_spacing[a] = options.spacing[a];
    itk_origin[a] = origin[a];
  }
  region.SetSize(itk_size);
  image->SetRegions(region);
  image->SetSpacing(itk_spacing);
  image->SetOrigin(itk_origin);
  CtImage::DirectionType direction;
  direction.SetIdentity();
  image->SetDirection(direction);
  image->Allocate();

  std::array<int, 3> samples{};
  for (int a = 0; a < 3; ++a) {
    samples[static_cast<std::size_t>(a)] =
        std::clamp(static_cast<int>(std::ceil(options.spacing[a] / 0.25 - 1e-9)), 4, 16);
  }
  const Renderer renderer{phantom.sdf,
                          origin,
                          options.spacing,
                          size,
                          samples,
                          image->GetBufferPointer(),
                          static_cast<float>(options.bone_hu),
                          static_cast<float>(options.tissue_hu)};
  // Slabs of slices, handed out to the worker threads one at a time.
  const std::int64_t slab = std::max<std::int64_t>(1, std::min<std::int64_t>(8, size[2] / 16));
  const std::int64_t slabs = (size[2] + slab - 1) / slab;
  std::atomic<std::int64_t> next{0};
  auto work = [&] {
    for (std::int64_t s = next++; s < slabs; s = next++) {
      renderer.block({0, size[0], 0, size[1], s * slab, std::min(size[2], (s + 1) * slab)});
    }
  };
  const unsigned threads = std::clamp(std::thread::hardware_concurrency(), 1u, 16u);
  if (threads <= 1 || slabs == 1) {
    work();
  } else {
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(work);
    for (std::thread& t : pool) t.join();
  }

  if (options.blur > 0.0) {
    using Blur = itk::DiscreteGaussianImageFilter<CtImage, CtImage>;
    auto blur = Blur::New();
    blur->SetInput(image);
    blur->SetVariance(options.blur * options.blur);
    blur->SetUseImageSpacingOn();
    blur->SetMaximumError(0.01);
    const double finest = options.spacing.minCoeff();
    blur->SetMaximumKernelWidth(std::max(32, 2 * static_cast<int>(std::ceil(4.0 * options.blur / finest)) + 3));
    try {
      blur->Update();
    } catch (const itk::ExceptionObject& e) {
      throw InvalidInputError(std::string("render_phantom: blur failed: ") + e.GetDescription());
    }
    image = blur->GetOutput();
    image->DisconnectPipeline();
  }

  if (options.noise > 0.0) {
    std::mt19937_64 rng(options.seed);
    std::normal_distribution<double> normal(0.0, options.noise);
    float* data = image->GetBufferPointer();
    const std::size_t count = image->GetLargestPossibleRegion().GetNumberOfPixels();
    for (std::size_t i = 0; i < count; ++i) data[i] = static_cast<float>(data[i] + normal(rng));
  }
  return image;
}

}  // namespace contourmesh
