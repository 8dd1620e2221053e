// SPDX-License-Identifier: BSD-3-Clause
#include "detail/shape_interpolation.h"

#include "contourmesh/reconstruct/contours.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <memory>
#include <utility>

namespace contourmesh::detail {

namespace {

// The value standing for "very far outside" when a level holds no region at all.
constexpr double kFar = 1e9;

struct Segment {
  Eigen::Vector2d a;
  Eigen::Vector2d d;  // b - a
  double inv_len2;    // 1 / |d|^2, 0 for a zero-length edge
};

// The squared distance from p to segment s; its square root (Eigen's norm) is the distance.
double squared_distance_to(const Segment& s, const Eigen::Vector2d& p) {
  const Eigen::Vector2d ap = p - s.a;
  const double t = std::clamp(ap.dot(s.d) * s.inv_len2, 0.0, 1.0);
  return (ap - t * s.d).squaredNorm();
}

// Whether squared distance d2 is nearer than `kept2` as the distances compare (two squares may share a
// root): the roots are taken only when the squares allow it, which is seldom.
bool nearer(double d2, double kept2) { return d2 < kept2 && std::sqrt(d2) < std::sqrt(kept2); }

struct Grid {
  Eigen::Vector2d origin;
  double h;
  int nx, ny;
  [[nodiscard]] Eigen::Vector2d node(int i, int j) const { return origin + h * Eigen::Vector2d(i, j); }
};

// Even-odd inside test of every node, row by row: the crossings of each row with the polygon edges,
// sorted, toggle the inside state.
std::vector<std::uint8_t> inside_nodes(const Grid& g, const std::vector<Polygon>& polygons) {
  std::vector<std::vector<double>> rows(static_cast<std::size_t>(g.ny));
  for (const Polygon& poly : polygons) {
    const std::size_t n = poly.size();
    for (std::size_t k = 0, prev = n - 1; k < n; prev = k++) {
      const Eigen::Vector2d& p = poly[prev];
      const Eigen::Vector2d& q = poly[k];
      if (p.y() == q.y()) continue;
      const double lo = std::min(p.y(), q.y()), hi = std::max(p.y(), q.y());
      const int j0 = std::max(0, static_cast<int>(std::floor((lo - g.origin.y()) / g.h)));
      const int j1 = std::min(g.ny - 1, static_cast<int>(std::ceil((hi - g.origin.y()) / g.h)));
      for (int j = j0; j <= j1; ++j) {
        const double y = g.origin.y() + g.h * j;
        if ((p.y() > y) == (q.y() > y)) continue;
        rows[static_cast<std::size_t>(j)].push_back(p.x() + (y - p.y()) * (q.x() - p.x()) / (q.y() - p.y()));
      }
    }
  }
  std::vector<std::uint8_t> inside(static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny), 0);
  for (int j = 0; j < g.ny; ++j) {
    auto& xs = rows[static_cast<std::size_t>(j)];
    std::sort(xs.begin(), xs.end());
    std::size_t c = 0;
    for (int i = 0; i < g.nx; ++i) {
      const double x = g.origin.x() + g.h * i;
      while (c < xs.size() && xs[c] < x) ++c;
      inside[static_cast<std::size_t>(j) * g.nx + i] = static_cast<std::uint8_t>(c & 1U);
    }
  }
  return inside;
}

// Signed distance to the polygons at every node: exact distances next to each edge, then two raster
// sweeps in which every node tries the nearest edges of its already visited neighbours (the vector
// propagation of Danielsson's distance transform, with exact point-segment distances).
std::vector<double> signed_distance(const Grid& g, const std::vector<Polygon>& polygons) {
  const std::size_t count = static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny);
  std::vector<Segment> segments;
  for (const Polygon& poly : polygons) {
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const Eigen::Vector2d& a = poly[k];
      const Eigen::Vector2d d = poly[(k + 1) % poly.size()] - a;
      const double len2 = d.squaredNorm();
      segments.push_back({a, d, len2 > 0.0 ? 1.0 / len2 : 0.0});
    }
  }
  if (segments.empty()) return std::vector<double>(count, kFar);
  // Squared distances, compared as their roots would be (nearer); the roots at the end.
  std::vector<double> dist2(count, std::numeric_limits<double>::infinity());
  std::vector<int> nearest(count, -1);
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const Eigen::Vector2d a = segments[s].a, b = segments[s].a + segments[s].d;
    const int i0 = std::max(0, static_cast<int>(std::floor((std::min(a.x(), b.x()) - g.origin.x()) / g.h)) - 1);
    const int i1 = std::min(g.nx - 1, static_cast<int>(std::ceil((std::max(a.x(), b.x()) - g.origin.x()) / g.h)) + 1);
    const int j0 = std::max(0, static_cast<int>(std::floor((std::min(a.y(), b.y()) - g.origin.y()) / g.h)) - 1);
    const int j1 = std::min(g.ny - 1, static_cast<int>(std::ceil((std::max(a.y(), b.y()) - g.origin.y()) / g.h)) + 1);
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const std::size_t idx = static_cast<std::size_t>(j) * g.nx + i;
        const double d2 = squared_distance_to(segments[s], g.node(i, j));
        if (nearer(d2, dist2[idx])) {
          dist2[idx] = d2;
          nearest[idx] = static_cast<int>(s);
        }
      }
    }
  }
  // The sweeps: each node tries its visited neighbours' nearest edges, in this order (the order decides
  // between edges at equal distance). A node's own nearest edge and squared distance are held in
  // registers while it does; only its neighbours are read from the arrays.
  const int nx = g.nx, ny = g.ny;
  const Eigen::Vector2d origin = g.origin;
  const double h = g.h;
  auto sweep_node = [&](int i, int j, std::initializer_list<std::pair<int, int>> neighbours) {
    const std::size_t idx = static_cast<std::size_t>(j) * nx + i;
    int own = nearest[idx];
    double best2 = dist2[idx];
    const Eigen::Vector2d p = origin + h * Eigen::Vector2d(i, j);
    for (const auto& [ni, nj] : neighbours) {
      if (ni < 0 || nj < 0 || ni >= nx || nj >= ny) continue;
      const int s = nearest[static_cast<std::size_t>(nj) * nx + ni];
      if (s < 0 || s == own) continue;
      const double d2 = squared_distance_to(segments[static_cast<std::size_t>(s)], p);
      if (nearer(d2, best2)) {
        best2 = d2;
        own = s;
      }
    }
    dist2[idx] = best2;
    nearest[idx] = own;
  };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) sweep_node(i, j, {{i - 1, j}, {i - 1, j - 1}, {i, j - 1}, {i + 1, j - 1}});
    for (int i = nx - 1; i >= 0; --i) sweep_node(i, j, {{i + 1, j}});
  }
  for (int j = ny - 1; j >= 0; --j) {
    for (int i = nx - 1; i >= 0; --i) sweep_node(i, j, {{i + 1, j}, {i + 1, j + 1}, {i, j + 1}, {i - 1, j + 1}});
    for (int i = 0; i < nx; ++i) sweep_node(i, j, {{i - 1, j}});
  }
  const std::vector<std::uint8_t> inside = inside_nodes(g, polygons);
  std::vector<double> dist(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double d = std::sqrt(dist2[k]);
    dist[k] = inside[k] ? -d : d;
  }
  return dist;
}

