// SPDX-License-Identifier: BSD-3-Clause
#include "detail/composite.h"

#include "detail/band_tiling.h"
#include "detail/outline.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>

namespace contourmesh::detail {

namespace {

// Copies of several contours on one plane, joined by bridges into one composite contour. Each bridge
// leaves a quad (a_i, a_i+1 of the composite so far; b_j, b_j+1 of the joined contour) to be closed by
// two faces, recorded as the cycle (a_i, b_j+1, b_j, a_i+1) that follows the composite's direction.
struct Composite {
  LevelContour ring;
  std::vector<std::pair<int, int>> origin;  ///< per point of `ring`: its copy and its index there
  std::vector<std::array<VertexRef, 4>> quads;
  std::vector<std::array<Eigen::Vector2d, 4>> quad_points;
};

// How many of the nearest pairs a bridge that must cross no contour is looked for among.
constexpr std::size_t kBridgeTries = 48;

// Whether segment p-q properly crosses an edge of one of `polygons` (touching does not count).
bool crosses_any(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const std::vector<const Polygon*>& polygons) {
  const Eigen::Vector2d lo = p.cwiseMin(q), hi = p.cwiseMax(q);
  for (const Polygon* polygon : polygons) {
    const Polygon& r = *polygon;
    for (std::size_t k = 0, prev = r.size() - 1; k < r.size(); prev = k++) {
      const Eigen::Vector2d &u = r[prev], &v = r[k];
      if (std::max(u.x(), v.x()) < lo.x() || std::min(u.x(), v.x()) > hi.x() || std::max(u.y(), v.y()) < lo.y() ||
          std::min(u.y(), v.y()) > hi.y()) {
        continue;
      }
      const double o1 = orient2d(p, q, u), o2 = orient2d(p, q, v);
      if (!((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0))) continue;
      const double o3 = orient2d(u, v, p), o4 = orient2d(u, v, q);
      if ((o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0)) return true;
    }
  }
  return false;
}

// The pair (point of `a`, point of `b`) a bridge joins: the nearest pair; with `obstacles`, the nearest of the
// kBridgeTries nearest pairs whose quad's sides cross none of those contours (a bridge across another
// contour makes the composite cross itself). With `other` (the other level), the bridge goes where that
// level joins what the bridge joins, if such a pair is not much farther than the nearest one:
// - across a wall (between a hole's copy and anything; `a_hole(i)` says whether point i of `a` comes from a
//   hole), where the other level has no material at the bridge's midpoint: the wall is open there (with
//   `opening`: a hole that opens is among the copies);
// - between two outer contours, where the other level has material there: the two are one contour (with
//   `outers`).
// A bridge elsewhere makes a composite that runs round the contours in another order than the other
// level's contour, and the band between them crosses the slab along the arcs in between. Without such a
// pair, the nearest clear one (with `obstacles`), then the nearest whose midpoint obeys the rule, then the
// nearest.
template <class AHole>
std::pair<std::size_t, std::size_t> bridge_ends(const LevelContour& a, const AHole& a_hole, const LevelContour& b,
                                                const Outline* other, bool opening, bool outers, double& distance,
                                                const std::vector<const Polygon*>* obstacles) {
  std::vector<std::tuple<double, std::size_t, std::size_t>> nearest;
  nearest.reserve(a.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    std::size_t bj = 0;
    for (std::size_t j = 0; j < b.points.size(); ++j) {
      const double d = (a.points[i] - b.points[j]).squaredNorm();
      if (d < best) {
        best = d;
        bj = j;
      }
    }
    nearest.emplace_back(best, i, bj);
  }
  std::sort(nearest.begin(), nearest.end());
  // Whether the pair's bridge breaks the rule above (false where no rule applies).
  const auto astray = [&](std::size_t i, std::size_t j) {
    const bool wall = a_hole(i) || b.is_hole;
    if (!other || (wall ? !opening : !outers)) return false;
    return other->contains(0.5 * (a.points[i] + b.points[j])) == wall;
  };
  const bool ruled = other && (opening || outers);
  if (obstacles) {
    // The first of the nearest pairs whose bridge, both sides of its quad, crosses no contour; one the
    // rule prefers if there is one not much farther than the nearest pair (a long bridge to a far opening
    // folds the band above it into pleats).
    const std::size_t na = a.points.size(), nb = b.points.size();
    const double reach = 2.0 * std::sqrt(std::get<0>(nearest.front())) + a.spacing() + b.spacing();
    for (const bool prefer : {true, false}) {
      if (prefer && !ruled) continue;
      std::size_t tried = 0;
      for (const auto& [d, i, j] : nearest) {
        if (prefer && std::sqrt(d) > reach) break;
        if (prefer && astray(i, j)) continue;
        if (++tried > kBridgeTries) break;
        if (!crosses_any(a.points[i], b.points[j], *obstacles) &&
            !crosses_any(b.points[(j + nb - 1) % nb], a.points[(i + 1) % na], *obstacles)) {
          distance = d;
          return {i, j};
        }
      }
    }
  }
  if (ruled) {
    for (const auto& [d, i, j] : nearest) {
      if (!astray(i, j)) {
        distance = d;
        return {i, j};
      }
    }
  }
  distance = std::get<0>(nearest.front());
  return {std::get<1>(nearest.front()), std::get<2>(nearest.front())};
}

// For each point of `guide`, the copy and the point of it nearest to that point (a grid of the copies'
// points, searched ring by ring of cells until no nearer point can remain).
std::vector<std::pair<int, int>> nearest_copy_points(const std::vector<LevelContour>& copies, const Polygon& guide) {
  Eigen::AlignedBox2d box;
  double spacing = 0.0;
  std::size_t count = 0;
  for (const LevelContour& c : copies) {
    box.extend(c.box);
    spacing += c.spacing() * static_cast<double>(c.points.size());
    count += c.points.size();
  }
  const double cell = std::max(2.0 * spacing / static_cast<double>(std::max<std::size_t>(count, 1)), 1e-6);
  const Eigen::Vector2d size = box.sizes();
  const int nx = std::max(1, static_cast<int>(std::ceil(size.x() / cell)) + 1);
  const int ny = std::max(1, static_cast<int>(std::ceil(size.y() / cell)) + 1);
  const auto cell_of = [&](const Eigen::Vector2d& p, int& ix, int& iy) {
    ix = std::clamp(static_cast<int>(std::floor((p.x() - box.min().x()) / cell)), 0, nx - 1);
    iy = std::clamp(static_cast<int>(std::floor((p.y() - box.min().y()) / cell)), 0, ny - 1);
  };
  std::vector<int> start(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) + 1, 0);
  std::vector<std::pair<int, int>> entries(count);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> fill;
    if (pass == 1) {
      for (std::size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
      fill.assign(start.begin(), start.end() - 1);
    }
    for (std::size_t c = 0; c < copies.size(); ++c) {
      for (std::size_t i = 0; i < copies[c].points.size(); ++i) {
        int ix = 0, iy = 0;
        cell_of(copies[c].points[i], ix, iy);
        const std::size_t slot =
            static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(ix);
        if (pass == 0) ++start[slot + 1];
        else entries[static_cast<std::size_t>(fill[slot]++)] = {static_cast<int>(c), static_cast<int>(i)};
      }
    }
  }
  std::vector<std::pair<int, int>> result(guide.size(), {-1, -1});
  for (std::size_t g = 0; g < guide.size(); ++g) {
    int cx = 0, cy = 0;
    cell_of(guide[g], cx, cy);
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r <= std::max(nx, ny); ++r) {
      // Points beyond ring r of cells are at least (r - 1) cells away (the guide point may lie off the box).
      const double reach = (r - 1) * cell;
      if (r > 0 && reach > 0.0 && reach * reach > best) break;
      for (int iy = cy - r; iy <= cy + r; ++iy) {
        for (int ix = cx - r; ix <= cx + r; ++ix) {
          if (std::max(std::abs(ix - cx), std::abs(iy - cy)) != r || ix < 0 || iy < 0 || ix >= nx || iy >= ny) continue;
          const std::size_t slot =
              static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(ix);
          for (int e = start[slot]; e < start[slot + 1]; ++e) {
            const auto [c, i] = entries[static_cast<std::size_t>(e)];
            const double d =
                (copies[static_cast<std::size_t>(c)].points[static_cast<std::size_t>(i)] - guide[g]).squaredNorm();
            if (d < best) {
              best = d;
              result[g] = {c, i};
            }
          }
        }
      }
    }
  }
  return result;
}

