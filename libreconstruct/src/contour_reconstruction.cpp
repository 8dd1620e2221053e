// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/contour_reconstruction.h"

#include "contourmesh/reconstruct/contour_deviation.h"
#include "contourmesh/reconstruct/contour_resampling.h"
#include "contourmesh/reconstruct/planar_contours.h"

#include <contourmesh/smooth/errors.h>

#include "contourmesh/internal/polygon2d.h"
#include "detail/single_slice.h"
#include "detail/slab_tiling.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>
#include <utility>

namespace contourmesh {

namespace {

using Polygon = std::vector<Eigen::Vector2d>;

std::string mm(double v) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << v;
  return s.str();
}

void check_options(const ContourReconstructionOptions& o, const std::string& what) {
  auto bad = [&](const std::string& text) { throw InvalidInputError(what + ": " + text); };
  if (!(o.sampling >= 0.0) || !std::isfinite(o.sampling)) bad("the sampling must be a finite number >= 0 mm");
  if (!(o.sampling_tolerance >= 0.0) || !std::isfinite(o.sampling_tolerance)) {
    bad("the sampling tolerance must be a finite number >= 0 mm");
  }
  if (!(o.slab_thickness >= 0.0) || !std::isfinite(o.slab_thickness)) {
    bad("the slab thickness must be a finite number >= 0 mm");
  }
}

Eigen::Vector2d centroid(const Polygon& p) {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  double a2 = 0.0;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    const double cross = p[j].x() * p[i].y() - p[i].x() * p[j].y();
    a2 += cross;
    c += (p[j] + p[i]) * cross;
  }
  if (a2 == 0.0) {
    for (const auto& q : p) c += q;
    return c / static_cast<double>(p.size());
  }
  return c / (3.0 * a2);
}

// Fraction of the smaller region covered by the other, estimated on a 64 x 64 grid of sample points.
double overlap_fraction(const Polygon& a, const Polygon& b) {
  const bool a_smaller = std::abs(signed_area(a)) <= std::abs(signed_area(b));
  const Polygon& small = a_smaller ? a : b;
  const Polygon& large = a_smaller ? b : a;
  Eigen::AlignedBox2d box;
  for (const auto& p : small) box.extend(p);
  constexpr int kGrid = 64;
  std::size_t inside = 0, both = 0;
  for (int i = 0; i < kGrid; ++i) {
    for (int j = 0; j < kGrid; ++j) {
      const Eigen::Vector2d p =
          box.min() + box.sizes().cwiseProduct(Eigen::Vector2d((i + 0.5) / kGrid, (j + 0.5) / kGrid));
      if (!point_in_polygon(small, p)) continue;
      ++inside;
      both += point_in_polygon(large, p) ? 1 : 0;
    }
  }
  return inside == 0 ? 0.0 : static_cast<double>(both) / static_cast<double>(inside);
}

// Per-slice in-plane offsets of the drift alignment (see DriftAlignment::Centroids).
std::vector<Eigen::Vector2d> drift_offsets(const ContourStack& stack, double min_overlap, std::size_t& aligned) {
  const auto& sl = stack.slices;
  std::vector<Eigen::Vector2d> offset(sl.size(), Eigen::Vector2d::Zero());
  for (std::size_t s = 1; s < sl.size(); ++s) {
    offset[s] = offset[s - 1];
    if (sl[s].contours.size() != 1 || sl[s - 1].contours.size() != 1) continue;
    const Polygon& below = sl[s - 1].contours[0].points;
    const Polygon& above = sl[s].contours[0].points;
    const double overlap = overlap_fraction(below, above);
    if (overlap <= std::min(1.0, 2.0 * min_overlap)) continue;
    // A drift, not a change of shape: the contours overlap at least as much once their centroids meet.
    // Where an outline widens on one side its centroid moves too, and shifting it would tile the slab
    // in a frame where the two contours agree less (the top of the breast set's Breast).
    const Eigen::Vector2d shift = centroid(above) - centroid(below);
    Polygon moved = above;
    for (Eigen::Vector2d& p : moved) p -= shift;
    if (overlap_fraction(below, moved) < overlap) continue;
    offset[s] += shift;
    ++aligned;
  }
  return offset;
}

