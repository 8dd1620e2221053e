// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/contours.h"

#include <contourmesh/smooth/errors.h>

#include "contourmesh/internal/polygon2d.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace contourmesh {

double signed_area(const std::vector<Eigen::Vector2d>& p) { return detail::polygon_signed_area(p); }

double perimeter(const std::vector<Eigen::Vector2d>& p) {
  double len = 0.0;
  const std::size_t n = p.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) len += (p[i] - p[j]).norm();
  return len;
}

bool point_in_polygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  return detail::polygon_contains(poly, p);
}

namespace {

// p lies in the bounding box of segment ab (used once p is known to be collinear with it).
bool within(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  return p.x() >= std::min(a.x(), b.x()) && p.x() <= std::max(a.x(), b.x()) && p.y() >= std::min(a.y(), b.y()) &&
         p.y() <= std::max(a.y(), b.y());
}

// Segments ab and cd share a point; returns it.
std::optional<Eigen::Vector2d> segments_meet(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                             const Eigen::Vector2d& c, const Eigen::Vector2d& d) {
  const double o1 = detail::orient2d(a, b, c), o2 = detail::orient2d(a, b, d), o3 = detail::orient2d(c, d, a),
               o4 = detail::orient2d(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) {
    const double t = o3 / (o3 - o4);
    return a + t * (b - a);
  }
  if (o1 == 0.0 && within(a, b, c)) return c;
  if (o2 == 0.0 && within(a, b, d)) return d;
  if (o3 == 0.0 && within(c, d, a)) return a;
  if (o4 == 0.0 && within(c, d, b)) return b;
  return std::nullopt;
}

}  // namespace

namespace {

// Two edges that share a point: edge `edge_a` of polygon `a` and `edge_b` of `b`, (a, edge_a) first.
struct Meeting {
  std::size_t a = 0, edge_a = 0, b = 0, edge_b = 0;
  Eigen::Vector2d where = Eigen::Vector2d::Zero();
};

// The first pair of edges, in (polygon, edge) order, that cross or touch, over the edges of all the
// closed polygons (edge k joins point k to point k + 1 mod n): pairs within one polygon (not its
// neighbouring edges) when `within`, pairs from two polygons when `between`. Exact orientation tests on
// a uniform grid of the edges' bounding boxes (cells about one mean edge long, at most ~4 per edge):
// about linear time for evenly sampled contours.
std::optional<Meeting> first_meeting(const std::vector<const std::vector<Eigen::Vector2d>*>& polygons, bool within,
                                     bool between) {
  struct Edge {
    std::size_t polygon, index, count;
    Eigen::Vector2d a, b;
  };
  std::vector<Edge> all;
  for (std::size_t q = 0; q < polygons.size(); ++q) {
    const auto& p = *polygons[q];
    for (std::size_t k = 0; k < p.size(); ++k) all.push_back({q, k, p.size(), p[k], p[(k + 1) % p.size()]});
  }
  const std::size_t n = all.size();
  if (n < 2) return std::nullopt;
  Eigen::Vector2d lo = all[0].a, hi = all[0].a;
  double total = 0.0;
  for (const Edge& e : all) {
    lo = lo.cwiseMin(e.a);
    hi = hi.cwiseMax(e.a);
    total += (e.b - e.a).norm();
  }
  const Eigen::Vector2d extent = hi - lo;
  double cell = std::max(total / static_cast<double>(n), 1e-300);
  const double max_cells = 4.0 * static_cast<double>(n) + 16.0;
  while ((std::floor(extent.x() / cell) + 1.0) * (std::floor(extent.y() / cell) + 1.0) > max_cells) cell *= 2.0;
  const auto nx = static_cast<std::size_t>(std::floor(extent.x() / cell)) + 1;
  const auto ny = static_cast<std::size_t>(std::floor(extent.y() / cell)) + 1;
  // floor((v - origin) / cell) clamped to [0, count - 1]; the cast truncates, which is floor for the
  // positive values it sees (and no libm call).
  auto cell_of = [&](double v, double origin, std::size_t count) {
    const double u = (v - origin) / cell;
    return std::min(count - 1, u > 0.0 ? static_cast<std::size_t>(u) : std::size_t{0});
  };
  // Edges per cell (counting sort into CSR).
  std::vector<std::size_t> start(nx * ny + 1, 0);
  std::vector<std::array<std::size_t, 4>> boxes(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d& a = all[k].a;
    const Eigen::Vector2d& b = all[k].b;
    boxes[k] = {cell_of(std::min(a.x(), b.x()), lo.x(), nx), cell_of(std::max(a.x(), b.x()), lo.x(), nx),
                cell_of(std::min(a.y(), b.y()), lo.y(), ny), cell_of(std::max(a.y(), b.y()), lo.y(), ny)};
    for (std::size_t y = boxes[k][2]; y <= boxes[k][3]; ++y) {
      for (std::size_t x = boxes[k][0]; x <= boxes[k][1]; ++x) ++start[y * nx + x + 1];
    }
  }
  for (std::size_t c = 0; c < nx * ny; ++c) start[c + 1] += start[c];
  std::vector<std::size_t> edges(start.back());
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < n; ++k) {
      for (std::size_t y = boxes[k][2]; y <= boxes[k][3]; ++y) {
        for (std::size_t x = boxes[k][0]; x <= boxes[k][1]; ++x) edges[fill[y * nx + x]++] = k;
      }
    }
  }
  std::optional<std::pair<std::size_t, std::size_t>> best;  // indices into `all`, which is in (polygon, edge) order
  Eigen::Vector2d where = Eigen::Vector2d::Zero();
  for (std::size_t c = 0; c < nx * ny; ++c) {
    for (std::size_t u = start[c]; u < start[c + 1]; ++u) {
      for (std::size_t v = u + 1; v < start[c + 1]; ++v) {
        const std::size_t i = std::min(edges[u], edges[v]);
        const std::size_t j = std::max(edges[u], edges[v]);
        const Edge& ei = all[i];
        const Edge& ej = all[j];
        if (ei.polygon == ej.polygon) {
          if (!within) continue;
          // Neighbours share a point by construction.
          if (ej.index == ei.index + 1 || (ei.index == 0 && ej.index == ei.count - 1)) continue;
        } else if (!between) {
          continue;
        }
        if (best && std::make_pair(i, j) >= *best) continue;
        if (const auto at = segments_meet(ei.a, ei.b, ej.a, ej.b)) {
          best = std::make_pair(i, j);
          where = *at;
        }
      }
    }
  }
  if (!best) return std::nullopt;
  const Edge& ei = all[best->first];
  const Edge& ej = all[best->second];
  return Meeting{ei.polygon, ei.index, ej.polygon, ej.index, where};
}

}  // namespace

