// SPDX-License-Identifier: BSD-3-Clause
#include "detail/slab_tiling.h"

#include "detail/band_tiling.h"
#include "detail/branching.h"
#include "detail/caps.h"
#include "detail/correspondence.h"
#include "detail/lifted_transition.h"
#include "detail/shape_interpolation.h"
#include "detail/slab_remeshing.h"
#include "detail/sliver_collapse.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>
#include <optional>

namespace contourmesh::detail {

namespace {

std::vector<Polygon> polygons(const Level& level) {
  std::vector<Polygon> out;
  for (const LevelContour& c : level.contours) out.push_back(c.points);
  return out;
}

double mean_spacing(const Level& a, const Level& b) {
  double sum = 0.0;
  std::size_t n = 0;
  for (const Level* level : {&a, &b}) {
    for (const LevelContour& c : level->contours) {
      sum += c.spacing() * static_cast<double>(c.points.size());
      n += c.points.size();
    }
  }
  return n ? sum / static_cast<double>(n) : 1.0;
}

// The shape-based interpolation of one group of a slab: the signed distance fields of its regions on
// both slices, and the levels extracted from them so far. Every level between the two slices comes
// from these same fields (a level set of (1 - t) d_lower + t d_upper, shifted so that it encloses the
// linear interpolation of the two regions' areas: level_for_area), so the halves of a halved slab
// and the steps of a refined band are pieces of one implicit surface. A level's contours are handed
// out once: the piece of the slab that claims a contour tiles it.
class Interpolation {
 public:
  Interpolation(const Level& lower, const Level& upper, double grid)
      : spacing_(mean_spacing(lower, upper)),
        w0_(lower.w),
        w1_(upper.w),
        area0_(region_area(lower)),
        area1_(region_area(upper)),
        fields_(signed_distance_pair(polygons(lower), polygons(upper), grid * spacing_)) {}

  [[nodiscard]] double w(double t) const { return w0_ + t * (w1_ - w0_); }

  // The contours of level t that belong to the piece whose contours are `lower` and `upper` and that
  // no other piece has taken: outer contours that meet the piece's outer contours, and their holes. Empty when the
  // level cannot be made or nothing belongs to the piece.
  std::vector<std::size_t> select(double t, const Level& lower, const Level& upper) {
    Extracted& e = level(t);
    std::vector<std::size_t> chosen;
    if (!e.contours) return chosen;
    const auto& contours = *e.contours;
    std::vector<std::uint8_t> is_chosen(contours.size(), 0);
    // A level's contours lie in the union of the regions of the two levels it comes between, and the
    // pieces' regions are apart: a contour belongs to the piece when it and one of the piece's outer
    // contours hold a point of each other.
    auto meets = [](const Polygon& a, const Eigen::AlignedBox2d& box_a, const LevelContour& b) {
      if (!box_a.intersects(b.box)) return false;
      const std::size_t step_a = std::max<std::size_t>(1, a.size() / 8),
                        step_b = std::max<std::size_t>(1, b.points.size() / 8);
      for (std::size_t i = 0; i < a.size(); i += step_a) {
        if (b.box.contains(a[i]) && point_in_polygon(b.points, a[i])) return true;
      }
      for (std::size_t i = 0; i < b.points.size(); i += step_b) {
        if (box_a.contains(b.points[i]) && point_in_polygon(a, b.points[i])) return true;
      }
      return false;
    };
    for (std::size_t k = 0; k < contours.size(); ++k) {
      const InterpolatedContour& c = contours[k];
      if (c.is_hole || e.claimed[k]) continue;
      Eigen::AlignedBox2d box;
      for (const Eigen::Vector2d& p : c.points) box.extend(p);
      bool belongs = false;
      for (const Level* level : {&lower, &upper}) {
        for (const LevelContour& o : level->contours) belongs = belongs || (!o.is_hole && meets(c.points, box, o));
      }
      if (belongs) {
        is_chosen[k] = 1;
        chosen.push_back(k);
      }
    }
    for (std::size_t k = 0; k < contours.size(); ++k) {
      const InterpolatedContour& c = contours[k];
      if (c.is_hole && !e.claimed[k] && is_chosen[static_cast<std::size_t>(c.parent)]) chosen.push_back(k);
    }
    return chosen;
  }

