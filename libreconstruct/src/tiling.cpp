#include "reconstruct/tiling.h"

#include "detail/cap_refinement.h"
#include "detail/polygon.h"

#include <smooth/errors.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

namespace contourmesh {

namespace {

using detail::Polygon;

// Memory per vertex of a tiled mesh while it is built and checked: positions, ids, about two triangles
// and the builder's vectors.
constexpr double kBytesPerTiledVertex = 120.0;

// A closed loop of mesh vertices lying in one plane w.
struct Ring {
  std::vector<Index> ids;
  std::vector<Eigen::Vector2d> pts;
  double w = 0.0;
};

class MeshBuilder {
 public:
  MeshBuilder(const ContourStack& stack, Index max_vertices) : stack_(stack), max_vertices_(max_vertices) {}

  Index add_vertex(const Eigen::Vector2d& uv, double w, std::int32_t slice, std::int32_t contour) {
    if (positions_.size() >= static_cast<std::size_t>(max_vertices_)) {
      throw LimitError("tiling: the mesh would have more than " + std::to_string(max_vertices_) + " vertices");
    }
    positions_.push_back(stack_.to_physical(uv, w));
    slices_.push_back(slice);
    contours_.push_back(contour);
    return static_cast<Index>(positions_.size() - 1);
  }
  void add_triangle(Index a, Index b, Index c, FaceRole role = FaceRole::Band) {
    triangles_.push_back({a, b, c});
    roles_.push_back(role);
  }
  std::vector<FaceRole> take_roles() { return std::move(roles_); }

  Mesh finish(bool flip) {
    Mesh mesh;
    mesh.positions.resize(3, static_cast<Eigen::Index>(positions_.size()));
    for (std::size_t i = 0; i < positions_.size(); ++i) mesh.positions.col(static_cast<Eigen::Index>(i)) = positions_[i];
    mesh.triangles = std::move(triangles_);
    if (flip) {
      for (Triangle& t : mesh.triangles) std::swap(t[1], t[2]);
    }
    mesh.slice_ids = std::move(slices_);
    mesh.contour_ids = std::move(contours_);
    return mesh;
  }

