// SPDX-License-Identifier: BSD-3-Clause
// contourmesh smooth IN -o OUT [--method M | --preset P]: any smoothing method of libsmooth on a mesh file,
// through its one entry point smooth(mesh, method, options).
#include "cli_common.h"
#include "progress_display.h"
#include "feature_options.h"
#include "method_options.h"

#include <contourmesh/vtk/atomic_file.h>
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/limits.h>
#include <contourmesh/smooth/metrics.h>
#include <contourmesh/smooth/smooth.h>

#include <CLI/CLI.hpp>

#include <iomanip>
#include <sstream>
#include <iostream>
#include <memory>
#include <optional>

namespace contourmesh::cli {

namespace {

struct SmoothArgs {
  std::string input;
  std::string output;
  MethodArgs selection;
  StepArgs steps;
  std::string format = "auto";
  std::string slice_array = "ContourId";
  std::string contour_array = "ContourIndex";
  FeatureArgs features;
  std::string labels_out;
  Index max_vertices = kDefaultMaxVertices;
  bool json = false;
  CommonArgs common;
};

// The summary lines and JSON fields of a method's own stages (detection, subdivision, profiles).
std::string describe_stages(const SmoothResult& r, const std::string& id_source, nlohmann::json& j) {
  std::ostringstream s;
  s << std::setprecision(4);
  if (!r.labels.empty()) {
    const LabelCounts c = count_labels(r.labels);
    j["id_source"] = id_source;
    j["edge_vertices"] = c.edges;
    j["corner_vertices"] = c.corners;
    j["noise_vertices"] = c.noise;
    j["seconds_detect"] = r.seconds.detect;
    s << "  features  " << c.edges << " edge, " << c.corners << " corner, " << c.noise << " noise";
    if (r.detection) {
      j["gamma"] = r.detection->gamma;
      j["candidates"] = r.detection->candidates;
      s << " of " << r.detection->candidates << " candidates (gamma " << r.detection->gamma << " mm";
    } else {
      s << " (creases of the result";
    }
    s << ", ids: " << id_source << ")\n";
  }
  if (r.method == SmoothingMethod::FeaturePreserving) {
    j["subdivided_vertices"] = r.subdivided_vertices;
    j["adaptive_vertices"] = r.adaptive_vertices;
    j["seconds_subdivide"] = r.seconds.subdivide;
    s << "  adaptive  " << r.subdivided_vertices << " vertices subdivided, " << r.adaptive_vertices
      << " vertices in the adaptive mesh\n";
  }
  if (r.method == SmoothingMethod::CrossSlice) {
    j["profiles"] = r.profiles;
    j["noise_across_mm"] = r.noise_across;
    j["noise_along_mm"] = r.noise_along;
    j["noise_across_from"] = std::string(to_string(r.noise_across_source));
    s << "  profiles  " << r.profiles << " contour vertices corrected across slices (noise " << r.noise_across
      << " mm across";
    if (r.noise_across_source == NoiseSource::AlongProfiles) s << ", from the contours: too few profiles across";
    s << ", " << r.noise_along << " mm along the contours)\n";
  }
  if (!r.labels.empty()) {
    s << "  seconds   detect " << r.seconds.detect;
    if (r.method == SmoothingMethod::FeaturePreserving) s << ", subdivide " << r.seconds.subdivide;
    s << ", smooth " << r.seconds.smooth << "\n";
  }
  return s.str();
}

int run_smooth(const SmoothArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  MethodConfig config = method_config(a.selection, a.steps, a.features);
  const SmoothingMethod method = config.method;
  MeshReadOptions read_options;
  read_options.arrays = {a.slice_array, a.contour_array};
  read_options.max_vertices = a.max_vertices;
  MeshWriteOptions write_options;
  write_options.format = parse_mesh_format(a.format);
  write_options.arrays = read_options.arrays;
  // Fail on bad options and output paths before reading or computing anything.
  if (write_options.format == MeshFormat::Auto) (void)format_from_extension(a.output);
  if (!a.labels_out.empty()) {
    if (!produces_labels(method)) {
      throw InvalidInputError("--labels-out needs a method that labels features (paper or cross-slice), not " +
                              std::string(to_string(method)));
    }
    if (!format_keeps_contour_ids(format_from_extension(a.labels_out))) {
      throw InvalidInputError(a.labels_out + ": labels need a .vtp or .ply file");
    }
  }
  apply_common_options(a.common);
  ProgressDisplay progress("smooth", a.common.quiet);

  check_output_path(a.output);
  if (!a.labels_out.empty()) check_output_path(a.labels_out);
  check_distinct_outputs({{"-o", a.output}, {"--labels-out", a.labels_out}});

  progress.stage("read");

  PreparedMesh input = prepare_for_method(config, read_mesh(a.input, read_options), a.features, a.input, "smooth");
  const Mesh mesh = std::move(input.mesh);
  const std::string id_source(to_string(input.id_source));
  const MeshAdjacency adjacency = build_adjacency(mesh);
  const double volume_before = enclosed_volume(mesh);
  const bool closed = adjacency.is_closed();

  config.options.progress = progress.callback();
  config.options.limits.max_vertices = a.max_vertices;
  SmoothResult r;
  try {
    r = smooth(mesh, method, config.options);  // also stops a diverging run (DivergenceError)
  } catch (const InvalidInputError&) {
    rethrow_with_context(a.input);
  }
  nlohmann::json j;
  const std::string summary = describe_stages(r, id_source, j);
  if (!a.labels_out.empty()) {
    MeshWriteOptions labels;
    labels.arrays = read_options.arrays;
    labels.point_scalars = label_arrays({r.labels, r.detection, r.creases, 0.0});
    labels.progress = progress.callback();
    write_mesh(mesh, a.labels_out, labels);
    j["labels_out"] = a.labels_out;
  }
  progress.stage("write");
  write_options.progress = progress.callback();
  write_mesh(r.mesh, a.output, write_options);
  progress.finish();

  const SmoothingOptions& baseline = config.options.baseline;
  const FeatureSmoothingOptions& paper = config.options.paper;
  double lambda = 0.0;
  if (is_baseline(method)) lambda = baseline.lambda.value_or(default_lambda(method));
  if (method == SmoothingMethod::FeaturePreserving) lambda = paper.lambda.value_or(default_lambda(paper.diffusion));
  const double mu = method == SmoothingMethod::FeaturePreserving ? paper.mu : baseline.mu;
  const double volume_after = enclosed_volume(r.mesh);
  if (a.json) {
    j["command"] = "smooth";
    j["input"] = a.input;
    j["output"] = a.output;
    j["method"] = std::string(to_string(method));
    if (const std::string p = preset_name(a.selection); !p.empty()) j["preset"] = p;
    if (method == SmoothingMethod::FeaturePreserving) j["diffusion"] = std::string(to_string(paper.diffusion));
    j["iterations"] = r.iterations;
    j["lambda"] = lambda;
    j["mu"] = mu;
    j["beta"] = baseline.beta;
    j["vertices"] = mesh.num_vertices();
    j["faces"] = mesh.num_faces();
    j["output_vertices"] = r.mesh.num_vertices();
    j["has_contour_ids"] = mesh.has_contour_ids();
    j["is_closed"] = closed;
    j["volume_before"] = volume_before;
    j["volume_after"] = volume_after;
    j["volume_change_percent"] = volume_before != 0.0 ? 100.0 * (volume_after - volume_before) / volume_before : 0.0;
    j["seconds_smooth"] = r.seconds.smooth;
    j["seconds"] = seconds_since(start);
    print_json(j);
    return kOk;
  }
  if (a.common.quiet) return kOk;
  std::cout << std::setprecision(6) << "smoothed " << a.input << " (" << mesh.num_vertices() << " vertices, "
            << mesh.num_faces() << " triangles" << (mesh.has_contour_ids() ? ", with contour ids" : "") << ")\n"
            << "  method    " << describe_selection(a.selection, method);
  if (r.iterations > 0) std::cout << ", " << r.iterations << " iterations";
  if (lambda > 0.0) std::cout << ", lambda " << lambda;
  std::cout << " in " << r.seconds.total << " s\n" << summary;
  if (closed) {
    std::cout << "  volume    " << volume_before << " -> " << volume_after << " ("
              << 100.0 * (volume_after - volume_before) / volume_before << " %)\n";
  } else {
    std::cout << "  open mesh: no enclosed volume\n";
  }
  std::cout << "  wrote     " << a.output << (a.labels_out.empty() ? "" : " and " + a.labels_out) << "\n";
  return kOk;
}

}  // namespace

void add_smooth_command(CLI::App& app) {
  auto args = std::make_shared<SmoothArgs>();
  CLI::App* cmd = app.add_subcommand(
      "smooth", "Smooth a mesh file: cross-slice smoothing (default), the paper's method or a baseline");
  cmd->add_option("input", args->input, "Input mesh (.stl .ply .vtp .obj); .vtp/.ply keep contour ids")->required();
  cmd->add_option("-o,--output", args->output, "Output mesh; format from the extension unless --format")->required();
  add_method_options(cmd, args->selection);
  add_step_options(cmd, args->steps);
  add_feature_options(cmd, args->features);
  cmd->add_option("--labels-out", args->labels_out,
                  "paper, cross-slice: also write the input mesh with per-vertex labels and curvatures (.vtp or .ply)");
  cmd->add_option("--format", args->format, "Output format: auto | stl | stl-ascii | ply | vtp | obj")
      ->capture_default_str();
  cmd->add_option("--slice-array", args->slice_array, "Point array holding the slice index c(i)")
      ->capture_default_str();
  cmd->add_option("--contour-array", args->contour_array, "Point array holding the contour index within a slice")
      ->capture_default_str();
  add_max_vertices_option(cmd, args->max_vertices);
  cmd->add_flag("--json", args->json, "Print one JSON object on stdout instead of the summary");
  add_common_options(cmd, args->common);
  cmd->callback([args] { set_exit_code(run_guarded("smooth", [&] { return run_smooth(*args); })); });
}

}  // namespace contourmesh::cli
