// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/internal/polygon2d.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace contourmesh::detail {

double polygon_signed_area(const Polygon& p) {
  double a = 0.0;
  const std::size_t n = p.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) a += p[j].x() * p[i].y() - p[i].x() * p[j].y();
  return 0.5 * a;
}

bool polygon_contains(const Polygon& polygon, const Eigen::Vector2d& p) {
  bool in = false;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    if (crosses_ray(polygon[j], polygon[i], p)) in = !in;
  }
  return in;
}

double polygon_signed_distance(const Polygon& v, const Eigen::Vector2d& p) {
  double d = (p - v[0]).squaredNorm();
  double s = 1.0;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i, ++i) {
    const Eigen::Vector2d e = v[j] - v[i];
    const Eigen::Vector2d w = p - v[i];
    const Eigen::Vector2d b = w - e * std::clamp(w.dot(e) / e.squaredNorm(), 0.0, 1.0);
    d = std::min(d, b.squaredNorm());
    // The edge winds around p: flip the sign (counts edges crossing p's horizontal line on one side).
    const bool c0 = p.y() >= v[i].y();
    const bool c1 = p.y() < v[j].y();
    const bool c2 = e.x() * w.y() > e.y() * w.x();
    if ((c0 && c1 && c2) || (!c0 && !c1 && !c2)) s = -s;
  }
  return s * std::sqrt(d);
}

namespace {

Eigen::AlignedBox2d box_of(const Polygon& p) {
  Eigen::AlignedBox2d b;
  for (const auto& v : p) b.extend(v);
  return b;
}

}  // namespace

namespace {

// The crossings of every scanline y_r = y0 + (r + 0.5) h, r < rows, with the polygon's edges, sorted per
// row, in one array: row r holds xs[start[r] .. start[r + 1]). Each edge visits only the rows it spans.
struct RowCrossings {
  std::vector<double> xs;
  std::vector<int> start;
};

RowCrossings row_crossings(const Polygon& poly, double y0, double h, int rows) {
  RowCrossings out;
  out.start.assign(static_cast<std::size_t>(rows) + 1, 0);
  const std::size_t n = poly.size();
  auto span = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q, int& r0, int& r1) {
    const double lo = std::min(p.y(), q.y()), hi = std::max(p.y(), q.y());
    r0 = std::max(0, static_cast<int>(std::floor((lo - y0) / h - 0.5)));
    r1 = std::min(rows - 1, static_cast<int>(std::ceil((hi - y0) / h - 0.5)));
  };
  auto crosses = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q, int r) {
    const double y = y0 + (r + 0.5) * h;
    return (p.y() > y) != (q.y() > y);
  };
  // Count, then fill.
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> fill;
    if (pass == 1) {
      for (int r = 0; r < rows; ++r) out.start[r + 1] += out.start[r];
      out.xs.resize(static_cast<std::size_t>(out.start[rows]));
      fill.assign(out.start.begin(), out.start.end() - 1);
    }
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const Eigen::Vector2d& p = poly[j];
      const Eigen::Vector2d& q = poly[i];
      if (p.y() == q.y()) continue;
      int r0 = 0, r1 = -1;
      span(p, q, r0, r1);
      for (int r = r0; r <= r1; ++r) {
        if (!crosses(p, q, r)) continue;
        if (pass == 0) {
          ++out.start[r + 1];
        } else {
          const double y = y0 + (r + 0.5) * h;
          out.xs[static_cast<std::size_t>(fill[r]++)] = p.x() + (y - p.y()) * (q.x() - p.x()) / (q.y() - p.y());
        }
      }
    }
  }
  for (int r = 0; r < rows; ++r) std::sort(out.xs.begin() + out.start[r], out.xs.begin() + out.start[r + 1]);
  return out;
}

}  // namespace

