// contourmesh smooth IN -o OUT --method ...: one of the baseline smoothers on a mesh file.
#include "cli_common.h"

#include <pipelines/mesh_io.h>
#include <smooth/adjacency.h>
#include <smooth/errors.h>
#include <smooth/metrics.h>
#include <smooth/smoothing.h>
#include <smooth/validation.h>

#include <CLI/CLI.hpp>

#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>

namespace contourmesh::cli {

namespace {

struct SmoothArgs {
  std::string input;
  std::string output;
  std::string method = "taubin";
  int iterations = 20;
  std::optional<double> lambda;
  double mu = -0.6732;
  double beta = 0.03;
  std::string boundary = "fixed";
  std::string format = "auto";
  std::string slice_array = "ContourId";
  std::string contour_array = "ContourIndex";
  bool json = false;
};

// Hard errors (non-finite coordinates, bad indices) throw; topology problems that the baseline
// smoothers tolerate are reported as a warning.
void check_mesh(const Mesh& mesh, const std::string& path) {
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
    std::cerr << "contourmesh smooth: warning: " << path << ": " << topology << " topology problem"
              << (topology == 1 ? "" : "s") << ", first: " << describe(problems.front()) << "\n";
  }
}

int run_smooth(const SmoothArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  MeshReadOptions read_options;
  read_options.arrays = {a.slice_array, a.contour_array};
  const Mesh mesh = read_mesh(a.input, read_options);
  check_mesh(mesh, a.input);

  SmoothingOptions options;
  options.method = parse_smoothing_method(a.method);
  options.iterations = a.iterations;
  options.lambda = a.lambda;
  options.mu = a.mu;
  options.beta = a.beta;
  if (a.boundary == "fixed") options.boundary = BoundaryPolicy::Fixed;
  else if (a.boundary == "free") options.boundary = BoundaryPolicy::Free;
  else throw InvalidInputError("--boundary must be 'fixed' or 'free', got '" + a.boundary + "'");
  check_smoothing_options(options, mesh.num_vertices());
  MeshWriteOptions write_options;
  write_options.format = parse_mesh_format(a.format);
  write_options.arrays = read_options.arrays;
  if (write_options.format == MeshFormat::Auto) (void)format_from_extension(a.output);  // fail before the work

  const MeshAdjacency adjacency = build_adjacency(mesh);
  const auto smooth_start = std::chrono::steady_clock::now();
  Mesh result = mesh;
  result.positions = smooth(mesh, adjacency, options);
  const double smooth_seconds = seconds_since(smooth_start);
  write_mesh(result, a.output, write_options);

  const double volume_before = enclosed_volume(mesh);
  const double volume_after = enclosed_volume(result);
  const bool closed = adjacency.is_closed();
  const double lambda = options.lambda.value_or(default_lambda(options.method));
  if (a.json) {
    nlohmann::json j;
    j["command"] = "smooth";
    j["input"] = a.input;
    j["output"] = a.output;
    j["method"] = std::string(to_string(options.method));
    j["iterations"] = options.iterations;
    j["lambda"] = lambda;
    j["mu"] = options.mu;
    j["beta"] = options.beta;
    j["vertices"] = mesh.num_vertices();
    j["faces"] = mesh.num_faces();
    j["has_contour_ids"] = mesh.has_contour_ids();
    j["is_closed"] = closed;
    j["volume_before"] = volume_before;
    j["volume_after"] = volume_after;
    j["volume_change_percent"] = volume_before != 0.0 ? 100.0 * (volume_after - volume_before) / volume_before : 0.0;
    j["seconds_smooth"] = smooth_seconds;
    j["seconds"] = seconds_since(start);
    print_json(j);
  } else {
    std::cout << std::setprecision(6) << "smoothed " << a.input << " (" << mesh.num_vertices() << " vertices, "
              << mesh.num_faces() << " triangles" << (mesh.has_contour_ids() ? ", with contour ids" : "") << ")\n"
              << "  method " << to_string(options.method) << ", " << options.iterations << " iterations, lambda "
              << lambda << " in " << smooth_seconds << " s\n";
    if (closed) {
      std::cout << "  volume " << volume_before << " -> " << volume_after << " ("
                << 100.0 * (volume_after - volume_before) / volume_before << " %)\n";
    } else {
      std::cout << "  open mesh: no enclosed volume\n";
    }
    std::cout << "  wrote " << a.output << "\n";
  }
  return kOk;
}

}  // namespace

void add_smooth_command(CLI::App& app) {
  auto args = std::make_shared<SmoothArgs>();
  CLI::App* cmd = app.add_subcommand("smooth", "Smooth a mesh file with one of the baseline methods");
  cmd->add_option("input", args->input, "Input mesh (.stl .ply .vtp .obj)")->required();
  cmd->add_option("-o,--output", args->output, "Output mesh; format from the extension unless --format")->required();
  cmd->add_option("--method", args->method, "none | laplacian | taubin | mcf | mindist")->capture_default_str();
  cmd->add_option("--iterations", args->iterations, "Number of iterations (>= 0)")->capture_default_str();
  cmd->add_option("--lambda", args->lambda,
                  "Step factor in (0, 1]; default: the paper's value for the method "
                  "(laplacian 0.3, taubin 0.6307, mcf 0.3, mindist 0.5)");
  cmd->add_option("--mu", args->mu, "Taubin's negative factor in [-1, 0)")->capture_default_str();
  cmd->add_option("--beta", args->beta, "MIN-DIST crease threshold on 1 - cos(dihedral angle), in [0, 2]")
      ->capture_default_str();
  cmd->add_option("--boundary", args->boundary, "fixed | free: whether boundary vertices of open meshes move")
      ->capture_default_str();
  cmd->add_option("--format", args->format, "Output format: auto | stl | stl-ascii | ply | vtp | obj")
      ->capture_default_str();
  cmd->add_option("--slice-array", args->slice_array, "Point array holding the slice index c(i)")->capture_default_str();
  cmd->add_option("--contour-array", args->contour_array, "Point array holding the contour index within a slice")
      ->capture_default_str();
  cmd->add_flag("--json", args->json, "Print one JSON object on stdout instead of the summary");
  cmd->callback([args] { set_exit_code(run_guarded("smooth", [&] { return run_smooth(*args); })); });
}

}  // namespace contourmesh::cli