 private:
  const ContourStack& stack_;
  Index max_vertices_;
  std::vector<Eigen::Vector3d> positions_;
  std::vector<std::int32_t> slices_, contours_;
  std::vector<Triangle> triangles_;
  std::vector<FaceRole> roles_;
};

double triangle_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}

// Fuchs-Kedem-Uselton: minimum-area band between `lower` and `upper` (same orientation), starting at
// lower[0] and its nearest upper point. Triangles are oriented so that, for counter-clockwise rings
// with lower below upper, normals point outward (away from the region's inside).
void tile_band(const Ring& lower, const Ring& upper, const TilingOptions& options, MeshBuilder& out) {
  const int m = static_cast<int>(lower.pts.size());
  const int n = static_cast<int>(upper.pts.size());
  int q0 = 0;
  double best = std::numeric_limits<double>::infinity();
  for (int j = 0; j < n; ++j) {
    const double d = (upper.pts[j] - lower.pts[0]).squaredNorm();
    if (d < best) {
      best = d;
      q0 = j;
    }
  }
  // The rings as 3-D points in programme order (lower from 0, upper from q0), made once: each cell of
  // the programme reads four of them, and wrapping the index (two integer divisions per point read)
  // was a quarter of the tiler's instructions.
  std::vector<Eigen::Vector3d> lower_points(static_cast<std::size_t>(m) + 1), upper_points(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= m; ++i) lower_points[i] = Eigen::Vector3d(lower.pts[i % m].x(), lower.pts[i % m].y(), lower.w);
  for (int j = 0; j <= n; ++j) {
    upper_points[j] = Eigen::Vector3d(upper.pts[(q0 + j) % n].x(), upper.pts[(q0 + j) % n].y(), upper.w);
  }
  auto P = [&](int i) -> const Eigen::Vector3d& { return lower_points[i]; };
  auto Q = [&](int j) -> const Eigen::Vector3d& { return upper_points[j]; };

  // Band of admissible j per row i around the diagonal j = i n / m.
  int half = n;
  if (static_cast<std::size_t>(m) * static_cast<std::size_t>(n) > options.full_dp_limit) {
    half = std::max({8, static_cast<int>(std::ceil(options.band_fraction * n)), (n + m - 1) / m + 2});
  }
  std::vector<int> lo(m + 1), hi(m + 1);
  for (int i = 0; i <= m; ++i) {
    const double c = static_cast<double>(i) * n / m;
    lo[i] = std::max(0, static_cast<int>(std::floor(c)) - half);
    hi[i] = std::min(n, static_cast<int>(std::ceil(c)) + half);
  }
  lo[0] = 0;
  hi[m] = n;
  std::vector<std::size_t> row_start(m + 2, 0);
  for (int i = 0; i <= m; ++i) row_start[i + 1] = row_start[i] + static_cast<std::size_t>(hi[i] - lo[i] + 1);
  check_allocation("tiling: contours of " + std::to_string(m) + " and " + std::to_string(n) + " points",
                   0.0, static_cast<double>(row_start[m + 1]) * (sizeof(double) + sizeof(std::uint8_t)), options.limits);
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> cost(row_start[m + 1], inf);
  std::vector<std::uint8_t> from_lower(row_start[m + 1], 0);  // 1: came by advancing i
  auto at = [&](int i, int j) { return row_start[i] + static_cast<std::size_t>(j - lo[i]); };
  cost[at(0, 0)] = 0.0;
  // Grid node (i, j) is the edge lower[i mod m] - upper[j mod n]; (0, j) and (m, j) are the same edge,
  // as are (i, 0) and (i, n). So that the start edge (0, 0) = (m, n) is the only edge met twice, the
  // path leaves (0, 0) along the lower ring and enters (m, n) along the upper ring: nodes (0, j > 0),
  // (m, 0) and (i < m, n) are never used.
  for (int i = 0; i <= m; ++i) {
    for (int j = lo[i]; j <= hi[i]; ++j) {
      if (i == 0 && j == 0) continue;
      if ((i == 0 && j > 0) || (i == m && j == 0) || (j == n && i < m)) continue;
      double c = inf;
      std::uint8_t fl = 0;
      if (i > 0 && j >= lo[i - 1] && j <= hi[i - 1] && cost[at(i - 1, j)] < inf) {
        c = cost[at(i - 1, j)] + triangle_area(P(i - 1), P(i), Q(j));
        fl = 1;
      }
      if (j > lo[i] && cost[at(i, j - 1)] < inf) {
        const double c2 = cost[at(i, j - 1)] + triangle_area(P(i), Q(j), Q(j - 1));
        if (c2 < c) {
          c = c2;
          fl = 0;
        }
      }
      cost[at(i, j)] = c;
      from_lower[at(i, j)] = fl;
    }
  }
  // Backtrack from (m, n).
  int i = m, j = n;
  auto lid = [&](int k) { return lower.ids[k % m]; };
  auto uid = [&](int k) { return upper.ids[(q0 + k) % n]; };
  while (i > 0 || j > 0) {
    if (from_lower[at(i, j)]) {
      out.add_triangle(lid(i - 1), lid(i), uid(j));
      --i;
    } else {
      out.add_triangle(lid(i), uid(j), uid(j - 1));
      --j;
    }
  }
}

// Copies of several rings on plane w, joined by bridges into one composite ring. Each bridge leaves a
// quad (a_i, a_i+1 of the composite so far; b_j, b_j+1 of the joined ring) to be closed by two
// triangles, recorded as the cycle (a_i, b_j+1, b_j, a_i+1) that follows the composite's direction.
struct Composite {
  Ring ring;
  std::vector<std::array<Index, 4>> quads;
};

Composite make_composite(const std::vector<Ring>& copies) {
  Composite comp;
  comp.ring = copies[0];
  std::vector<bool> used(copies.size(), false);
  used[0] = true;
  for (std::size_t round = 1; round < copies.size(); ++round) {
    // Nearest vertex pair between the composite and any ring not yet joined.
    double best = std::numeric_limits<double>::infinity();
    std::size_t which = 0;
    int ba = 0, bb = 0;
    for (std::size_t r = 0; r < copies.size(); ++r) {
      if (used[r]) continue;
      for (std::size_t a = 0; a < comp.ring.pts.size(); ++a) {
        for (std::size_t b = 0; b < copies[r].pts.size(); ++b) {
          const double d = (comp.ring.pts[a] - copies[r].pts[b]).squaredNorm();
          if (d < best) {
            best = d;
            which = r;
            ba = static_cast<int>(a);
            bb = static_cast<int>(b);
          }
        }
      }
    }
    used[which] = true;
    const Ring& x = copies[which];
    const int na = static_cast<int>(comp.ring.pts.size());
    const int nb = static_cast<int>(x.pts.size());
    Ring merged;
    merged.w = comp.ring.w;
    for (int k = 1; k <= na; ++k) {  // a_i+1 ... a_i
      merged.ids.push_back(comp.ring.ids[(ba + k) % na]);
      merged.pts.push_back(comp.ring.pts[(ba + k) % na]);
    }
    for (int k = 0; k < nb; ++k) {  // b_j+1 = x[bb] ... b_j = x[bb - 1]
      merged.ids.push_back(x.ids[(bb + k) % nb]);
      merged.pts.push_back(x.pts[(bb + k) % nb]);
    }
    comp.quads.push_back({comp.ring.ids[ba], x.ids[bb], x.ids[(bb + nb - 1) % nb], comp.ring.ids[(ba + 1) % na]});
    comp.ring = std::move(merged);
  }
  return comp;
}

// Closes a bridge quad; `forward` keeps the cycle's direction (composite is the upper ring of its band).
void close_quad(const std::array<Index, 4>& q, bool forward, const std::vector<Eigen::Vector3d>& pos, MeshBuilder& out) {
  std::array<Index, 4> c = q;
  if (!forward) std::reverse(c.begin(), c.end());
  const double d02 = (pos[0] - pos[2]).squaredNorm();
  const double d13 = (pos[1] - pos[3]).squaredNorm();
  if (d02 <= d13) {
    out.add_triangle(c[0], c[1], c[2], FaceRole::Bridge);
    out.add_triangle(c[0], c[2], c[3], FaceRole::Bridge);
  } else {
    out.add_triangle(c[1], c[2], c[3], FaceRole::Bridge);
    out.add_triangle(c[1], c[3], c[0], FaceRole::Bridge);
  }
}

// Straight band between a ring and its copy on another plane (same vertex count, same order).
void tile_copy_band(const Ring& lower, const Ring& upper, MeshBuilder& out) {
  const std::size_t n = lower.ids.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = (i + 1) % n;
    out.add_triangle(lower.ids[i], lower.ids[k], upper.ids[k]);
    out.add_triangle(lower.ids[i], upper.ids[k], upper.ids[i]);
  }
}

