// SPDX-License-Identifier: BSD-3-Clause
// Helpers for the tests of the tiler's private phases: levels made from polygons, and slab meshes turned
// into plain meshes.
#pragma once

#include "detail/tiling_types.h"

#include <contourmesh/smooth/mesh.h>

#include <cmath>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

namespace contourmesh::test {

/// n points on a circle, counter-clockwise (clockwise for a hole).
inline detail::Polygon circle_points(double cx, double cy, double r, int n, bool clockwise = false) {
  detail::Polygon p;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n * (clockwise ? -1.0 : 1.0);
    p.emplace_back(cx + r * std::cos(a), cy + r * std::sin(a));
  }
  return p;
}

/// An annulus arc from angle a0 to a1 (counter-clockwise), radii r0 < r1, n steps.
inline detail::Polygon arc_points(double a0, double a1, double r0, double r1, int n) {
  detail::Polygon c;
  for (int k = 0; k <= n; ++k) {
    const double a = a0 + (a1 - a0) * k / n;
    c.emplace_back(r1 * std::cos(a), r1 * std::sin(a));
  }
  for (int k = n; k >= 0; --k) {
    const double a = a0 + (a1 - a0) * k / n;
    c.emplace_back(r0 * std::cos(a), r0 * std::sin(a));
  }
  return c;
}

/// A level contour on plane w whose points are vertices the slab adds itself (a composite's or an
/// intermediate contour's), without ids.
inline detail::LevelContour local_contour(const detail::Polygon& points, double w, detail::SlabMesh& mesh) {
  detail::LevelContour c;
  c.points = points;
  for (const Eigen::Vector2d& p : points) c.ids.push_back(mesh.add_vertex(p, w));
  detail::finish_contour(c);
  return c;
}

/// A slab mesh's directed edges and how often each occurs.
inline std::map<std::pair<detail::VertexRef, detail::VertexRef>, int> directed_edges(const detail::SlabMesh& m) {
  std::map<std::pair<detail::VertexRef, detail::VertexRef>, int> edges;
  for (const Triangle& t : m.triangles) {
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  }
  return edges;
}

/// Vertices of the stack's own contours, numbered as the driver numbers them, with their positions.
struct TestStack {
  std::vector<Eigen::Vector3d> positions;

  /// A level contour on plane w whose points become stack vertices.
  detail::LevelContour contour(const detail::Polygon& points, double w, bool is_hole = false, int parent = -1) {
    detail::LevelContour c;
    c.points = points;
    c.is_hole = is_hole;
    c.parent = parent;
    for (const Eigen::Vector2d& p : points) {
      c.ids.push_back(static_cast<Index>(positions.size()));
      positions.emplace_back(p.x(), p.y(), w);
    }
    detail::finish_contour(c);
    return c;
  }

  [[nodiscard]] detail::SlabMesh slab() const {
    detail::SlabMesh m;
    m.stack_vertices = &positions;
    return m;
  }

  /// The stack vertices and every slab's vertices and faces as one mesh (slab by slab, in order).
  [[nodiscard]] Mesh assemble(const std::vector<const detail::SlabMesh*>& slabs) const {
    std::size_t n = positions.size();
    for (const auto* s : slabs) n += s->vertices.size();
    Mesh mesh;
    mesh.positions.resize(3, static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < positions.size(); ++i) mesh.positions.col(static_cast<Eigen::Index>(i)) = positions[i];
    std::size_t offset = positions.size();
    for (const auto* s : slabs) {
      for (std::size_t v = 0; v < s->vertices.size(); ++v) {
        mesh.positions.col(static_cast<Eigen::Index>(offset + v)) = s->vertices[v];
      }
      for (const Triangle& t : s->triangles) {
        Triangle g;
        for (int k = 0; k < 3; ++k) {
          g[k] = detail::is_local(t[k]) ? static_cast<Index>(offset + detail::local_index(t[k])) : t[k];
        }
        mesh.triangles.push_back(g);
      }
      offset += s->vertices.size();
    }
    return mesh;
  }
};

}  // namespace contourmesh::test
