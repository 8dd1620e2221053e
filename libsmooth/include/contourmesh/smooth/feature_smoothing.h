// SPDX-License-Identifier: BSD-3-Clause
// The paper's method end to end (Xu et al. 2006, Algorithm 1): detect features, subdivide
// adaptively around them, smooth the adaptive mesh with a linear isotropic scheme, resume the
// original resolution.
#pragma once

#include "contourmesh/smooth/adaptive_subdivision.h"
#include "contourmesh/smooth/feature_detection.h"
#include "contourmesh/smooth/limits.h"
#include "contourmesh/smooth/mesh.h"
#include "contourmesh/smooth/progress.h"
#include "contourmesh/smooth/smoothing.h"

#include <cstdint>
#include <optional>
#include <span>

namespace contourmesh {

enum class OutputResolution {
  Original,  ///< each input vertex takes the smoothed position of its copy; input connectivity (default)
  Adaptive,  ///< the smoothed adaptive mesh itself (denser around features; suits FEM, paper section 5)
};

struct FeatureSmoothingOptions {
  DetectionOptions detection;
  /// At most this many subdivision levels around each feature vertex (paper: rarely more than 3), >= 0.
  int max_levels = 3;
  /// The isotropic scheme on the adaptive mesh: SmoothingMethod::Taubin (eq. 6, default) or
  /// SmoothingMethod::Laplacian (eq. 5).
  SmoothingMethod diffusion = SmoothingMethod::Taubin;
  /// Paper section 6: Taubin 0.6307 / -0.6732, 40 iterations (more than the baselines' 20, because the
  /// adaptive mesh is denser around features).
  int iterations = 40;
  std::optional<double> lambda;  ///< unset: 0.6307 for Taubin, 0.3 for Laplacian
  double mu = -0.6732;
  OutputResolution output = OutputResolution::Original;
  BoundaryPolicy boundary = BoundaryPolicy::Fixed;
  /// Empty or one flag per input vertex: locked vertices never move. Not owned.
  std::span<const std::uint8_t> locked;
  /// Stages "detect", "subdivide", "smooth"; return false to cancel (CancelledError).
  ProgressCallback progress;
  /// Optional: sees the adaptive mesh's positions after every smoothing iteration; its first n columns
  /// are the input vertices (used for the volume-shrinking curve).
  IterationObserver on_iteration;
  /// Vertex cap and memory budget of the adaptive mesh (LimitError before a subdivision level that
  /// would exceed them).
  ResourceLimits limits;
};

/// Wall-clock seconds per stage (the paper's Table 1).
struct StageTimings {
  double detect = 0.0;
  double subdivide = 0.0;
  double smooth = 0.0;
  double total = 0.0;
};

struct FeatureSmoothingResult {
  Mesh mesh;                   ///< smoothed, at the requested resolution, with the input's ids
  FeatureDetection detection;  ///< labels and the numbers behind them, per input vertex
  std::size_t subdivided_vertices = 0;  ///< input vertices subdivided at least once
  Index adaptive_vertices = 0;          ///< vertices of the adaptive mesh
  std::vector<std::size_t> per_level;   ///< vertices subdivided at each level
  StageTimings seconds;
};

/// Runs Algorithm 1. The default detection needs contour ids (InvalidInputError otherwise): recover them
/// with assign_ids_by_slice_planes, or set detection.mode = DetectionMode::CurvatureOnly. Throws
/// InvalidInputError for options out of range, LimitError when the adaptive mesh would exceed
/// `options.limits`, and CancelledError on request.
[[nodiscard]] FeatureSmoothingResult feature_preserving_smooth(const Mesh& mesh,
                                                               const FeatureSmoothingOptions& options = {});

}  // namespace contourmesh