// The value of f = (1 - t) lower + t upper - level at one node, as zero_level sees it: a growing level
// stays within the union of the two regions, a shrinking one around their intersection, and exact
// zeros move a hair (`nudge`) outside so that no crossing sits on a node.
double node_value(double lo, double up, double t, double level, double nudge) {
  double v = (1.0 - t) * lo + t * up - level;
  if (level > 0.0) v = std::max(v, std::min(lo, up));
  if (level < 0.0) v = std::min(v, std::max(lo, up));
  return v < 0.0 ? v : std::max(v, nudge);
}

// Twice the area, in cells, of the part of the unit cell with corner values f[0..3] (counter-clockwise
// from (0, 0): (0, 0), (1, 0), (1, 1), (0, 1)) where the bilinear-free marching-squares reading of
// zero_level puts the inside (f < 0): corners and the linear crossings on the edges, a saddle resolved by
// the mean of the corners. Summed over the cells, this is the area zero_level's polygons enclose (outer
// minus holes), without building them.
double cell_inside_area2(const double f[4]) {
  static constexpr double kCorner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const bool neg[4] = {f[0] < 0.0, f[1] < 0.0, f[2] < 0.0, f[3] < 0.0};
  // The boundary walk: inside corners and crossings, in counter-clockwise order.
  double x[8], y[8];
  int n = 0;
  for (int k = 0; k < 4; ++k) {
    const int m = (k + 1) % 4;
    if (neg[k]) {
      x[n] = kCorner[k][0];
      y[n++] = kCorner[k][1];
    }
    if (neg[k] != neg[m]) {
      const double s = f[k] / (f[k] - f[m]);
      x[n] = kCorner[k][0] + s * (kCorner[m][0] - kCorner[k][0]);
      y[n++] = kCorner[k][1] + s * (kCorner[m][1] - kCorner[k][1]);
    }
  }
  // Twice the signed area of the polygon through the walk's points idx[0 .. count).
  auto shoelace = [&](const int* idx, int count) {
    double a = 0.0;
    for (int i = 0; i < count; ++i) {
      const int p = idx[i], q = idx[(i + 1) % count];
      a += x[p] * y[q] - x[q] * y[p];
    }
    return a;
  };
  const bool saddle = neg[0] == neg[2] && neg[1] == neg[3] && neg[0] != neg[1];
  if (!saddle || (f[0] + f[1] + f[2] + f[3]) < 0.0) {
    // One inside piece, or none (a saddle whose centre is inside joins both corners through it): the walk
    // is its boundary.
    static constexpr int kWalk[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    return shoelace(kWalk, n);
  }
  // A saddle whose centre is outside: two corner triangles. The walk is corner, crossing, crossing,
  // corner, crossing, crossing (starting at corner 0 when it is inside, else at corner 1's crossing).
  static constexpr int kCorner0[2][3] = {{0, 1, 5}, {2, 3, 4}}, kCrossing0[2][3] = {{0, 1, 2}, {3, 4, 5}};
  const auto& triangles = neg[0] ? kCorner0 : kCrossing0;
  return shoelace(triangles[0], 3) + shoelace(triangles[1], 3);
}

}  // namespace

