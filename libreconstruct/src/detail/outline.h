// SPDX-License-Identifier: BSD-3-Clause
// Private: point-in-outline tests against one level, many points at a time.
#pragma once

#include "detail/bucket_lists.h"
#include "detail/tiling_types.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace contourmesh::detail {

/// Whether a point lies inside one of the outer contours of a level (its holes filled: a hole is
/// background enclosed by material, not an opening of the wall). The even-odd rule of
/// point_in_polygon, over the edges that can cross the point's ray only: each contour's edges are
/// filed in horizontal strips by the rows they span, and an edge that does not span the point's height
/// never crosses its ray, so the answer is point_in_polygon's. A bridge may test hundreds of midpoints
/// against the same level. The level must outlive the Outline.
class Outline {
 public:
  explicit Outline(const Level& level) {
    for (const LevelContour& c : level.contours) {
      if (c.is_hole || c.points.size() < 3) continue;
      Strips s;
      s.points = &c.points;
      s.box = c.box;
      const double height = c.box.max().y() - c.box.min().y();
      s.rows = height > 0.0 ? std::max<int>(1, static_cast<int>(c.points.size() / 8)) : 1;
      s.scale = height > 0.0 ? s.rows / height : 0.0;
      const std::size_t n = c.points.size();
      file_in_buckets(
          static_cast<std::size_t>(s.rows),
          [&](const auto& file) {
            for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
              const double y0 = std::min(c.points[i].y(), c.points[j].y());
              const double y1 = std::max(c.points[i].y(), c.points[j].y());
              for (int r = s.row(y0); r <= s.row(y1); ++r) file(static_cast<std::size_t>(r), static_cast<int>(i));
            }
          },
          s.start, s.edges);
      strips_.push_back(std::move(s));
    }
  }

  [[nodiscard]] bool contains(const Eigen::Vector2d& p) const {
    for (const Strips& s : strips_) {
      if (!s.box.contains(p)) continue;
      const Polygon& poly = *s.points;
      const std::size_t n = poly.size();
      bool in = false;
      const auto r = static_cast<std::size_t>(s.row(p.y()));
      for (int e = s.start[r]; e < s.start[r + 1]; ++e) {
        const auto k = static_cast<std::size_t>(s.edges[static_cast<std::size_t>(e)]);
        if (crosses_ray(poly[k == 0 ? n - 1 : k - 1], poly[k], p)) in = !in;
      }
      if (in) return true;
    }
    return false;
  }

 private:
  struct Strips {
    const Polygon* points = nullptr;
    Eigen::AlignedBox2d box;
    int rows = 1;
    double scale = 0.0;
    std::vector<int> start;  // per row, where its edges begin in `edges` (one more entry: the end)
    std::vector<int> edges;  // the edges (by end point) whose heights reach each row, row by row
    [[nodiscard]] int row(double y) const {
      return std::clamp(static_cast<int>(std::floor((y - box.min().y()) * scale)), 0, rows - 1);
    }
  };
  std::vector<Strips> strips_;
};

}  // namespace contourmesh::detail
