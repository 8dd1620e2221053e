// SPDX-License-Identifier: BSD-3-Clause
// A phantom as the truth that surface_accuracy measures meshes against: its signed distance and
// normal, samples of its analytic surface, and the distance to its sharp edges and corners (the
// feature region). Shared by `contourmesh run`, `contourmesh compare` and the tiling-quality tool, so
// that they all report the same numbers for the same mesh (docs/results.md, "Definitions").
#pragma once

#include "contourmesh/reconstruct/phantom.h"
#include "contourmesh/smooth/surface_metrics.h"

namespace contourmesh {

struct PhantomTruthOptions {
  /// mm: edge length of the grid whose crossings of the zero set sample the true surface
  /// (sample_implicit_surface), > 0. Finer is more exact and slower (the cost grows as 1 / spacing^2).
  double sample_spacing = 0.4;
  /// mm the phantom's bounding box is grown by before sampling, >= 0.
  double margin = 2.0;
};

/// The truth of `phantom`: signed distance (negative inside), outward normal, samples of the analytic
/// surface, and the distance to the nearest feature point (left empty for a phantom without sharp
/// features, so that everything counts as smooth). The feature distance of each truth sample is
/// computed once here and looked up afterwards, since every measured mesh asks for it again. Throws
/// InvalidInputError for a spacing <= 0 or a negative margin.
[[nodiscard]] SurfaceTruth phantom_surface_truth(const Phantom& phantom, const PhantomTruthOptions& options = {});

}  // namespace contourmesh
