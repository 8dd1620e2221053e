// SPDX-License-Identifier: BSD-3-Clause
#include "feature_options.h"

#include "cli_common.h"

#include <contourmesh/smooth/errors.h>

#include <CLI/CLI.hpp>

#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>
#include <vector>

namespace contourmesh::cli {

void add_detection_options(CLI::App* cmd, FeatureArgs& args) {
  cmd->add_option("--gamma", args.gamma, "Umbrella threshold in mm (default: 2 x mean over contour vertices)");
  cmd->add_option("--delta", args.delta, "Curvature agreement threshold, 1/mm (default: 0.5 x |k0|)");
  cmd->add_option("--measure", args.measure,
                  "Umbrella measure: length (|U|, the paper; default) | normal (|U.n|)");
  cmd->add_option("--prefilter", args.prefilter,
                  "Taubin iterations on a copy used for detection only (>= 0; default 0)");
  cmd->add_option("--in-slice", args.in_slice,
                  "Feature lines within a slice plane (cap rims): noise (the paper's rule; default) | along-line "
                  "(continuity along the line itself)");
  cmd->add_option("--window", args.window, "Contour vertices per curve fit (odd, >= 5; default 7)");
  cmd->add_option("--corner-spread", args.corner_spread,
                  "Normal spread (0..1/3: 1/3 at a box corner) above which a candidate goes to the corner vote; "
                  "above 1/3: off (default 0.1; the xu2006 preset: off)");
}

void add_feature_options(CLI::App* cmd, FeatureArgs& args) {
  add_detection_options(cmd, args);
  cmd->add_option("--slice-axis", args.slice_axis,
                  "x | y | z: recover missing contour ids by binning vertices along this axis");
}

void apply_detection_args(const FeatureArgs& a, DetectionOptions& o) {
  if (a.gamma) o.gamma = a.gamma;
  if (a.delta) o.delta = a.delta;
  if (a.measure) {
    if (*a.measure == "length") o.measure = UmbrellaMeasure::Length;
    else if (*a.measure == "normal") o.measure = UmbrellaMeasure::NormalComponent;
    else throw InvalidInputError("--measure must be length or normal, got '" + *a.measure + "'");
  }
  if (a.in_slice) {
    if (*a.in_slice == "noise") o.in_slice = InSliceFeatures::Noise;
    else if (*a.in_slice == "along-line") o.in_slice = InSliceFeatures::AlongFeatureLine;
    else throw InvalidInputError("--in-slice must be noise or along-line, got '" + *a.in_slice + "'");
  }
  if (a.prefilter) o.prefilter_iterations = *a.prefilter;
  if (a.window) o.window = *a.window;
  if (a.corner_spread) o.corner_spread = *a.corner_spread;
}

std::optional<Eigen::Vector3d> slice_axis_option(const FeatureArgs& args) {
  if (args.slice_axis.empty()) return std::nullopt;
  if (args.slice_axis == "x") return Eigen::Vector3d::UnitX();
  if (args.slice_axis == "y") return Eigen::Vector3d::UnitY();
  if (args.slice_axis == "z") return Eigen::Vector3d::UnitZ();
  throw InvalidInputError("--slice-axis must be x, y or z, got '" + args.slice_axis + "'");
}

PreparedMesh prepare_input(Mesh mesh, const std::string& path, const std::string& command, ContourIdUse use,
                           const FeatureArgs& args, MissingIds missing) {
  InputPolicyOptions options;
  options.ids = use;
  options.slice_axis = slice_axis_option(args);
  options.missing_ids = missing;
  PreparedMesh prepared;
  try {
    prepared = prepare_input_mesh(std::move(mesh), options);
  } catch (const InvalidInputError&) {
    rethrow_with_context(path);
  }
  for (const std::string& line : prepared.warnings) {
    std::cerr << "contourmesh " << command << ": warning: " << path << ": " << cli_wording(line) << "\n";
  }
  return prepared;
}

std::vector<PointScalars> detection_arrays(const FeatureDetection& d) {
  auto from = [](const char* name, const Eigen::VectorXd& v) {
    return PointScalars{name, std::vector<double>(v.data(), v.data() + v.size()), ScalarType::Float64};
  };
  PointScalars labels{"FeatureLabel", {}, ScalarType::Int32};
  for (VertexLabel l : d.labels) labels.values.push_back(static_cast<double>(l));
  return {labels,
          from("Umbrella", d.umbrella),
          from("KappaMin", d.curvature.kappa_min),
          from("KappaMax", d.curvature.kappa_max),
          from("KBelow", d.k_below),
          from("K0", d.k0),
          from("KAbove", d.k_above),
          from("Psi", d.psi)};
}

}  // namespace contourmesh::cli
