// SPDX-License-Identifier: BSD-3-Clause
#include "detail/branching.h"

#include "detail/band_tiling.h"
#include "detail/caps.h"
#include "detail/composite.h"
#include "detail/correspondence.h"
#include "detail/crossing_band.h"
#include "contourmesh/reconstruct/contours.h"

#include "contourmesh/internal/union_find.h"

#include <algorithm>
#include <optional>

namespace contourmesh::detail {

namespace {

// When every contour of `inner` (of level `in`) lies inside one contour of `outer` (of level `of`), the
// contours of `outer` that hold them, one per contour of `inner`; empty otherwise. The holders must be
// outer contours without holes in their level, the others outer contours, and none may touch another.
std::vector<int> holders(const Level& of, const std::vector<int>& outer, const Level& in,
                         const std::vector<int>& inner) {
  std::vector<Polygon> polygons;
  for (int o : outer) {
    const LevelContour& c = of.contours[static_cast<std::size_t>(o)];
    if (c.is_hole) return {};
    for (const LevelContour& h : of.contours) {
      if (h.is_hole && h.parent == o) return {};
    }
    polygons.push_back(c.points);
  }
  std::vector<int> holder;
  for (int i : inner) {
    const LevelContour& c = in.contours[static_cast<std::size_t>(i)];
    if (c.is_hole) return {};
    int found = -1;
    for (int o : outer) {
      const LevelContour& h = of.contours[static_cast<std::size_t>(o)];
      if (h.box.contains(c.box) && std::all_of(c.points.begin(), c.points.end(), [&](const Eigen::Vector2d& p) {
            return point_in_polygon(h.points, p);
          })) {
        found = o;
        break;
      }
    }
    if (found < 0) return {};
    holder.push_back(found);
    polygons.push_back(c.points);
  }
  if (find_polygon_crossing(polygons)) return {};
  return holder;
}

// Contours `inner` of level `in` inside one contour `single` of the other level: all are copied onto
// plane w and joined to their originals by straight bands, and the flat region between the copy of
// `single` and the others is triangulated like a cap with holes (faces of role Bridge): well-shaped
// faces where a composite's band would fan long slivers across the region.
void nested_fill(const LevelContour& single, bool single_below, const Level& in, const std::vector<int>& inner,
                 double w, const TilingOptions& options, SlabMesh& out) {
  const LevelContour outer = copy_contour(single, w, out);
  if (single_below) emit_copy_band(single.ids, outer.ids, out);
  else emit_copy_band(outer.ids, single.ids, out);
  std::vector<LevelContour> holes;
  for (int m : inner) {
    const LevelContour& c = in.contours[static_cast<std::size_t>(m)];
    LevelContour copy = copy_contour(c, w, out);
    if (single_below) emit_copy_band(copy.ids, c.ids, out);
    else emit_copy_band(c.ids, copy.ids, out);
    std::reverse(copy.points.begin(), copy.points.end());
    std::reverse(copy.ids.begin(), copy.ids.end());
    holes.push_back(std::move(copy));
  }
  fill_planar(outer, holes, w, single_below, FaceRole::Bridge, options, out);
  ++out.stats.composites;
}

// Tiles a group whose contours on one side each lie inside a contour of the other side: each holder
// with one contour inside gets a band, with several a nested fill, with none a cap. False when the
// group is not nested so.
bool tile_nested(const Level& lower, const Level& upper, const std::vector<int>& L, const std::vector<int>& U,
                 double extension, const TilingOptions& options, SlabMesh& out) {
  for (const bool holders_below : {true, false}) {
    const Level& of = holders_below ? lower : upper;
    const Level& in = holders_below ? upper : lower;
    const std::vector<int>& outer = holders_below ? L : U;
    const std::vector<int>& inner = holders_below ? U : L;
    const std::vector<int> holder = holders(of, outer, in, inner);
    if (holder.empty()) continue;
    for (int o : outer) {
      std::vector<int> inside;
      for (std::size_t k = 0; k < inner.size(); ++k) {
        if (holder[k] == o) inside.push_back(inner[k]);
      }
      const LevelContour& h = of.contours[static_cast<std::size_t>(o)];
      if (inside.empty()) {
        cap_end(h, {}, of.w, extension, holders_below, options, out);
      } else if (inside.size() == 1) {
        const LevelContour& c = in.contours[static_cast<std::size_t>(inside[0])];
        if (holders_below)
          emit_band(h, c, untwisted_band(h.points, lower.w, c.points, upper.w, options, h.spacing()), out);
        else emit_band(c, h, untwisted_band(c.points, lower.w, h.points, upper.w, options, h.spacing()), out);
      } else {
        nested_fill(h, holders_below, in, inside, 0.5 * (lower.w + upper.w), options, out);
      }
    }
    return true;
  }
  return false;
}

// The band between two rings of a branching (a composite, and a composite or a contour): the least-area
// band or, where their outlines cross, the crossing band when it leaves less flat and sliver area. The
// least-area band goes to `band` when given (to be inserted at d.position), else to `out`; a crossing
// band always goes to `out`.
void composite_band(const DeferredBand& d, const TilingOptions& options, SlabMesh& out, SlabMesh* band) {
  SlabMesh least = out.scratch();
  emit_band(d.lower, d.upper,
            untwisted_band(d.lower.points, d.wl, d.upper.points, d.wu, options,
                           0.5 * (d.lower.spacing() + d.upper.spacing())),
            least);
  if (options.band_refinement == BandRefinement::Interpolated) {
    std::optional<CrossingBand> crossing =
        crossing_band(d.lower, d.wl, d.upper, d.wu, d.lower_composite, d.upper_composite, out);
    if (crossing && crossing->defects.score() < measure_defects(least).score() && find_split_faces(*crossing, out)) {
      absorb_crossing_band(std::move(*crossing), out);
      return;
    }
  }
  if (band) *band = std::move(least);
  else out.absorb(std::move(least));
}

}  // namespace

// How far beyond its plane a pocket over a hole of the other level is closed, as a share of the slab.
constexpr double kOverHoleCap = 0.25;

void tile_composite(const Level& lower, const Level& upper, const TilingOptions& options, SlabMesh& out,
                    std::vector<DeferredBand>* deferred, const Correspondence* given) {
  std::optional<Correspondence> computed;
  const Correspondence& links = given ? *given : computed.emplace(correspond(lower, upper, options));
  const std::size_t na = lower.contours.size(), nb = upper.contours.size();
  const double w0 = lower.w, w1 = upper.w;
  const double extension = options.end_caps == EndCaps::HalfSpacing ? 0.5 * (w1 - w0) : 0.0;
  const double pocket_extension = options.end_caps == EndCaps::HalfSpacing ? kOverHoleCap * (w1 - w0) : 0.0;
  UnionFind<> groups(na + nb);
  for (std::size_t i = 0; i < na; ++i) {
    for (int j : links.up[i]) groups.unite(i, na + static_cast<std::size_t>(j));
  }
  // Members of each group on each side: contours with partners, and opening holes with their outer's.
  std::vector<std::vector<int>> lower_of(na + nb), upper_of(na + nb);
  for (std::size_t i = 0; i < na; ++i) {
    const LevelContour& c = lower.contours[i];
    if (!links.up[i].empty()) lower_of[groups.find(i)].push_back(static_cast<int>(i));
    else if (links.opens_up[i] && !links.over_hole_up[i])
      lower_of[groups.find(static_cast<std::size_t>(c.parent))].push_back(static_cast<int>(i));
  }
  for (std::size_t j = 0; j < nb; ++j) {
    const LevelContour& c = upper.contours[j];
    if (!links.down[j].empty()) upper_of[groups.find(na + j)].push_back(static_cast<int>(j));
    else if (links.opens_down[j] && !links.over_hole_down[j]) {
      upper_of[groups.find(na + static_cast<std::size_t>(c.parent))].push_back(static_cast<int>(j));
    }
  }
  for (std::size_t g = 0; g < na + nb; ++g) {
    const auto& L = lower_of[g];
    const auto& U = upper_of[g];
    if (L.empty() || U.empty()) continue;
    if (L.size() == 1 && U.size() == 1) {
      const LevelContour& a = lower.contours[static_cast<std::size_t>(L[0])];
      const LevelContour& b = upper.contours[static_cast<std::size_t>(U[0])];
      emit_band(a, b, untwisted_band(a.points, w0, b.points, w1, options, 0.5 * (a.spacing() + b.spacing())), out);
      continue;
    }
    if (tile_nested(lower, upper, L, U, extension, options, out)) continue;
    const bool both = L.size() > 1 && U.size() > 1;
    // The crossing band needs simple composite rings: bridges that cross no contour.
    const bool clear = options.band_refinement == BandRefinement::Interpolated;
    const double wl = L.size() > 1 ? (both ? w0 + (w1 - w0) / 3.0 : 0.5 * (w0 + w1)) : w0;
    const double wu = U.size() > 1 ? (both ? w0 + 2.0 * (w1 - w0) / 3.0 : 0.5 * (w0 + w1)) : w1;
    // A composite tiled to one contour bridges its pieces where that contour passes from piece to piece
    // (guided_bridge); of two composites the upper one is made first and guides the lower one.
    LevelContour lower_ring, upper_ring;
    if (both && clear) {
      upper_ring = composite_of(upper, U, lower, wu, false, clear, out);
      lower_ring = composite_of(lower, L, upper, wl, true, clear, out, &upper_ring.points);
    } else {
      const Polygon* lower_guide =
          clear && U.size() == 1 ? &upper.contours[static_cast<std::size_t>(U[0])].points : nullptr;
      const Polygon* upper_guide =
          clear && L.size() == 1 ? &lower.contours[static_cast<std::size_t>(L[0])].points : nullptr;
      lower_ring = L.size() > 1 ? composite_of(lower, L, upper, wl, true, clear, out, lower_guide)
                                : lower.contours[static_cast<std::size_t>(L[0])];
      upper_ring = U.size() > 1 ? composite_of(upper, U, lower, wu, false, clear, out, upper_guide)
                                : upper.contours[static_cast<std::size_t>(U[0])];
    }
    if (deferred) {
      deferred->push_back({lower_ring, upper_ring, wl, wu, out.triangles.size(), L.size() > 1, U.size() > 1});
      continue;
    }
    composite_band({lower_ring, upper_ring, wl, wu, out.triangles.size(), L.size() > 1, U.size() > 1}, options, out,
                   nullptr);
  }
  // Ends: outer contours with no partner (with their holes), and holes that end inside a continuing
  // outer contour. A pocket over a hole of the other level is closed near its own plane (kOverHoleCap of
  // the slab beyond it), above the other cavity's roof, which the band between that cavity's contours
  // lays across the slab: a cavity of its own, not one bridged across the wall to the outside.
  auto close_ends = [&](const Level& level, const std::vector<std::vector<int>>& partners,
                        const std::vector<std::uint8_t>& opens, const std::vector<std::uint8_t>& over_hole,
                        bool upward) {
    for (std::size_t c = 0; c < level.contours.size(); ++c) {
      const LevelContour& k = level.contours[c];
      if (!partners[c].empty()) continue;
      if (over_hole[c]) {
        cap_hole_end(k, level.w, pocket_extension, upward, options, out);
        continue;
      }
      if (opens[c]) continue;
      if (!k.is_hole) {
        std::vector<const LevelContour*> holes;
        for (const LevelContour& h : level.contours) {
          if (h.is_hole && h.parent == static_cast<int>(c)) holes.push_back(&h);
        }
        cap_end(k, holes, level.w, extension, upward, options, out);
      } else if (k.parent >= 0 && !partners[static_cast<std::size_t>(k.parent)].empty()) {
        cap_hole_end(k, level.w, extension, upward, options, out);
      }
    }
  };
  close_ends(lower, links.up, links.opens_up, links.over_hole_up, true);
  close_ends(upper, links.down, links.opens_down, links.over_hole_down, false);
}

void finish_composite(const std::vector<DeferredBand>& deferred, const TilingOptions& options, SlabMesh& out) {
  std::vector<SlabMesh> bands(deferred.size());
  for (std::size_t k = 0; k < deferred.size(); ++k) composite_band(deferred[k], options, out, &bands[k]);
  // From the last, so that the earlier positions still hold.
  for (std::size_t k = deferred.size(); k-- > 0;) {
    const auto at = static_cast<std::ptrdiff_t>(deferred[k].position);
    out.triangles.insert(out.triangles.begin() + at, bands[k].triangles.begin(), bands[k].triangles.end());
    out.roles.insert(out.roles.begin() + at, bands[k].roles.begin(), bands[k].roles.end());
  }
}

}  // namespace contourmesh::detail
