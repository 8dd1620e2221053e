// SPDX-License-Identifier: BSD-3-Clause
#include "detail/single_slice.h"

#include "detail/cross_section.h"

#include "contourmesh/internal/polygon2d.h"

#include <algorithm>
#include <array>
#include <cstdint>

namespace contourmesh::detail {

namespace {

using Polygon = std::vector<Eigen::Vector2d>;

bool segments_touch(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                    const Eigen::Vector2d& d) {
  const double o1 = orient2d(a, b, c), o2 = orient2d(a, b, d), o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
  return ((o1 >= 0.0) != (o2 >= 0.0) || o1 == 0.0 || o2 == 0.0) &&
         ((o3 >= 0.0) != (o4 >= 0.0) || o3 == 0.0 || o4 == 0.0);
}

// Does the polygon lie strictly inside the region the section bounds (no segment meets it, and its
// first point is inside by the even-odd rule)?
bool inside_section(const Polygon& polygon, const std::vector<SectionSegment>& section) {
  Eigen::AlignedBox2d box;
  for (const auto& p : polygon) box.extend(p);
  for (const auto& seg : section) {
    Eigen::AlignedBox2d sb;
    sb.extend(seg[0]);
    sb.extend(seg[1]);
    if (!sb.intersects(box)) continue;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      if (segments_touch(polygon[i], polygon[(i + 1) % polygon.size()], seg[0], seg[1])) return false;
    }
  }
  const Eigen::Vector2d& p = polygon.front();
  bool in = false;
  for (const auto& seg : section) {
    if (crosses_ray(seg[0], seg[1], p)) in = !in;
  }
  return in;
}

double axial(const Mesh& mesh, const ContourStack& stack, Index i) {
  return (mesh.positions.col(i) - stack.origin).dot(stack.axis_w);
}

}  // namespace

UnmeshedContours unmeshed_contours(const Mesh& mesh, const ContourStack& stack) {
  UnmeshedContours out;
  out.flags.resize(stack.slices.size());
  for (std::size_t s = 0; s < stack.slices.size(); ++s) out.flags[s].assign(stack.slices[s].contours.size(), 1);
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    const auto s = static_cast<std::size_t>(mesh.slice_ids[i]), c = static_cast<std::size_t>(mesh.contour_ids[i]);
    if (mesh.slice_ids[i] >= 0 && mesh.contour_ids[i] >= 0 && s < out.flags.size() && c < out.flags[s].size())
      out.flags[s][c] = 0;
  }
  for (std::size_t s = 0; s < out.flags.size(); ++s) {
    for (std::size_t c = 0; c < out.flags[s].size(); ++c) {
      if (out.flags[s][c]) out.list.emplace_back(s, c);
    }
  }
  return out;
}

std::pair<double, double> half_gaps(const ContourStack& stack, std::size_t s) {
  const auto& sl = stack.slices;
  const double below = s > 0 ? sl[s].w - sl[s - 1].w : sl[s + 1].w - sl[s].w;
  const double above = s + 1 < sl.size() ? sl[s + 1].w - sl[s].w : below;
  return {0.5 * below, 0.5 * above};
}

TilingResult single_slice_slab(const ContourStack& stack, std::size_t s, std::size_t c, double below, double above,
                               const TilingOptions& tiling) {
  const auto& cs = stack.slices[s].contours;
  std::vector<Contour> group{cs[c]};
  std::vector<std::int32_t> original{static_cast<std::int32_t>(c)};
  group[0].parent = -1;
  for (std::size_t h = 0; h < cs.size(); ++h) {
    if (cs[h].is_hole && cs[h].parent == static_cast<int>(c)) {
      group.push_back(cs[h]);
      group.back().parent = 0;
      original.push_back(static_cast<std::int32_t>(h));
    }
  }
  ContourStack mini;
  mini.origin = stack.origin;
  mini.axis_u = stack.axis_u;
  mini.axis_v = stack.axis_v;
  mini.axis_w = stack.axis_w;
  const double w = stack.slices[s].w;
  mini.slices = {{w - below, group}, {w, group}, {w + above, group}};
  TilingOptions o = tiling;
  o.end_caps = EndCaps::AtEndSlice;
  o.threads = 1;
  TilingResult r = tile_contours(mini, o);
  Mesh& m = r.mesh;
  for (Index i = 0; i < m.num_vertices(); ++i) {
    if (m.slice_ids[i] == 1 && m.contour_ids[i] >= 0) {
      m.slice_ids[i] = static_cast<std::int32_t>(s);
      m.contour_ids[i] = original[static_cast<std::size_t>(m.contour_ids[i])];
    } else {
      m.slice_ids[i] = kNoId;
      m.contour_ids[i] = kNoId;
    }
  }
  return r;
}