  // Takes the `chosen` contours of level t (from select) as a new level with new vertices.
  Level take(double t, const std::vector<std::size_t>& chosen, SlabMesh& out) {
    Extracted& e = level(t);
    const auto& contours = *e.contours;
    std::vector<int> index(contours.size(), -1);
    Level result;
    result.w = w(t);
    for (std::size_t k : chosen) {
      const InterpolatedContour& c = contours[k];
      LevelContour lc;
      lc.points = c.points;
      lc.is_hole = c.is_hole;
      lc.parent = c.is_hole ? index[static_cast<std::size_t>(c.parent)] : -1;
      for (const Eigen::Vector2d& p : lc.points) lc.ids.push_back(out.add_vertex(p, result.w));
      finish_contour(lc);
      index[k] = static_cast<int>(result.contours.size());
      result.contours.push_back(std::move(lc));
      e.claimed[k] = 1;
    }
    out.stats.intermediate_contours += result.contours.size();
    return result;
  }

  /// Which contours are taken, to undo the claims of a candidate tiling that is dropped.
  using Claims = std::map<double, std::vector<std::uint8_t>>;
  [[nodiscard]] Claims claims() const {
    Claims c;
    for (const auto& [t, e] : levels_) c[t] = e.claimed;
    return c;
  }
  void restore(const Claims& c) {
    for (auto& [t, e] : levels_) {
      const auto it = c.find(t);
      if (it != c.end()) e.claimed = it->second;
      else std::fill(e.claimed.begin(), e.claimed.end(), 0);
    }
  }

 private:
  struct Extracted {
    std::optional<std::vector<InterpolatedContour>> contours;
    std::vector<std::uint8_t> claimed;
  };

  Extracted& level(double t) {
    auto it = levels_.find(t);
    if (it == levels_.end()) {
      Extracted e;
      // The level keeps the area of the linear interpolation between the slices' regions: the volume of
      // the slice-wise (prism) model, which the zero level of averaged distances falls short of where
      // the two regions differ in shape.
      const double iso = level_for_area(fields_, t, (1.0 - t) * area0_ + t * area1_);
      e.contours = interpolate_contours(fields_, t, spacing_, iso);
      if (e.contours) e.claimed.assign(e.contours->size(), 0);
      it = levels_.emplace(t, std::move(e)).first;
    }
    return it->second;
  }

  static double region_area(const Level& level) {
    double a = 0.0;
    for (const LevelContour& c : level.contours) a += c.is_hole ? -c.area : c.area;
    return a;
  }

