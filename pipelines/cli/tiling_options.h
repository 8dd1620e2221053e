// SPDX-License-Identifier: BSD-3-Clause
// The tiler's options on the command line, shared by `reconstruct` and `run` (both routes): every field
// of TilingOptions except the thread count and the limits, which --threads and --max-vertices set.
#pragma once

#include <contourmesh/reconstruct/tiling.h>

#include <cstddef>
#include <string>

namespace CLI {
class App;
}

namespace contourmesh::cli {

struct TilingArgs {
  std::string end_caps = "half-spacing";
  std::string cap_refinement = "interior";
  std::string branching = "interpolated";
  int max_branching_depth = TilingOptions{}.max_branching_depth;
  std::string band_refinement = "interpolated";
  double max_band_sliver_share = TilingOptions{}.max_band_sliver_share;
  double max_band_aspect = TilingOptions{}.max_band_aspect;
  int max_intermediate_contours = TilingOptions{}.max_intermediate_contours;
  double interpolation_grid = TilingOptions{}.interpolation_grid;
  double min_overlap = TilingOptions{}.min_overlap_fraction;
  double min_overlap_of_larger = TilingOptions{}.min_overlap_of_larger;
  std::size_t full_dp_limit = TilingOptions{}.full_dp_limit;
  double band_fraction = TilingOptions{}.band_fraction;
};

/// Registers --end-caps, --cap-refinement, --branching, --max-branching-depth, --band-refinement,
/// --max-band-sliver-share, --max-band-aspect, --max-intermediate-contours, --interpolation-grid,
/// --min-overlap, --min-overlap-of-larger, --full-dp-limit and --band-fraction on `command`.
void add_tiling_options(CLI::App* command, TilingArgs& args);

/// The tiling options of the arguments (threads and limits at their defaults). Throws InvalidInputError
/// naming the option for a name that is not one of the choices or a value out of range.
[[nodiscard]] TilingOptions tiling_options(const TilingArgs& args);

}  // namespace contourmesh::cli
