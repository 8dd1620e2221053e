// SPDX-License-Identifier: BSD-3-Clause
#include "detail/cap_refinement.h"

#include "contourmesh/reconstruct/contours.h"
#include "detail/edge_map.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace contourmesh::detail {

namespace {

class Triangulation {
 public:
  std::vector<Eigen::Vector2d> pos;
  std::vector<PolygonVertex> id;          // boundary id, or {-1, interior index}
  std::vector<std::array<int, 3>> tris;   // counter-clockwise; a dead triangle has tris[t][0] < 0
  EdgeMap edge_to_tri;  // directed edge (u, v) -> triangle
  EdgeMap constrained;  // undirected boundary edges (the values are not read)

  static std::uint64_t key(int u, int v) { return EdgeMap::key(u, v); }
  static std::uint64_t ukey(int u, int v) { return u < v ? key(u, v) : key(v, u); }

  int add(int a, int b, int c) {
    const int t = static_cast<int>(tris.size());
    tris.push_back({a, b, c});
    edge_to_tri.assign(key(a, b), t);
    edge_to_tri.assign(key(b, c), t);
    edge_to_tri.assign(key(c, a), t);
    return t;
  }
  void kill(int t) {
    const auto [a, b, c] = tris[t];
    for (auto k : {key(a, b), key(b, c), key(c, a)}) {
      const int* holder = edge_to_tri.find(k);
      if (holder != nullptr && *holder == t) edge_to_tri.erase(k);
    }
    tris[t] = {-1, -1, -1};
  }

  // Is d strictly inside the circumcircle of the counter-clockwise triangle (a, b, c)?
  bool in_circle(int a, int b, int c, int d) const {
    const Eigen::Vector2d A = pos[a] - pos[d], B = pos[b] - pos[d], C = pos[c] - pos[d];
    const double det = (A.squaredNorm()) * (B.x() * C.y() - C.x() * B.y()) -
                       (B.squaredNorm()) * (A.x() * C.y() - C.x() * A.y()) +
                       (C.squaredNorm()) * (A.x() * B.y() - B.x() * A.y());
    return det > 1e-12 * (A.squaredNorm() + B.squaredNorm() + C.squaredNorm()) *
                     std::max({A.squaredNorm(), B.squaredNorm(), C.squaredNorm()});
  }
  static double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  }

  // Flips edges until every non-boundary edge is locally Delaunay; `stack` holds edges to check.
  void legalize(std::vector<std::pair<int, int>> stack) {
    int guard = 0;
    while (!stack.empty() && guard++ < 1000000) {
      const auto [a, b] = stack.back();
      stack.pop_back();
      if (constrained.contains(ukey(a, b))) continue;
      const int* i1 = edge_to_tri.find(key(a, b));
      const int* i2 = edge_to_tri.find(key(b, a));
      if (i1 == nullptr || i2 == nullptr) continue;
      const int t1 = *i1, t2 = *i2;
      const int c = third(t1, a, b), d = third(t2, b, a);
      if (!in_circle(a, b, c, d)) continue;
      // The quad a, d, b, c must be strictly convex for the flip to stay valid.
      if (cross(pos[c], pos[a], pos[d]) <= 0.0 || cross(pos[d], pos[b], pos[c]) <= 0.0) continue;
      kill(t1);
      kill(t2);
      add(a, d, c);
      add(d, b, c);
      stack.push_back({a, d});
      stack.push_back({d, b});
      stack.push_back({b, c});
      stack.push_back({c, a});
    }
  }

  int third(int t, int a, int b) const {
    for (int v : tris[t]) {
      if (v != a && v != b) return v;
    }
    return -1;
  }

  void flip_all() {
    std::vector<std::pair<int, int>> stack;
    for (const auto& t : tris) {
      if (t[0] < 0) continue;
      stack.push_back({t[0], t[1]});
      stack.push_back({t[1], t[2]});
      stack.push_back({t[2], t[0]});
    }
    legalize(std::move(stack));
  }
};

}  // namespace