struct ContourRef {
  int slice;
  int index;
};

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::size_t find(std::size_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(std::size_t a, std::size_t b) { parent_[find(a)] = find(b); }

 private:
  std::vector<std::size_t> parent_;
};

// The contours of the stack with normalised orientation and parents.
struct PreparedStack {
  std::vector<std::vector<Contour>> slices;
};

PreparedStack prepare(const ContourStack& stack) {
  PreparedStack out;
  out.slices.resize(stack.slices.size());
  for (std::size_t s = 0; s < stack.slices.size(); ++s) {
    if (s > 0 && !(stack.slices[s].w > stack.slices[s - 1].w)) {
      throw InvalidInputError("tiling: slice " + std::to_string(s) + " (w = " + std::to_string(stack.slices[s].w) +
                              ") is not above slice " + std::to_string(s - 1));
    }
    auto& contours = out.slices[s] = stack.slices[s].contours;
    for (std::size_t c = 0; c < contours.size(); ++c) {
      Contour& k = contours[c];
      const std::string name = "tiling: contour " + std::to_string(c) + " of slice " + std::to_string(s);
      for (std::size_t i = 0; i < k.points.size(); ++i) {
        if (!k.points[i].allFinite()) throw InvalidInputError(name + ": point " + std::to_string(i) + " is not finite");
      }
      // Repeated points (a closing point equal to the first, or a stutter) add nothing.
      auto& pts = k.points;
      pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
      while (pts.size() > 1 && pts.back() == pts.front()) pts.pop_back();
      if (pts.size() < 3) {
        throw InvalidInputError(name + " has " + std::to_string(pts.size()) + " distinct point" +
                                (pts.size() == 1 ? "" : "s") + " (at least 3 needed)");
      }
      if (const auto x = find_self_intersection(pts)) {
        std::ostringstream msg;
        msg << name << " intersects itself: its edges " << x->first << " and " << x->second << " meet at ("
            << x->where.x() << ", " << x->where.y() << ") mm";
        throw InvalidInputError(msg.str());
      }
      const double a = signed_area(k.points);
      if ((k.is_hole && a > 0.0) || (!k.is_hole && a < 0.0)) std::reverse(k.points.begin(), k.points.end());
    }
    // The contours of a slice bound disjoint regions: none may meet another (overlapping holes made
    // the tiler produce non-manifold meshes; found by fuzzing).
    {
      std::vector<std::vector<Eigen::Vector2d>> outlines;
      outlines.reserve(contours.size());
      for (const Contour& k : contours) outlines.push_back(k.points);
      if (const auto x = find_polygon_crossing(outlines)) {
        std::ostringstream msg;
        msg << "tiling: contours " << x->first << " and " << x->second << " of slice " << s << " meet: edge "
            << x->first_edge << " of the first and edge " << x->second_edge << " of the second at (" << x->where.x()
            << ", " << x->where.y() << ") mm";
        throw InvalidInputError(msg.str());
      }
    }
    for (std::size_t c = 0; c < contours.size(); ++c) {
      Contour& k = contours[c];
      if (!k.is_hole) {
        k.parent = -1;
        continue;
      }
      // With no crossings, one point tells whether a contour lies inside another.
      for (std::size_t h = 0; h < contours.size(); ++h) {
        if (h != c && contours[h].is_hole && point_in_polygon(contours[h].points, k.points[0])) {
          throw InvalidInputError("tiling: hole contour " + std::to_string(c) + " of slice " + std::to_string(s) +
                                  " lies inside hole contour " + std::to_string(h) +
                                  " (a region inside a hole is an outer contour)");
        }
      }
      // A parent that does not contain the hole is ignored, as a missing one.
      const bool valid = k.parent >= 0 && static_cast<std::size_t>(k.parent) < contours.size() &&
                         !contours[k.parent].is_hole && point_in_polygon(contours[k.parent].points, k.points[0]);
      if (!valid) {
        // Find the smallest outer contour that contains the hole.
        int best = -1;
        double best_area = std::numeric_limits<double>::infinity();
        for (std::size_t o = 0; o < contours.size(); ++o) {
          if (contours[o].is_hole || !point_in_polygon(contours[o].points, k.points[0])) continue;
          const double area = std::abs(signed_area(contours[o].points));
          if (area < best_area) {
            best_area = area;
            best = static_cast<int>(o);
          }
        }
        if (best < 0) {
          throw InvalidInputError("tiling: hole contour " + std::to_string(c) + " of slice " + std::to_string(s) +
                                  " lies in no outer contour");
        }
        k.parent = best;
      }
    }
  }
  return out;
}

}  // namespace

