#include "detail/lifted_transition.h"

#include "detail/cap_refinement.h"
#include "reconstruct/contours.h"

#include <algorithm>
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

struct Node {
  const LevelContour* contour;
  bool upper;
  int parent = -1;  // smallest contour of either level that contains this one
};

}  // namespace

bool lifted_transition(const Level& lower, const Level& upper, SlabMesh& out) {
  std::vector<Node> nodes;
  std::vector<Polygon> polygons;
  for (const LevelContour& c : lower.contours) nodes.push_back({&c, false});
  for (const LevelContour& c : upper.contours) nodes.push_back({&c, true});
  if (nodes.empty()) return false;
  for (const Node& n : nodes) polygons.push_back(n.contour->points);
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
    std::vector<VertexRef> interior;
    interior.reserve(region.interior.size());
    for (const Eigen::Vector2d& p : region.interior) {
      double d_lower = std::numeric_limits<double>::infinity(), d_upper = d_lower;
      (nodes[f.outer].upper ? d_upper : d_lower) = distance_to_polygon(outer.points, p);
      for (std::size_t k = 0; k < holes.size(); ++k) {
        double& d = nodes[f.holes[k]].upper ? d_upper : d_lower;
        d = std::min(d, distance_to_polygon(holes[k].points, p));
      }
      interior.push_back(out.add_vertex(p, lower.w + (upper.w - lower.w) * d_lower / std::max(d_lower + d_upper, 1e-300)));
    }
    for (const auto& t : region.triangles) {
      VertexRef v[3];
      for (int k = 0; k < 3; ++k) {
        const std::size_t i = static_cast<std::size_t>(t[k].vertex);
        v[k] = t[k].polygon < 0    ? interior[i]
               : t[k].polygon == 0 ? outer.ids[i]
                                   : holes[static_cast<std::size_t>(t[k].polygon - 1)].ids[i];
      }
      if (f.up) out.add_triangle(v[0], v[1], v[2], FaceRole::Band);
      else out.add_triangle(v[0], v[2], v[1], FaceRole::Band);
    }
  }
  return true;
}

}  // namespace contourmesh::detail