  double spacing_;
  double w0_, w1_;
  double area0_, area1_;
  DistancePair fields_;
  std::map<double, Extracted> levels_;
};

// Flips that remove slivers may move the surface by at most this share of the slab's thickness.
constexpr double kMaxFlipDeviation = 0.25;
// ... and split edges longer than this many contour spacings.
constexpr double kMinSplitLength = 0.5;
// Collapses that remove slivers join vertices at most this many contour spacings apart, and move the
// surface by at most a tenth of that.
constexpr double kMaxCollapseLength = 1.0;
constexpr double kMaxCollapseDeviation = 0.1;

// A candidate tiling whose flat and sliver area (TilingDefects::score) is at most this share of its area
// is kept without trying the costlier ones.
constexpr double kGoodEnough = 0.02;

// Halves are not tried for a group of more than kFutileHalvesContours contours whose best candidate has
// at most kFutileHalvesPoorShare of its area flat or in slivers, less than kFutileHalvesBridgeShare of
// that in bridges (SlabTiler::halves_futile).
constexpr std::size_t kFutileHalvesContours = 6;
constexpr double kFutileHalvesPoorShare = 0.05;
constexpr double kFutileHalvesBridgeShare = 0.5;

// Whether settle may try the halves.
enum class Halving { IfWanted, Never };

// Where a slab lies in its group's interpolation: levels t0 and t1 of `interpolation`, or, without
// one, between two slices (t0 = 0, t1 = 1 of the interpolation a group makes when it needs one).
struct Span {
  Interpolation* interpolation = nullptr;
  double t0 = 0.0;
  double t1 = 1.0;
};

// The points moved by shear * w (SlabMesh::shear).
Polygon sheared(const Polygon& points, double w, const Eigen::Vector2d& shear) {
  Polygon out = points;
  for (Eigen::Vector2d& p : out) p += shear * w;
  return out;
}

// A candidate tiling built against a rival it must beat (the halves of a slab against its composite or
// lifted transition, a refined band against the direct one): its flat and sliver area so far, measured
// as faces are appended to its mesh. Faces only add to that area, so once it reaches the rival's the
// candidate has lost, and the rest of it need not be built (branch and bound).
//
// Candidates nest: the halves of a slab hold pieces whose own candidates are being built. A nested
// candidate adds to the outer one at least the lesser of its area so far and `floor`, what its piece adds
// when it loses (the best of its rivals), so its faces count towards the outer bounds too: when an outer
// candidate has lost, the nested work is abandoned up to it (Abandoned). The one exception is a nested
// piece that would part (try_parting), whose caps can add less: the outer candidate is given up all the
// same. On the real scans and the phantoms the meshes are those of building every candidate whole.
class Bound {
 public:
  Bound(double rival, double floor, Bound* outer) : rival_(rival), floor_(floor), outer_(outer) {}

  // Thrown by lost() to abandon every candidate up to the outer `bound`, which has lost; caught there
  // (build_halves, refine_band), it never leaves the tiler.
  struct Abandoned {
    const Bound* bound;
  };

  // Whether the faces of `mesh` (this candidate's, only ever appended to) already hold at least the
  // rival's flat and sliver area. Throws Abandoned when an outer candidate has lost.
  bool lost(const SlabMesh& mesh) {
    measure_more_defects(mesh, measured_, so_far_);
    measured_ = mesh.triangles.size();
    if (!(so_far_.score() < rival_)) return true;
    double added = std::min(floor_, so_far_.score());
    for (const Bound* b = outer_; b; b = b->outer_) {
      const double at_least = b->so_far_.score() + added;
      if (!(at_least < b->rival_)) throw Abandoned{b};
      added = std::min(b->floor_, at_least);
    }
    return false;
  }
  // The defects of all the faces measured: measure_defects of the whole candidate.
  [[nodiscard]] const TilingDefects& defects() const { return so_far_; }

 private:
  double rival_;
  double floor_;
  Bound* outer_;
  TilingDefects so_far_;
  std::size_t measured_ = 0;
};

// Makes `bound` the innermost candidate being built (SlabTiler::active_) for its lifetime.
class Candidate {
 public:
  Candidate(Bound*& active, Bound& bound) : active_(active), outer_(active) { active_ = &bound; }
  ~Candidate() { active_ = outer_; }
  Candidate(const Candidate&) = delete;
  Candidate& operator=(const Candidate&) = delete;

 private:
  Bound*& active_;
  Bound* outer_;
};

class SlabTiler {
 public:
  explicit SlabTiler(const TilingOptions& options) : options_(options) {}

