// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/contour_resampling.h"

#include <contourmesh/smooth/errors.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace contourmesh {

namespace {
using Polygon = std::vector<Eigen::Vector2d>;
}  // namespace

std::vector<Eigen::Vector2d> resample_drawn(const std::vector<Eigen::Vector2d>& polygon, double spacing,
                                           double tolerance) {
  if (!(spacing > 0.0) || !std::isfinite(spacing)) throw InvalidInputError("resampling: the spacing must be > 0 mm");
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
    throw InvalidInputError("resampling: the tolerance must be >= 0 mm");
  const std::size_t n = polygon.size();
  if (n < 3) throw InvalidInputError("resampling: a polygon needs at least 3 points");
  // Start at the sharpest corner, which any simplification keeps.
  std::size_t start = 0;
  double sharpest = 2.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = polygon[i] - polygon[(i + n - 1) % n];
    const Eigen::Vector2d b = polygon[(i + 1) % n] - polygon[i];
    if (!(a.norm() > 0.0) || !(b.norm() > 0.0)) continue;
    const double c = a.normalized().dot(b.normalized());
    if (c < sharpest) {
      sharpest = c;
      start = i;
    }
  }
  auto at = [&](std::size_t k) -> const Eigen::Vector2d& { return polygon[(start + k) % n]; };
  // Greedy chords: from an anchor, extend while the chord stays short and every skipped point close.
  std::vector<std::size_t> kept{0};
  std::size_t anchor = 0;
  while (anchor < n) {
    std::size_t best = anchor + 1;
    for (std::size_t j = anchor + 2; j <= n; ++j) {
      const Eigen::Vector2d& a = at(anchor);
      const Eigen::Vector2d& b = at(j);  // j == n is the start again
      const Eigen::Vector2d d = b - a;
      const double len = d.norm();
      if (len > spacing) break;
      bool close = len > 0.0;
      for (std::size_t k = anchor + 1; k < j && close; ++k) {
        const Eigen::Vector2d q = at(k) - a;
        const double t = q.dot(d) / (len * len);
        close = t > 0.0 && t < 1.0 && std::abs(d.x() * q.y() - d.y() * q.x()) / len <= tolerance;
      }
      if (!close) break;
      best = j;
    }
    if (best < n) kept.push_back(best);
    anchor = best;
  }
  if (kept.size() < 3) {  // a contour smaller than the spacing: keep its shape as drawn
    kept.resize(n);
    std::iota(kept.begin(), kept.end(), 0);
  }
  std::vector<Eigen::Vector2d> out;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const Eigen::Vector2d& a = at(kept[i]);
    const Eigen::Vector2d& b = at(i + 1 < kept.size() ? kept[i + 1] : 0);
    const auto pieces = static_cast<std::size_t>(std::max(1.0, std::ceil((b - a).norm() / spacing - 1e-9)));
    for (std::size_t k = 0; k < pieces; ++k)
      out.push_back(a + (b - a) * (static_cast<double>(k) / static_cast<double>(pieces)));
  }
  return out;
}

namespace {

// Splits every edge of `p` longer than `limit` into ceil(length / piece) equal parts.
void split_long_edges(Polygon& p, double limit, double piece) {
  Polygon out;
  out.reserve(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector2d& a = p[i];
    const Eigen::Vector2d& b = p[(i + 1) % p.size()];
    const double len = (b - a).norm();
    out.push_back(a);
    if (len <= limit) continue;
    const auto pieces = static_cast<std::size_t>(std::ceil(len / piece));
    for (std::size_t k = 1; k < pieces; ++k)
      out.push_back(a + (b - a) * (static_cast<double>(k) / static_cast<double>(pieces)));
  }
  p = std::move(out);
}

double longest_edge(const Polygon& p) {
  double m = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) m = std::max(m, (p[(i + 1) % p.size()] - p[i]).norm());
  return m;
}

}  // namespace

ResamplingReport resample_drawn_stack(ContourStack& stack, double spacing, double tolerance) {
  ResamplingReport report;
  for (SliceContours& slice : stack.slices) {
    auto& cs = slice.contours;
    std::vector<Polygon> simplified(cs.size());
    for (std::size_t c = 0; c < cs.size(); ++c) {
      report.points_before += cs[c].points.size();
      simplified[c] = resample_drawn(cs[c].points, spacing, tolerance);
    }
    // Simplification moves a contour by up to `tolerance`: where that makes contours meet, keep
    // every drawn point (subdividing only).
    auto exact = [&](std::size_t c) {
      simplified[c] = resample_drawn(cs[c].points, spacing, 0.0);
      ++report.exact_fallbacks;
    };
    for (std::size_t c = 0; c < cs.size(); ++c) {
      if (find_self_intersection(simplified[c])) exact(c);
    }
    if (tolerance > 0.0 && cs.size() > 1 && find_polygon_crossing(simplified)) {
      for (std::size_t c = 0; c < cs.size(); ++c) exact(c);
    }
    // Even sampling within each outer contour and its holes.
    for (std::size_t o = 0; o < cs.size(); ++o) {
      if (cs[o].is_hole) continue;
      std::vector<std::size_t> group{o};
      for (std::size_t h = 0; h < cs.size(); ++h) {
        if (cs[h].is_hole && cs[h].parent == static_cast<int>(o)) group.push_back(h);
      }
      // A cap spaces its interior vertices by the mean edge of its outer polygon: the outer contour's,
      // or a hole's own when the hole is capped (it ends inside material, or becomes a hollow slab).
      auto mean_edge = [&](std::size_t c) {
        return perimeter(simplified[c]) / static_cast<double>(simplified[c].size());
      };
      for (int pass = 0; pass < 32; ++pass) {
        bool changed = false;
        const double outer_mean = mean_edge(o);
        for (std::size_t c : group) {
          const double piece = std::min(outer_mean, mean_edge(c));
          if (longest_edge(simplified[c]) <= 1.4 * piece) continue;
          split_long_edges(simplified[c], 1.4 * piece, piece);
          changed = true;
        }
        if (!changed) break;
      }
    }
    for (std::size_t c = 0; c < cs.size(); ++c) {
      cs[c].points = std::move(simplified[c]);
      report.points_after += cs[c].points.size();
    }
  }
  return report;
}

}  // namespace contourmesh
