// SPDX-License-Identifier: BSD-3-Clause
// One entry point for every smoothing method of the library (docs/smoothing.md, "One entry point and
// the presets"): the baselines of smoothing.h, the paper's method (feature_smoothing.h) and cross-slice
// smoothing (cross_slice.h), each configured by its own sub-struct of one options struct; and the named
// presets, among them the paper's literal configuration.
#pragma once

#include "contourmesh/smooth/crease_detection.h"
#include "contourmesh/smooth/cross_slice.h"
#include "contourmesh/smooth/feature_detection.h"
#include "contourmesh/smooth/feature_smoothing.h"
#include "contourmesh/smooth/limits.h"
#include "contourmesh/smooth/mesh.h"
#include "contourmesh/smooth/progress.h"
#include "contourmesh/smooth/smoothing.h"

#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

namespace contourmesh {

/// Options of every method, one sub-struct per family; smooth() reads the one of the method it runs.
/// Each family's defaults are its documented defaults (the baselines': the paper's section 6).
struct SmoothOptions {
  /// Laplacian, Taubin, mean curvature flow, MIN-DIST flow. Its `method` member is ignored: smooth()
  /// sets it from its argument.
  SmoothingOptions baseline;
  /// The paper's method (SmoothingMethod::FeaturePreserving).
  FeatureSmoothingOptions paper;
  /// Cross-slice smoothing (SmoothingMethod::CrossSlice).
  CrossSliceOptions cross_slice;
  /// Smoothing iterations of the method that runs, in place of its family's own count; unset: the
  /// family's count. Ignored by methods without an iteration count (None, CrossSlice). >= 0.
  std::optional<int> iterations;
  /// Progress of every stage ("detect", "subdivide", "smooth"); return false to cancel
  /// (CancelledError). Replaces the families' own `progress` members, which smooth() ignores.
  ProgressCallback progress;
  /// Vertex cap and memory budget: the input is checked against the vertex cap, and the paper's
  /// adaptive mesh against both (LimitError). Replaces `paper.limits`, which smooth() ignores.
  ResourceLimits limits;
};

/// The result of any method.
struct SmoothResult {
  SmoothingMethod method = SmoothingMethod::None;
  /// The smoothed mesh: the input's connectivity and ids, or for the paper's method with
  /// OutputResolution::Adaptive its smoothed adaptive mesh, or for cross-slice smoothing with
  /// CreaseRestoration::Subdivide its restored, subdivided mesh (in both, the input's vertices first).
  Mesh mesh;
  /// One label per input vertex from methods that label features (FeaturePreserving, CrossSlice);
  /// empty otherwise.
  std::vector<VertexLabel> labels;
  /// The paper's method: the feature detection behind its labels (umbrella, gamma, curvatures).
  std::optional<FeatureDetection> detection;
  /// Cross-slice smoothing: the creases of its result behind its labels.
  std::optional<CreaseDetection> creases;
  /// Wall-clock seconds per stage (the paper's Table 1); stages a method does not have stay 0.
  StageTimings seconds;
  /// Smoothing iterations that ran (0 for None and for methods without an iteration count).
  int iterations = 0;
  /// The paper's method: input vertices subdivided at least once, and the adaptive mesh's vertices.
  std::size_t subdivided_vertices = 0;
  Index adaptive_vertices = 0;
  /// Cross-slice smoothing: contour vertices corrected from their cross-slice profile, and the noise
  /// levels (mm) it used across the slices and along the contours, and where the first came from.
  std::size_t profiles = 0;
  double noise_across = 0.0, noise_along = 0.0;
  NoiseSource noise_across_source = NoiseSource::AcrossProfiles;
};

/// The iteration count a method runs by default, from its family's default options: 20 for the
/// baselines (the paper's section 6), 40 for the paper's method, 0 for None and CrossSlice.
[[nodiscard]] int default_iterations(SmoothingMethod method);

/// The iteration count smooth(mesh, method, options) runs: options.iterations, else the family's own.
[[nodiscard]] int iterations_of(SmoothingMethod method, const SmoothOptions& options);

/// True for the methods whose result carries per-vertex feature labels (FeaturePreserving, CrossSlice).
[[nodiscard]] bool produces_labels(SmoothingMethod method);

/// The options of the paper's Algorithm 2 that a method labels with (the paper's `detection`); nullptr
/// for other methods (cross-slice smoothing labels the creases of its result, `cross_slice.features`).
[[nodiscard]] DetectionOptions* detection_options_of(SmoothingMethod method, SmoothOptions& options);

/// Smooths `mesh` with `method`. FeaturePreserving and CrossSlice need contour ids (see their
/// headers); baselines do not. Every iteration, and the result, are checked against the input's
/// bounding box (divergence.h: divergence_guard, then the families' own `on_iteration` observers), so a
/// diverging run stops with DivergenceError instead of returning overflowing coordinates. Throws
/// InvalidInputError for options out of range or missing ids, LimitError beyond `options.limits`,
/// DivergenceError, CancelledError on request.
[[nodiscard]] SmoothResult smooth(const Mesh& mesh, SmoothingMethod method, const SmoothOptions& options = {});

/// The labels of a method and what they were found from.
struct FeatureLabels {
  std::vector<VertexLabel> labels;          ///< one per input vertex
  std::optional<FeatureDetection> detection;  ///< the paper's method
  std::optional<CreaseDetection> creases;     ///< cross-slice smoothing
  double seconds = 0.0;                       ///< wall-clock time of what ran
};

/// The labels smooth(mesh, method, options) reports, without its smoothed mesh: for the paper's method
/// its detection stage alone (it labels the input); for cross-slice smoothing the whole method (it
/// labels the creases of its result). Throws InvalidInputError for a method without labels
/// (produces_labels), and as smooth().
[[nodiscard]] FeatureLabels label_features(const Mesh& mesh, SmoothingMethod method, const SmoothOptions& options = {});

/// Named configurations.
enum class Preset {
  /// The project's default: cross-slice smoothing with its default options.
  Default,
  /// The paper's literal configuration (Xu et al. 2006, sections 3-6), to reproduce its figures: the
  /// feature-preserving method with Taubin diffusion lambda 0.6307 / mu -0.6732 for 40 iterations,
  /// at most 3 subdivision levels; detection by |U| (UmbrellaMeasure::Length) above gamma = 2 x its
  /// mean, curve windows of 7 contour vertices, delta 0.5 |k0|, in-slice feature lines labelled noise,
  /// corners only by the vote of umbilic vertices (the corner-spread extension off), no pre-filter.
  Xu2006,
};

/// "default", "xu2006".
[[nodiscard]] std::string_view to_string(Preset preset);
/// Inverse of to_string; throws InvalidInputError listing the valid names.
[[nodiscard]] Preset parse_preset(std::string_view name);

/// A method and its options.
struct MethodConfig {
  SmoothingMethod method = SmoothingMethod::CrossSlice;
  SmoothOptions options;
};

/// The method and options of a preset. Every option the preset fixes is set explicitly, so a change of
/// a library default does not change the preset.
[[nodiscard]] MethodConfig preset(Preset preset);

}  // namespace contourmesh
