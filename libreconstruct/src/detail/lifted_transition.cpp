// SPDX-License-Identifier: BSD-3-Clause
#include "detail/lifted_transition.h"

#include "detail/cap_refinement.h"
#include "contourmesh/reconstruct/contours.h"

#include <algorithm>
#include <array>
#include <map>
#include <cmath>
#include <limits>

namespace contourmesh::detail {

namespace {

double distance_to_polygon(const Polygon& poly, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0, prev = poly.size() - 1; k < poly.size(); prev = k++) {
    const Eigen::Vector2d a = poly[prev], d = poly[k] - a;
    const double len2 = d.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * d - p).squaredNorm());
  }
  return std::sqrt(best);
}

struct NestNode {
  const LevelContour* contour;
  bool upper;
  int parent = -1;  // smallest contour of either level that contains this one
};

}  // namespace

bool lifted_transition(const Level& lower, const Level& upper, SlabMesh& out) {
  std::vector<NestNode> nodes;
  std::vector<Polygon> polygons;
  for (const LevelContour& c : lower.contours) nodes.push_back({&c, false});
  for (const LevelContour& c : upper.contours) nodes.push_back({&c, true});
  if (nodes.empty()) return false;
  for (const NestNode& n : nodes) polygons.push_back(n.contour->points);
  if (find_polygon_crossing(polygons)) return false;
  // Nesting: with nothing crossing, one point tells whether a contour lies inside another.
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const LevelContour& c = *nodes[i].contour;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      const LevelContour& o = *nodes[j].contour;
      if (j == i || o.area <= c.area || o.area >= best || !o.box.contains(c.box)) continue;
      if (point_in_polygon(o.points, c.points[0])) {
        best = o.area;
        nodes[i].parent = static_cast<int>(j);
      }
    }
  }
  // A face of the arrangement is a contour with its children as holes. It is in a level's region when an
  // odd number of that level's contours enclose it (the contour itself included).
  struct Face {
    std::size_t outer;
    std::vector<std::size_t> holes;
    bool up;  // the lower level alone has material: the face looks up
  };
  std::vector<Face> faces;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    int in_lower = 0, in_upper = 0;
    for (int k = static_cast<int>(i); k >= 0; k = nodes[static_cast<std::size_t>(k)].parent) {
      (nodes[static_cast<std::size_t>(k)].upper ? in_upper : in_lower) ^= 1;
    }
    if (in_lower == in_upper) continue;
    Face f{i, {}, in_lower == 1};
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      if (nodes[j].parent == static_cast<int>(i)) f.holes.push_back(j);
    }
    // Lifting needs contours of both levels around the face; a face of one level only is an end.
    bool has_lower = !nodes[i].upper, has_upper = nodes[i].upper;
    for (std::size_t h : f.holes) (nodes[h].upper ? has_upper : has_lower) = true;
    if (!has_lower || !has_upper) return false;
    faces.push_back(std::move(f));
  }
  // Every contour bounds exactly one face (crossing it changes one level's parity only).
  for (const Face& f : faces) {
    // Outer boundary counter-clockwise, holes clockwise, with their vertices.
    auto oriented = [&](std::size_t k, bool ccw) {
      LevelContour c = *nodes[k].contour;
      if ((signed_area(c.points) > 0.0) != ccw) {
        std::reverse(c.points.begin(), c.points.end());
        std::reverse(c.ids.begin(), c.ids.end());
      }
      return c;
    };
    const LevelContour outer = oriented(f.outer, true);
    std::vector<LevelContour> holes;
    std::vector<Polygon> hole_points;
    for (std::size_t h : f.holes) {
      holes.push_back(oriented(h, false));
      hole_points.push_back(holes.back().points);
    }
    double spacing = 0.0;
    std::size_t points = 0;
    for (const LevelContour* c : {&outer}) {
      spacing += c->spacing() * static_cast<double>(c->points.size());
      points += c->points.size();
    }
    for (const LevelContour& h : holes) {
      spacing += h.spacing() * static_cast<double>(h.points.size());
      points += h.points.size();
    }
    const RefinedCap region = triangulate_refined(outer.points, hole_points, spacing / static_cast<double>(points));
    auto lift = [&](const Eigen::Vector2d& p) {
      double d_lower = std::numeric_limits<double>::infinity(), d_upper = d_lower;
      (nodes[f.outer].upper ? d_upper : d_lower) = distance_to_polygon(outer.points, p);
      for (std::size_t k = 0; k < holes.size(); ++k) {
        double& d = nodes[f.holes[k]].upper ? d_upper : d_lower;
        d = std::min(d, distance_to_polygon(holes[k].points, p));
      }
      return lower.w + (upper.w - lower.w) * d_lower / std::max(d_lower + d_upper, 1e-300);
    };
    // Corners: boundary corners (polygon, vertex) as they are, interior ones numbered after them.
    struct Corner {
      int polygon;  // 0 outer, k + 1 hole k, -1 interior
      int vertex;
      Eigen::Vector2d p;
    };
    std::vector<Corner> corners;
    std::map<std::pair<int, int>, int> corner_of;
    auto corner = [&](const PolygonVertex& v) {
      if (v.polygon < 0) {
        const auto key = std::make_pair(-1, v.vertex);
        const auto it = corner_of.find(key);
        if (it != corner_of.end()) return it->second;
        corners.push_back({-1, v.vertex, region.interior[static_cast<std::size_t>(v.vertex)]});
        return corner_of[key] = static_cast<int>(corners.size()) - 1;
      }
      const auto key = std::make_pair(v.polygon, v.vertex);
      const auto it = corner_of.find(key);
      if (it != corner_of.end()) return it->second;
      const LevelContour& c = v.polygon == 0 ? outer : holes[static_cast<std::size_t>(v.polygon - 1)];
      corners.push_back({v.polygon, v.vertex, c.points[static_cast<std::size_t>(v.vertex)]});
      return corner_of[key] = static_cast<int>(corners.size()) - 1;
    };
    std::vector<std::array<int, 3>> tris;
    for (const auto& t : region.triangles) tris.push_back({corner(t[0]), corner(t[1]), corner(t[2])});
    // An edge joining two contour points of the same level that are not neighbours on one contour lies
    // in that level's plane, where the fill on the level's other side may lay the same edge: split it at
    // its midpoint, which the lift takes off the plane.
    auto level_of = [&](const Corner& c) {
      if (c.polygon < 0) return -1;
      return nodes[c.polygon == 0 ? f.outer : f.holes[static_cast<std::size_t>(c.polygon - 1)]].upper ? 1 : 0;
    };
    auto in_plane = [&](int a, int b) {
      const Corner &ca = corners[static_cast<std::size_t>(a)], &cb = corners[static_cast<std::size_t>(b)];
      if (ca.polygon < 0 || cb.polygon < 0 || level_of(ca) != level_of(cb)) return false;
      if (ca.polygon != cb.polygon) return true;
      const int n =
          static_cast<int>((ca.polygon == 0 ? outer : holes[static_cast<std::size_t>(ca.polygon - 1)]).points.size());
      const int d = std::abs(ca.vertex - cb.vertex);
      return d != 1 && d != n - 1;
    };
    for (bool split = true; split;) {
      split = false;
      std::map<std::pair<int, int>, std::vector<std::size_t>> faces_of;
      for (std::size_t t = 0; t < tris.size(); ++t) {
        for (int k = 0; k < 3; ++k) {
          const int a = tris[t][k], b = tris[t][(k + 1) % 3];
          faces_of[{std::min(a, b), std::max(a, b)}].push_back(t);
        }
      }
      for (const auto& [edge, around] : faces_of) {
        if (!in_plane(edge.first, edge.second)) continue;
        const int m = static_cast<int>(corners.size());
        corners.push_back({-1, -1,
                           0.5 * (corners[static_cast<std::size_t>(edge.first)].p +
                                  corners[static_cast<std::size_t>(edge.second)].p)});
        for (std::size_t t : around) {
          // (a, b, c) with the edge a-b becomes (a, m, c) and (m, b, c), keeping the orientation.
          std::array<int, 3> tri = tris[t];
          int k = 0;
          while (!((tri[k] == edge.first && tri[(k + 1) % 3] == edge.second) ||
                   (tri[k] == edge.second && tri[(k + 1) % 3] == edge.first))) {
            ++k;
          }
          const int a = tri[k], b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
          tris[t] = {a, m, c};
          tris.push_back({m, b, c});
        }
        split = true;
        break;  // the face lists changed: collect them again
      }
    }
    std::vector<VertexRef> ref(corners.size());
    for (std::size_t k = 0; k < corners.size(); ++k) {
      const Corner& c = corners[k];
      if (c.polygon < 0) {
        ref[k] = out.add_vertex(c.p, lift(c.p));
      } else {
        const LevelContour& contour = c.polygon == 0 ? outer : holes[static_cast<std::size_t>(c.polygon - 1)];
        ref[k] = contour.ids[static_cast<std::size_t>(c.vertex)];
      }
    }
    for (const auto& t : tris) {
      if (f.up)
        out.add_triangle(ref[static_cast<std::size_t>(t[0])], ref[static_cast<std::size_t>(t[1])],
                         ref[static_cast<std::size_t>(t[2])], FaceRole::Band);
      else
        out.add_triangle(ref[static_cast<std::size_t>(t[0])], ref[static_cast<std::size_t>(t[2])],
                         ref[static_cast<std::size_t>(t[1])], FaceRole::Band);
    }
  }
  return true;
}

}  // namespace contourmesh::detail
