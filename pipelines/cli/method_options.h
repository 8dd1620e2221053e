// SPDX-License-Identifier: BSD-3-Clause
// Method selection shared by `smooth`, `run` and `detect`: --method, --preset, --iterations and the
// per-family options (steps, boundary, the paper's subdivision), turned into libsmooth's method and
// SmoothOptions. Only options given on the command line override the preset's or the method's defaults.
#pragma once

#include "feature_options.h"

#include <contourmesh/smooth/smooth.h>

#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace contourmesh::cli {

struct MethodArgs {
  std::string method;  ///< --method; empty: the preset's method
  std::string preset;  ///< --preset; empty: the default preset (unless --method is given)
  std::optional<int> iterations;
  std::optional<std::string> creases;  ///< --creases: none | restore (cross-slice smoothing)
  /// --off-slice-volume: free | preserve (cross-slice smoothing); unset: free, but `run` keeps the volume
  /// on drawn contours
  std::optional<std::string> off_slice_volume;
};

/// Step options of `smooth` (run and detect keep the defaults).
struct StepArgs {
  std::optional<double> lambda, mu, beta;
  std::optional<std::string> boundary;
  std::optional<int> max_levels;
  std::optional<std::string> diffusion;
  bool keep_adaptive = false;
};

/// Registers --method and --preset (the two exclude each other) and, with `iterations`, --iterations,
/// --creases and --off-slice-volume.
void add_method_options(CLI::App* command, MethodArgs& args, bool iterations = true);
/// Registers --lambda, --mu, --beta, --boundary, --max-levels, --diffusion, --keep-adaptive.
void add_step_options(CLI::App* command, StepArgs& args);

/// The method and options selected: the preset (default: Preset::Default), or --method with the
/// library's defaults for it; then --iterations, --creases, --off-slice-volume, the step options and the
/// detection options given. Throws InvalidInputError for an unknown name, --iterations on a method without an
/// iteration count, --creases or --off-slice-volume on a method other than cross-slice smoothing,
/// --keep-adaptive without the paper's method, or a detection option out of its vocabulary.
[[nodiscard]] MethodConfig method_config(const MethodArgs& args, const StepArgs& steps, const FeatureArgs& features);

/// Runs the one input policy (prepare_input) on a mesh read from `path` for the selected method: the
/// contour ids are made usable for the methods that use them (paper, cross-slice) and passed through
/// for the others. Without usable ids the paper's method falls back to curvature-only detection (set in
/// `config`, with a warning); cross-slice smoothing cannot, so such a mesh is an InvalidInputError naming
/// `path` and saying how to recover the ids.
[[nodiscard]] PreparedMesh prepare_for_method(MethodConfig& config, Mesh mesh, const FeatureArgs& features,
                                              const std::string& path, const std::string& command);

/// The point arrays of a method's labels, for --labels-out and `detect`: FeatureLabel (0 smooth, 1 edge,
/// 2 corner, 3 noise), then the paper's detection arrays (detection_arrays) or cross-slice's crease
/// strengths (EdgeStrength, CornerStrength).
[[nodiscard]] std::vector<PointScalars> label_arrays(const FeatureLabels& labels);

/// The counts of edge, corner and noise labels.
struct LabelCounts {
  std::size_t edges = 0, corners = 0, noise = 0;
};
[[nodiscard]] LabelCounts count_labels(const std::vector<VertexLabel>& labels);

/// "paper", "cross-slice (preset default)", "paper (preset xu2006)": the selection in words.
[[nodiscard]] std::string describe_selection(const MethodArgs& args, SmoothingMethod method);

/// The preset's name when one was used ("default" when neither --method nor --preset was given), else
/// empty.
[[nodiscard]] std::string preset_name(const MethodArgs& args);

}  // namespace contourmesh::cli