  // `depth`: how many times the slab has been halved; `refine`: whether bands may be refined (not
  // inside a refinement); `top`: the slab between two slices, whose groups the statistics count.
  // With a `bound` on `out`, stops after the group that makes the candidate lose.
  void tile(const Level& lower, const Level& upper, Span span, int depth, bool refine, bool top, SlabMesh& out,
            Bound* bound = nullptr) {
    const Correspondence links = correspond(lower, upper, options_);
    const double extension = options_.end_caps == EndCaps::HalfSpacing ? 0.5 * (upper.w - lower.w) : 0.0;
    for (const ContourGroup& group : contour_groups(lower, upper, links)) {
      std::vector<std::pair<int, int>> pairs;
      switch (classify_group(group, lower, upper, links, &pairs)) {
        case GroupChange::EndsAbove:
          cap_outers(lower, group.lower, extension, true, out);
          break;
        case GroupChange::EndsBelow:
          cap_outers(upper, group.upper, extension, false, out);
          break;
        case GroupChange::OneToOne:
          one_to_one(lower, upper, group, pairs, span, depth, refine, top, out);
          break;
        case GroupChange::Topology:
          if (top) ++out.stats.branchings;
          topology_change(restrict_level(lower, group.lower), restrict_level(upper, group.upper),
                          restrict_correspondence(links, group), span, depth, out);
          break;
      }
      if (bound && bound->lost(out)) return;
    }
  }

 private:
  void cap_outers(const Level& level, const std::vector<int>& members, double extension, bool upward, SlabMesh& out,
                  FaceRole role = FaceRole::Cap) {
    for (int c : members) {
      const LevelContour& outer = level.contours[static_cast<std::size_t>(c)];
      if (outer.is_hole) continue;
      std::vector<const LevelContour*> holes;
      for (int h : members) {
        const LevelContour& k = level.contours[static_cast<std::size_t>(h)];
        if (k.is_hole && k.parent == c) holes.push_back(&k);
      }
      cap_end(outer, holes, level.w, extension, upward, options_, out, role);
    }
  }

  // The interpolation of `span`, or a new one for the group (lower, upper) between two slices.
  Span with_interpolation(const Level& lower, const Level& upper, Span span,
                          std::unique_ptr<Interpolation>& owned) const {
    if (span.interpolation) return span;
    owned = std::make_unique<Interpolation>(lower, upper, options_.interpolation_grid);
    return {owned.get(), 0.0, 1.0};
  }

