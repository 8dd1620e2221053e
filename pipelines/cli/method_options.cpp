// SPDX-License-Identifier: BSD-3-Clause
#include "method_options.h"

#include <contourmesh/smooth/errors.h>

#include <CLI/CLI.hpp>

namespace contourmesh::cli {

void add_method_options(CLI::App* cmd, MethodArgs& args, bool iterations) {
  CLI::Option* method = cmd->add_option(
      "--method", args.method,
      "none | laplacian | taubin | mcf | mindist | paper | cross-slice, with the library's defaults for it "
      "(default: the preset's method)");
  CLI::Option* preset = cmd->add_option(
      "--preset", args.preset,
      "default (cross-slice smoothing) | xu2006 (the paper's literal configuration: its method, Taubin 40 "
      "iterations, |U|, its rules only); the default when --method is not given");
  method->excludes(preset);
  if (!iterations) return;
  cmd->add_option("--iterations", args.iterations,
                  "Smoothing iterations (>= 0); default: the method's (20 for the baselines, 40 for paper)");
  cmd->add_option("--creases", args.creases,
                  "cross-slice: none | restore (sharpen the creases the image's blur rounded: the mesh is refined "
                  "around them, the input's vertices first; default none)");
  cmd->add_option("--off-slice-volume", args.off_slice_volume,
                  "cross-slice: free | preserve (give back the volume the normal filter of the vertices between "
                  "the slices takes; default free, but run on drawn contours preserves it)");
}

void add_step_options(CLI::App* cmd, StepArgs& args) {
  cmd->add_option("--lambda", args.lambda,
                  "Step factor in (0, 1]; default: the paper's value for the method "
                  "(paper/taubin 0.6307, laplacian 0.3, mcf 0.3, mindist 0.5)");
  cmd->add_option("--mu", args.mu, "Taubin's negative factor in [-1, 0) (default -0.6732)");
  cmd->add_option("--beta", args.beta,
                  "MIN-DIST crease threshold on 1 - cos(dihedral angle), in [0, 2] (default 0.03)");
  cmd->add_option("--boundary", args.boundary,
                  "fixed | free: whether boundary vertices of open meshes move (default fixed)");
  cmd->add_option("--max-levels", args.max_levels,
                  "paper: subdivision levels around a feature vertex (>= 0; default 3)");
  cmd->add_option("--diffusion", args.diffusion, "paper: taubin | laplacian on the adaptive mesh (default taubin)");
  cmd->add_flag("--keep-adaptive", args.keep_adaptive, "paper: output the smoothed adaptive mesh itself");
}

MethodConfig method_config(const MethodArgs& args, const StepArgs& steps, const FeatureArgs& features) {
  MethodConfig c;
  if (!args.method.empty()) {
    c.method = parse_smoothing_method(args.method);
  } else {
    c = preset(args.preset.empty() ? Preset::Default : parse_preset(args.preset));
  }
  if (args.iterations) {
    if (c.method != SmoothingMethod::None && default_iterations(c.method) == 0) {
      throw InvalidInputError("--iterations: " + std::string(to_string(c.method)) + " has no iteration count");
    }
    c.options.iterations = *args.iterations;
  }
  // An option the selected method has no use for is a mistake worth reporting, not ignoring.
  const auto refuse = [&](bool given, const char* option, bool applies) {
    if (given && !applies) {
      throw InvalidInputError(std::string(option) + " does not apply to " + std::string(to_string(c.method)) +
                              " smoothing");
    }
  };
  const bool cross_slice = c.method == SmoothingMethod::CrossSlice;
  refuse(args.creases.has_value(), "--creases", cross_slice);
  refuse(args.off_slice_volume.has_value(), "--off-slice-volume", cross_slice);
  if (args.creases) {
    if (*args.creases == "none") c.options.cross_slice.crease_restoration = CreaseRestoration::None;
    else if (*args.creases == "restore") c.options.cross_slice.crease_restoration = CreaseRestoration::Subdivide;
    else throw InvalidInputError("--creases must be 'none' or 'restore', got '" + *args.creases + "'");
  }
  if (args.off_slice_volume) {
    OffSliceVolume& v = c.options.cross_slice.off_slice.volume;
    if (*args.off_slice_volume == "free") v = OffSliceVolume::Free;
    else if (*args.off_slice_volume == "preserve") v = OffSliceVolume::Preserve;
    else throw InvalidInputError("--off-slice-volume must be 'free' or 'preserve', got '" + *args.off_slice_volume +
                                 "'");
  }
  const bool paper = c.method == SmoothingMethod::FeaturePreserving;
  const bool baseline = is_baseline(c.method) && c.method != SmoothingMethod::None;
  refuse(steps.lambda.has_value(), "--lambda", paper || baseline);
  refuse(steps.mu.has_value(), "--mu", paper || baseline);
  refuse(steps.beta.has_value(), "--beta", baseline);
  refuse(steps.boundary.has_value(), "--boundary", paper || baseline);
  refuse(steps.max_levels.has_value(), "--max-levels", paper);
  refuse(steps.diffusion.has_value(), "--diffusion", paper);
  SmoothOptions& o = c.options;
  if (steps.lambda) o.baseline.lambda = o.paper.lambda = *steps.lambda;
  if (steps.mu) o.baseline.mu = o.paper.mu = *steps.mu;
  if (steps.beta) o.baseline.beta = *steps.beta;
  if (steps.boundary) {
    if (*steps.boundary == "fixed") o.baseline.boundary = o.paper.boundary = BoundaryPolicy::Fixed;
    else if (*steps.boundary == "free") o.baseline.boundary = o.paper.boundary = BoundaryPolicy::Free;
    else throw InvalidInputError("--boundary must be 'fixed' or 'free', got '" + *steps.boundary + "'");
  }
  if (steps.max_levels) o.paper.max_levels = *steps.max_levels;
  if (steps.diffusion) o.paper.diffusion = parse_smoothing_method(*steps.diffusion);
  if (steps.keep_adaptive) {
    if (!paper) throw InvalidInputError("--keep-adaptive needs --method paper");
    o.paper.output = OutputResolution::Adaptive;
  }
  if (DetectionOptions* d = detection_options_of(c.method, o)) {
    apply_detection_args(features, *d);
  } else {
    const std::pair<bool, const char*> given[] = {
        {features.gamma.has_value(), "--gamma"},     {features.delta.has_value(), "--delta"},
        {features.measure.has_value(), "--measure"}, {features.in_slice.has_value(), "--in-slice"},
        {features.prefilter.has_value(), "--prefilter"}, {features.window.has_value(), "--window"},
        {features.corner_spread.has_value(), "--corner-spread"}};
    for (const auto& [is_given, option] : given) {
      refuse(is_given, option, false);
    }
  }
  return c;
}

PreparedMesh prepare_for_method(MethodConfig& config, Mesh mesh, const FeatureArgs& features, const std::string& path,
                                const std::string& command) {
  switch (config.method) {
    case SmoothingMethod::FeaturePreserving: {
      PreparedMesh prepared = prepare_input(std::move(mesh), path, command, ContourIdUse::Detection, features);
      if (prepared.detection_mode == DetectionMode::CurvatureOnly) {
        config.options.paper.detection.mode = DetectionMode::CurvatureOnly;
      }
      return prepared;
    }
    case SmoothingMethod::CrossSlice:
      if (!mesh.has_contour_ids() && features.slice_axis.empty()) {
        throw InvalidInputError(path +
                                ": cross-slice smoothing needs contour ids: write the mesh as .vtp or .ply with them, "
                                "give --slice-axis to recover them, or choose another --method");
      }
      return prepare_input(std::move(mesh), path, command, ContourIdUse::Detection, features, MissingIds::Refuse);
    default:
      return prepare_input(std::move(mesh), path, command, ContourIdUse::PassThrough, features);
  }
}

std::vector<PointScalars> label_arrays(const FeatureLabels& f) {
  if (f.detection) return detection_arrays(*f.detection);
  PointScalars labels{"FeatureLabel", {}, ScalarType::Int32};
  for (VertexLabel l : f.labels) labels.values.push_back(static_cast<double>(l));
  std::vector<PointScalars> arrays{labels};
  if (f.creases) {
    const auto from = [](const char* name, const Eigen::VectorXd& v) {
      return PointScalars{name, std::vector<double>(v.data(), v.data() + v.size()), ScalarType::Float64};
    };
    arrays.push_back(from("EdgeStrength", f.creases->edge_strength));
    arrays.push_back(from("CornerStrength", f.creases->corner_strength));
  }
  return arrays;
}

LabelCounts count_labels(const std::vector<VertexLabel>& labels) {
  LabelCounts c;
  for (VertexLabel l : labels) {
    c.edges += l == VertexLabel::Edge;
    c.corners += l == VertexLabel::Corner;
    c.noise += l == VertexLabel::Noise;
  }
  return c;
}

std::string preset_name(const MethodArgs& args) {
  if (!args.method.empty()) return {};
  return args.preset.empty() ? std::string(to_string(Preset::Default)) : args.preset;
}

std::string describe_selection(const MethodArgs& args, SmoothingMethod method) {
  std::string text(to_string(method));
  if (const std::string p = preset_name(args); !p.empty()) text += " (preset " + p + ")";
  return text;
}

}  // namespace contourmesh::cli
