// SPDX-License-Identifier: BSD-3-Clause
#include "detail/contour_noise.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <random>
#include <thread>

namespace contourmesh::detail {

namespace {

constexpr double kBumpCutoff = 3.726653172078671e-06;  // exp(-12.5): a Gaussian at 5 sigma

// SplitMix64's finaliser: spreads nearby seeds over the whole 64-bit range.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// The contour-noise stream of one slice: a different stream from the CT noise (which runs an mt19937_64
// seeded with the seed itself), and from every other slice.
std::mt19937_64 slice_stream(std::uint64_t seed, std::int64_t slice) {
  constexpr std::uint64_t kContourStream = 0x636f6e746f757273ull;  // "contours"
  return std::mt19937_64(mix(mix(seed ^ kContourStream) + static_cast<std::uint64_t>(slice)));
}

// Uniform in [lo, hi), from the top 53 bits (the same numbers on every standard library).
double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

double length_weighted_rms(const std::vector<CurveSample>& boundary, const std::vector<double>& values) {
  double sum = 0.0, length = 0.0;
  for (std::size_t i = 0; i < boundary.size(); ++i) {
    sum += boundary[i].length * values[i] * values[i];
    length += boundary[i].length;
  }
  return length > 0.0 ? std::sqrt(sum / length) : 0.0;
}

// Marching squares on one leaf cell [x0, x1] x [y0, y1] with corner values v (counter-clockwise from
// (x0, y0)); inside is v < 0, as in the renderer.
void leaf_segments(const std::array<Vec2, 4>& corner, const std::array<double, 4>& v, double centre_value,
                   std::vector<CurveSample>& out) {
  std::array<Vec2, 4> crossing;  // on edge e between corners e and e + 1
  std::array<bool, 4> crosses{};
  int count = 0;
  for (int e = 0; e < 4; ++e) {
    const int f = (e + 1) % 4;
    if ((v[e] < 0.0) == (v[f] < 0.0)) continue;
    const double t = v[e] / (v[e] - v[f]);
    crossing[e] = corner[e] + t * (corner[f] - corner[e]);
    crosses[e] = true;
    ++count;
  }
  auto segment = [&](int a, int b) {
    out.push_back({0.5 * (crossing[a] + crossing[b]), (crossing[a] - crossing[b]).norm()});
  };
  if (count == 2) {
    int a = -1, b = -1;
    for (int e = 0; e < 4; ++e) {
      if (!crosses[e]) continue;
      (a < 0 ? a : b) = e;
    }
    segment(a, b);
  } else if (count == 4) {
    // A saddle: corners 0 and 2 on one side, 1 and 3 on the other. The centre's side is connected.
    if ((centre_value < 0.0) == (v[0] < 0.0)) {
      segment(0, 1);  // cuts off corner 1
      segment(2, 3);  // cuts off corner 3
    } else {
      segment(3, 0);
      segment(1, 2);
    }
  }
}

}  // namespace

double ContourNoiseField::operator()(double x, double y) const {
  double f = 0.0;
  for (const Wave& w : waves) f += w.amplitude * std::cos(w.k.x() * x + w.k.y() * y + w.phase);
  for (const Bump& b : bumps) {
    const double dx = x - b.centre.x(), dy = y - b.centre.y();
    const double r2 = dx * dx + dy * dy;
    if (r2 < b.reach2) f += b.amplitude * (std::exp(-r2 * b.inv_two_sigma2) - kBumpCutoff);
  }
  return f;
}

std::vector<CurveSample> section_boundary(const ScalarField& sdf, const Eigen::AlignedBox2d& area, double z,
                                          double cell) {
  std::vector<CurveSample> out;
  if (area.isEmpty() || !(cell > 0.0)) return out;
  // A square of side cell * 2^levels over the area.
  const double side = area.sizes().maxCoeff();
  int levels = 0;
  while (cell * std::pow(2.0, levels) < side) ++levels;
  const double half_root = 0.5 * cell * std::pow(2.0, levels);
  const Vec2 centre = area.center();
  auto value = [&](const Vec2& p) { return sdf(Vec3(p.x(), p.y(), z)); };
  struct Search {
    const decltype(value)& f;
    std::vector<CurveSample>& out;
    void cell(const Vec2& c, double half, int level) const {
      const double d = f(c);
      if (std::abs(d) > half * std::sqrt(2.0)) return;  // no boundary within the cell
      if (level == 0) {
        const std::array<Vec2, 4> corner = {Vec2(c.x() - half, c.y() - half), Vec2(c.x() + half, c.y() - half),
                                            Vec2(c.x() + half, c.y() + half), Vec2(c.x() - half, c.y() + half)};
        const std::array<double, 4> v = {f(corner[0]), f(corner[1]), f(corner[2]), f(corner[3])};
        leaf_segments(corner, v, d, out);
        return;
      }
      const double q = 0.5 * half;
      for (int k = 0; k < 4; ++k) cell(c + Vec2((k & 1) ? q : -q, (k & 2) ? q : -q), q, level - 1);
    }
  };
  const Search search{value, out};
  search.cell(centre, half_root, levels);
  return out;
}

ContourNoiseField make_contour_noise_field(const std::vector<CurveSample>& boundary, double rms, std::uint64_t seed,
                                           std::int64_t slice, const ContourNoiseModel& model) {
  double perimeter = 0.0;
  for (const CurveSample& s : boundary) perimeter += s.length;
  if (!(rms > 0.0) || !(perimeter > 0.0)) return {};
  std::vector<double> cumulative;  // boundary length up to and including each sample
  cumulative.reserve(boundary.size());
  for (const CurveSample& s : boundary) cumulative.push_back((cumulative.empty() ? 0.0 : cumulative.back()) + s.length);

  std::mt19937_64 rng = slice_stream(seed, slice);
  ContourNoiseField best;
  double best_scale = 0.0;
  std::vector<double> waves(boundary.size()), bumps(boundary.size()), total(boundary.size());
  for (int attempt = 0; attempt < std::max(1, model.attempts); ++attempt) {
    ContourNoiseField f;
    // Plane waves: wavelength, direction, phase and relative amplitude uniform; their mean square over
    // the plane (sum of amplitude^2 / 2) is wave_share * rms^2.
    double plane_square = 0.0;
    for (int i = 0; i < model.waves; ++i) {
      const double wavelength = uniform(rng, model.min_wavelength, model.max_wavelength);
      const double direction = uniform(rng, 0.0, 2.0 * kPi);
      const double phase = uniform(rng, 0.0, 2.0 * kPi);
      const double amplitude = uniform(rng, 0.5, 1.0);
      const double k = 2.0 * kPi / wavelength;
      f.waves.push_back({Vec2(k * std::cos(direction), k * std::sin(direction)), phase, amplitude});
      plane_square += 0.5 * amplitude * amplitude;
    }
    const double wave_scale = plane_square > 0.0 ? std::sqrt(model.wave_share / plane_square) * rms : 0.0;
    for (auto& w : f.waves) w.amplitude *= wave_scale;
    // Bumps: one per bump_spacing of boundary, centred at uniformly chosen boundary points, random width,
    // sign and relative height; together their RMS over the boundary is sqrt(1 - wave_share) * rms.
    const int count = std::clamp(static_cast<int>(std::lround(perimeter / model.bump_spacing)), 1, model.max_bumps);
    for (int j = 0; j < count; ++j) {
      const double at = uniform(rng, 0.0, perimeter);
      const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), at);
      const std::size_t index = std::min<std::size_t>(static_cast<std::size_t>(it - cumulative.begin()),
                                                      boundary.size() - 1);
      const double sigma = uniform(rng, model.min_bump_sigma, model.max_bump_sigma);
      const double sign = uniform(rng, 0.0, 1.0) < 0.5 ? -1.0 : 1.0;
      const double height = uniform(rng, 0.5, 1.0);
      f.bumps.push_back(
          {boundary[index].point, sigma, 1.0 / (2.0 * sigma * sigma), 25.0 * sigma * sigma, sign * height});
    }
    ContourNoiseField only_bumps;
    only_bumps.bumps = f.bumps;
    ContourNoiseField only_waves;
    only_waves.waves = f.waves;
    for (std::size_t i = 0; i < boundary.size(); ++i) {
      waves[i] = only_waves(boundary[i].point.x(), boundary[i].point.y());
      bumps[i] = only_bumps(boundary[i].point.x(), boundary[i].point.y());
    }
    const double bump_rms = length_weighted_rms(boundary, bumps);
    const double bump_scale = bump_rms > 0.0 ? std::sqrt(1.0 - model.wave_share) * rms / bump_rms : 0.0;
    for (auto& b : f.bumps) b.amplitude *= bump_scale;
    for (std::size_t i = 0; i < boundary.size(); ++i) total[i] = waves[i] + bump_scale * bumps[i];
    // The final scaling to the exact RMS. A draw whose waves and bumps cancel on a small section would need
    // a large factor (and a large field elsewhere in the plane): it is redrawn.
    const double total_rms = length_weighted_rms(boundary, total);
    if (!(total_rms > 0.0)) continue;
    const double scale = rms / total_rms;
    if (best_scale == 0.0 || std::abs(std::log(scale)) < std::abs(std::log(best_scale))) {
      for (auto& w : f.waves) w.amplitude *= scale;
      for (auto& b : f.bumps) b.amplitude *= scale;
      best = std::move(f);
      best_scale = scale;
    }
    if (scale <= model.max_rescale) break;
  }
  // max |f| <= sum |wave amplitudes| + the largest sum of |bump amplitudes| over the bumps that reach one
  // point. The bumps reaching a point all overlap any one of them, so that sum is at most the largest,
  // over the bumps j, of the amplitudes of the bumps whose reach meets j's. The same for the gradient: a
  // wave's is at most |amplitude| |k|, a bump's |amplitude| / sigma exp(-1/2).
  double bumps_bound = 0.0, bumps_slope = 0.0;
  for (const auto& j : best.bumps) {
    double sum = 0.0, slope = 0.0;
    for (const auto& i : best.bumps) {
      const double reach = 5.0 * (i.sigma + j.sigma);
      if ((i.centre - j.centre).squaredNorm() > reach * reach) continue;
      sum += std::abs(i.amplitude);
      slope += std::abs(i.amplitude) / i.sigma * std::exp(-0.5);
    }
    bumps_bound = std::max(bumps_bound, sum);
    bumps_slope = std::max(bumps_slope, slope);
  }
  best.bound = bumps_bound;
  best.lipschitz = bumps_slope;
  for (const auto& w : best.waves) {
    best.bound += std::abs(w.amplitude);
    best.lipschitz += std::abs(w.amplitude) * w.k.norm();
  }
  return best;
}