TilingResult tile_contours(const ContourStack& stack, const TilingOptions& options, const ProgressCallback& progress) {
  if (!(options.min_overlap_fraction > 0.0 && options.min_overlap_fraction <= 1.0)) {
    throw InvalidInputError("tiling: min_overlap_fraction must be in (0, 1]");
  }
  const PreparedStack prepared = prepare(stack);
  const auto& slices = prepared.slices;
  const std::size_t S = slices.size();
  TilingResult result;

  // Correspondence edges between slice s and s + 1: up[s][c] lists partners of (s, c) in s + 1.
  std::vector<std::vector<std::vector<int>>> up(S), down(S);
  for (std::size_t s = 0; s < S; ++s) {
    up[s].resize(slices[s].size());
    down[s].resize(slices[s].size());
  }
  for (std::size_t s = 0; s + 1 < S; ++s) {
    const auto& a = slices[s];
    const auto& b = slices[s + 1];
    auto link = [&](std::size_t i, std::size_t j) {
      const double area_i = std::abs(signed_area(a[i].points));
      const double area_j = std::abs(signed_area(b[j].points));
      const double overlap = detail::overlap_area(a[i].points, b[j].points);
      if (overlap > options.min_overlap_fraction * std::min(area_i, area_j)) {
        up[s][i].push_back(static_cast<int>(j));
        down[s + 1][j].push_back(static_cast<int>(i));
      }
    };
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].is_hole) continue;
      for (std::size_t j = 0; j < b.size(); ++j) {
        if (!b[j].is_hole) link(i, j);
      }
    }
    // Holes correspond only when their outer contours do.
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (!a[i].is_hole) continue;
      for (std::size_t j = 0; j < b.size(); ++j) {
        if (!b[j].is_hole) continue;
        const auto& parents_up = up[s][a[i].parent];
        if (std::find(parents_up.begin(), parents_up.end(), b[j].parent) != parents_up.end()) link(i, j);
      }
    }
  }

  // A hole with no partner on a side whose outer contour continues there either ends (the material on
  // that side covers it: a cavity's roof, capped below) or opens (its region is background there: the
  // cavity reaches the outside, as the inside of a skull through the orbits). An opening hole is tiled
  // with its outer contour's group, which joins the boundaries of both into the next slice's contours.
  std::vector<std::vector<bool>> opens_up(S), opens_down(S);
  for (std::size_t s = 0; s < S; ++s) {
    opens_up[s].assign(slices[s].size(), false);
    opens_down[s].assign(slices[s].size(), false);
  }
  auto covered_fraction = [&](const Contour& hole, std::size_t other, const std::vector<int>& outers) {
    double covered = 0.0;
    for (int o : outers) {
      covered += detail::overlap_area(hole.points, slices[other][o].points);
      for (const Contour& h : slices[other]) {
        if (h.is_hole && h.parent == o) covered -= detail::overlap_area(hole.points, h.points);
      }
    }
    return covered / std::abs(signed_area(hole.points));
  };
  for (std::size_t s = 0; s < S; ++s) {
    for (std::size_t c = 0; c < slices[s].size(); ++c) {
      const Contour& h = slices[s][c];
      if (!h.is_hole) continue;
      if (s + 1 < S && up[s][c].empty() && !up[s][h.parent].empty()) {
        opens_up[s][c] = covered_fraction(h, s + 1, up[s][h.parent]) < 0.5;
      }
      if (s > 0 && down[s][c].empty() && !down[s][h.parent].empty()) {
        opens_down[s][c] = covered_fraction(h, s - 1, down[s][h.parent]) < 0.5;
      }
    }
  }

  // Contours with no partner on either side would be zero-thickness sheets: drop them (their holes too).
  std::vector<std::vector<bool>> kept(S);
  for (std::size_t s = 0; s < S; ++s) {
    kept[s].assign(slices[s].size(), true);
    for (std::size_t c = 0; c < slices[s].size(); ++c) {
      if (up[s][c].empty() && down[s][c].empty() && !opens_up[s][c] && !opens_down[s][c]) {
        kept[s][c] = false;
        ++result.stats.dropped_contours;
      }
    }
  }

  // Vertices of every kept contour, slice by slice; with the copies of branching groups and end caps,
  // and cap interiors, the mesh has roughly twice as many.
  {
    double points = 0.0;
    for (std::size_t s = 0; s < S; ++s) {
      for (std::size_t c = 0; c < slices[s].size(); ++c) points += kept[s][c] ? slices[s][c].points.size() : 0.0;
    }
    check_allocation("tiling", points, 2.0 * points * kBytesPerTiledVertex, options.limits);
  }
  // Vertices of every kept contour, slice by slice.
  MeshBuilder builder(stack, options.limits.max_vertices);
  std::vector<std::vector<Ring>> rings(S);
  for (std::size_t s = 0; s < S; ++s) {
    rings[s].resize(slices[s].size());
    for (std::size_t c = 0; c < slices[s].size(); ++c) {
      if (!kept[s][c]) continue;
      Ring& r = rings[s][c];
      r.w = stack.slices[s].w;
      r.pts = slices[s][c].points;
      for (const auto& p : r.pts) {
        r.ids.push_back(builder.add_vertex(p, r.w, static_cast<std::int32_t>(s), static_cast<std::int32_t>(c)));
      }
      if (slices[s][c].is_hole) ++result.stats.hole_contours;
    }
  }
  auto copy_ring = [&](const Ring& r, double w) {
    Ring copy;
    copy.w = w;
    copy.pts = r.pts;
    for (const auto& p : r.pts) copy.ids.push_back(builder.add_vertex(p, w, kNoId, kNoId));
    return copy;
  };
  auto close_all = [&](const Composite& comp, const std::vector<Ring>& copies, bool forward) {
    // Quad corners lie on the copies; collect their 2-D positions from all copies.
    for (const auto& q : comp.quads) {
      std::vector<Eigen::Vector3d> pos(4, Eigen::Vector3d::Zero());
      for (int k = 0; k < 4; ++k) {
        for (const Ring& r : copies) {
          for (std::size_t v = 0; v < r.ids.size(); ++v) {
            if (r.ids[v] == q[k]) pos[k] = Eigen::Vector3d(r.pts[v].x(), r.pts[v].y(), 0.0);
          }
        }
      }
      close_quad(q, forward, pos, builder);
    }
  };

  // Tile each slab.
  for (std::size_t s = 0; s + 1 < S; ++s) {
    const std::size_t na = slices[s].size();
    const std::size_t nb = slices[s + 1].size();
    UnionFind groups(na + nb);
    for (std::size_t i = 0; i < na; ++i) {
      for (int j : up[s][i]) groups.unite(i, na + static_cast<std::size_t>(j));
    }
    std::vector<std::vector<int>> lower_of(na + nb), upper_of(na + nb);
    for (std::size_t i = 0; i < na; ++i) {
      if (!kept[s][i]) continue;
      if (!up[s][i].empty()) lower_of[groups.find(i)].push_back(static_cast<int>(i));
      if (opens_up[s][i]) lower_of[groups.find(static_cast<std::size_t>(slices[s][i].parent))].push_back(static_cast<int>(i));
    }
    for (std::size_t j = 0; j < nb; ++j) {
      if (!kept[s + 1][j]) continue;
      if (!down[s + 1][j].empty()) upper_of[groups.find(na + j)].push_back(static_cast<int>(j));
      if (opens_down[s + 1][j]) {
        upper_of[groups.find(na + static_cast<std::size_t>(slices[s + 1][j].parent))].push_back(static_cast<int>(j));
      }
    }
    const double w0 = stack.slices[s].w;
    const double w1 = stack.slices[s + 1].w;
    for (std::size_t g = 0; g < na + nb; ++g) {
      const auto& L = lower_of[g];
      const auto& U = upper_of[g];
      if (L.empty() || U.empty()) continue;
      if (L.size() == 1 && U.size() == 1) {
        tile_band(rings[s][L[0]], rings[s + 1][U[0]], options, builder);
        ++result.stats.one_to_one;
        continue;
      }
      ++result.stats.branchings;
      // Several contours on a side: copy them onto an intermediate plane and join the copies.
      const bool both = L.size() > 1 && U.size() > 1;
      Ring lower_ring = rings[s][L[0]];
      Ring upper_ring = rings[s + 1][U[0]];
      if (L.size() > 1) {
        const double w = both ? w0 + (w1 - w0) / 3.0 : 0.5 * (w0 + w1);
        std::vector<Ring> copies;
        for (int i : L) {
          copies.push_back(copy_ring(rings[s][i], w));
          tile_copy_band(rings[s][i], copies.back(), builder);
        }
        const Composite comp = make_composite(copies);
        close_all(comp, copies, /*forward=*/false);  // the composite is the lower ring of its band
        lower_ring = comp.ring;
      }
      if (U.size() > 1) {
        const double w = both ? w0 + 2.0 * (w1 - w0) / 3.0 : 0.5 * (w0 + w1);
        std::vector<Ring> copies;
        for (int j : U) {
          copies.push_back(copy_ring(rings[s + 1][j], w));
          tile_copy_band(copies.back(), rings[s + 1][j], builder);
        }
        const Composite comp = make_composite(copies);
        close_all(comp, copies, /*forward=*/true);  // the composite is the upper ring of its band
        upper_ring = comp.ring;
      }
      tile_band(lower_ring, upper_ring, options, builder);
    }
    if (progress && !progress("tile", static_cast<double>(s + 1) / static_cast<double>(S))) {
      throw CancelledError("tiling");
    }
  }

  // Ends: outer contours (with their holes) and holes inside continuing outers. With
  // EndCaps::HalfSpacing the ending rings are first extended by half the slice spacing (a straight band
  // to a copy), as a slice samples a slab of that thickness.
  auto extend = [&](std::size_t s, const Ring& r, bool upward) {
    if (options.end_caps == EndCaps::AtEndSlice || S < 2) return r;
    const double gap = upward ? (s + 1 < S ? stack.slices[s + 1].w - stack.slices[s].w
                                           : stack.slices[s].w - stack.slices[s - 1].w)
                              : (s > 0 ? stack.slices[s].w - stack.slices[s - 1].w
                                       : stack.slices[s + 1].w - stack.slices[s].w);
    Ring copy = copy_ring(r, r.w + (upward ? 0.5 : -0.5) * gap);
    if (upward) tile_copy_band(r, copy, builder);
    else tile_copy_band(copy, r, builder);
    return copy;
  };
  auto cap = [&](const Ring& outer, const std::vector<Ring>& holes, bool facing_up) {
    std::vector<Polygon> hole_polys;
    for (const Ring& h : holes) hole_polys.push_back(h.pts);
    // Interior vertices about one contour spacing apart keep the cap's umbrella balanced.
    const double spacing = options.cap_refinement == CapRefinement::Interior ? perimeter(outer.pts) / outer.pts.size() : 0.0;
    const detail::RefinedCap refined = detail::triangulate_refined(outer.pts, hole_polys, spacing);
    std::vector<Index> interior;
    for (const auto& p : refined.interior) interior.push_back(builder.add_vertex(p, outer.w, kNoId, kNoId));
    for (const auto& t : refined.triangles) {
      Index v[3];
      for (int k = 0; k < 3; ++k) {
        v[k] = t[k].polygon < 0    ? interior[t[k].vertex]
               : t[k].polygon == 0 ? outer.ids[t[k].vertex]
                                   : holes[t[k].polygon - 1].ids[t[k].vertex];
      }
      if (facing_up) builder.add_triangle(v[0], v[1], v[2], FaceRole::Cap);
      else builder.add_triangle(v[0], v[2], v[1], FaceRole::Cap);
    }
    ++result.stats.caps;
  };
  for (std::size_t s = 0; s < S; ++s) {
    const auto& cs = slices[s];
    for (std::size_t c = 0; c < cs.size(); ++c) {
      if (!kept[s][c]) continue;
      const int ci = static_cast<int>(c);
      if (!cs[c].is_hole) {
        for (const bool upward : {true, false}) {
          if (!(upward ? up[s][c] : down[s][c]).empty()) continue;
          std::vector<Ring> holes;
          for (std::size_t h = 0; h < cs.size(); ++h) {
            if (kept[s][h] && cs[h].is_hole && cs[h].parent == ci) holes.push_back(extend(s, rings[s][h], upward));
          }
          cap(extend(s, rings[s][c], upward), holes, upward);
        }
      } else {
        // A hole ending inside a continuing outer: close it with a cap facing into the cavity. Its
        // inside is triangulated as a counter-clockwise polygon (the hole ring reversed).
        const int p = cs[c].parent;
        for (const bool upward : {true, false}) {
          const bool hole_ends = (upward ? up[s][c] : down[s][c]).empty() && !(upward ? opens_up : opens_down)[s][c];
          const bool parent_continues = !(upward ? up[s][p] : down[s][p]).empty();
          if (!hole_ends || !parent_continues) continue;
          Ring r = extend(s, rings[s][c], upward);
          std::reverse(r.pts.begin(), r.pts.end());
          std::reverse(r.ids.begin(), r.ids.end());
          cap(r, {}, !upward);
        }
      }
    }
  }

  const bool left_handed = stack.axis_u.cross(stack.axis_v).dot(stack.axis_w) < 0.0;
  result.face_roles = builder.take_roles();
  result.mesh = builder.finish(left_handed);
  return result;
}

}  // namespace contourmesh
