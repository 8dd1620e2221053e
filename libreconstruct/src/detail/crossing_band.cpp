// SPDX-License-Identifier: BSD-3-Clause
#include "detail/crossing_band.h"

#include "detail/bucket_lists.h"
#include "detail/cap_refinement.h"
#include "contourmesh/reconstruct/contours.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace contourmesh::detail {

namespace {

// Edge `ea` of the lower ring crosses edge `eb` of the upper one at parameters ta, tb along them.
struct Crossing {
  std::size_t ea = 0, eb = 0;
  double ta = 0.0, tb = 0.0;
  Eigen::Vector2d p;
  bool lower_exits = false;  // the lower ring leaves the upper ring's region here
};

// How two segments meet: 1 a proper crossing (with its parameters), 0 not at all, -1 touching or
// collinear.
int meet(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& q0, const Eigen::Vector2d& q1,
         double& ta, double& tb) {
  if (std::max(p0.x(), p1.x()) < std::min(q0.x(), q1.x()) || std::max(q0.x(), q1.x()) < std::min(p0.x(), p1.x()) ||
      std::max(p0.y(), p1.y()) < std::min(q0.y(), q1.y()) || std::max(q0.y(), q1.y()) < std::min(p0.y(), p1.y())) {
    return 0;
  }
  const double o1 = orient2d(p0, p1, q0), o2 = orient2d(p0, p1, q1);
  if ((o1 > 0.0 && o2 > 0.0) || (o1 < 0.0 && o2 < 0.0)) return 0;
  const double o3 = orient2d(q0, q1, p0), o4 = orient2d(q0, q1, p1);
  if ((o3 > 0.0 && o4 > 0.0) || (o3 < 0.0 && o4 < 0.0)) return 0;
  if (o1 == 0.0 || o2 == 0.0 || o3 == 0.0 || o4 == 0.0) return -1;
  ta = o3 / (o3 - o4);
  tb = o1 / (o1 - o2);
  return 1;
}

// The edges of a ring in a uniform grid, to find the edges that may meet a segment.
class EdgeGrid {
 public:
  EdgeGrid(const Polygon& ring, const Eigen::AlignedBox2d& box, double cell)
      : ring_(ring), origin_(box.min()), cell_(cell) {
    nx_ = static_cast<std::size_t>(std::floor(box.sizes().x() / cell)) + 1;
    ny_ = static_cast<std::size_t>(std::floor(box.sizes().y() / cell)) + 1;
    seen_.assign(ring.size(), std::numeric_limits<std::size_t>::max());
    // Each cell's edges in ascending order (cell c: entries start_[c] to start_[c + 1]).
    file_in_buckets(
        nx_ * ny_,
        [&](const auto& file) {
          for (std::size_t e = 0; e < ring.size(); ++e) {
            for_cells(ring[e], ring[(e + 1) % ring.size()], [&](std::size_t c) { file(c, e); });
          }
        },
        start_, entries_);
  }

  // Calls f(edge) once for each edge of the ring whose cells meet segment a-b's bounding box; `query`
  // must differ from the previous call's.
  template <class F>
  void visit(const Eigen::Vector2d& a, const Eigen::Vector2d& b, std::size_t query, F&& f) {
    for_cells(a, b, [&](std::size_t c) {
      for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) {
        const std::size_t e = entries_[k];
        if (seen_[e] == query) continue;
        seen_[e] = query;
        f(e);
      }
    });
  }

  // Whether two edges of the ring that are not neighbours meet.
  bool self_crossing() {
    const std::size_t n = ring_.size();
    bool found = false;
    for (std::size_t i = 0; i < n && !found; ++i) {
      visit(ring_[i], ring_[(i + 1) % n], i, [&](std::size_t j) {
        if (j == i || j == (i + 1) % n || i == (j + 1) % n) return;
        double ta = 0.0, tb = 0.0;
        if (meet(ring_[i], ring_[(i + 1) % n], ring_[j], ring_[(j + 1) % n], ta, tb) != 0) found = true;
      });
    }
    std::fill(seen_.begin(), seen_.end(), std::numeric_limits<std::size_t>::max());
    return found;
  }

