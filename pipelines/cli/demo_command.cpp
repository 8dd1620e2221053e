// contourmesh demo: the main job until the reconstruction stage lands. Generates a noisy contour stack
// of a cylinder with a sharp ridge (known analytic surface), smooths it, writes an STL and reports how
// far the mesh is from the true surface before and after, overall and at the ridge.
#include "cli_common.h"

#include <pipelines/mesh_io.h>
#include <smooth/adjacency.h>
#include <smooth/errors.h>
#include <smooth/metrics.h>
#include <smooth/shapes.h>
#include <smooth/smoothing.h>

#include <CLI/CLI.hpp>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <numbers>

namespace contourmesh::cli {

namespace {

struct DemoArgs {
  std::string output = "out/demo.stl";
  std::string method = "taubin";
  int iterations = 20;
  std::optional<double> lambda;
  double noise = 0.15;
  std::uint64_t seed = 7;
  double radius = 20.0;
  double ridge = 6.0;
  double slice_spacing = 2.0;
  double sampling = 0.7;
  int slices = 36;
  bool json = false;
};

int run_demo(const DemoArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  if (!(a.radius > 0) || !(a.ridge >= 0) || !(a.sampling > 0) || !(a.noise >= 0)) {
    throw InvalidInputError("--radius and --sampling must be > 0, --ridge and --noise >= 0");
  }
  const double half_width = 0.35;  // radians either side of the ridge tip
  ContourStackSpec spec;
  spec.curve = ridge_circle_curve(a.radius, a.ridge, half_width);
  spec.slices = a.slices;
  spec.slice_spacing = a.slice_spacing;
  spec.points_per_contour = std::max(3, static_cast<int>(std::lround(2.0 * std::numbers::pi * a.radius / a.sampling)));
  Mesh mesh = make_contour_stack(spec);
  add_noise(mesh, {a.noise, a.seed, NoiseDirection::InPlane});
  const ScalarField sdf = contour_stack_sdf(spec);

  // Feature region: vertices within 2 mm (in-plane) of the ridge tip or of its two concave creases.
  std::vector<Index> ridge_vertices;
  const double tip = a.radius + a.ridge;
  const Eigen::Vector2d lines[3] = {{tip, 0.0},
                                    {a.radius * std::cos(half_width), a.radius * std::sin(half_width)},
                                    {a.radius * std::cos(half_width), -a.radius * std::sin(half_width)}};
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    for (const auto& l : lines) {
      if ((mesh.positions.col(i).head<2>() - l).norm() < 2.0) {
        ridge_vertices.push_back(i);
        break;
      }
    }
  }

  SmoothingOptions options;
  options.method = parse_smoothing_method(a.method);
  options.iterations = a.iterations;
  options.lambda = a.lambda;
  check_smoothing_options(options, mesh.num_vertices());
  MeshWriteOptions write_options;
  (void)format_from_extension(a.output);

  const MeshAdjacency adjacency = build_adjacency(mesh);
  const auto smooth_start = std::chrono::steady_clock::now();
  Mesh result = mesh;
  result.positions = smooth(mesh, adjacency, options);
  const double smooth_seconds = seconds_since(smooth_start);
  std::filesystem::create_directories(std::filesystem::path(a.output).parent_path().empty()
                                          ? std::filesystem::path(".")
                                          : std::filesystem::path(a.output).parent_path());
  write_mesh(result, a.output, write_options);

  const DistanceStats before = distance_to_surface(mesh.positions, sdf);
  const DistanceStats after = distance_to_surface(result.positions, sdf);
  const DistanceStats ridge_before = distance_to_surface(mesh.positions, sdf, ridge_vertices);
  const DistanceStats ridge_after = distance_to_surface(result.positions, sdf, ridge_vertices);
  const double v0 = enclosed_volume(mesh);
  const double v1 = enclosed_volume(result);
  if (a.json) {
    nlohmann::json j;
    j["command"] = "demo";
    j["output"] = a.output;
    j["method"] = std::string(to_string(options.method));
    j["iterations"] = options.iterations;
    j["vertices"] = mesh.num_vertices();
    j["faces"] = mesh.num_faces();
    j["slices"] = spec.slices;
    j["is_closed"] = adjacency.is_closed();
    j["volume_before"] = v0;
    j["volume_after"] = v1;
    j["volume_change_percent"] = 100.0 * (v1 - v0) / v0;
    j["rms_distance_before"] = before.rms;
    j["rms_distance_after"] = after.rms;
    j["ridge_rms_distance_before"] = ridge_before.rms;
    j["ridge_rms_distance_after"] = ridge_after.rms;
    j["seconds_smooth"] = smooth_seconds;
    j["seconds"] = seconds_since(start);
    print_json(j);
    return kOk;
  }
  std::cout << std::fixed << std::setprecision(3)
            << "ContourMesh demo: noisy contour stack of a cylinder with a sharp ridge\n"
            << "  shape     radius " << a.radius << " mm, ridge " << a.ridge << " mm, " << spec.slices << " slices "
            << a.slice_spacing << " mm apart, in-plane noise " << a.noise << " mm (seed " << a.seed << ")\n"
            << "  mesh      " << mesh.num_vertices() << " vertices, " << mesh.num_faces() << " triangles, "
            << (adjacency.is_closed() ? "closed" : "open") << ", with contour ids\n"
            << "  smoothing " << to_string(options.method) << ", " << options.iterations << " iterations, "
            << smooth_seconds << " s\n"
            << "  volume    " << std::setprecision(1) << v0 << " -> " << v1 << " mm^3 (" << std::setprecision(3)
            << 100.0 * (v1 - v0) / v0 << " %)\n"
            << "  distance to the true surface, RMS: all " << before.rms << " -> " << after.rms << " mm, ridge "
            << ridge_before.rms << " -> " << ridge_after.rms << " mm (" << ridge_vertices.size() << " vertices)\n"
            << "  wrote     " << a.output << " (binary STL) in " << seconds_since(start) << " s total\n";
  return kOk;
}

}  // namespace

void add_demo_command(CLI::App& app) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* cmd = app.add_subcommand(
      "demo", "Generate a noisy contour-stack mesh with a sharp ridge, smooth it, write it and report its accuracy");
  cmd->add_option("-o,--output", args->output, "Output mesh (.stl .ply .vtp .obj)")->capture_default_str();
  cmd->add_option("--method", args->method, "none | laplacian | taubin | mcf | mindist")->capture_default_str();
  cmd->add_option("--iterations", args->iterations, "Number of iterations (>= 0)")->capture_default_str();
  cmd->add_option("--lambda", args->lambda, "Step factor in (0, 1]; default: the paper's value for the method");
  cmd->add_option("--noise", args->noise, "In-plane Gaussian noise sigma, mm")->capture_default_str();
  cmd->add_option("--seed", args->seed, "Noise seed")->capture_default_str();
  cmd->add_option("--radius", args->radius, "Cylinder radius, mm")->capture_default_str();
  cmd->add_option("--ridge", args->ridge, "Ridge height, mm")->capture_default_str();
  cmd->add_option("--slices", args->slices, "Number of slices (>= 2)")->capture_default_str();
  cmd->add_option("--slice-spacing", args->slice_spacing, "Distance between slices, mm")->capture_default_str();
  cmd->add_option("--sampling", args->sampling, "In-plane distance between contour points, mm")->capture_default_str();
  cmd->add_flag("--json", args->json, "Print one JSON object on stdout instead of the summary");
  cmd->callback([args] { set_exit_code(run_guarded("demo", [&] { return run_demo(*args); })); });
}

}  // namespace contourmesh::cli
