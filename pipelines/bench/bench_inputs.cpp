// SPDX-License-Identifier: BSD-3-Clause
#include "bench_inputs.h"

#include <contourmesh/vtk/vtk_convert.h>
#include <contourmesh/reconstruct/tiling.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

namespace contourmesh::bench {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// splitmix64: a tiny generator whose output is the same on every platform.
class SplitMix {
 public:
  explicit SplitMix(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  double gaussian() {  // Box-Muller
    const double u1 = 1.0 - uniform();
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
  }

 private:
  std::uint64_t state_;
};

// Angle difference wrapped to [-pi, pi).
double wrap(double a) { return a - kTwoPi * std::floor((a + std::numbers::pi) / kTwoPi); }

// A triangular ridge of `height` and half-width `half_width` radians centred at angle 0.
double ridge(double angle, double height, double half_width) {
  return height * std::max(0.0, 1.0 - std::abs(wrap(angle)) / half_width);
}

}  // namespace

StackLayout stack_layout(std::int64_t target) {
  StackLayout l;
  l.points_per_contour =
      static_cast<int>(std::clamp<double>(std::round(std::sqrt(static_cast<double>(target))), 64, 500));
  l.objects = static_cast<int>(std::max<std::int64_t>(1, target / 500'000));
  const double p = l.points_per_contour;
  // Per object: the contours, the two half-spacing copies of the end contours, and two refined caps
  // with interior vertices about one point spacing apart (about 0.09 p^2 each).
  const double per_object = static_cast<double>(target) / l.objects - 2.0 * p - 2.0 * 0.092 * p * p;
  l.slices = std::max(8, static_cast<int>(std::lround(per_object / p)));
  return l;
}

ContourStack make_bench_stack(const StackLayout& layout) {
  ContourStack stack;
  stack.slices.resize(static_cast<std::size_t>(layout.slices));
  const double base_radius = layout.points_per_contour * layout.point_spacing / kTwoPi;
  const int grid = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(layout.objects))));
  const double pitch = 3.0 * base_radius;  // tubes never touch: radius stays below 1.45 base_radius
  for (int s = 0; s < layout.slices; ++s) {
    SliceContours& slice = stack.slices[static_cast<std::size_t>(s)];
    slice.w = s * layout.slice_spacing;
    const double t = static_cast<double>(s) / std::max(1, layout.slices - 1);  // 0 .. 1 along the tubes
    for (int k = 0; k < layout.objects; ++k) {
      const Eigen::Vector2d centre((k % grid) * pitch, (k / grid) * pitch);
      const double phase = 1.7 * k;
      const double swell = 1.0 + 0.12 * std::sin(kTwoPi * 1.5 * t + phase);  // shaft, metaphysis, ...
      const double radius = base_radius * swell;
      const double ellipse_angle = 0.4 * k;
      const double ridge_straight = 0.9 + 1.3 * k;                            // runs across the slices
      const double ridge_spiral = ridge_straight + 2.5 + 0.5 * std::numbers::pi * t;  // quarter turn
      const int count = std::max(16, static_cast<int>(std::lround(layout.points_per_contour * swell)));
      SplitMix rng(0x5EED0000ULL + static_cast<std::uint64_t>(s) * 1'000'003ULL + static_cast<std::uint64_t>(k));
      Contour contour;
      contour.points.reserve(static_cast<std::size_t>(count));
      for (int i = 0; i < count; ++i) {
        // Strictly increasing angles and a positive radius: a simple, counter-clockwise polygon.
        const double theta = kTwoPi * (i + 0.5 * (rng.uniform() - 0.5)) / count;
        double r = radius * (1.0 + 0.12 * std::cos(2.0 * (theta - ellipse_angle)));
        r += ridge(theta - ridge_straight, 0.12 * radius, 0.3);
        r += ridge(theta - ridge_spiral, 0.08 * radius, 0.25);
        r += 0.2 * layout.point_spacing * rng.gaussian();
        contour.points.emplace_back(centre.x() + r * std::cos(theta), centre.y() + r * std::sin(theta));
      }
      slice.contours.push_back(std::move(contour));
    }
  }
  return stack;
}

namespace {

// The inputs of the current size; `mesh_ready` once the mesh and polydata are there.
struct Cache {
  BenchInput input;
  bool mesh_ready = false;
};

Cache& cache_for(std::int64_t target) {
  static std::unique_ptr<Cache> cache;
  if (!cache || cache->input.target != target) {
    cache.reset();  // free the previous size first
    cache = std::make_unique<Cache>();
    cache->input.target = target;
    cache->input.stack = make_bench_stack(stack_layout(target));
  }
  return *cache;
}

void set_mesh(Cache& c, Mesh&& mesh) {
  c.input.mesh = std::move(mesh);
  c.input.polydata = to_polydata(c.input.mesh);
  c.mesh_ready = true;
}

}  // namespace

const ContourStack& bench_stack(std::int64_t target) { return cache_for(target).input.stack; }

const BenchInput& bench_input(std::int64_t target) {
  Cache& c = cache_for(target);
  if (!c.mesh_ready) set_mesh(c, tile_contours(c.input.stack).mesh);
  return c.input;
}

void keep_tiled_mesh(std::int64_t target, Mesh&& mesh) {
  Cache& c = cache_for(target);
  if (!c.mesh_ready) set_mesh(c, std::move(mesh));
}

void set_vertex_rate(benchmark::State& state, double vertices) {
  state.counters["vertices"] = static_cast<double>(bench_input(state.range(0)).mesh.num_vertices());
  state.counters["vertices_per_s"] =
      benchmark::Counter(vertices * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

}  // namespace contourmesh::bench