RefinedCap triangulate_refined(const Polygon& outer, const std::vector<Polygon>& holes, double target_edge) {
  RefinedCap cap;
  const auto ears = triangulate_with_holes(outer, holes);
  if (!(target_edge > 0.0)) {
    cap.triangles = ears;
    return cap;
  }
  Triangulation tr;
  {
    double area = std::abs(signed_area(outer));
    const std::size_t expected = static_cast<std::size_t>(2.5 * area / (target_edge * target_edge)) + outer.size();
    tr.edge_to_tri.reserve(6 * expected);
    tr.tris.reserve(4 * expected);
  }
  // Vertex table: every boundary vertex once.
  std::vector<std::vector<int>> index_of(holes.size() + 1);
  auto add_polygon = [&](const Polygon& poly, int p) {
    index_of[p].resize(poly.size());
    for (std::size_t k = 0; k < poly.size(); ++k) {
      index_of[p][k] = static_cast<int>(tr.pos.size());
      tr.pos.push_back(poly[k]);
      tr.id.push_back({p, static_cast<int>(k)});
    }
    for (std::size_t k = 0; k < poly.size(); ++k) {
      tr.constrained.insert(Triangulation::ukey(index_of[p][k], index_of[p][(k + 1) % poly.size()]), 0);
    }
  };
  add_polygon(outer, 0);
  for (std::size_t h = 0; h < holes.size(); ++h) add_polygon(holes[h], static_cast<int>(h) + 1);
  for (const auto& t : ears) {
    const int a = index_of[t[0].polygon][t[0].vertex];
    const int b = index_of[t[1].polygon][t[1].vertex];
    const int c = index_of[t[2].polygon][t[2].vertex];
    if (Triangulation::cross(tr.pos[a], tr.pos[b], tr.pos[c]) <= 0.0) {
      // A degenerate ear: keep the ear-clipped result rather than refine a broken triangulation.
      cap.triangles = ears;
      return cap;
    }
    tr.add(a, b, c);
  }
  tr.flip_all();

  // Refine: centroids of triangles with an edge longer than 1.5 h, until none or a budget is spent.
  double area = std::abs(signed_area(outer));
  for (const auto& h : holes) area -= std::abs(signed_area(h));
  const std::size_t budget = static_cast<std::size_t>(4.0 * area / (target_edge * target_edge)) + 16;
  const double limit2 = (1.5 * target_edge) * (1.5 * target_edge);
  for (int pass = 0; pass < 64 && cap.interior.size() < budget; ++pass) {
    bool inserted = false;
    const std::size_t count = tr.tris.size();
    for (std::size_t t = 0; t < count && cap.interior.size() < budget; ++t) {
      const auto tri = tr.tris[t];
      if (tri[0] < 0) continue;
      const auto& A = tr.pos[tri[0]];
      const auto& B = tr.pos[tri[1]];
      const auto& C = tr.pos[tri[2]];
      const double longest = std::max({(A - B).squaredNorm(), (B - C).squaredNorm(), (C - A).squaredNorm()});
      if (longest <= limit2) continue;
      // A thin triangle's centroid lies next to its corners: inserting it makes slivers, and again at the
      // same place in the next pass (a narrow slit of a C-shaped cap filled up with coincident points).
      const Eigen::Vector2d centroid = (A + B + C) / 3.0;
      const double too_near2 = 0.09 * target_edge * target_edge;
      if ((centroid - A).squaredNorm() < too_near2 || (centroid - B).squaredNorm() < too_near2 ||
          (centroid - C).squaredNorm() < too_near2) {
        continue;
      }
      const int p = static_cast<int>(tr.pos.size());
      tr.pos.push_back(centroid);
      tr.id.push_back({-1, static_cast<int>(cap.interior.size())});
      cap.interior.push_back(tr.pos.back());
      tr.kill(static_cast<int>(t));
      tr.add(tri[0], tri[1], p);
      tr.add(tri[1], tri[2], p);
      tr.add(tri[2], tri[0], p);
      tr.legalize({{tri[0], tri[1]}, {tri[1], tri[2]}, {tri[2], tri[0]}});
      inserted = true;
    }
    if (!inserted) break;
  }

  // Relax interior vertices towards the mean of their neighbours, keeping every triangle positive.
  const int first_interior = static_cast<int>(tr.pos.size() - cap.interior.size());
  for (int round = 0; round < 2 && !cap.interior.empty(); ++round) {
    std::vector<Eigen::Vector2d> sum(tr.pos.size(), Eigen::Vector2d::Zero());
    std::vector<int> n(tr.pos.size(), 0);
    std::vector<std::vector<int>> incident(tr.pos.size());
    for (std::size_t ti = 0; ti < tr.tris.size(); ++ti) {
      const auto& t = tr.tris[ti];
      if (t[0] < 0) continue;
      for (int k = 0; k < 3; ++k) {
        sum[t[k]] += tr.pos[t[(k + 1) % 3]];
        ++n[t[k]];
        incident[t[k]].push_back(static_cast<int>(ti));
      }
    }
    for (int v = first_interior; v < static_cast<int>(tr.pos.size()); ++v) {
      if (!n[v]) continue;
      const Eigen::Vector2d old = tr.pos[v];
      tr.pos[v] = sum[v] / n[v];
      // Undo a move that would fold a triangle.
      bool folded = false;
      for (int ti : incident[v]) {
        const auto& t = tr.tris[ti];
        if (Triangulation::cross(tr.pos[t[0]], tr.pos[t[1]], tr.pos[t[2]]) <= 0.0) folded = true;
      }
      if (folded) tr.pos[v] = old;
    }
    tr.flip_all();
  }
  for (int v = first_interior; v < static_cast<int>(tr.pos.size()); ++v) cap.interior[v - first_interior] = tr.pos[v];
  for (const auto& t : tr.tris) {
    if (t[0] < 0) continue;
    cap.triangles.push_back({tr.id[t[0]], tr.id[t[1]], tr.id[t[2]]});
  }
  return cap;
}

}  // namespace contourmesh::detail