 private:
  template <class F>
  void for_cells(const Eigen::Vector2d& a, const Eigen::Vector2d& b, F&& f) const {
    auto index = [&](double x, double o, std::size_t n) {
      const double k = std::floor((x - o) / cell_);
      return static_cast<std::size_t>(std::clamp(k, 0.0, static_cast<double>(n - 1)));
    };
    const std::size_t x0 = index(std::min(a.x(), b.x()), origin_.x(), nx_),
                      x1 = index(std::max(a.x(), b.x()), origin_.x(), nx_);
    const std::size_t y0 = index(std::min(a.y(), b.y()), origin_.y(), ny_),
                      y1 = index(std::max(a.y(), b.y()), origin_.y(), ny_);
    for (std::size_t y = y0; y <= y1; ++y) {
      for (std::size_t x = x0; x <= x1; ++x) f(y * nx_ + x);
    }
  }

  const Polygon& ring_;
  Eigen::Vector2d origin_;
  double cell_;
  std::size_t nx_ = 1, ny_ = 1;
  std::vector<std::size_t> start_;
  std::vector<std::size_t> entries_;
  std::vector<std::size_t> seen_;
};

double distance_to_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const Eigen::Vector2d d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

// A corner of a face of the arrangement: a ring vertex or a crossing.
struct ArrangementNode {
  VertexRef ref;
  Eigen::Vector2d p;
  bool on_lower, on_upper;
  bool lower_edge;  // the boundary edge from this node to the next lies on the lower ring
};

// Where the rings' crossings are along one ring: the crossings in ring order, and each crossing's
// place in it.
struct RingOrder {
  std::vector<std::size_t> along;
  std::vector<std::size_t> place;
};

// The crossings in order along a ring (key: edge, parameter); false when two coincide.
bool order_along(const std::vector<Crossing>& xs, bool lower, RingOrder& order) {
  order.along.resize(xs.size());
  for (std::size_t k = 0; k < xs.size(); ++k) order.along[k] = k;
  auto key = [&](std::size_t k) {
    return lower ? std::make_pair(xs[k].ea, xs[k].ta) : std::make_pair(xs[k].eb, xs[k].tb);
  };
  std::sort(order.along.begin(), order.along.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  order.place.assign(xs.size(), 0);
  for (std::size_t k = 0; k < xs.size(); ++k) {
    order.place[order.along[k]] = k;
    if (k > 0 && key(order.along[k]) == key(order.along[k - 1])) return false;
  }
  return true;
}

// The ring vertices strictly between the k-th crossing along the ring and the next one.
std::vector<std::size_t> arc_vertices(const std::vector<Crossing>& xs, const RingOrder& order, bool lower,
                                      std::size_t n, std::size_t k) {
  const Crossing& a = xs[order.along[k]];
  const Crossing& b = xs[order.along[(k + 1) % order.along.size()]];
  const std::size_t ea = lower ? a.ea : a.eb, eb = lower ? b.ea : b.eb;
  const double ta = lower ? a.ta : a.tb, tb = lower ? b.ta : b.tb;
  std::size_t count = (eb + n - ea) % n;
  if (count == 0 && tb <= ta) count = n;  // round the whole ring
  std::vector<std::size_t> out;
  for (std::size_t i = 1; i <= count; ++i) out.push_back((ea + i) % n);
  return out;
}

}  // namespace