namespace {

// A closed prism around hole `c` of slice `s`, oriented as a cavity (normals into the hole).
TilingResult cavity(const ContourStack& stack, std::size_t s, std::size_t c, double below, double above,
                    const TilingOptions& tiling) {
  ContourStack one = stack;
  for (auto& slice : one.slices) slice.contours.clear();
  Contour hole = stack.slices[s].contours[c];
  hole.is_hole = false;
  hole.parent = -1;
  std::reverse(hole.points.begin(), hole.points.end());
  one.slices[s].contours.push_back(hole);
  TilingResult r = single_slice_slab(one, s, 0, below, above, tiling);
  for (Index i = 0; i < r.mesh.num_vertices(); ++i) {
    if (r.mesh.contour_ids[i] == 0) r.mesh.contour_ids[i] = static_cast<std::int32_t>(c);
  }
  for (Triangle& t : r.mesh.triangles) std::swap(t[1], t[2]);
  return r;
}

}  // namespace

std::optional<TilingResult> fitting_cavity(const Mesh& surface, const std::vector<Index>& near_faces,
                                           const ContourStack& stack, std::size_t s, std::size_t c,
                                           const TilingOptions& tiling, bool& thinned) {
  const auto [below, above] = half_gaps(stack, s);
  const double w = stack.slices[s].w;
  for (const double f : {1.0, 0.5, 0.25, 0.1}) {
    bool fits = true;
    for (const double at : {w - 0.998 * f * below, w - 0.5 * f * below, w + 0.5 * f * above, w + 0.998 * f * above}) {
      fits = fits && inside_section(stack.slices[s].contours[c].points,
                                    cross_section_of(surface, &near_faces, stack, at, false));
    }
    if (!fits) continue;
    thinned = f < 1.0;
    return cavity(stack, s, c, f * below, f * above, tiling);
  }
  return std::nullopt;
}

std::vector<std::vector<Index>> faces_near_slices(const Mesh& mesh, const ContourStack& stack) {
  const std::size_t S = stack.slices.size();
  std::vector<std::vector<Index>> out(S);
  if (S < 2) return out;
  std::vector<double> lo(S), hi(S), w(S);
  for (std::size_t s = 0; s < S; ++s) {
    const auto [below, above] = half_gaps(stack, s);
    w[s] = stack.slices[s].w;
    lo[s] = w[s] - below;
    hi[s] = w[s] + above;
  }
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    const std::array<double, 3> h{axial(mesh, stack, t[0]), axial(mesh, stack, t[1]), axial(mesh, stack, t[2])};
    const double fmin = *std::min_element(h.begin(), h.end()), fmax = *std::max_element(h.begin(), h.end());
    // The slices are in increasing w: the first slice whose slab may end at or above fmin.
    auto first = static_cast<std::size_t>(std::lower_bound(hi.begin(), hi.end(), fmin) - hi.begin());
    for (std::size_t s = first; s < S && lo[s] <= fmax; ++s) out[s].push_back(static_cast<Index>(f));
  }
  return out;
}

double covered_by_adjacent_slices(const ContourStack& stack, std::size_t s, std::size_t c) {
  const Contour& contour = stack.slices[s].contours[c];
  const double area = std::abs(signed_area(contour.points));
  if (!(area > 0.0)) return 0.0;
  Eigen::AlignedBox2d box;
  for (const auto& p : contour.points) box.extend(p);
  auto box_of = [](const Contour& k) {
    Eigen::AlignedBox2d b;
    for (const auto& p : k.points) b.extend(p);
    return b;
  };
  double best = 0.0;
  for (const std::size_t t : {s - 1, s + 1}) {
    if (t >= stack.slices.size()) continue;  // s - 1 wraps round for s = 0
    const auto& others = stack.slices[t].contours;
    double covered = 0.0;
    for (const Contour& k : others) {
      if (!box.intersects(box_of(k))) continue;
      const double a = overlap_area(contour.points, k.points);
      covered += k.is_hole ? -a : a;
    }
    best = std::max(best, covered / area);
  }
  return std::clamp(best, 0.0, 1.0);
}

void append_part(Mesh& mesh, const TilingResult& part, std::vector<FaceRole>* roles) {
  const Index base = mesh.num_vertices();
  const Mesh& p = part.mesh;
  mesh.positions.conservativeResize(3, base + p.num_vertices());
  mesh.positions.rightCols(p.num_vertices()) = p.positions;
  mesh.slice_ids.insert(mesh.slice_ids.end(), p.slice_ids.begin(), p.slice_ids.end());
  mesh.contour_ids.insert(mesh.contour_ids.end(), p.contour_ids.begin(), p.contour_ids.end());
  for (const Triangle& t : p.triangles) mesh.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  if (roles) roles->insert(roles->end(), part.face_roles.begin(), part.face_roles.end());
}

}  // namespace contourmesh::detail