  void one_to_one(const Level& lower, const Level& upper, const ContourGroup& group,
                  const std::vector<std::pair<int, int>>& pairs, Span span, int depth, bool refine, bool top,
                  SlabMesh& out) {
    SlabMesh direct = out.scratch();
    BandQuality quality;
    bool twisted = false;
    for (const auto& [a, b] : pairs) {
      const LevelContour& lo = lower.contours[static_cast<std::size_t>(a)];
      const LevelContour& hi = upper.contours[static_cast<std::size_t>(b)];
      bool pair_twisted = false;
      // Inside a refinement of a sheared slab (SlabMesh::shear), whose intermediate contours are a few
      // spacings apart once sheared, the band is solved as it will be: as tiled, the programme would join
      // points straight across, which the shear leans into slivers.
      const bool judged = !refine && !out.shear.isZero();
      const Polygon lo_points = judged ? sheared(lo.points, lower.w, out.shear) : Polygon{};
      const Polygon hi_points = judged ? sheared(hi.points, upper.w, out.shear) : Polygon{};
      const Polygon& lp = judged ? lo_points : lo.points;
      const Polygon& hp = judged ? hi_points : hi.points;
      const std::vector<BandTriangle> band =
          untwisted_band(lp, lower.w, hp, upper.w, options_, 0.5 * (lo.spacing() + hi.spacing()), &pair_twisted);
      const BandQuality q =
          band_quality(lp, lower.w, hp, upper.w, band, judged ? Eigen::Vector2d::Zero() : out.shear);
      emit_band(lo, hi, band, direct);
      quality.area += q.area;
      quality.sliver_area += q.sliver_area;
      quality.longest_cross_edge = std::max(quality.longest_cross_edge, q.longest_cross_edge);
      twisted = twisted || pair_twisted;
    }
    if (top) direct.stats.one_to_one += pairs.size();
    // The direct tiling's defects, measured once when first needed.
    std::optional<TilingDefects> direct_defects;
    auto direct_measure = [&]() -> const TilingDefects& {
      if (!direct_defects) direct_defects = measure_defects(direct);
      return *direct_defects;
    };
    if (options_.band_refinement == BandRefinement::Interpolated &&
        quality.sliver_share() > options_.max_band_sliver_share) {
      // A nearly flat band between nested contours: the lifted triangulation of the region between.
      SlabMesh lifted = out.scratch();
      if (lifted_transition(restrict_level(lower, group.lower), restrict_level(upper, group.upper), lifted) &&
          measure_defects(lifted).score() < direct_measure().score()) {
        if (top) lifted.stats.one_to_one += pairs.size();
        direct = std::move(lifted);
        direct_defects.reset();
        const TilingDefects& d = direct_measure();
        quality.area = d.area;
        quality.sliver_area = d.sliver_area;
        twisted = false;
      }
    }
    if (twisted && options_.branching == Branching::Interpolated && depth < options_.max_branching_depth) {
      // A topology change in disguise: the halves through the mid-level, if they do better.
      const Level lo = restrict_level(lower, group.lower), hi = restrict_level(upper, group.upper);
      if (top) ++direct.stats.branchings;
      if (try_halves(lo, hi, span, depth, direct_measure(), 0.0, out)) return;
      if (try_parting(lo, hi, direct_measure(), out)) return;
    }
    if (refine && options_.band_refinement == BandRefinement::Interpolated &&
        quality.sliver_share() > options_.max_band_sliver_share) {
      // Tile the group again through intermediate contours and keep whichever has less poorly shaped area.
      const Level lo = restrict_level(lower, group.lower), hi = restrict_level(upper, group.upper);
      const double spacing = mean_spacing(lo, hi);
      const int steps = static_cast<int>(
          std::clamp(std::ceil(quality.longest_cross_edge / (options_.max_band_aspect * spacing)), 2.0,
                     static_cast<double>(options_.max_intermediate_contours) + 1.0));
      SlabMesh refined = out.scratch();
      std::unique_ptr<Interpolation> owned;
      const Span s = with_interpolation(lo, hi, span, owned);
      const Interpolation::Claims before = s.interpolation->claims();
      if (refine_band(lo, hi, s, steps, depth, direct_measure().score(), refined)) {
        if (top) ++refined.stats.refined_bands;
        out.absorb(std::move(refined));
        return;
      }
      s.interpolation->restore(before);
    }
    out.absorb(std::move(direct));
  }

  // Tiles lower -> upper through `steps` - 1 intermediate levels into `out` and returns true when that
  // leaves less flat and sliver area than `rival`, the direct band's (given up as soon as it cannot:
  // Bound); false also when an intermediate level cannot be made.
  bool refine_band(const Level& lower, const Level& upper, Span span, int steps, int depth, double rival,
                   SlabMesh& out) {
    Bound bound(rival, rival, active_);
    const Candidate candidate(active_, bound);
    try {
      return refine_through(lower, upper, span, steps, depth, bound, out);
    } catch (const Bound::Abandoned& abandoned) {
      if (abandoned.bound != &bound) throw;
      return false;
    }
  }

