// SPDX-License-Identifier: BSD-3-Clause
#include "detail/stack_preparation.h"

#include <contourmesh/smooth/errors.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace contourmesh::detail {

std::vector<std::vector<Contour>> prepare_stack(const ContourStack& stack) {
  std::vector<std::vector<Contour>> out(stack.slices.size());
  for (std::size_t s = 0; s < stack.slices.size(); ++s) {
    if (s > 0 && !(stack.slices[s].w > stack.slices[s - 1].w)) {
      throw InvalidInputError("tiling: slice " + std::to_string(s) + " (w = " + std::to_string(stack.slices[s].w) +
                              ") is not above slice " + std::to_string(s - 1));
    }
    auto& contours = out[s] = stack.slices[s].contours;
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

}  // namespace contourmesh::detail