DistancePair signed_distance_pair(const std::vector<Polygon>& lower, const std::vector<Polygon>& upper, double h,
                                  std::size_t max_nodes) {
  DistancePair out;
  Eigen::AlignedBox2d box;
  for (const auto* set : {&lower, &upper}) {
    for (const Polygon& p : *set) {
      for (const Eigen::Vector2d& v : p) box.extend(v);
    }
  }
  if (box.isEmpty() || !(h > 0.0)) return out;
  const Eigen::Vector2d size = box.sizes();
  auto nodes = [&](double step) {
    return (std::ceil(size.x() / step) + 5.0) * (std::ceil(size.y() / step) + 5.0);
  };
  while (nodes(h) > static_cast<double>(std::max<std::size_t>(max_nodes, 64))) h *= 1.25;
  Grid g{box.min() - Eigen::Vector2d::Constant(2.0 * h), h, static_cast<int>(std::ceil(size.x() / h)) + 5,
         static_cast<int>(std::ceil(size.y() / h)) + 5};
  out.origin = g.origin;
  out.h = h;
  out.nx = g.nx;
  out.ny = g.ny;
  out.lower = signed_distance(g, lower);
  out.upper = signed_distance(g, upper);
  return out;
}

std::vector<Polygon> zero_level(const DistancePair& fields, double t, double level) {
  const int nx = fields.nx, ny = fields.ny;
  std::vector<Polygon> loops;
  if (nx < 2 || ny < 2) return loops;
  const std::size_t count = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  // Values at the nodes; exact zeros move a hair outside so that no crossing sits on a node (two
  // loops would touch there).
  const double nudge = 1e-7 * fields.h;
  // (arrays filled whole at once: not zeroed first)
  const std::unique_ptr<double[]> f(new double[count]);
  for (std::size_t k = 0; k < count; ++k) f[k] = node_value(fields.lower[k], fields.upper[k], t, level, nudge);
  // Which nodes are inside, one byte each: runs of eight cells whose nine nodes on both rows are all
  // inside or all outside hold no crossing and are passed over in one step (most of the grid).
  const std::unique_ptr<std::uint8_t[]> inside(new std::uint8_t[count]);
  for (std::size_t k = 0; k < count; ++k) inside[k] = f[k] < 0.0 ? 1 : 0;
  auto uniform_run = [&](std::size_t a, std::size_t b) {  // nodes a .. a + 8 and b .. b + 8
    std::uint64_t x = 0, y = 0;
    std::memcpy(&x, inside.get() + a, sizeof x);
    std::memcpy(&y, inside.get() + b, sizeof y);
    const std::uint64_t all = inside[a] ? 0x0101010101010101ULL : 0;
    return x == all && y == all && inside[a + 8] == inside[a] && inside[b + 8] == inside[a];
  };
  // Grid edges: horizontal (i, j)-(i + 1, j) has id j * nx + i; vertical (i, j)-(i, j + 1) has id
  // count + j * nx + i. A crossing is named by its edge.
  auto crossing = [&](std::size_t id) -> Eigen::Vector2d {
    const bool vertical = id >= count;
    const std::size_t base = vertical ? id - count : id;
    const int i = static_cast<int>(base % static_cast<std::size_t>(nx));
    const int j = static_cast<int>(base / static_cast<std::size_t>(nx));
    const std::size_t a = base, b = vertical ? base + static_cast<std::size_t>(nx) : base + 1;
    const double s = f[a] / (f[a] - f[b]);
    const Eigen::Vector2d pa = fields.origin + fields.h * Eigen::Vector2d(i, j);
    return pa + s * fields.h * (vertical ? Eigen::Vector2d(0, 1) : Eigen::Vector2d(1, 0));
  };
  // (edge, next edge) for every crossing where the level leaves a cell's inside: a few per cell the level
  // passes, so nothing is kept per node of the grid.
  std::vector<std::pair<std::size_t, std::size_t>> links;
  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      const std::size_t c0 = static_cast<std::size_t>(j) * nx + i;
      if (i + 9 <= nx && uniform_run(c0, c0 + static_cast<std::size_t>(nx))) {
        i += 7;  // cells i .. i + 7
        continue;
      }
      const std::size_t c[4] = {c0, c0 + 1, c0 + 1 + static_cast<std::size_t>(nx), c0 + static_cast<std::size_t>(nx)};
      const bool neg[4] = {f[c[0]] < 0.0, f[c[1]] < 0.0, f[c[2]] < 0.0, f[c[3]] < 0.0};
      if (neg[0] == neg[1] && neg[1] == neg[2] && neg[2] == neg[3]) continue;
      // Cell edges counter-clockwise: bottom c0-c1, right c1-c2, top c2-c3, left c3-c0.
      const std::size_t edge[4] = {c0, count + c0 + 1, c0 + static_cast<std::size_t>(nx), count + c0};
      const bool saddle = neg[0] == neg[2] && neg[1] == neg[3];
      const bool centre_inside = (f[c[0]] + f[c[1]] + f[c[2]] + f[c[3]]) < 0.0;
      for (int k = 0; k < 4; ++k) {
        if (!(neg[k] && !neg[(k + 1) % 4])) continue;  // start at a crossing from inside to outside
        int partner = -1;
        if (saddle) {
          partner = centre_inside ? (k + 1) % 4 : (k + 3) % 4;
        } else {
          for (int m = 1; m < 4; ++m) {
            const int e = (k + m) % 4;
            if (!neg[e] && neg[(e + 1) % 4]) partner = e;
          }
        }
        links.emplace_back(edge[k], edge[partner]);
      }
    }
  }
  // Each edge starts one link at most (the cell where the level leaves across it): sorted by edge, the
  // links are the starts in order, and the link leaving edge e is found by binary search.
  std::sort(links.begin(), links.end());
  std::vector<std::uint8_t> used(links.size(), 0);
  auto find = [&](std::size_t e) -> std::size_t {
    const auto it =
        std::lower_bound(links.begin(), links.end(), e,
                         [](const std::pair<std::size_t, std::size_t>& a, std::size_t x) { return a.first < x; });
    return it != links.end() && it->first == e ? static_cast<std::size_t>(it - links.begin()) : links.size();
  };
  for (std::size_t s = 0; s < links.size(); ++s) {
    if (used[s]) continue;
    Polygon loop;
    for (std::size_t k = s; k < links.size() && !used[k]; k = find(links[k].second)) {
      used[k] = 1;
      loop.push_back(crossing(links[k].first));
    }
    if (loop.size() >= 3) loops.push_back(std::move(loop));
  }
  return loops;
}