  bool refine_through(const Level& lower, const Level& upper, Span span, int steps, int depth, Bound& bound,
                      SlabMesh& out) {
    std::vector<double> ts;
    std::vector<std::vector<std::size_t>> chosen;
    for (int k = 1; k < steps; ++k) {
      ts.push_back(span.t0 + (span.t1 - span.t0) * k / steps);
      chosen.push_back(span.interpolation->select(ts.back(), lower, upper));
      if (chosen.back().empty()) return false;
    }
    Level previous = lower;
    double t_previous = span.t0;
    for (std::size_t k = 0; k < ts.size(); ++k) {
      Level next = span.interpolation->take(ts[k], chosen[k], out);
      tile(previous, next, {span.interpolation, t_previous, ts[k]}, depth, false, false, out, &bound);
      if (bound.lost(out)) return false;
      previous = std::move(next);
      t_previous = ts[k];
    }
    tile(previous, upper, {span.interpolation, t_previous, span.t1}, depth, false, false, out, &bound);
    return !bound.lost(out);
  }

  // A group of many contours whose composite (or lifted transition) is nearly good and owes little of
  // its poor area to its bridges is not halved: halving would move the bridges off the mid-plane, but the
  // poor area lies elsewhere in the group (a skull section whose pores come and go), and the halves
  // re-tile every contour of it. On the head-and-neck scan 4 of the 62 halves this passes over had won,
  // by 56 mm^2 of flat and sliver area in all, at a fifth of the tiling's time (docs/benchmarks.md,
  // "Tiling: halves that cannot pay").
  static bool halves_futile(const Level& lower, const Level& upper, const TilingDefects& d) {
    return lower.contours.size() + upper.contours.size() > kFutileHalvesContours &&
           !(d.score() > kFutileHalvesPoorShare * d.area) && d.bridge_area < kFutileHalvesBridgeShare * d.score();
  }

  static bool wants_halves(const TilingDefects& d) {
    // The halves cost a level of interpolation and the tilings of both; they are tried when the
    // composite has flat bridges or leaves a noticeable share of its area flat or in slivers.
    return d.bridge_area > 0.0 || d.score() > kGoodEnough * d.area;
  }

  // A group whose topology changes: the composite of the finest level, or the halves of the slab
  // through the interpolated mid-level, whichever leaves less poorly shaped area; when both are worse
  // than parting the group, the parting.
  //
  // Where halves may be tried, the composite's costly bands are solved only when the choice needs them:
  // without them the composite already has its bridges and most of its flat and sliver area, which is
  // often enough to know that the lifted transition beats it. The halves, the costliest candidate, are
  // built last, against the best of the others, and given up as soon as they cannot win (Bound).
  void topology_change(const Level& lower, const Level& upper, const Correspondence& links, Span span, int depth,
                       SlabMesh& out) {
    const bool may_halve = options_.branching == Branching::Interpolated && depth < options_.max_branching_depth;
    SlabMesh composite = out.scratch();
    std::vector<DeferredBand> pending;
    tile_composite(lower, upper, options_, composite, may_halve ? &pending : nullptr, &links);
    const TilingDefects partial = measure_defects(composite);
    if (pending.empty()) {  // nothing deferred: the composite is complete
      settle_composite(lower, upper, span, depth, std::move(composite), partial, out);
      return;
    }
    if (partial.poor_area <= 0.0) {
      finish_composite(pending, options_, composite);
      settle_composite(lower, upper, span, depth, std::move(composite), measure_defects(composite), out);
      return;
    }
    // The composite has poorly shaped faces whatever its bands: the lifted transition is tried.
    SlabMesh lifted = out.scratch();
    std::optional<TilingDefects> lifted_defects;
    if (lifted_transition(lower, upper, lifted)) lifted_defects = measure_defects(lifted);
    if (lifted_defects && lifted_defects->score() < partial.score()) {  // it beats the composite
      settle(lower, upper, span, depth, std::move(lifted), *lifted_defects, out);
      return;
    }
    finish_composite(pending, options_, composite);
    TilingDefects best = measure_defects(composite);
    SlabMesh* chosen = &composite;
    if (lifted_defects && lifted_defects->score() < best.score()) {
      best = *lifted_defects;
      chosen = &lifted;
    }
    const Halving halving = halves_futile(lower, upper, best) ? Halving::Never : Halving::IfWanted;
    if (halving == Halving::Never ||
        !(partial.bridge_area > 0.0 && (!lifted_defects || wants_halves(*lifted_defects)))) {
      settle(lower, upper, span, depth, std::move(*chosen), best, out, halving);
      return;
    }
    // Halves are tried whichever of the composite and the lifted transition wins. They win where they
    // beat the better of the two, and also where they beat the lifted transition and the unfinished
    // composite: the choice made when the halves were built before the composite was finished. Finishing
    // usually adds area, but a crossing band splits faces and can take some away.
    const double partial_rival =
        lifted_defects ? std::min(partial.score(), lifted_defects->score()) : partial.score();
    Halves halves = build_halves(lower, upper, span, depth, std::max(partial_rival, best.score()), best.score(), out);
    if (halves.won) {
      if (!try_parting(lower, upper, halves.defects, out)) out.absorb(std::move(halves.mesh));
      return;
    }
    halves.undo();
    if (!try_parting(lower, upper, best, out)) out.absorb(std::move(*chosen));
  }