double overlap_area(const Polygon& a, const Polygon& b, int rows) {
  if (a.size() < 3 || b.size() < 3) return 0.0;
  const Eigen::AlignedBox2d ba = box_of(a), bb = box_of(b);
  const Eigen::AlignedBox2d common = ba.intersection(bb);
  if (common.isEmpty() || common.sizes().x() <= 0.0 || common.sizes().y() <= 0.0) return 0.0;
  const double h = common.sizes().y() / rows;
  const RowCrossings ca = row_crossings(a, common.min().y(), h, rows);
  const RowCrossings cb = row_crossings(b, common.min().y(), h, rows);
  double area = 0.0;
  for (int r = 0; r < rows; ++r) {
    const double* xa = ca.xs.data() + ca.start[r];
    const double* xb = cb.xs.data() + cb.start[r];
    const int na = ca.start[r + 1] - ca.start[r], nb = cb.start[r + 1] - cb.start[r];
    // Intersect the two sorted interval lists [x0, x1], [x2, x3], ...
    int i = 0, j = 0;
    while (i + 1 < na && j + 1 < nb) {
      const double lo = std::max(xa[i], xb[j]);
      const double hi = std::min(xa[i + 1], xb[j + 1]);
      if (hi > lo) area += (hi - lo) * h;
      if (xa[i + 1] < xb[j + 1]) i += 2;
      else j += 2;
    }
  }
  return area;
}

namespace {

struct Node {
  Eigen::Vector2d p;
  PolygonVertex id;
  int prev = -1;
  int next = -1;
};

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

bool in_triangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                 const Eigen::Vector2d& p) {
  return cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0;
}

class Ring {
 public:
  int add_loop(const Polygon& poly, int polygon_index) {
    const int first = static_cast<int>(nodes_.size());
    const int n = static_cast<int>(poly.size());
    for (int k = 0; k < n; ++k) {
      Node node;
      node.p = poly[k];
      node.id = {polygon_index, k};
      node.prev = first + (k + n - 1) % n;
      node.next = first + (k + 1) % n;
      nodes_.push_back(node);
    }
    return first;
  }

