// contourmesh smooth IN -o OUT --method ...: the paper's method or a baseline smoother on a mesh file.
#include "cli_common.h"
#include "progress_display.h"
#include "feature_options.h"

#include <pipelines/atomic_file.h>
#include <pipelines/mesh_io.h>
#include <smooth/adjacency.h>
#include <smooth/divergence.h>
#include <smooth/errors.h>
#include <smooth/feature_smoothing.h>
#include <smooth/limits.h>
#include <smooth/metrics.h>
#include <smooth/smoothing.h>

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
  std::string method = "paper";
  std::optional<int> iterations;
  std::optional<double> lambda;
  double mu = -0.6732;
  double beta = 0.03;
  std::string boundary = "fixed";
  std::string format = "auto";
  std::string slice_array = "ContourId";
  std::string contour_array = "ContourIndex";
  // The paper's method.
  FeatureArgs features;
  int max_levels = 3;
  std::string diffusion = "taubin";
  bool keep_adaptive = false;
  std::string labels_out;
  Index max_vertices = kDefaultMaxVertices;
  bool json = false;
  CommonArgs common;
};

int run_smooth(const SmoothArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  const bool paper = a.method == "paper";
  MeshReadOptions read_options;
  read_options.arrays = {a.slice_array, a.contour_array};
  read_options.max_vertices = a.max_vertices;
  MeshWriteOptions write_options;
  write_options.format = parse_mesh_format(a.format);
  write_options.arrays = read_options.arrays;
  // Fail on bad options and output paths before reading or computing anything.
  if (write_options.format == MeshFormat::Auto) (void)format_from_extension(a.output);
  BoundaryPolicy boundary = BoundaryPolicy::Fixed;
  if (a.boundary == "free") boundary = BoundaryPolicy::Free;
  else if (a.boundary != "fixed") throw InvalidInputError("--boundary must be 'fixed' or 'free', got '" + a.boundary + "'");
  if (!a.labels_out.empty()) {
    if (!paper) throw InvalidInputError("--labels-out needs --method paper (the labels come from its detection)");
    if (!format_keeps_contour_ids(format_from_extension(a.labels_out))) {
      throw InvalidInputError(a.labels_out + ": labels need a .vtp or .ply file");
    }
  }
  if (a.keep_adaptive && !paper) throw InvalidInputError("--keep-adaptive needs --method paper");
  apply_common_options(a.common);
  ProgressDisplay progress("smooth", a.common.quiet);

  check_output_path(a.output);
  if (!a.labels_out.empty()) check_output_path(a.labels_out);
  check_distinct_outputs({{"-o", a.output}, {"--labels-out", a.labels_out}});

  progress.stage("read");

  PreparedMesh input = prepare_input(read_mesh(a.input, read_options), a.input, "smooth",
                                     paper ? ContourIdUse::Detection : ContourIdUse::PassThrough, a.features);
  Mesh mesh = std::move(input.mesh);
  const MeshAdjacency adjacency = build_adjacency(mesh);
  const double volume_before = enclosed_volume(mesh);
  const bool closed = adjacency.is_closed();

  nlohmann::json j;
  Mesh result;
  double smooth_seconds = 0.0;
  int iterations = 0;
  double lambda = 0.0;
  std::string id_source;
  std::string summary;
  if (paper) {
    FeatureSmoothingOptions o;
    o.detection = detection_options(a.features);
    if (input.detection_mode == DetectionMode::CurvatureOnly) o.detection.mode = DetectionMode::CurvatureOnly;
    id_source = to_string(input.id_source);
    o.max_levels = a.max_levels;
    o.diffusion = parse_smoothing_method(a.diffusion);
    o.iterations = a.iterations.value_or(40);
    o.lambda = a.lambda;
    o.mu = a.mu;
    o.boundary = boundary;
    o.output = a.keep_adaptive ? OutputResolution::Adaptive : OutputResolution::Original;
    o.progress = progress.callback();
    o.limits.max_vertices = a.max_vertices;
    o.on_iteration = divergence_guard(mesh.positions, "smoothing");
    FeatureSmoothingResult r;
    try {
      r = feature_preserving_smooth(mesh, o);
    } catch (const InvalidInputError&) {
      rethrow_with_context(a.input);
    }
    result = r.mesh;
    iterations = o.iterations;
    lambda = o.lambda.value_or(default_lambda(o.diffusion));
    smooth_seconds = r.seconds.total;
    const auto& d = r.detection;
    j["diffusion"] = std::string(to_string(o.diffusion));
    j["id_source"] = id_source;
    j["gamma"] = d.gamma;
    j["candidates"] = d.candidates;
    j["edge_vertices"] = d.edges;
    j["corner_vertices"] = d.corners;
    j["noise_vertices"] = d.noise;
    j["subdivided_vertices"] = r.subdivided_vertices;
    j["adaptive_vertices"] = r.adaptive_vertices;
    j["seconds_detect"] = r.seconds.detect;
    j["seconds_subdivide"] = r.seconds.subdivide;
    j["seconds_smooth"] = r.seconds.smooth;
    std::ostringstream s;
    s << std::setprecision(4) << "  features  " << d.edges << " edge, " << d.corners << " corner, " << d.noise
      << " noise of " << d.candidates << " candidates (gamma " << d.gamma << " mm, ids: " << id_source << ")\n"
      << "  adaptive  " << r.subdivided_vertices << " vertices subdivided, " << r.adaptive_vertices
      << " vertices in the adaptive mesh\n"
      << "  seconds   detect " << r.seconds.detect << ", subdivide " << r.seconds.subdivide << ", smooth "
      << r.seconds.smooth << "\n";
    summary = s.str();
    if (!a.labels_out.empty()) {
      MeshWriteOptions labels;
      labels.arrays = read_options.arrays;
      labels.point_scalars = detection_arrays(d);
      labels.progress = progress.callback();
      write_mesh(mesh, a.labels_out, labels);
      j["labels_out"] = a.labels_out;
    }
  } else {
    SmoothingOptions options;
    options.method = parse_smoothing_method(a.method);
    options.iterations = a.iterations.value_or(20);
    options.lambda = a.lambda;
    options.mu = a.mu;
    options.beta = a.beta;
    options.boundary = boundary;
    options.progress = progress.callback();
    options.on_iteration = divergence_guard(mesh.positions, "smoothing");
    const auto t = std::chrono::steady_clock::now();
    result = mesh;
    try {
      result.positions = smooth(mesh, adjacency, options);
    } catch (const InvalidInputError&) {
      rethrow_with_context(a.input);
    }
    smooth_seconds = seconds_since(t);
    iterations = options.iterations;
    lambda = options.lambda.value_or(default_lambda(options.method));
    j["seconds_smooth"] = smooth_seconds;
  }
  // The guard saw every iteration; this also covers the resolution step of the paper's method.
  try {
    check_not_diverged(result.positions, DivergenceBounds::of(mesh.positions), "smoothing");
  } catch (const InvalidInputError&) {
    rethrow_with_context(a.input);
  }
  progress.stage("write");
  write_options.progress = progress.callback();
  write_mesh(result, a.output, write_options);
  progress.finish();

  const double volume_after = enclosed_volume(result);
  if (a.json) {
    j["command"] = "smooth";
    j["input"] = a.input;
    j["output"] = a.output;
    j["method"] = a.method;
    j["iterations"] = iterations;
    j["lambda"] = lambda;
    j["mu"] = a.mu;
    j["beta"] = a.beta;
    j["vertices"] = mesh.num_vertices();
    j["faces"] = mesh.num_faces();
    j["output_vertices"] = result.num_vertices();
    j["has_contour_ids"] = mesh.has_contour_ids();
    j["is_closed"] = closed;
    j["volume_before"] = volume_before;
    j["volume_after"] = volume_after;
    j["volume_change_percent"] = volume_before != 0.0 ? 100.0 * (volume_after - volume_before) / volume_before : 0.0;
    j["seconds"] = seconds_since(start);
    print_json(j);
    return kOk;
  }
  if (a.common.quiet) return kOk;
  std::cout << std::setprecision(6) << "smoothed " << a.input << " (" << mesh.num_vertices() << " vertices, "
            << mesh.num_faces() << " triangles" << (mesh.has_contour_ids() ? ", with contour ids" : "") << ")\n"
            << "  method    " << a.method << ", " << iterations << " iterations, lambda " << lambda << " in "
            << smooth_seconds << " s\n"
            << summary;
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
  CLI::App* cmd = app.add_subcommand("smooth", "Smooth a mesh file: the paper's method or a baseline");
  cmd->add_option("input", args->input, "Input mesh (.stl .ply .vtp .obj); .vtp/.ply keep contour ids")->required();
  cmd->add_option("-o,--output", args->output, "Output mesh; format from the extension unless --format")->required();
  cmd->add_option("--method", args->method, "paper | none | laplacian | taubin | mcf | mindist")->capture_default_str();
  cmd->add_option("--iterations", args->iterations, "Number of iterations (>= 0); default 40 for paper, 20 otherwise");
  cmd->add_option("--lambda", args->lambda,
                  "Step factor in (0, 1]; default: the paper's value for the method "
                  "(paper/taubin 0.6307, laplacian 0.3, mcf 0.3, mindist 0.5)");
  cmd->add_option("--mu", args->mu, "Taubin's negative factor in [-1, 0)")->capture_default_str();
  cmd->add_option("--beta", args->beta, "MIN-DIST crease threshold on 1 - cos(dihedral angle), in [0, 2]")
      ->capture_default_str();
  cmd->add_option("--boundary", args->boundary, "fixed | free: whether boundary vertices of open meshes move")
      ->capture_default_str();
  add_feature_options(cmd, args->features);
  cmd->add_option("--max-levels", args->max_levels, "paper: subdivision levels around a feature vertex (>= 0)")
      ->capture_default_str();
  cmd->add_option("--diffusion", args->diffusion, "paper: taubin | laplacian on the adaptive mesh")
      ->capture_default_str();
  cmd->add_flag("--keep-adaptive", args->keep_adaptive, "paper: output the smoothed adaptive mesh itself");
  cmd->add_option("--labels-out", args->labels_out,
                  "paper: also write the input mesh with per-vertex labels and curvatures (.vtp or .ply)");
  cmd->add_option("--format", args->format, "Output format: auto | stl | stl-ascii | ply | vtp | obj")
      ->capture_default_str();
  cmd->add_option("--slice-array", args->slice_array, "Point array holding the slice index c(i)")->capture_default_str();
  cmd->add_option("--contour-array", args->contour_array, "Point array holding the contour index within a slice")
      ->capture_default_str();
  add_max_vertices_option(cmd, args->max_vertices);
  cmd->add_flag("--json", args->json, "Print one JSON object on stdout instead of the summary");
  add_common_options(cmd, args->common);
  cmd->callback([args] { set_exit_code(run_guarded("smooth", [&] { return run_smooth(*args); })); });
}

}  // namespace contourmesh::cli