  // The complete composite `composite` with defects `best`: the lifted transition instead when it has
  // less poorly shaped area, then settle.
  void settle_composite(const Level& lower, const Level& upper, Span span, int depth, SlabMesh&& composite,
                        TilingDefects best, SlabMesh& out) {
    if (best.poor_area > 0.0) {
      SlabMesh lifted = out.scratch();
      if (lifted_transition(lower, upper, lifted)) {
        const TilingDefects d = measure_defects(lifted);
        if (d.score() < best.score()) {
          settle(lower, upper, span, depth, std::move(lifted), d, out);
          return;
        }
      }
    }
    settle(lower, upper, span, depth, std::move(composite), best, out);
  }

  // `candidate` (defects `best`) against the halves, when they are worth trying, and the parting.
  void settle(const Level& lower, const Level& upper, Span span, int depth, SlabMesh&& candidate,
              TilingDefects best, SlabMesh& out, Halving halving = Halving::IfWanted) {
    if (halving == Halving::IfWanted && options_.branching == Branching::Interpolated &&
        depth < options_.max_branching_depth &&
        wants_halves(best)) {
      SlabMesh halves = out.scratch();
      if (try_halves(lower, upper, span, depth, best, best.score(), halves)) {
        best = measure_defects(halves);
        if (!try_parting(lower, upper, best, out)) out.absorb(std::move(halves));
        return;
      }
    }
    if (!try_parting(lower, upper, best, out)) out.absorb(std::move(candidate));
  }

  // Where every way of joining the group across the slab leaves more poorly shaped area than capping
  // both sides (a thin wall whose slits and pockets change from slice to slice gives bands that cross
  // the wall's inside), the lower contours are capped a quarter of the slab above their plane and the
  // upper ones a quarter below theirs: a flat cut through the piece instead of a sheet across it. Adds
  // the caps to `out` and returns true when the rival has more poorly shaped area than the caps and
  // joins the levels across far more than they are apart (parting changes the piece's topology: it is
  // kept for tilings that fail outright).
  bool try_parting(const Level& lower, const Level& upper, const TilingDefects& rival, SlabMesh& out) {
    if (rival.poor_area <= 0.0) return false;
    double cap_area = 0.0;  // the caps cover both levels' regions
    for (const Level* level : {&lower, &upper}) {
      for (const LevelContour& c : level->contours) cap_area += c.is_hole ? -c.area : c.area;
    }
    if (cap_area >= rival.score()) return false;
    // Only a tiling that joins the levels across far more than they are apart has failed.
    Polygon lower_points, upper_points;
    for (const LevelContour& c : lower.contours)
      lower_points.insert(lower_points.end(), c.points.begin(), c.points.end());
    for (const LevelContour& c : upper.contours)
      upper_points.insert(upper_points.end(), c.points.begin(), c.points.end());
    const double spacing = mean_spacing(lower, upper);
    if (rival.longest_edge <=
        2.0 * std::hypot(contour_distance(lower_points, upper_points), upper.w - lower.w) + 2.0 * spacing) {
      return false;
    }
    const double quarter = 0.25 * (upper.w - lower.w);
    std::vector<int> all_lower(lower.contours.size()), all_upper(upper.contours.size());
    std::iota(all_lower.begin(), all_lower.end(), 0);
    std::iota(all_upper.begin(), all_upper.end(), 0);
    cap_outers(lower, all_lower, quarter, true, out, FaceRole::Bridge);
    cap_outers(upper, all_upper, quarter, false, out, FaceRole::Bridge);
    ++out.stats.partings;
    return true;
  }

