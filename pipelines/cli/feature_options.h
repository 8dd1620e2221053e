// Options and helpers shared by `smooth --method paper` and `detect`.
#pragma once

#include <pipelines/mesh_io.h>
#include <smooth/adjacency.h>
#include <smooth/feature_detection.h>
#include <smooth/input_policy.h>
#include <smooth/mesh.h>

#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace contourmesh::cli {

struct FeatureArgs {
  std::optional<double> gamma;
  std::optional<double> delta;
  std::string measure = "length";
  std::string in_slice = "noise";
  int prefilter = 0;
  int window = 7;
  double corner_spread = 0.1;
  std::string slice_axis;  ///< "", "x", "y" or "z"
};

/// Registers --gamma, --delta, --measure, --in-slice, --prefilter, --window, --corner-spread.
void add_detection_options(CLI::App* cmd, FeatureArgs& args);
/// The detection options and --slice-axis.
void add_feature_options(CLI::App* command, FeatureArgs& args);

/// Detection options from the arguments (throws InvalidInputError for a bad --measure).
[[nodiscard]] DetectionOptions detection_options(const FeatureArgs& args);

/// The slice axis of --slice-axis (x, y or z), unset when not given; InvalidInputError otherwise.
[[nodiscard]] std::optional<Eigen::Vector3d> slice_axis_option(const FeatureArgs& args);

/// Runs the one input policy (prepare_input_mesh, smooth/input_policy.h; the VTK filter runs the same)
/// on a mesh read from `path`: each warning is one line "contourmesh COMMAND: warning: PATH: ...", and
/// an error is rethrown naming `path` (exit 2). `use` says whether the contour ids feed the paper's
/// detection (then they are made usable: see ContourIdUse::Detection; --slice-axis recovers missing or
/// unusable ids, and without usable ids detection falls back to curvature-only with a warning).
[[nodiscard]] PreparedMesh prepare_input(Mesh mesh, const std::string& path, const std::string& command,
                                         ContourIdUse use, const FeatureArgs& args);

/// The per-vertex arrays of a detection, for --labels-out: FeatureLabel (0 smooth, 1 edge, 2 corner,
/// 3 noise), Umbrella, KappaMin, KappaMax, KBelow, K0, KAbove, Psi.
[[nodiscard]] std::vector<PointScalars> detection_arrays(const FeatureDetection& detection);

}  // namespace contourmesh::cli
