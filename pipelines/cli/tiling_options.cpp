// SPDX-License-Identifier: BSD-3-Clause
#include "tiling_options.h"

#include <contourmesh/smooth/errors.h>

#include <CLI/CLI.hpp>

namespace contourmesh::cli {

void add_tiling_options(CLI::App* cmd, TilingArgs& args) {
  cmd->add_option("--end-caps", args.end_caps,
                  "Where objects end: half-spacing (half a slice beyond the last contour) | end-slice")
      ->capture_default_str();
  cmd->add_option("--cap-refinement", args.cap_refinement,
                  "Caps: interior (constrained Delaunay with interior vertices) | ear-clipping")
      ->capture_default_str();
  cmd->add_option("--branching", args.branching,
                  "Where contours split, merge or a hole opens: interpolated (shape-based interpolation, mid-plane "
                  "composites only at the finest level) | mid-plane (composites only)")
      ->capture_default_str();
  cmd->add_option("--max-branching-depth", args.max_branching_depth,
                  "Times a slab whose topology changes is halved through interpolated contours, >= 0")
      ->capture_default_str();
  cmd->add_option("--band-refinement", args.band_refinement,
                  "Bands made of slivers: interpolated (tiled again through intermediate contours, then slivers "
                  "flipped or split) | none")
      ->capture_default_str();
  cmd->add_option("--max-band-sliver-share", args.max_band_sliver_share,
                  "A band is refined when faces under 10 degrees hold more than this share of its area, 0 to 1")
      ->capture_default_str();
  cmd->add_option("--max-band-aspect", args.max_band_aspect,
                  "Intermediate contours at most this many contour spacings apart across a refined band, > 0")
      ->capture_default_str();
  cmd->add_option("--max-intermediate-contours", args.max_intermediate_contours,
                  "At most this many intermediate contours per refined band, >= 1")
      ->capture_default_str();
  cmd->add_option("--interpolation-grid", args.interpolation_grid,
                  "Grid of the shape-based interpolation, in contour spacings, (0, 1]")
      ->capture_default_str();
  cmd->add_option("--min-overlap", args.min_overlap,
                  "Contours of adjacent slices correspond when their regions overlap by more than this fraction "
                  "of the smaller, (0, 1]")
      ->capture_default_str();
  cmd->add_option("--min-overlap-of-larger", args.min_overlap_of_larger,
                  "... and of the larger, [0, 1) (a speck does not continue a contour 100 times its size)")
      ->capture_default_str();
  cmd->add_option("--full-dp-limit", args.full_dp_limit,
                  "Contour pairs that the coarse-to-fine programme cannot serve (a contour under 32 points) get "
                  "the full minimum-area programme up to m x n points, larger ones a band around the diagonal")
      ->capture_default_str();
  cmd->add_option("--band-fraction", args.band_fraction,
                  "Half-width of that band, as a fraction of the contour's points, 0 to 1")
      ->capture_default_str();
}

TilingOptions tiling_options(const TilingArgs& a) {
  TilingOptions o;
  if (a.end_caps == "half-spacing") o.end_caps = EndCaps::HalfSpacing;
  else if (a.end_caps == "end-slice") o.end_caps = EndCaps::AtEndSlice;
  else throw InvalidInputError("--end-caps must be half-spacing or end-slice, got '" + a.end_caps + "'");
  if (a.cap_refinement == "interior") o.cap_refinement = CapRefinement::Interior;
  else if (a.cap_refinement == "ear-clipping") o.cap_refinement = CapRefinement::EarClipping;
  else throw InvalidInputError("--cap-refinement must be interior or ear-clipping, got '" + a.cap_refinement + "'");
  if (a.branching == "interpolated") o.branching = Branching::Interpolated;
  else if (a.branching == "mid-plane") o.branching = Branching::MidPlaneComposite;
  else throw InvalidInputError("--branching must be interpolated or mid-plane, got '" + a.branching + "'");
  if (a.band_refinement == "interpolated") o.band_refinement = BandRefinement::Interpolated;
  else if (a.band_refinement == "none") o.band_refinement = BandRefinement::None;
  else throw InvalidInputError("--band-refinement must be interpolated or none, got '" + a.band_refinement + "'");
  auto check = [](bool ok, const std::string& what) {
    if (!ok) throw InvalidInputError(what);
  };
  check(a.max_branching_depth >= 0, "--max-branching-depth must be >= 0");
  check(a.max_band_sliver_share >= 0.0 && a.max_band_sliver_share <= 1.0, "--max-band-sliver-share must be in [0, 1]");
  check(a.max_band_aspect > 0.0 && std::isfinite(a.max_band_aspect), "--max-band-aspect must be > 0");
  check(a.max_intermediate_contours >= 1, "--max-intermediate-contours must be >= 1");
  check(a.interpolation_grid > 0.0 && a.interpolation_grid <= 1.0, "--interpolation-grid must be in (0, 1]");
  check(a.min_overlap > 0.0 && a.min_overlap <= 1.0, "--min-overlap must be in (0, 1]");
  check(a.min_overlap_of_larger >= 0.0 && a.min_overlap_of_larger < 1.0, "--min-overlap-of-larger must be in [0, 1)");
  check(a.band_fraction >= 0.0 && a.band_fraction <= 1.0, "--band-fraction must be in [0, 1]");
  o.max_branching_depth = a.max_branching_depth;
  o.max_band_sliver_share = a.max_band_sliver_share;
  o.max_band_aspect = a.max_band_aspect;
  o.max_intermediate_contours = a.max_intermediate_contours;
  o.interpolation_grid = a.interpolation_grid;
  o.min_overlap_fraction = a.min_overlap;
  o.min_overlap_of_larger = a.min_overlap_of_larger;
  o.full_dp_limit = a.full_dp_limit;
  o.band_fraction = a.band_fraction;
  return o;
}

}  // namespace contourmesh::cli