  // The slab tiled lower -> mid-level -> upper, when the mid-level has contours for the group and the
  // halves leave less poorly shaped area than their rival (`won`; otherwise the mesh may be partial),
  // with the claims on the interpolation's contours to undo if it is dropped.
  struct Halves {
    SlabMesh mesh;
    TilingDefects defects;
    bool won = false;
    std::unique_ptr<Interpolation> owned;
    Interpolation* interpolation = nullptr;
    Interpolation::Claims before;
    void undo() { interpolation->restore(before); }
  };

  // The halves as a scratch mesh of `parent`, built until they lose to `rival`; `floor`: what the
  // group adds to an outer candidate when they lose (Bound).
  Halves build_halves(const Level& lower, const Level& upper, Span span, int depth, double rival, double floor,
                      const SlabMesh& parent) {
    Halves h;
    h.mesh = parent.scratch();
    span = with_interpolation(lower, upper, span, h.owned);
    h.interpolation = span.interpolation;
    h.before = span.interpolation->claims();
    const double tm = 0.5 * (span.t0 + span.t1);
    const std::vector<std::size_t> chosen = span.interpolation->select(tm, lower, upper);
    if (!chosen.empty()) {
      const Level middle = span.interpolation->take(tm, chosen, h.mesh);
      Bound bound(rival, floor, active_);
      const Candidate candidate(active_, bound);
      try {
        tile(lower, middle, {span.interpolation, span.t0, tm}, depth + 1, true, false, h.mesh, &bound);
        if (!bound.lost(h.mesh)) {
          tile(middle, upper, {span.interpolation, tm, span.t1}, depth + 1, true, false, h.mesh, &bound);
          h.won = !bound.lost(h.mesh);
        }
      } catch (const Bound::Abandoned& abandoned) {
        if (abandoned.bound != &bound) throw;
        return h;
      }
      h.defects = bound.defects();
    }
    return h;
  }

  // Tiles lower -> mid-level -> upper into `out` and returns true when that leaves less poorly shaped
  // area than `rival`; otherwise adds nothing.
  bool try_halves(const Level& lower, const Level& upper, Span span, int depth, const TilingDefects& rival,
                  double floor, SlabMesh& out) {
    Halves h = build_halves(lower, upper, span, depth, rival.score(), floor, out);
    if (h.won) {
      out.absorb(std::move(h.mesh));
      return true;
    }
    h.undo();
    return false;
  }

  const TilingOptions& options_;
  // The innermost candidate being built whose pieces count towards the outer ones (Bound).
  Bound* active_ = nullptr;
};

}  // namespace

void tile_slab(const Level& lower, const Level& upper, const TilingOptions& options, SlabMesh& out) {
  SlabTiler(options).tile(lower, upper, {}, 0, true, true, out);
  if (options.band_refinement == BandRefinement::Interpolated) {
    const double spacing = mean_spacing(lower, upper);
    improve_slab_faces(out, kMaxFlipDeviation * (upper.w - lower.w), kMinSplitLength * spacing);
    collapse_slivers(out, kMaxCollapseLength * spacing, kMaxCollapseDeviation * spacing);
  }
}

}  // namespace contourmesh::detail