  // Joins the hole loop starting at `hole_start` to the ring containing `outer_start` (Eberly).
  void eliminate_hole(int outer_start, int hole_start) {
    // Rightmost vertex M of the hole.
    int m = hole_start;
    for (int k = nodes_[hole_start].next; k != hole_start; k = nodes_[k].next) {
      if (nodes_[k].p.x() > nodes_[m].p.x()) m = k;
    }
    const Eigen::Vector2d M = nodes_[m].p;
    // Nearest crossing of the ray M + t (1, 0), t > 0, with the outer ring.
    double best_x = std::numeric_limits<double>::infinity();
    int best = -1;
    int k = outer_start;
    do {
      const int nk = nodes_[k].next;
      const Eigen::Vector2d& a = nodes_[k].p;
      const Eigen::Vector2d& b = nodes_[nk].p;
      if ((a.y() <= M.y() && b.y() >= M.y()) || (b.y() <= M.y() && a.y() >= M.y())) {
        double x;
        if (a.y() == b.y()) x = std::min(a.x(), b.x());
        else x = a.x() + (M.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
        if (x >= M.x() && x < best_x) {
          best_x = x;
          best = a.x() > b.x() ? k : nk;  // the endpoint with the larger x
        }
      }
      k = nk;
    } while (k != outer_start);
    if (best < 0) best = outer_start;  // degenerate: should not happen for a hole inside the outer
    // A reflex vertex inside triangle (M, I, P) blocks P: take the one closest in angle to the ray.
    const Eigen::Vector2d I(best_x, M.y());
    const Eigen::Vector2d P = nodes_[best].p;
    int chosen = best;
    double best_angle = std::numeric_limits<double>::infinity();
    if (std::isfinite(best_x)) {
      k = outer_start;
      do {
        const Node& n = nodes_[k];
        const bool reflex = cross(nodes_[n.prev].p, n.p, nodes_[n.next].p) <= 0.0;
        if (k != best && reflex && n.p.x() >= M.x()) {
          const bool inside = (P.y() >= M.y()) ? in_triangle(M, I, P, n.p) : in_triangle(M, P, I, n.p);
          if (inside) {
            const Eigen::Vector2d d = n.p - M;
            const double angle = std::atan2(std::abs(d.y()), d.x());
            if (angle < best_angle) {
              best_angle = angle;
              chosen = k;
            }
          }
        }
        k = n.next;
      } while (k != outer_start);
    }
    // Splice: ... chosen -> m -> (hole) -> m' -> chosen' -> old chosen.next ...
    const int chosen_next = nodes_[chosen].next;
    const int m_prev = nodes_[m].prev;
    Node m_copy = nodes_[m];
    Node c_copy = nodes_[chosen];
    const int m2 = static_cast<int>(nodes_.size());
    const int c2 = m2 + 1;
    nodes_.push_back(m_copy);
    nodes_.push_back(c_copy);
    nodes_[chosen].next = m;
    nodes_[m].prev = chosen;
    nodes_[m_prev].next = m2;
    nodes_[m2].prev = m_prev;
    nodes_[m2].next = c2;
    nodes_[c2].prev = m2;
    nodes_[c2].next = chosen_next;
    nodes_[chosen_next].prev = c2;
  }

  std::vector<std::array<PolygonVertex, 3>> clip(int start) {
    std::vector<std::array<PolygonVertex, 3>> out;
    int size = 1;
    for (int k = nodes_[start].next; k != start; k = nodes_[k].next) ++size;
    build_grid(start, size);
    int cur = start;
    int stall = 0;
    while (size > 3) {
      if (is_ear(cur) || stall > size) {
        if (stall > size) cur = fallback(cur);
        const Node& n = nodes_[cur];
        out.push_back({nodes_[n.prev].id, n.id, nodes_[n.next].id});
        nodes_[n.prev].next = n.next;
        nodes_[n.next].prev = n.prev;
        alive_[static_cast<std::size_t>(cur)] = 0;
        cur = n.prev;  // the neighbours may have become ears
        --size;
        stall = 0;
      } else {
        cur = nodes_[cur].next;
        ++stall;
      }
    }
    const Node& n = nodes_[cur];
    out.push_back({nodes_[n.prev].id, n.id, nodes_[n.next].id});
    return out;
  }

 private:
  // The ring's nodes in a uniform grid over their bounding box (CSR by cell, about one node per cell), so
  // that an ear test looks only at the nodes in its triangle's box instead of walking the whole ring.
  void build_grid(int start, int size) {
    alive_.assign(nodes_.size(), 0);
    Eigen::AlignedBox2d box;
    int k = start;
    do {
      alive_[static_cast<std::size_t>(k)] = 1;
      box.extend(nodes_[k].p);
      k = nodes_[k].next;
    } while (k != start);
    const int cells = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(size))));
    origin_ = box.min();
    const Eigen::Vector2d extent = box.sizes();
    nx_ = extent.x() > 0.0 ? cells : 1;
    ny_ = extent.y() > 0.0 ? cells : 1;
    inv_cell_ = Eigen::Vector2d(extent.x() > 0.0 ? nx_ / extent.x() : 0.0, extent.y() > 0.0 ? ny_ / extent.y() : 0.0);
    cell_start_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) + 1, 0);
    k = start;
    do {
      ++cell_start_[cell_of(nodes_[k].p) + 1];
      k = nodes_[k].next;
    } while (k != start);
    for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
    cell_nodes_.assign(static_cast<std::size_t>(size), -1);
    std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
    k = start;
    do {
      cell_nodes_[static_cast<std::size_t>(fill[cell_of(nodes_[k].p)]++)] = k;
      k = nodes_[k].next;
    } while (k != start);
  }
  // Column (x) or row (y) of a coordinate, clamped to the grid: monotonic, so that a point within a box
  // lies in a cell between the cells of the box's corners.
  [[nodiscard]] int axis_cell(double v, int d) const {
    const int n = d == 0 ? nx_ : ny_;
    const double t = (v - origin_[d]) * inv_cell_[d];
    if (!(t > 0.0)) return 0;
    return t >= n ? n - 1 : static_cast<int>(t);
  }
  [[nodiscard]] std::size_t cell_of(const Eigen::Vector2d& p) const {
    return static_cast<std::size_t>(axis_cell(p.y(), 1)) * static_cast<std::size_t>(nx_) +
           static_cast<std::size_t>(axis_cell(p.x(), 0));
  }

  // Whether the corner at b is an ear: strictly convex, and no vertex of the ring but its own three that
  // is not strictly convex lies in its triangle (bridge duplicates of its corners aside; a convex vertex
  // inside would bring a reflex one with it). Only the grid cells of the triangle's box can hold one.
  [[nodiscard]] bool is_ear(int b) const {
    const Node& nb = nodes_[b];
    const Eigen::Vector2d& A = nodes_[nb.prev].p;
    const Eigen::Vector2d& B = nb.p;
    const Eigen::Vector2d& C = nodes_[nb.next].p;
    if (cross(A, B, C) <= 0.0) return false;
    const Eigen::Vector2d lo = A.cwiseMin(B).cwiseMin(C), hi = A.cwiseMax(B).cwiseMax(C);
    const int i0 = axis_cell(lo.x(), 0), i1 = axis_cell(hi.x(), 0);
    const int j0 = axis_cell(lo.y(), 1), j1 = axis_cell(hi.y(), 1);
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const std::size_t c = static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i);
        for (int e = cell_start_[c]; e < cell_start_[c + 1]; ++e) {
          const int k = cell_nodes_[static_cast<std::size_t>(e)];
          if (!alive_[static_cast<std::size_t>(k)] || k == nb.prev || k == b || k == nb.next) continue;
          const Node& n = nodes_[k];
          if (n.p == A || n.p == B || n.p == C) continue;  // bridge duplicates
          if (cross(nodes_[n.prev].p, n.p, nodes_[n.next].p) > 0.0) continue;  // convex vertices cannot block
          if (in_triangle(A, B, C, n.p)) return false;
        }
      }
    }
    return true;
  }

  // No ear found in a full turn (numerically degenerate input): clip the most convex corner.
  int fallback(int start) const {
    int best = start;
    double best_cross = -std::numeric_limits<double>::infinity();
    int k = start;
    do {
      const Node& n = nodes_[k];
      const double c = cross(nodes_[n.prev].p, n.p, nodes_[n.next].p);
      if (c > best_cross) {
        best_cross = c;
        best = k;
      }
      k = n.next;
    } while (k != start);
    return best;
  }

  std::vector<Node> nodes_;
  // Scratch of clip(): per node, whether it is still in the ring; the grid of the ring's nodes.
  std::vector<std::uint8_t> alive_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero(), inv_cell_ = Eigen::Vector2d::Zero();
  int nx_ = 1, ny_ = 1;
  std::vector<int> cell_start_, cell_nodes_;
};

}  // namespace

std::vector<std::array<PolygonVertex, 3>> triangulate_with_holes(const Polygon& outer,
                                                                 const std::vector<Polygon>& holes) {
  Ring ring;
  const int start = ring.add_loop(outer, 0);
  // Eberly: holes in order of decreasing rightmost x.
  std::vector<int> order(holes.size());
  for (std::size_t h = 0; h < holes.size(); ++h) order[h] = static_cast<int>(h);
  auto max_x = [&](int h) {
    double m = -std::numeric_limits<double>::infinity();
    for (const auto& p : holes[h]) m = std::max(m, p.x());
    return m;
  };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return max_x(a) > max_x(b); });
  for (int h : order) {
    if (holes[h].size() < 3) continue;
    const int hole_start = ring.add_loop(holes[h], h + 1);
    ring.eliminate_hole(start, hole_start);
  }
  return ring.clip(start);
}

std::vector<std::array<int, 3>> triangulate_polygon(const Polygon& polygon) {
  std::vector<std::array<int, 3>> out;
  for (const auto& t : triangulate_with_holes(polygon, {})) out.push_back({t[0].vertex, t[1].vertex, t[2].vertex});
  return out;
}

}  // namespace contourmesh::detail