namespace {

// crossing_band for counter-clockwise rings.
std::optional<CrossingBand> crossing_band_ccw(const LevelContour& lower, double wl, const LevelContour& upper,
                                              double wu, bool split_lower, bool split_upper, const SlabMesh& parent) {
  const Polygon& A = lower.points;
  const Polygon& B = upper.points;
  const std::size_t na = A.size(), nb = B.size();
  Eigen::AlignedBox2d box_a, box_b;  // a composite's ring has no box of its own
  for (const Eigen::Vector2d& p : A) box_a.extend(p);
  for (const Eigen::Vector2d& p : B) box_b.extend(p);
  if (na < 3 || nb < 3 || !box_a.intersects(box_b)) return std::nullopt;
  const double spacing = 0.5 * (lower.spacing() + upper.spacing());
  const Eigen::AlignedBox2d box = box_a.merged(box_b);
  const double cell = std::max(4.0 * spacing, std::sqrt(box.volume() / static_cast<double>(na + nb)));
  if (!(cell > 0.0) || !std::isfinite(cell)) return std::nullopt;
  EdgeGrid grid_a(A, box, cell), grid_b(B, box, cell);
  if (grid_a.self_crossing() || grid_b.self_crossing()) return std::nullopt;

  // The crossings, each proper: a touching pair gives up.
  std::vector<Crossing> xs;
  bool degenerate = false;
  for (std::size_t ea = 0; ea < na && !degenerate; ++ea) {
    const Eigen::Vector2d &p0 = A[ea], &p1 = A[(ea + 1) % na];
    grid_b.visit(p0, p1, ea, [&](std::size_t eb) {
      const Eigen::Vector2d &q0 = B[eb], &q1 = B[(eb + 1) % nb];
      Crossing x;
      const int m = meet(p0, p1, q0, q1, x.ta, x.tb);
      if (m < 0) degenerate = true;
      if (m <= 0) return;
      // A crossing next to a ring vertex would make faces of no area there.
      const double near = 1e-6 * spacing;
      if (std::min(x.ta, 1.0 - x.ta) * (p1 - p0).norm() < near ||
          std::min(x.tb, 1.0 - x.tb) * (q1 - q0).norm() < near) {
        degenerate = true;
        return;
      }
      x.ea = ea;
      x.eb = eb;
      x.p = p0 + x.ta * (p1 - p0);
      const Eigen::Vector2d da = p1 - p0, db = q1 - q0;
      x.lower_exits = db.x() * da.y() - db.y() * da.x() < 0.0;  // the lower ring turns to the upper's right
      xs.push_back(x);
    });
  }
  if (degenerate || xs.empty() || xs.size() % 2 != 0) return std::nullopt;
  RingOrder on_a, on_b;
  if (!order_along(xs, true, on_a) || !order_along(xs, false, on_b)) return std::nullopt;
  const std::size_t n = xs.size();
  // Along each ring, crossings alternate between leaving and entering the other ring's region.
  for (std::size_t k = 0; k < n; ++k) {
    if (xs[on_a.along[k]].lower_exits == xs[on_a.along[(k + 1) % n]].lower_exits) return std::nullopt;
    if (xs[on_b.along[k]].lower_exits == xs[on_b.along[(k + 1) % n]].lower_exits) return std::nullopt;
  }

  CrossingBand band;
  band.mesh = parent.scratch();
  std::vector<VertexRef> crossing_ref(n);
  for (std::size_t k = 0; k < n; ++k) crossing_ref[k] = band.mesh.add_vertex(xs[k].p, 0.5 * (wl + wu));

  // The faces of the arrangement where one ring alone encloses material. Where the lower ring alone
  // does, the face's boundary runs forward along the lower ring's arcs (those outside the upper region)
  // and backward along the upper ring's arcs (inside the lower region); where the upper one alone does,
  // the other way round. Each arc bounds exactly one such face.
  struct Face {
    std::vector<ArrangementNode> nodes;
    bool up;
  };
  std::vector<Face> faces;
  std::vector<std::uint8_t> used_a(n, 0), used_b(n, 0);
  auto crossing_node = [&](std::size_t x, bool lower_edge) {
    return ArrangementNode{crossing_ref[x], xs[x].p, true, true, lower_edge};
  };
  for (const bool up : {true, false}) {
    // up: start on lower arcs that leave the upper region; down: on upper arcs outside the lower one.
    const RingOrder& first = up ? on_a : on_b;
    const RingOrder& second = up ? on_b : on_a;
    std::vector<std::uint8_t>& used_first = up ? used_a : used_b;
    std::vector<std::uint8_t>& used_second = up ? used_b : used_a;
    const LevelContour& ring_first = up ? lower : upper;
    const LevelContour& ring_second = up ? upper : lower;
    for (std::size_t start = 0; start < n; ++start) {
      // A lower arc starting where the lower ring exits lies outside the upper region; an upper arc
      // starting there lies inside the lower region.
      if (xs[first.along[start]].lower_exits != up || used_first[start]) continue;
      Face face{{}, up};
      std::size_t k = start;
      for (std::size_t steps = 0;; ++steps) {
        if (steps > n || used_first[k]) return std::nullopt;
        used_first[k] = 1;
        face.nodes.push_back(crossing_node(first.along[k], up));
        for (std::size_t v : arc_vertices(xs, first, up, ring_first.points.size(), k)) {
          face.nodes.push_back({ring_first.ids[v], ring_first.points[v], up, !up, up});
        }
        const std::size_t end = first.along[(k + 1) % n];
        // Back along the other ring, over its arc that ends at `end`.
        const std::size_t j = (second.place[end] + n - 1) % n;
        if (used_second[j] || xs[second.along[j]].lower_exits != up) return std::nullopt;
        used_second[j] = 1;
        face.nodes.push_back(crossing_node(end, !up));
        std::vector<std::size_t> back = arc_vertices(xs, second, !up, ring_second.points.size(), j);
        for (auto it = back.rbegin(); it != back.rend(); ++it) {
          face.nodes.push_back({ring_second.ids[*it], ring_second.points[*it], !up, up, !up});
        }
        k = first.place[second.along[j]];
        if (k == start) break;
      }
      faces.push_back(std::move(face));
    }
  }
  if (std::find(used_a.begin(), used_a.end(), 0) != used_a.end() ||
      std::find(used_b.begin(), used_b.end(), 0) != used_b.end()) {
    return std::nullopt;
  }

  // The faces and crossings keep the band's Euler characteristic only when they are as many: the
  // regions inside both rings form one piece and the rings enclose no pocket outside both (either adds
  // a handle to the surface the band's annulus would have had).
  if (faces.size() != n) return std::nullopt;
  for (const Face& face : faces) {
    Polygon points;
    for (const ArrangementNode& v : face.nodes) points.push_back(v.p);
    if (signed_area(points) <= 0.0) return std::nullopt;
    const std::size_t m = points.size();
    const RefinedCap region = triangulate_refined(points, {}, spacing);
    auto lift = [&](const Eigen::Vector2d& p) {
      double d_lower = std::numeric_limits<double>::infinity(), d_upper = d_lower;
      for (std::size_t i = 0; i < m; ++i) {
        const double d = distance_to_segment(points[i], points[(i + 1) % m], p);
        double& target = face.nodes[i].lower_edge ? d_lower : d_upper;
        target = std::min(target, d);
      }
      return wl + (wu - wl) * d_lower / std::max(d_lower + d_upper, 1e-300);
    };
    // Corners: the face's nodes 0..m-1, then interior and split points.
    std::vector<Eigen::Vector2d> extra;
    auto corner = [&](const PolygonVertex& v) {
      return v.polygon < 0 ? static_cast<int>(m) + v.vertex : v.vertex;
    };
    for (const Eigen::Vector2d& p : region.interior) extra.push_back(p);
    std::vector<std::array<int, 3>> tris;
    for (const auto& t : region.triangles) tris.push_back({corner(t[0]), corner(t[1]), corner(t[2])});
    // An edge across the face between two corners of one ring lies in that ring's plane (a crossing
    // lies on both), where the ring's other side may hold the same edge: split at its midpoint, which
    // the lift takes off the plane.
    auto in_plane = [&](int a, int b) {
      if (a >= static_cast<int>(m) || b >= static_cast<int>(m)) return false;
      const int d = std::abs(a - b);
      if (d == 1 || d == static_cast<int>(m) - 1) return false;
      const ArrangementNode &na_ = face.nodes[static_cast<std::size_t>(a)];
      const ArrangementNode &nb_ = face.nodes[static_cast<std::size_t>(b)];
      return (na_.on_lower && nb_.on_lower) || (na_.on_upper && nb_.on_upper);
    };
    auto point = [&](int c) { return c < static_cast<int>(m) ? points[static_cast<std::size_t>(c)]
                                                             : extra[static_cast<std::size_t>(c) - m]; };
    for (bool split = true; split;) {
      split = false;
      for (std::size_t t = 0; t < tris.size() && !split; ++t) {
        for (int k = 0; k < 3 && !split; ++k) {
          const int a = tris[t][static_cast<std::size_t>(k)], b = tris[t][static_cast<std::size_t>((k + 1) % 3)];
          if (!in_plane(a, b)) continue;
          const int mid = static_cast<int>(m + extra.size());
          extra.push_back(0.5 * (point(a) + point(b)));
          // Every face with the edge a-b: (a, b, c) becomes (a, mid, c) and (mid, b, c).
          const std::size_t count = tris.size();
          for (std::size_t s = 0; s < count; ++s) {
            std::array<int, 3>& tri = tris[s];
            for (int q = 0; q < 3; ++q) {
              const int u = tri[static_cast<std::size_t>(q)], v = tri[static_cast<std::size_t>((q + 1) % 3)];
              if (!((u == a && v == b) || (u == b && v == a))) continue;
              const int c = tri[static_cast<std::size_t>((q + 2) % 3)];
              tri = {u, mid, c};
              tris.push_back({mid, v, c});
              break;
            }
          }
          split = true;
        }
      }
    }
    std::vector<VertexRef> ref(m + extra.size());
    for (std::size_t i = 0; i < m; ++i) ref[i] = face.nodes[i].ref;
    for (std::size_t i = 0; i < extra.size(); ++i) ref[m + i] = band.mesh.add_vertex(extra[i], lift(extra[i]));
    for (const auto& t : tris) {
      const VertexRef a = ref[static_cast<std::size_t>(t[0])], b = ref[static_cast<std::size_t>(t[1])],
                      c = ref[static_cast<std::size_t>(t[2])];
      if (face.up) band.mesh.add_triangle(a, b, c, FaceRole::Band);
      else band.mesh.add_triangle(a, c, b, FaceRole::Band);
    }
  }

  // The parent's face on the other side of each ring edge that crossings split.
  std::map<std::pair<VertexRef, VertexRef>, std::vector<std::size_t>> split_edges;  // ring edge -> crossings
  // A ring that may not be split (a slice's or an interpolated level's contour, whose edges the next
  // slab shares) keeps its edge: the crossings on it are joined to the edge by a fan standing between
  // the edge and the crossings half-way down (or up), which takes the place of the band's faces there.
  std::map<std::size_t, std::vector<std::size_t>> fans_lower, fans_upper;  // unsplit edge -> crossings
  for (std::size_t k = 0; k < n; ++k) {
    const Crossing& x = xs[k];
    if (split_lower) split_edges[{lower.ids[x.ea], lower.ids[(x.ea + 1) % na]}].push_back(k);
    else fans_lower[x.ea].push_back(k);
    if (split_upper) split_edges[{upper.ids[x.eb], upper.ids[(x.eb + 1) % nb]}].push_back(k);
    else fans_upper[x.eb].push_back(k);
  }
  for (const bool on_lower : {true, false}) {
    for (const auto& [e, crossings] : on_lower ? fans_lower : fans_upper) {
      const LevelContour& ring = on_lower ? lower : upper;
      std::vector<std::pair<double, VertexRef>> along;
      for (std::size_t k : crossings) along.emplace_back(on_lower ? xs[k].ta : xs[k].tb, crossing_ref[k]);
      std::sort(along.begin(), along.end());
      // Upper edge b -> b': fan from b over P1 ... Pk, b'; lower edge a -> a': fan from a' over Pk ... P1, a
      // (the faces of the arrangement use the crossings' edges the other way round).
      const VertexRef from = on_lower ? ring.ids[(e + 1) % ring.ids.size()] : ring.ids[e];
      std::vector<VertexRef> seq;
      if (on_lower) {
        for (auto it = along.rbegin(); it != along.rend(); ++it) seq.push_back(it->second);
        seq.push_back(ring.ids[e]);
      } else {
        for (const auto& entry : along) seq.push_back(entry.second);
        seq.push_back(ring.ids[(e + 1) % ring.ids.size()]);
      }
      for (std::size_t i = 0; i + 1 < seq.size(); ++i) band.mesh.add_triangle(from, seq[i], seq[i + 1], FaceRole::Band);
    }
  }
  for (const auto& [edge, crossings] : split_edges) {
    // The crossings in order from the edge's first end to its second.
    const bool lower_edge = lower.ids[xs[crossings[0]].ea] == edge.first &&
                            lower.ids[(xs[crossings[0]].ea + 1) % na] == edge.second;
    std::vector<std::pair<double, VertexRef>> along;
    for (std::size_t k : crossings) along.emplace_back(lower_edge ? xs[k].ta : xs[k].tb, crossing_ref[k]);
    std::sort(along.begin(), along.end());
    std::vector<VertexRef> refs;
    for (const auto& entry : along) refs.push_back(entry.second);
    band.split_edges.emplace_back(edge, std::move(refs));
  }
  band.defects = measure_defects(band.mesh);
  return band;
}

}  // namespace