// Moves every vertex back by the offset of its position along the axis (linear between slice planes,
// constant beyond the ends): affine within each gap, so triangles stay flat and the surface embedded.
void shear_back(Mesh& mesh, const ContourStack& stack, const std::vector<Eigen::Vector2d>& offset) {
  const auto& sl = stack.slices;
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    Eigen::Vector3d x = mesh.positions.col(i);
    const double w = (x - stack.origin).dot(stack.axis_w);
    Eigen::Vector2d o;
    if (w <= sl.front().w) {
      o = offset.front();
    } else if (w >= sl.back().w) {
      o = offset.back();
    } else {
      const auto it =
          std::upper_bound(sl.begin(), sl.end(), w, [](double v, const SliceContours& s) { return v < s.w; });
      const std::size_t s = static_cast<std::size_t>(it - sl.begin()) - 1;
      const double t = (w - sl[s].w) / (sl[s + 1].w - sl[s].w);
      o = (1.0 - t) * offset[s] + t * offset[s + 1];
    }
    mesh.positions.col(i) = x + o.x() * stack.axis_u + o.y() * stack.axis_v;
  }
}

}  // namespace

namespace {

// Every contour in one plane: slabs of the given thickness, or an error.
void one_slice(ContourReconstruction& out, std::size_t s, const std::string& what,
               const ContourReconstructionOptions& options) {
  const ContourStack& stack = out.contours;
  if (!(options.slab_thickness > 0.0)) {
    const std::string axis = stack.axis_w == Eigen::Vector3d::UnitZ() ? "z" : "w";
    throw InvalidInputError(what + ": every contour lies in one slice (" + axis + " = " + mm(stack.slices[s].w) +
                            " mm): a surface needs contours on two slices, or a slab thickness");
  }
  const double half = 0.5 * options.slab_thickness;
  out.mesh = Mesh{};
  out.mesh.positions.resize(3, 0);
  for (std::size_t c = 0; c < stack.slices[s].contours.size(); ++c) {
    if (stack.slices[s].contours[c].is_hole) continue;
    detail::append_part(out.mesh, detail::single_slice_slab(stack, s, c, half, half, options.tiling));
    ++out.report.slabs;
  }
  out.report.warnings.push_back(what + ": every contour lies in one slice: made a slab " + mm(options.slab_thickness) +
                                " mm thick");
}

// tile_contours, in drift-aligned coordinates when asked (see DriftAlignment::Centroids).
void tile(ContourReconstruction& out, const ContourReconstructionOptions& options, const ProgressCallback& progress) {
  const ContourStack& stack = out.contours;
  std::vector<Eigen::Vector2d> offset;
  ContourStack aligned;
  const ContourStack* to_tile = &stack;
  if (options.alignment == DriftAlignment::Centroids) {
    offset = drift_offsets(stack, options.tiling.min_overlap_fraction, out.report.aligned_gaps);
    if (out.report.aligned_gaps > 0) {
      aligned = stack;
      for (std::size_t s = 0; s < aligned.slices.size(); ++s) {
        for (Contour& c : aligned.slices[s].contours) {
          for (Eigen::Vector2d& p : c.points) p -= offset[s];
        }
      }
      to_tile = &aligned;
    }
  }
  TilingResult tiled = detail::tile_contours_judged(*to_tile, options.tiling, progress, offset);
  out.report.tiling = tiled.stats;
  out.mesh = std::move(tiled.mesh);
  if (out.report.aligned_gaps > 0) shear_back(out.mesh, stack, offset);
}

// Contours the tiler dropped (no partner on either adjacent slice): slabs, hollow slabs for holes, or
// a warning naming them.
void single_slice_contours(ContourReconstruction& out, const std::string& what,
                           const ContourReconstructionOptions& options) {
  const ContourStack& stack = out.contours;
  ContourReconstructionReport& report = out.report;
  const bool make_slabs =
      options.single_slice == SingleSliceContours::Slab && options.tiling.end_caps == EndCaps::HalfSpacing;
  const detail::UnmeshedContours unmeshed = detail::unmeshed_contours(out.mesh, stack);
  std::size_t dropped = 0, cavities = 0, thinned = 0;
  std::string names;
  auto drop = [&](std::size_t s, std::size_t c) {
    ++dropped;
    if (dropped <= 5) names += (names.empty() ? "" : ", ") + std::to_string(c) + " of slice " + std::to_string(s);
  };
  // Outer contours first, as slabs (with their holes); then holes inside the surface as it then is.
  std::vector<std::pair<std::size_t, std::size_t>> holes;
  for (const auto& [s, c] : unmeshed.list) {
    const Contour& contour = stack.slices[s].contours[c];
    if (!make_slabs) {
      drop(s, c);
    } else if (!contour.is_hole) {
      const auto [below, above] = detail::half_gaps(stack, s);
      detail::append_part(out.mesh, detail::single_slice_slab(stack, s, c, below, above, options.tiling));
      ++report.slabs;
    } else if (!unmeshed.contains(s, contour.parent)) {
      holes.emplace_back(s, c);  // a hole of a slab is inside it
    }
  }
  std::vector<TilingResult> cavity_parts;  // appended after the checks, which cut the surface
  if (!holes.empty()) {
    const auto near = detail::faces_near_slices(out.mesh, stack);
    for (const auto& [s, c] : holes) {
      bool thin = false;
      if (auto part = detail::fitting_cavity(out.mesh, near[s], stack, s, c, options.tiling, thin)) {
        cavity_parts.push_back(std::move(*part));
        ++cavities;
        thinned += thin ? 1 : 0;
      } else {
        drop(s, c);
      }
    }
  }
  for (const auto& part : cavity_parts) detail::append_part(out.mesh, part);
  report.slabs += cavities;
  if (report.slabs > 0) {
    std::string text = what + ": " + std::to_string(report.slabs) + " contour" + (report.slabs == 1 ? "" : "s") +
                       " drawn on one slice only (no partner on an adjacent slice): made " +
                       (report.slabs == 1 ? "a slab" : "slabs") + " reaching half-way to the adjacent slices";
    if (cavities > 0) {
      text += "; " + std::to_string(cavities) + (cavities == report.slabs ? " (all holes)" : " of them holes") +
              " made hollow";
      if (thinned > 0) text += ", " + std::to_string(thinned) + " thinner to stay inside the surface around";
    }
    report.warnings.push_back(text);
  }
  if (dropped > 0) {
    report.warnings.push_back(what + ": " + std::to_string(dropped) + " contour" + (dropped == 1 ? "" : "s") +
                              " with no partner on an adjacent slice not meshed (contour " + names +
                              (dropped > 5 ? ", ..." : "") + ")");
  }
}

}  // namespace

