#include "feature_options.h"

#include <smooth/contour_structure.h>
#include <smooth/errors.h>
#include <smooth/validation.h>

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

namespace {

void warn(const std::string& command, const std::string& text) {
  std::cerr << "contourmesh " << command << ": warning: " << text << "\n";
}

// The coordinate axis within about 2 degrees of `axis`, if any (CT slices are nearly always axial).
std::optional<Eigen::Vector3d> nearest_coordinate_axis(const Eigen::Vector3d& axis) {
  for (int k = 0; k < 3; ++k) {
    if (std::abs(axis[k]) > std::cos(2.0 * 3.14159265358979 / 180.0)) return Eigen::Vector3d::Unit(k);
  }
  return std::nullopt;
}

}  // namespace

std::string prepare_contour_ids(Mesh& mesh, const MeshAdjacency& adjacency, const FeatureArgs& args,
                                const std::string& path, const std::string& command, DetectionOptions& detection) {
  std::optional<Eigen::Vector3d> axis;
  if (!args.slice_axis.empty()) {
    if (args.slice_axis == "x") axis = Eigen::Vector3d::UnitX();
    else if (args.slice_axis == "y") axis = Eigen::Vector3d::UnitY();
    else if (args.slice_axis == "z") axis = Eigen::Vector3d::UnitZ();
    else throw InvalidInputError("--slice-axis must be x, y or z, got '" + args.slice_axis + "'");
  }
  if (mesh.has_contour_ids()) {
    if (const std::size_t gaps = compact_slice_ids(mesh)) {
      warn(command, path + ": the slice ids skip " + std::to_string(gaps) + " unused value" + (gaps == 1 ? "" : "s") +
                        ": renumbered them consecutively");
    }
    const std::string problem = find_contour_id_problem(mesh, adjacency);
    if (problem.empty()) return "file";
    // Inconsistent ids: recover them from the geometry where it allows, else fall back.
    std::vector<Eigen::Vector3d> axes;
    if (axis) {
      axes.push_back(*axis);
    } else {
      try {
        const Eigen::Vector3d estimate = estimate_slice_axis(mesh);
        axes.push_back(estimate);
        if (const auto snapped = nearest_coordinate_axis(estimate)) axes.push_back(*snapped);
      } catch (const InvalidInputError&) {
      }
    }
    for (const Eigen::Vector3d& a : axes) {
      if (repair_contour_ids(mesh, adjacency, a)) {
        warn(command, path + ": inconsistent contour ids (" + problem + "): corrected them from the slice planes");
        return "file-repaired";
      }
    }
    Mesh recovered = mesh;
    for (const Eigen::Vector3d& a : axes) {
      if (assign_ids_by_slice_planes(recovered, adjacency, a)) {
        warn(command, path + ": inconsistent contour ids (" + problem + "): recovered them from the slice planes");
        mesh = std::move(recovered);
        return "slice-planes";
      }
    }
    warn(command, path + ": inconsistent contour ids (" + problem +
                      ") and no slice planes to recover them from: using curvature-only feature detection");
    mesh.slice_ids.clear();
    mesh.contour_ids.clear();
    detection.mode = DetectionMode::CurvatureOnly;
    return "none";
  }
  if (axis) {
    if (!assign_ids_by_slice_planes(mesh, adjacency, *axis)) {
      throw InvalidInputError(path + ": its vertices do not lie on planes normal to " + args.slice_axis +
                              ", so contour ids cannot be recovered (not a contour-based mesh?)");
    }
    return "slice-planes";
  }
  warn(command, path + " has no contour ids: using curvature-only feature detection "
                       "(give --slice-axis to recover the ids of a contour-stack mesh)");
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

void check_mesh(Mesh& mesh, const std::string& path, const std::string& command) {
  // read_mesh already refuses these; meshes from elsewhere may not have been checked.
  if (!mesh.positions.allFinite()) {
    for (Index i = 0; i < mesh.num_vertices(); ++i) {
      if (!mesh.positions.col(i).allFinite()) {
        throw InvalidInputError(path + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
      }
    }
  }
  if ((!mesh.slice_ids.empty() || !mesh.contour_ids.empty()) && !mesh.has_contour_ids()) {
    throw InvalidInputError(path + ": the contour-id arrays do not hold one entry per vertex");
  }
  MeshRepair repair;
  try {
    repair = repair_mesh(mesh);  // also checks the indices
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(path + ": " + e.what());
  }
  if (mesh.num_faces() == 0) {
    throw InvalidInputError(path + ": no triangles left after dropping the degenerate and duplicate ones");
  }
  if (repair.changed()) warn(command, path + ": repaired: " + repair.describe());
  const auto problems = find_mesh_problems(mesh);
  if (!problems.empty()) {
    std::ostringstream text;
    text << path << ": " << problems.size() << (problems.size() >= ValidationOptions{}.max_problems ? "+" : "")
         << " topology problem" << (problems.size() == 1 ? "" : "s") << " left as they are, first: "
         << describe(problems.front());
    warn(command, text.str());
  }
}

}  // namespace contourmesh::cli
