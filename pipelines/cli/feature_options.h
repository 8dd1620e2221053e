// SPDX-License-Identifier: BSD-3-Clause
// Options and helpers shared by `smooth`, `run` and `detect` for the methods that detect features.
#pragma once

#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/feature_detection.h>
#include <contourmesh/smooth/input_policy.h>
#include <contourmesh/smooth/mesh.h>

#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace contourmesh::cli {

/// Detection options as given on the command line; unset ones keep the method's (or preset's) value.
struct FeatureArgs {
  std::optional<double> gamma;
  std::optional<double> delta;
  std::optional<std::string> measure;
  std::optional<std::string> in_slice;
  std::optional<int> prefilter;
  std::optional<int> window;
  std::optional<double> corner_spread;
  std::string slice_axis;  ///< "", "x", "y" or "z"
};

/// Registers --gamma, --delta, --measure, --in-slice, --prefilter, --window, --corner-spread.
void add_detection_options(CLI::App* cmd, FeatureArgs& args);
/// The detection options and --slice-axis.
void add_feature_options(CLI::App* command, FeatureArgs& args);

/// Sets the detection options that were given on the command line, leaving the others as they are
/// (throws InvalidInputError for a bad --measure or --in-slice).
void apply_detection_args(const FeatureArgs& args, DetectionOptions& options);

/// The slice axis of --slice-axis (x, y or z), unset when not given; InvalidInputError otherwise.
[[nodiscard]] std::optional<Eigen::Vector3d> slice_axis_option(const FeatureArgs& args);

/// Runs the one input policy (prepare_input_mesh, contourmesh/smooth/input_policy.h; the VTK filter runs the same)
/// on a mesh read from `path`: each warning is one line "contourmesh COMMAND: warning: PATH: ...", and
/// an error is rethrown naming `path` (exit 2). `use` says whether the contour ids are needed (then they
/// are made usable: see ContourIdUse::Detection; --slice-axis recovers missing or unusable ids), and
/// `missing` what happens without usable ids: curvature-only detection with a warning, or an error.
[[nodiscard]] PreparedMesh prepare_input(Mesh mesh, const std::string& path, const std::string& command,
                                         ContourIdUse use, const FeatureArgs& args,
                                         MissingIds missing = MissingIds::CurvatureOnly);

/// The per-vertex arrays of a detection, for --labels-out: FeatureLabel (0 smooth, 1 edge, 2 corner,
/// 3 noise), Umbrella, KappaMin, KappaMax, KBelow, K0, KAbove, Psi.
[[nodiscard]] std::vector<PointScalars> detection_arrays(const FeatureDetection& detection);

}  // namespace contourmesh::cli