// Runs of at most this many guide points nearest to one copy, between two runs nearest to another, are
// taken for the other's: where two copies are about equally near (at a bridge of the guide's own composite,
// or where a copy's end faces another), the nearest copy flickers for a point or two, and the passages it
// adds would hide the one passage the guide makes from piece to piece (guided_bridge).
constexpr std::size_t kMaxGuideFlicker = 4;

// `labels` with the flickers above replaced by the label of the point before each.
void smooth_guide_labels(std::vector<std::pair<int, int>>& labels) {
  const std::size_t n = labels.size();
  if (n < 3 * (kMaxGuideFlicker + 1)) return;
  // Start at a change of copy, so that no run wraps round the end of the ring.
  std::size_t start = 0;
  while (start < n && labels[start].first == labels[(start + n - 1) % n].first) ++start;
  if (start == n) return;                                 // one copy throughout
  std::vector<std::pair<std::size_t, std::size_t>> runs;  // (first point, length), from `start` on
  for (std::size_t k = 0; k < n;) {
    const int c = labels[(start + k) % n].first;
    std::size_t len = 1;
    while (k + len < n && labels[(start + k + len) % n].first == c) ++len;
    runs.emplace_back((start + k) % n, len);
    k += len;
  }
  const std::size_t m = runs.size();
  if (m < 3) return;
  for (std::size_t r = 0; r < m; ++r) {
    const auto [first, len] = runs[r];
    const int before = labels[(runs[(r + m - 1) % m].first + runs[(r + m - 1) % m].second - 1) % n].first;
    const int after = labels[runs[(r + 1) % m].first].first;
    if (len > kMaxGuideFlicker || before != after || before < 0) continue;
    const std::pair<int, int> fill = labels[(first + n - 1) % n];
    for (std::size_t k = 0; k < len; ++k) labels[(first + k) % n] = fill;
  }
}

