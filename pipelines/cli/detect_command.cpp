// contourmesh detect IN -o labels.vtp: the feature labels of a method (the default preset's, the paper's, ...)
// without smoothing: libsmooth's detect_features(mesh, method, options), Algorithm 2 with that method's
// detection options.
#include "cli_common.h"
#include "progress_display.h"
#include "feature_options.h"
#include "method_options.h"

#include <pipelines/atomic_file.h>
#include <pipelines/mesh_io.h>
#include <smooth/adjacency.h>
#include <smooth/errors.h>
#include <smooth/feature_detection.h>
#include <smooth/smooth.h>
#include <smooth/limits.h>

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
  DetectionOptions* detection = detection_options_of(config.method, config.options);
  if (detection == nullptr) {
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
  Mesh mesh = read_mesh(a.input, read_options);
  check_mesh(mesh, a.input, "detect");
  const MeshAdjacency adjacency = build_adjacency(mesh);
  const std::string id_source = prepare_contour_ids(mesh, adjacency, a.features, a.input, "detect", *detection);
  const auto t = std::chrono::steady_clock::now();
  const FeatureDetection d = detect_features(mesh, config.method, config.options);
  const double detect_seconds = seconds_since(t);
  const DetectionOptions& options = *detection;
  MeshWriteOptions write_options;
  write_options.arrays = read_options.arrays;
  write_options.point_scalars = detection_arrays(d);
  write_mesh(mesh, a.output, write_options);
  if (a.json) {
    nlohmann::json j;
    j["command"] = "detect";
    j["input"] = a.input;
    j["output"] = a.output;
    j["method"] = std::string(to_string(config.method));
    if (const std::string p = preset_name(a.selection); !p.empty()) j["preset"] = p;
    j["id_source"] = id_source;
    j["mode"] = options.mode == DetectionMode::ContourContinuity ? "contour-continuity" : "curvature-only";
    j["vertices"] = mesh.num_vertices();
    j["gamma"] = d.gamma;
    j["mean_umbrella"] = d.mean_umbrella;
    j["candidates"] = d.candidates;
    j["edge_vertices"] = d.edges;
    j["corner_vertices"] = d.corners;
    j["noise_vertices"] = d.noise;
    j["seconds_detect"] = detect_seconds;
    j["seconds"] = seconds_since(start);
    print_json(j);
    return kOk;
  }
  if (a.common.quiet) return kOk;
  std::cout << std::setprecision(4) << "detected features on " << a.input << " (" << mesh.num_vertices()
            << " vertices, ids: " << id_source << "; labels of " << describe_selection(a.selection, config.method)
            << ")\n"
            << "  " << d.candidates << " candidates above gamma " << d.gamma << " mm: " << d.edges << " edge, "
            << d.corners << " corner, " << d.noise << " noise\n"
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
  cmd->add_option("--slice-array", args->slice_array, "Point array holding the slice index c(i)")->capture_default_str();
  cmd->add_option("--contour-array", args->contour_array, "Point array holding the contour index within a slice")
      ->capture_default_str();
  add_max_vertices_option(cmd, args->max_vertices);
  cmd->add_flag("--json", args->json, "Print one JSON object on stdout instead of the summary");
  add_common_options(cmd, args->common);
  cmd->callback([args] { set_exit_code(run_guarded("detect", [&] { return run_detect(*args); })); });
}

}  // namespace contourmesh::cli