ContourReconstruction reconstruct_from_contours(const ContourStack& input, const std::string& what,
                                                const ContourReconstructionOptions& options,
                                                const ProgressCallback& progress) {
  check_options(options, what);
  ContourReconstruction out;
  ContourReconstructionReport& report = out.report;
  out.contours = input;
  std::vector<std::size_t> occupied;
  for (std::size_t s = 0; s < input.slices.size(); ++s) {
    const auto& cs = input.slices[s].contours;
    if (!cs.empty()) occupied.push_back(s);
    report.contours += cs.size();
    for (const Contour& c : cs) {
      report.hole_contours += c.is_hole ? 1 : 0;
      report.points_drawn += c.points.size();
    }
  }
  report.slices = occupied.size();
  if (report.contours == 0) throw InvalidInputError(what + ": no contours");
  report.slicewise_volume = slicewise_volume(input);
  const auto t0 = std::chrono::steady_clock::now();
  if (options.sampling > 0.0) resample_drawn_stack(out.contours, options.sampling, options.sampling_tolerance);
  for (const SliceContours& s : out.contours.slices) {
    for (const Contour& c : s.contours) report.points_tiled += c.points.size();
  }
  if (occupied.size() == 1) {
    one_slice(out, occupied[0], what, options);
  } else {
    tile(out, options, progress);
    if (report.tiling.dropped_contours > 0) single_slice_contours(out, what, options);
  }
  report.seconds_tile = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (out.mesh.num_faces() == 0)
    throw InvalidInputError(what + ": no contour continues into an adjacent slice: nothing to tile");
  return out;
}

}  // namespace contourmesh