// How many guide points either side of its passage from the composite to a copy a guided bridge may end at.
constexpr std::size_t kGuideReach = 8;

// Checks the bridge (ba, bb) that joins copy `r` to the composite against `guide` (the one contour the
// composite is tiled to; `labels`: its points' nearest copy points) and replaces it where it would give
// the composite another order of its pieces than the guide's: then the bridge goes where the guide passes
// from the composite's pieces to r (the guide's point pair where its nearest copy changes from a joined
// one to r gives the two ends). Only where the guide enters r once and leaves it once (r is one stretch
// of the guide), and the new quad crosses no contour; false (the bridge stays) otherwise.
bool guided_bridge(const Composite& comp, const std::vector<LevelContour>& copies, std::size_t r,
                   const std::vector<bool>& used, const std::vector<std::pair<int, int>>& labels,
                   const std::vector<const Polygon*>& obstacles, std::size_t& ba, std::size_t& bb) {
  const std::size_t n = labels.size();
  std::size_t entries = 0, exits = 0, entry = 0, exit = 0;
  for (std::size_t g = 0; g < n; ++g) {
    const int c0 = labels[g].first, c1 = labels[(g + 1) % n].first;
    if (c0 < 0 || c1 < 0) return false;
    const bool in0 = used[static_cast<std::size_t>(c0)], in1 = used[static_cast<std::size_t>(c1)];
    if (in0 && c1 == static_cast<int>(r)) {
      ++entries;
      entry = g;
    } else if (c0 == static_cast<int>(r) && in1) {
      ++exits;
      exit = g;
    }
  }
  if (entries != 1 || exits != 1) return false;
  const std::size_t na = comp.ring.points.size(), nb = copies[r].points.size();
  std::vector<std::vector<int>> position(copies.size());
  for (std::size_t k = 0; k < na; ++k) {
    auto& p = position[static_cast<std::size_t>(comp.origin[k].first)];
    if (p.empty()) p.assign(copies[static_cast<std::size_t>(comp.origin[k].first)].points.size(), -1);
    p[static_cast<std::size_t>(comp.origin[k].second)] = static_cast<int>(k);
  }
  const auto ring_index = [&](const std::pair<int, int>& label) {
    const std::vector<int>& at = position[static_cast<std::size_t>(label.first)];
    return at.empty() ? -1 : at[static_cast<std::size_t>(label.second)];
  };
  // The given bridge stands when it lies where the guide skips both contours: on the composite between
  // where the guide leaves it and where it comes back, on r between where the guide leaves r and where it
  // entered. Any bridge there gives the composite the guide's order of the pieces (the nearest is the
  // shortest); one elsewhere does not.
  const int leave = ring_index(labels[entry]), back = ring_index(labels[(exit + 1) % n]);
  if (leave >= 0 && back >= 0) {
    const auto on_arc = [](std::size_t x, std::size_t from, std::size_t to, std::size_t m) {
      return (x + m - from) % m <= (to + m - from) % m;
    };
    const std::size_t r_in = static_cast<std::size_t>(labels[(entry + 1) % n].second);
    const std::size_t r_out = static_cast<std::size_t>(labels[exit].second);
    if (on_arc(ba, static_cast<std::size_t>(leave), static_cast<std::size_t>(back), na) &&
        on_arc(bb, r_out, r_in, nb)) {
      return false;
    }
  }
  // Pairs of a composite point met just before the entry and a point of r met just after it; the first
  // whose quad crosses no contour.
  std::vector<std::size_t> before, after;
  for (std::size_t s = 0; s < kGuideReach; ++s) {
    const auto [c0, i0] = labels[(entry + n - s) % n];
    if (!used[static_cast<std::size_t>(c0)]) break;
    const int k = ring_index({c0, i0});
    if (k >= 0) before.push_back(static_cast<std::size_t>(k));
  }
  for (std::size_t s = 1; s <= kGuideReach; ++s) {
    const auto [c1, i1] = labels[(entry + s) % n];
    if (c1 != static_cast<int>(r)) break;
    after.push_back(static_cast<std::size_t>(i1));
  }
  const Polygon& ap = comp.ring.points;
  const Polygon& bp = copies[r].points;
  // Nearest the passage first: by how many guide points the two ends lie from it, then by length.
  std::vector<std::tuple<std::size_t, double, std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < before.size(); ++i) {
    for (std::size_t j = 0; j < after.size(); ++j) {
      pairs.emplace_back(i + j, (ap[before[i]] - bp[after[j]]).squaredNorm(), before[i], after[j]);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  for (const auto& [steps, d, a, b] : pairs) {
    if (!crosses_any(ap[a], bp[b], obstacles) && !crosses_any(bp[(b + nb - 1) % nb], ap[(a + 1) % na], obstacles)) {
      ba = a;
      bb = b;
      return true;
    }
  }
  return false;
}

Composite make_composite(const std::vector<LevelContour>& copies, const Level& other, bool clear_bridges,
                         const Polygon* guide) {
  Composite comp;
  comp.ring = copies[0];
  for (std::size_t i = 0; i < copies[0].points.size(); ++i) comp.origin.emplace_back(0, static_cast<int>(i));
  std::vector<std::pair<int, int>> labels;
  if (guide && clear_bridges && !guide->empty()) {
    labels = nearest_copy_points(copies, *guide);
    smooth_guide_labels(labels);
  }
  std::vector<bool> used(copies.size(), false);
  used[0] = true;
  const bool opening = std::any_of(copies.begin(), copies.end(), [](const LevelContour& c) { return c.is_hole; });
  std::optional<Outline> outline;
  if (opening || clear_bridges) outline.emplace(other);
  for (std::size_t round = 1; round < copies.size(); ++round) {
    // The contour not yet joined that is nearest to the composite, bridged by the rule of bridge_ends;
    // with a guide, where the guide says so instead (guided_bridge).
    double best = std::numeric_limits<double>::infinity();
    std::size_t which = 0, ba = 0, bb = 0;
    for (std::size_t r = 0; r < copies.size(); ++r) {
      if (used[r]) continue;
      double d = 0.0;
      std::vector<const Polygon*> obstacles;
      if (clear_bridges) {
        obstacles.push_back(&comp.ring.points);
        for (std::size_t o = 0; o < copies.size(); ++o) {
          if (!used[o]) obstacles.push_back(&copies[o].points);
        }
      }
      const auto from_hole = [&](std::size_t i) {
        return copies[static_cast<std::size_t>(comp.origin[i].first)].is_hole;
      };
      const auto [a, b] = bridge_ends(comp.ring, from_hole, copies[r], outline ? &*outline : nullptr, opening,
                                      clear_bridges, d, clear_bridges ? &obstacles : nullptr);
      if (d < best) {
        best = d;
        which = r;
        ba = a;
        bb = b;
      }
    }
    if (!labels.empty()) {
      std::vector<const Polygon*> obstacles{&comp.ring.points};
      for (std::size_t o = 0; o < copies.size(); ++o) {
        if (!used[o]) obstacles.push_back(&copies[o].points);
      }
      guided_bridge(comp, copies, which, used, labels, obstacles, ba, bb);
    }
    used[which] = true;
    const LevelContour& x = copies[which];
    const std::size_t na = comp.ring.points.size(), nb = x.points.size();
    LevelContour merged;
    std::vector<std::pair<int, int>> origin;
    for (std::size_t k = 1; k <= na; ++k) {  // a_i+1 ... a_i
      merged.ids.push_back(comp.ring.ids[(ba + k) % na]);
      merged.points.push_back(comp.ring.points[(ba + k) % na]);
      origin.push_back(comp.origin[(ba + k) % na]);
    }
    for (std::size_t k = 0; k < nb; ++k) {  // b_j+1 = x[bb] ... b_j = x[bb - 1]
      merged.ids.push_back(x.ids[(bb + k) % nb]);
      merged.points.push_back(x.points[(bb + k) % nb]);
      origin.emplace_back(static_cast<int>(which), static_cast<int>((bb + k) % nb));
    }
    const std::size_t bj = (bb + nb - 1) % nb, ai1 = (ba + 1) % na;
    comp.quads.push_back({comp.ring.ids[ba], x.ids[bb], x.ids[bj], comp.ring.ids[ai1]});
    comp.quad_points.push_back({comp.ring.points[ba], x.points[bb], x.points[bj], comp.ring.points[ai1]});
    comp.ring = std::move(merged);
    comp.origin = std::move(origin);
  }
  return comp;
}

// Closes a bridge quad by its shorter diagonal; `forward` keeps the cycle's direction (the composite is
// the upper contour of its band).
void close_quad(std::array<VertexRef, 4> c, std::array<Eigen::Vector2d, 4> p, bool forward, SlabMesh& out) {
  if (!forward) {
    std::reverse(c.begin(), c.end());
    std::reverse(p.begin(), p.end());
  }
  if ((p[0] - p[2]).squaredNorm() <= (p[1] - p[3]).squaredNorm()) {
    out.add_triangle(c[0], c[1], c[2], FaceRole::Bridge);
    out.add_triangle(c[0], c[2], c[3], FaceRole::Bridge);
  } else {
    out.add_triangle(c[1], c[2], c[3], FaceRole::Bridge);
    out.add_triangle(c[1], c[3], c[0], FaceRole::Bridge);
  }
}

}  // namespace

// The contours `members` of `level` copied onto plane w and joined into one composite contour; `below`
// says whether the originals lie below the plane.
LevelContour composite_of(const Level& level, const std::vector<int>& members, const Level& other, double w, bool below,
                          bool clear_bridges, SlabMesh& out, const Polygon* guide) {
  std::vector<LevelContour> copies;
  for (int i : members) {
    const LevelContour& c = level.contours[static_cast<std::size_t>(i)];
    copies.push_back(copy_contour(c, w, out));
    if (below) emit_copy_band(c.ids, copies.back().ids, out);
    else emit_copy_band(copies.back().ids, c.ids, out);
  }
  const Composite comp = make_composite(copies, other, clear_bridges, guide);
  for (std::size_t q = 0; q < comp.quads.size(); ++q) close_quad(comp.quads[q], comp.quad_points[q], !below, out);
  ++out.stats.composites;
  return comp.ring;
}

}  // namespace contourmesh::detail