double level_area(const DistancePair& fields, double t, double level) {
  const int nx = fields.nx, ny = fields.ny;
  if (nx < 2 || ny < 2) return 0.0;
  const double nudge = 1e-7 * fields.h;
  const double* lo = fields.lower.data();
  const double* up = fields.upper.data();
  double full = 0.0;     // cells wholly inside
  double partial = 0.0;  // twice the inside area of the others, in cells
  std::vector<double> row0(static_cast<std::size_t>(nx)), row1(static_cast<std::size_t>(nx));
  for (int i = 0; i < nx; ++i) row0[static_cast<std::size_t>(i)] = node_value(lo[i], up[i], t, level, nudge);
  for (int j = 0; j + 1 < ny; ++j) {
    const std::size_t base = static_cast<std::size_t>(j + 1) * static_cast<std::size_t>(nx);
    for (int i = 0; i < nx; ++i) {
      row1[static_cast<std::size_t>(i)] = node_value(lo[base + i], up[base + i], t, level, nudge);
    }
    for (int i = 0; i + 1 < nx; ++i) {
      const std::size_t a = static_cast<std::size_t>(i);
      const double f[4] = {row0[a], row0[a + 1], row1[a + 1], row1[a]};
      const bool all_in = f[0] < 0.0 && f[1] < 0.0 && f[2] < 0.0 && f[3] < 0.0;
      const bool all_out = f[0] >= 0.0 && f[1] >= 0.0 && f[2] >= 0.0 && f[3] >= 0.0;
      if (all_in) full += 1.0;
      else if (!all_out) partial += cell_inside_area2(f);
    }
    std::swap(row0, row1);
  }
  return (full + 0.5 * partial) * fields.h * fields.h;
}

