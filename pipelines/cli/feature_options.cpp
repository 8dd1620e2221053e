#include "feature_options.h"

#include <smooth/contour_structure.h>
#include <smooth/errors.h>
#include <smooth/validation.h>

#include <CLI/CLI.hpp>

#include <iostream>

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
  return o;
}

std::string prepare_contour_ids(Mesh& mesh, const MeshAdjacency& adjacency, const FeatureArgs& args,
                                const std::string& path, const std::string& command, DetectionOptions& detection) {
  if (mesh.has_contour_ids()) return "file";
  if (!args.slice_axis.empty()) {
    Eigen::Vector3d axis;
    if (args.slice_axis == "x") axis = Eigen::Vector3d::UnitX();
    else if (args.slice_axis == "y") axis = Eigen::Vector3d::UnitY();
    else if (args.slice_axis == "z") axis = Eigen::Vector3d::UnitZ();
    else throw InvalidInputError("--slice-axis must be x, y or z, got '" + args.slice_axis + "'");
    if (!assign_ids_by_slice_planes(mesh, adjacency, axis)) {
      throw InvalidInputError(path + ": its vertices do not lie on planes normal to " + args.slice_axis +
                              ", so contour ids cannot be recovered (not a contour-based mesh?)");
    }
    return "slice-planes";
  }
  std::cerr << "contourmesh " << command << ": warning: " << path
            << " has no contour ids: using curvature-only feature detection "
               "(give --slice-axis to recover the ids of a contour-stack mesh)\n";
  detection.mode = DetectionMode::CurvatureOnly;
  return "none";
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

void check_mesh(const Mesh& mesh, const std::string& path, const std::string& command) {
  const auto problems = find_mesh_problems(mesh);
  std::size_t topology = 0;
  for (const MeshProblem& p : problems) {
    if (p.kind == MeshProblemKind::NonFiniteCoordinate || p.kind == MeshProblemKind::IndexOutOfRange ||
        p.kind == MeshProblemKind::IdSizeMismatch) {
      throw InvalidInputError(path + ": " + describe(p));
    }
    ++topology;
  }
  if (topology) {
    std::cerr << "contourmesh " << command << ": warning: " << path << ": " << topology << " topology problem"
              << (topology == 1 ? "" : "s") << ", first: " << describe(problems.front()) << "\n";
  }
}

}  // namespace contourmesh::cli