std::vector<ContourNoiseField> contour_noise_fields(const ScalarField& sdf, const Eigen::AlignedBox3d& bounds,
                                                    const std::vector<double>& slice_z, double thickness, double rms,
                                                    std::uint64_t seed) {
  std::vector<ContourNoiseField> fields(slice_z.size());
  if (!(rms > 0.0)) return fields;
  constexpr double kCell = 0.5;  // mm: the boundary's quadrature cells
  const Eigen::AlignedBox2d area(bounds.min().head<2>() - Vec2::Constant(1.0),
                                 bounds.max().head<2>() + Vec2::Constant(1.0));
  auto one = [&](std::size_t k) {
    const double z = slice_z[k];
    if (z < bounds.min().z() - 0.5 * thickness || z > bounds.max().z() + 0.5 * thickness) return;
    std::vector<CurveSample> boundary;
    for (double offset : {0.0, -0.25, 0.25, -0.45, 0.45}) {
      boundary = section_boundary(sdf, area, z + offset * thickness, kCell);
      if (!boundary.empty()) break;
    }
    fields[k] = make_contour_noise_field(boundary, rms, seed, static_cast<std::int64_t>(k));
  };
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t k = next++; k < slice_z.size(); k = next++) one(k);
  };
  const unsigned threads = std::clamp(std::thread::hardware_concurrency(), 1u, 16u);
  if (threads <= 1 || slice_z.size() < 2) {
    work();
  } else {
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(work);
    for (std::thread& t : pool) t.join();
  }
  return fields;
}

}  // namespace contourmesh::detail
