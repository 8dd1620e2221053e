#include "feature_options.h"

#include "cli_common.h"

#include <smooth/errors.h>

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
  cmd->add_option("--measure", args.measure, "Umbrella measure: length (|U|, the paper) | normal (|U.n|)")
      ->capture_default_str();
  cmd->add_option("--prefilter", args.prefilter, "Taubin iterations on a copy used for detection only (>= 0)")
      ->capture_default_str();
  cmd->add_option("--in-slice", args.in_slice,
                  "Feature lines within a slice plane (cap rims): noise (the paper's rule) | along-line "
                  "(continuity along the line itself)")
      ->capture_default_str();
  cmd->add_option("--window", args.window, "Contour vertices per curve fit (odd, >= 5)")->capture_default_str();
  cmd->add_option("--corner-spread", args.corner_spread,
                  "Normal spread (0..1/3: 1/3 at a box corner) above which a candidate goes to the corner vote; "
                  "above 1/3: off")
      ->capture_default_str();
}

void add_feature_options(CLI::App* cmd, FeatureArgs& args) {
  add_detection_options(cmd, args);
  cmd->add_option("--slice-axis", args.slice_axis,
                  "x | y | z: recover missing contour ids by binning vertices along this axis");
}

DetectionOptions detection_options(const FeatureArgs& a) {
  DetectionOptions o;
  o.gamma = a.gamma;
  o.delta = a.delta;
  if (a.measure == "length") o.measure = UmbrellaMeasure::Length;
  else if (a.measure == "normal") o.measure = UmbrellaMeasure::NormalComponent;
  else throw InvalidInputError("--measure must be length or normal, got '" + a.measure + "'");
  if (a.in_slice == "noise") o.in_slice = InSliceFeatures::Noise;
  else if (a.in_slice == "along-line") o.in_slice = InSliceFeatures::AlongFeatureLine;
  else throw InvalidInputError("--in-slice must be noise or along-line, got '" + a.in_slice + "'");
  o.prefilter_iterations = a.prefilter;
  o.window = a.window;
  o.corner_spread = a.corner_spread;
  return o;
}

std::optional<Eigen::Vector3d> slice_axis_option(const FeatureArgs& args) {
  if (args.slice_axis.empty()) return std::nullopt;
  if (args.slice_axis == "x") return Eigen::Vector3d::UnitX();
  if (args.slice_axis == "y") return Eigen::Vector3d::UnitY();
  if (args.slice_axis == "z") return Eigen::Vector3d::UnitZ();
  throw InvalidInputError("--slice-axis must be x, y or z, got '" + args.slice_axis + "'");
}

PreparedMesh prepare_input(Mesh mesh, const std::string& path, const std::string& command, ContourIdUse use,
                           const FeatureArgs& args) {
  InputPolicyOptions options;
  options.ids = use;
  options.slice_axis = slice_axis_option(args);
  options.missing_ids = MissingIds::CurvatureOnly;
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