std::optional<SelfIntersection> find_self_intersection(const std::vector<Eigen::Vector2d>& p) {
  const std::size_t n = p.size();
  if (n < 4) return std::nullopt;  // a triangle's edges are all neighbours
  for (std::size_t i = 0; i < n; ++i) {
    if (!p[i].allFinite()) return SelfIntersection{i, i, p[i]};
  }
  const auto m = first_meeting({&p}, true, false);
  if (!m) return std::nullopt;
  return SelfIntersection{m->edge_a, m->edge_b, m->where};
}

std::optional<PolygonCrossing> find_polygon_crossing(const std::vector<std::vector<Eigen::Vector2d>>& polygons) {
  std::vector<const std::vector<Eigen::Vector2d>*> refs;
  for (const auto& p : polygons) {
    for (const Eigen::Vector2d& v : p) {
      if (!v.allFinite()) return std::nullopt;  // not comparable; find_self_intersection reports it
    }
    refs.push_back(&p);
  }
  const auto m = first_meeting(refs, false, true);
  if (!m) return std::nullopt;
  return PolygonCrossing{m->a, m->edge_a, m->b, m->edge_b, m->where};
}

std::vector<Eigen::Vector2d> resample_closed(const std::vector<Eigen::Vector2d>& poly, double spacing) {
  if (!(spacing > 0.0)) throw InvalidInputError("resample_closed: spacing must be > 0");
  if (poly.size() < 3) throw InvalidInputError("resample_closed: a closed contour needs at least 3 points");
  const double total = perimeter(poly);
  const auto count = static_cast<std::size_t>(std::max(3.0, std::round(total / spacing)));
  const double step = total / static_cast<double>(count);
  std::vector<Eigen::Vector2d> out;
  out.reserve(count);
  std::size_t seg = 0;         // current segment poly[seg] -> poly[seg + 1 mod n]
  double seg_start = 0.0;      // arc length at poly[seg]
  const std::size_t n = poly.size();
  for (std::size_t k = 0; k < count; ++k) {
    const double s = k * step;
    double seg_len = (poly[(seg + 1) % n] - poly[seg]).norm();
    while (seg_start + seg_len < s && seg + 1 < n) {
      seg_start += seg_len;
      ++seg;
      seg_len = (poly[(seg + 1) % n] - poly[seg]).norm();
    }
    const double t = seg_len > 0.0 ? std::clamp((s - seg_start) / seg_len, 0.0, 1.0) : 0.0;
    out.push_back(poly[seg] + t * (poly[(seg + 1) % n] - poly[seg]));
  }
  return out;
}

}  // namespace contourmesh
