// SPDX-License-Identifier: BSD-3-Clause
// contourmesh detect IN -o labels.vtp: the feature labels of a method (the default preset's, the paper's)
// on the input mesh, without writing a smoothed mesh: libsmooth's label_features(mesh, method, options).
#include "cli_common.h"
#include "progress_display.h"
#include "feature_options.h"
#include "method_options.h"

#include <contourmesh/vtk/atomic_file.h>
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/feature_detection.h>
#include <contourmesh/smooth/smooth.h>
#include <contourmesh/smooth/limits.h>

#include <CLI/CLI.hpp>

#include <iomanip>
#include <iostream>
#include <memory>

namespace contourmesh::cli {

namespace {

struct DetectArgs {
  std::string input;
  std::string output;
  MethodArgs selection;
  FeatureArgs features;
  std::string slice_array = "ContourId";
  std::string contour_array = "ContourIndex";
  Index max_vertices = kDefaultMaxVertices;
  bool json = false;
  CommonArgs common;
};

int run_detect(const DetectArgs& a) {
  apply_common_options(a.common);
  const auto start = std::chrono::steady_clock::now();
  MethodConfig config = method_config(a.selection, StepArgs{}, a.features);
  if (!produces_labels(config.method)) {
    throw InvalidInputError("detect: " + std::string(to_string(config.method)) +
                            " does not label features (paper and cross-slice do)");
  }
  if (!format_keeps_contour_ids(format_from_extension(a.output))) {
    throw InvalidInputError(a.output + ": labels need a .vtp or .ply file");
  }
  check_output_path(a.output);
  MeshReadOptions read_options;
  read_options.arrays = {a.slice_array, a.contour_array};
  read_options.max_vertices = a.max_vertices;
  ProgressDisplay progress("detect", a.common.quiet);
  progress.stage("read");
  PreparedMesh input = prepare_for_method(config, read_mesh(a.input, read_options), a.features, a.input, "detect");
  const Mesh mesh = std::move(input.mesh);
  const std::string id_source(to_string(input.id_source));
  config.options.progress = progress.callback();
  config.options.limits.max_vertices = a.max_vertices;
  FeatureLabels f;
  try {
    f = label_features(mesh, config.method, config.options);
  } catch (const InvalidInputError&) {
    rethrow_with_context(a.input);
  }
  const LabelCounts counts = count_labels(f.labels);
  MeshWriteOptions write_options;
  write_options.arrays = read_options.arrays;
  write_options.point_scalars = label_arrays(f);
  progress.stage("write");
  write_options.progress = progress.callback();
  write_mesh(mesh, a.output, write_options);
  progress.finish();
  if (a.json) {
    nlohmann::json j;
    j["command"] = "detect";
    j["input"] = a.input;
    j["output"] = a.output;
    j["method"] = std::string(to_string(config.method));
    if (const std::string p = preset_name(a.selection); !p.empty()) j["preset"] = p;
    j["id_source"] = id_source;
    j["vertices"] = mesh.num_vertices();
    j["edge_vertices"] = counts.edges;
    j["corner_vertices"] = counts.corners;
    j["noise_vertices"] = counts.noise;
    if (f.detection) {
      const DetectionOptions& options = config.options.paper.detection;
      j["mode"] = options.mode == DetectionMode::ContourContinuity ? "contour-continuity" : "curvature-only";
      j["gamma"] = f.detection->gamma;
      j["mean_umbrella"] = f.detection->mean_umbrella;
      j["candidates"] = f.detection->candidates;
    } else {
      j["mode"] = "creases";
    }
    j["seconds_detect"] = f.seconds;
    j["seconds"] = seconds_since(start);
    print_json(j);
    return kOk;
  }
  if (a.common.quiet) return kOk;
  std::cout << std::setprecision(4) << "detected features on " << a.input << " (" << mesh.num_vertices()
            << " vertices, ids: " << id_source << "; labels of " << describe_selection(a.selection, config.method)
            << ")\n  ";
  if (f.detection) std::cout << f.detection->candidates << " candidates above gamma " << f.detection->gamma << " mm: ";
  else std::cout << "creases of the smoothed mesh: ";
  std::cout << counts.edges << " edge, " << counts.corners << " corner, " << counts.noise << " noise\n"
            << "  wrote " << a.output << " (point array FeatureLabel: 0 smooth, 1 edge, 2 corner, 3 noise) in "
            << seconds_since(start) << " s\n";
  return kOk;
}

}  // namespace

void add_detect_command(CLI::App& app) {
  auto args = std::make_shared<DetectArgs>();
  CLI::App* cmd = app.add_subcommand(
      "detect", "Label feature and noise vertices by contour continuity, as a smoothing method would (no smoothing)");
  cmd->add_option("input", args->input, "Input mesh (.vtp/.ply with contour ids, or any mesh with --slice-axis)")
      ->required();
  cmd->add_option("-o,--output", args->output, "Labelled mesh (.vtp or .ply)")->required();
  add_method_options(cmd, args->selection, false);
  add_feature_options(cmd, args->features);
  cmd->add_option("--slice-array", args->slice_array, "Point array holding the slice index c(i)")
      ->capture_default_str();
  cmd->add_option("--contour-array", args->contour_array, "Point array holding the contour index within a slice")
      ->capture_default_str();
  add_max_vertices_option(cmd, args->max_vertices);
  cmd->add_flag("--json", args->json, "Print one JSON object on stdout instead of the summary");
  add_common_options(cmd, args->common);
  cmd->callback([args] { set_exit_code(run_guarded("detect", [&] { return run_detect(*args); })); });
}

}  // namespace contourmesh::cli