std::optional<CrossingBand> crossing_band(const LevelContour& lower, double wl, const LevelContour& upper, double wu,
                                          bool split_lower, bool split_upper, const SlabMesh& parent) {
  const double area_lower = signed_area(lower.points), area_upper = signed_area(upper.points);
  if (area_lower > 0.0 && area_upper > 0.0) {
    return crossing_band_ccw(lower, wl, upper, wu, split_lower, split_upper, parent);
  }
  if (!(area_lower < 0.0 && area_upper < 0.0)) return std::nullopt;
  // Two holes: reversed, the rings enclose the void, so every face turns over.
  auto reversed = [](LevelContour c) {
    std::reverse(c.points.begin(), c.points.end());
    std::reverse(c.ids.begin(), c.ids.end());
    return c;
  };
  std::optional<CrossingBand> band =
      crossing_band_ccw(reversed(lower), wl, reversed(upper), wu, split_lower, split_upper, parent);
  if (band) {
    for (Triangle& t : band->mesh.triangles) std::swap(t[1], t[2]);
  }
  return band;
}

bool find_split_faces(CrossingBand& band, const SlabMesh& parent) {
  std::map<std::pair<VertexRef, VertexRef>, std::pair<std::size_t, int>> holder;  // edge -> (face, count)
  for (const auto& entry : band.split_edges) holder[entry.first] = {0, 0};
  for (std::size_t f = 0; f < parent.triangles.size(); ++f) {
    const Triangle& t = parent.triangles[f];
    for (int q = 0; q < 3; ++q) {
      const VertexRef u = t[q], v = t[(q + 1) % 3];
      for (const auto& key : {std::make_pair(u, v), std::make_pair(v, u)}) {
        const auto it = holder.find(key);
        if (it == holder.end()) continue;
        it->second.first = f;
        ++it->second.second;
      }
    }
  }
  std::map<std::size_t, int> faces_split;
  band.splits.clear();
  for (const auto& [edge, refs] : band.split_edges) {
    const auto [f, count] = holder[edge];
    if (count != 1 || faces_split[f]++ > 0) return false;  // one face, split on one edge only
    const Triangle& t = parent.triangles[f];
    int q = 0;
    while (!((t[q] == edge.first && t[(q + 1) % 3] == edge.second) ||
             (t[q] == edge.second && t[(q + 1) % 3] == edge.first))) {
      ++q;
    }
    const VertexRef u = t[q], v = t[(q + 1) % 3], c = t[(q + 2) % 3];
    std::vector<VertexRef> along = refs;
    if (u != edge.first) std::reverse(along.begin(), along.end());
    std::vector<Triangle> pieces;
    VertexRef from = u;
    for (VertexRef r : along) {
      pieces.push_back({from, r, c});
      from = r;
    }
    pieces.push_back({from, v, c});
    band.splits.emplace_back(f, std::move(pieces));
  }
  return true;
}

void absorb_crossing_band(CrossingBand&& band, SlabMesh& parent) {
  parent.absorb(std::move(band.mesh));
  for (auto& [f, pieces] : band.splits) {
    const FaceRole role = parent.roles[f];
    parent.triangles[f] = pieces[0];
    for (std::size_t k = 1; k < pieces.size(); ++k) parent.add_triangle(pieces[k][0], pieces[k][1], pieces[k][2], role);
  }
}

}  // namespace contourmesh::detail
