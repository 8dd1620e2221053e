// SPDX-License-Identifier: BSD-3-Clause
#include "detail/caps.h"

#include "detail/band_tiling.h"
#include "detail/cap_refinement.h"
#include "contourmesh/reconstruct/contours.h"

#include <algorithm>

namespace contourmesh::detail {

namespace {

// The contour itself, or its copy `extension` beyond plane w joined to it by a straight band.
LevelContour extend(const LevelContour& c, double w, double extension, bool upward, SlabMesh& out) {
  if (!(extension > 0.0)) return c;
  LevelContour copy = copy_contour(c, upward ? w + extension : w - extension, out);
  if (upward) emit_copy_band(c.ids, copy.ids, out);
  else emit_copy_band(copy.ids, c.ids, out);
  return copy;
}

}  // namespace

void fill_planar(const LevelContour& outer, const std::vector<LevelContour>& holes, double w, bool facing_up,
                 FaceRole role, const TilingOptions& options, SlabMesh& out) {
  std::vector<Polygon> hole_polygons;
  for (const LevelContour& h : holes) hole_polygons.push_back(h.points);
  // Interior vertices about one contour spacing apart keep the cap's umbrella balanced.
  const double spacing = options.cap_refinement == CapRefinement::Interior ? outer.spacing() : 0.0;
  const RefinedCap refined = triangulate_refined(outer.points, hole_polygons, spacing);
  std::vector<VertexRef> interior;
  interior.reserve(refined.interior.size());
  for (const Eigen::Vector2d& p : refined.interior) interior.push_back(out.add_vertex(p, w));
  for (const auto& t : refined.triangles) {
    VertexRef v[3];
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = static_cast<std::size_t>(t[k].vertex);
      v[k] = t[k].polygon < 0    ? interior[i]
             : t[k].polygon == 0 ? outer.ids[i]
                                 : holes[static_cast<std::size_t>(t[k].polygon - 1)].ids[i];
    }
    if (facing_up) out.add_triangle(v[0], v[1], v[2], role);
    else out.add_triangle(v[0], v[2], v[1], role);
  }
}

namespace {

void cap(const LevelContour& outer, const std::vector<LevelContour>& holes, double w, bool facing_up, FaceRole role,
         const TilingOptions& options, SlabMesh& out) {
  fill_planar(outer, holes, w, facing_up, role, options, out);
  if (role == FaceRole::Cap) ++out.stats.caps;
}

}  // namespace

void cap_end(const LevelContour& outer, const std::vector<const LevelContour*>& holes, double w, double extension,
             bool upward, const TilingOptions& options, SlabMesh& out, FaceRole role) {
  std::vector<LevelContour> extended_holes;
  for (const LevelContour* h : holes) extended_holes.push_back(extend(*h, w, extension, upward, out));
  const LevelContour extended = extend(outer, w, extension, upward, out);
  cap(extended, extended_holes, upward ? w + extension : w - extension, upward, role, options, out);
}

void cap_hole_end(const LevelContour& hole, double w, double extension, bool upward, const TilingOptions& options,
                  SlabMesh& out) {
  // The hole's inside is triangulated as a counter-clockwise polygon (the hole reversed), facing into
  // the cavity.
  LevelContour r = extend(hole, w, extension, upward, out);
  std::reverse(r.points.begin(), r.points.end());
  std::reverse(r.ids.begin(), r.ids.end());
  cap(r, {}, upward ? w + std::max(extension, 0.0) : w - std::max(extension, 0.0), !upward, FaceRole::Cap, options,
      out);
}

}  // namespace contourmesh::detail
