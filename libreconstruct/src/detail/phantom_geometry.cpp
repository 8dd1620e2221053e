// SPDX-License-Identifier: BSD-3-Clause
#include "detail/phantom_geometry.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <thread>
#include <unordered_map>

namespace contourmesh::detail {

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

namespace {

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

}  // namespace

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

void sample_segment(const Vec3& a, const Vec3& b, const ScalarField& whole, std::vector<Vec3>& out) {
  const int fine = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.02)));
  sample_curve([&](double t) { return Vec3(a + t * (b - a)); }, fine, whole, out);
}

void sample_prism_edges(const std::vector<Vec2>& section, const Vec3& origin, const Vec3& u, const Vec3& v,
                        const Vec3& axis, double half_length, const ScalarField& whole, std::vector<Vec3>& out) {
  for (std::size_t i = 0, j = section.size() - 1; i < section.size(); j = i, ++i) {
    const Vec3 a = origin + section[i].x() * u + section[i].y() * v;
    const Vec3 b = origin + section[j].x() * u + section[j].y() * v;
    sample_segment(a - half_length * axis, a + half_length * axis, whole, out);
    for (double w : {-half_length, half_length}) sample_segment(a + w * axis, b + w * axis, whole, out);
  }
}

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

}  // namespace contourmesh::detail
