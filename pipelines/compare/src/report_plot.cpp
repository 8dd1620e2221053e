// SPDX-License-Identifier: BSD-3-Clause
#include "compare/report.h"

#include "png_canvas.h"
#include "report_format.h"

#include <algorithm>
#include <cmath>

namespace contourmesh {

namespace fs = std::filesystem;
using report_detail::fixed;

namespace {

// Tick step of about `target` ticks over `range`: 1, 2 or 5 times a power of ten.
double nice_step(double range, int target) {
  const double raw = range / std::max(target, 1);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * p >= raw) return m * p;
  }
  return 10.0 * p;
}

std::string tick_label(double v, double step) {
  const int digits = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
  return fixed(std::abs(v) < 1e-12 ? 0.0 : v, digits);
}

bool smoothed(const MethodResult& m) {
  const bool none = m.spec.key == MethodKey(SmoothingMethod::None);
  const bool raw_voxel = m.spec.key == MethodKey(ExternalMethod::VoxelFlyingEdges);
  return !none && !raw_voxel;
}

}  // namespace

void write_volume_curve_png(const Comparison& c, const fs::path& path, int width, int height) {
  using detail::Align;
  detail::Canvas canvas(width, height, {1.0, 1.0, 1.0});
  const double left = 80, right = width - 300.0, bottom = 60, top = height - 50.0;
  // Iterative methods are curves. Methods without intermediate results (windowed sinc, cross-slice smoothing) are
  // markers at their iteration count, or at the right end when they have none.
  const auto marker = [](const MethodResult& m) { return m.volume_curve.empty() && smoothed(m); };
  std::size_t iterations = 1;
  double lo = 0.0, hi = 0.0;
  const auto extend = [&](double rate) {
    if (!std::isfinite(rate)) return;
    lo = std::min(lo, 100.0 * rate);
    hi = std::max(hi, 100.0 * rate);
  };
  for (const MethodResult& m : c.methods) {
    if (!m.volume_curve.empty()) {
      iterations = std::max(iterations, m.volume_curve.size() - 1);
      for (double v : m.volume_curve) extend(v);
    } else if (marker(m)) {
      iterations = std::max(iterations, static_cast<std::size_t>(m.iterations));
      extend(-m.volume_change_percent / 100.0);
    }
  }
  if (hi - lo < 1e-6) {
    lo -= 0.5;
    hi += 0.5;
  }
  const double ystep = nice_step(hi - lo, 8);
  lo = std::floor(lo / ystep) * ystep;
  hi = std::ceil(hi / ystep) * ystep;
  const double xmax = static_cast<double>(iterations);
  const auto X = [&](double k) { return left + (right - left) * k / xmax; };
  const auto Y = [&](double v) { return bottom + (top - bottom) * (v - lo) / (hi - lo); };
  const detail::Rgb grid = {0.88, 0.88, 0.88}, ink = {0.1, 0.1, 0.1};

  for (double v = lo; v <= hi + 1e-9 * ystep; v += ystep) {
    canvas.line(left, Y(v), right, Y(v), std::abs(v) < 1e-9 * ystep ? detail::Rgb{0.6, 0.6, 0.6} : grid, 1.0);
    canvas.text(tick_label(v, ystep), left - 8, Y(v), ink, 13, Align::End, Align::Center);
  }
  const double xstep = nice_step(xmax, 8);
  for (double k = 0; k <= xmax + 1e-9; k += xstep) {
    canvas.line(X(k), bottom, X(k), top, grid, 1.0);
    canvas.text(tick_label(k, 1.0), X(k), bottom - 8, ink, 13, Align::Center, Align::End);
  }
  canvas.line(left, bottom, right, bottom, ink, 1.2);
  canvas.line(left, bottom, left, top, ink, 1.2);
  canvas.text("iteration", 0.5 * (left + right), 12, ink, 15, Align::Center, Align::Start);
  canvas.text("volume shrinking rate (V0 - Vk) / V0, %", 22, 0.5 * (bottom + top), ink, 15, Align::Center,
              Align::Center, false, true);
  canvas.text("Volume shrinking rate against iteration", 0.5 * (left + right), height - 15.0, ink, 17, Align::Center,
              Align::End, true);

  const auto diamond = [&](double x, double y, const detail::Rgb& color) {
    constexpr double r = 6.0;
    for (double d = -r; d <= r; d += 0.5)
      canvas.line(x - (r - std::abs(d)), y + d, x + (r - std::abs(d)), y + d, color, 1.0);
  };
  int legend_row = 0;
  for (const MethodResult& m : c.methods) {
    const bool is_marker = marker(m);
    if (m.volume_curve.empty() && !is_marker) continue;
    const detail::Rgb color = m.spec.colour;
    const double w = m.spec.preset.empty() ? 2.0 : 3.0;
    for (std::size_t k = 1; k < m.volume_curve.size(); ++k) {
      const double a = m.volume_curve[k - 1], b = m.volume_curve[k];
      if (!std::isfinite(a) || !std::isfinite(b)) continue;
      canvas.line(X(static_cast<double>(k - 1)), Y(100.0 * a), X(static_cast<double>(k)), Y(100.0 * b), color, w);
    }
    const double ly = top - 10.0 - 24.0 * legend_row++;
    if (is_marker) {
      diamond(X(m.iterations > 0 ? m.iterations : xmax), Y(-m.volume_change_percent), color);
      diamond(right + 35, ly, color);
    } else {
      canvas.line(right + 20, ly, right + 50, ly, color, w);
    }
    canvas.text(m.spec.legend + (is_marker && m.iterations == 0 ? ", no iterations" : ""), right + 58, ly, ink, 13,
                Align::Start, Align::Center);
  }
  canvas.text("markers: methods without intermediate steps", right + 20, top - 14.0 - 24.0 * legend_row,
              {0.4, 0.4, 0.4}, 11, Align::Start, Align::Center);
  canvas.write_png(path);
}

}  // namespace contourmesh