double level_for_area(const DistancePair& fields, double t, double target_area) {
  const std::size_t count =
      static_cast<std::size_t>(std::max(fields.nx, 0)) * static_cast<std::size_t>(std::max(fields.ny, 0));
  if (count < 4) return 0.0;
  const double cell = fields.h * fields.h;
  auto area_at = [&](double iso) { return level_area(fields, t, iso); };
  double iso = 0.0;
  double area = area_at(iso);
  if (std::abs(area - target_area) <= cell) return 0.0;
  // The value from which each node is inside the level: its blend, except that a growing level never
  // takes a node outside both regions and a shrinking one never gives up a node inside both.
  const bool grow = target_area > area;
  constexpr double kNever = std::numeric_limits<double>::infinity();
  // (made in place of the array nth_element partly sorts; `inside` counts those below the level 0)
  std::vector<double> sorted;
  sorted.reserve(count);
  std::size_t below = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const double lo = fields.lower[k], up = fields.upper[k];
    const double blend = (1.0 - t) * lo + t * up;
    const double from = grow ? (std::min(lo, up) < 0.0 ? blend : kNever) : (std::max(lo, up) < 0.0 ? -kNever : blend);
    below += from < iso ? 1 : 0;
    sorted.push_back(from);
  }
  // The area inside grows by about one cell per node that the level passes: the node count to add is
  // the area missing over a cell, and the level is the value of the node with that rank. Then secant
  // steps on the area, which is continuous and monotonic in the level.
  const double tolerance = std::max(cell, 1e-3 * std::abs(target_area));
  const auto inside = static_cast<double>(below);
  const double rank = std::clamp(inside + (target_area - area) / cell, 0.0, static_cast<double>(count - 1));
  auto nth = sorted.begin() + static_cast<std::ptrdiff_t>(std::round(rank));
  std::nth_element(sorted.begin(), nth, sorted.end());
  if (!std::isfinite(*nth)) return 0.0;
  double previous_iso = iso, previous_area = area;
  iso = grow ? std::max(*nth, 0.0) : std::min(*nth, 0.0);
  area = area_at(iso);
  for (int step = 0; step < 4 && std::abs(area - target_area) > tolerance && area != previous_area; ++step) {
    double next = iso + (target_area - area) * (iso - previous_iso) / (area - previous_area);
    next = grow ? std::max(next, 0.0) : std::min(next, 0.0);
    previous_iso = iso;
    previous_area = area;
    iso = next;
    area = area_at(iso);
  }
  return iso;
}

namespace {

bool level_is_valid(const std::vector<InterpolatedContour>& level) {
  std::vector<Polygon> polys;
  for (const auto& c : level) {
    if (c.points.size() < 3 || find_self_intersection(c.points)) return false;
    polys.push_back(c.points);
  }
  return !find_polygon_crossing(polys);
}

}  // namespace

std::optional<std::vector<InterpolatedContour>> interpolate_contours(const DistancePair& fields, double t,
                                                                     double spacing, double iso) {
  std::vector<Polygon> loops = zero_level(fields, t, iso);
  // Loops shorter than three spacings would become triangles or less.
  std::erase_if(loops, [&](const Polygon& p) { return perimeter(p) < 3.0 * spacing; });
  std::vector<double> areas;
  for (const Polygon& p : loops) areas.push_back(signed_area(p));
  for (int attempt = 0; attempt < 3; ++attempt) {
    const double step = spacing / static_cast<double>(1 << attempt);
    std::vector<InterpolatedContour> level;
    for (std::size_t k = 0; k < loops.size(); ++k) {
      InterpolatedContour c;
      c.points = resample_closed(loops[k], step);
      c.is_hole = areas[k] < 0.0;
      level.push_back(std::move(c));
    }
    // Parents: the smallest outer that contains the hole (the zero level nests properly).
    std::vector<InterpolatedContour> kept;
    std::vector<int> index(level.size(), -1);
    for (std::size_t k = 0; k < level.size(); ++k) {
      if (level[k].is_hole) continue;
      index[k] = static_cast<int>(kept.size());
      kept.push_back(level[k]);
    }
    for (std::size_t k = 0; k < level.size(); ++k) {
      if (!level[k].is_hole) continue;
      int best = -1;
      double best_area = std::numeric_limits<double>::infinity();
      for (std::size_t o = 0; o < level.size(); ++o) {
        if (level[o].is_hole || std::abs(areas[o]) <= std::abs(areas[k]) || std::abs(areas[o]) >= best_area) continue;
        if (point_in_polygon(loops[o], loops[k][0])) {
          best = static_cast<int>(o);
          best_area = std::abs(areas[o]);
        }
      }
      if (best < 0) continue;  // its outer was too small to keep
      level[k].parent = index[static_cast<std::size_t>(best)];
      kept.push_back(level[k]);
    }
    if (level_is_valid(kept)) return kept;
  }
  return std::nullopt;
}

}  // namespace contourmesh::detail
