// contourmesh run [IN] -o OUT: the whole chain, read (or generate) -> segment -> contours -> tile ->
// smooth -> export. With no input it runs on a built-in phantom with noise, and reports accuracy
// against the phantom's analytic surface.
#include "cli_common.h"
#include "feature_options.h"
#include "method_options.h"
#include "progress_display.h"

#include <pipelines/atomic_file.h>
#include <pipelines/mesh_io.h>
#include <reconstruct/phantom.h>
#include <reconstruct/reconstruction.h>
#include <reconstruct/volume.h>
#include <smooth/adjacency.h>
#include <smooth/errors.h>
#include <smooth/limits.h>
#include <smooth/metrics.h>
#include <smooth/smooth.h>
#include <smooth/topology.h>

#include <CLI/CLI.hpp>

#include <filesystem>
#include <iomanip>
#include <sstream>
#include <iostream>
#include <memory>
#include <optional>

namespace contourmesh::cli {

namespace {

struct RunArgs {
  std::string input;
  std::string output = "out/femur.stl";
  std::string shape = "femur";
  std::string spacing = "0.7,0.7,2";
  double noise = 20.0;
  double contour_noise = 0.0;
  double blur = 0.5;
  std::uint64_t seed = 1;
  std::optional<double> threshold;
  MethodArgs selection;
  double feature_radius = 2.0;
  std::string end_caps = "half-spacing";
  std::string format = "auto";
  std::string labels_out;
  Index max_vertices = kDefaultMaxVertices;
  bool json = false;
  FeatureArgs detection;
  CommonArgs common;
};

int run_run(const RunArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  MethodConfig config = method_config(a.selection, StepArgs{}, a.detection);
  const SmoothingMethod method = config.method;
  // Fail on bad options and output paths before the work.
  MeshWriteOptions write_options;
  write_options.format = parse_mesh_format(a.format);
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
  if (!(a.feature_radius > 0.0)) throw InvalidInputError("--feature-radius must be > 0 mm");
  check_contour_noise(a.contour_noise);
  apply_common_options(a.common);
  ProgressDisplay progress("run", a.common.quiet);
  // The default output goes to out/: create the directory, then check it can take the file.
  const std::filesystem::path out(a.output);
  if (!out.parent_path().empty() && !std::filesystem::exists(out.parent_path())) {
    std::error_code ec;
    std::filesystem::create_directories(out.parent_path(), ec);
    if (ec) {
      throw InvalidInputError(a.output + ": cannot create the directory '" + out.parent_path().string() +
                              "': " + ec.message());
    }
  }
  check_output_path(out);
  if (!a.labels_out.empty()) check_output_path(a.labels_out);

  // 1. Read or generate the volume.
  auto t = std::chrono::steady_clock::now();
  std::optional<Phantom> phantom;
  CtImage::Pointer image;
  std::string source;
  progress.stage(a.input.empty() ? "phantom" : "read");
  if (a.input.empty()) {
    phantom = make_phantom(parse_phantom_shape(a.shape));
    PhantomVolumeOptions vo;
    vo.spacing = parse_spacing(a.spacing);
    vo.noise = a.noise;
    vo.contour_noise = a.contour_noise;
    vo.blur = a.blur;
    vo.seed = a.seed;
    image = render_phantom(*phantom, vo);
    std::ostringstream s;
    s << "phantom '" << a.shape << "' (" << vo.noise << " HU noise, ";
    if (vo.contour_noise > 0.0) s << vo.contour_noise << " mm contour noise, ";
    s << vo.blur << " mm blur)";
    source = s.str();
  } else {
    image = read_volume(a.input);
    source = a.input;
  }
  const double seconds_volume = seconds_since(t);

  // 2. Reconstruct.
  ReconstructionOptions ro;
  if (a.end_caps == "end-slice") ro.tiling.end_caps = EndCaps::AtEndSlice;
  else if (a.end_caps != "half-spacing") throw InvalidInputError("--end-caps must be half-spacing or end-slice");
  // A phantom is segmented at its partial-volume iso-level, real CT at the bone default.
  const PhantomVolumeOptions phantom_defaults;
  ro.segmentation.threshold =
      a.threshold.value_or(phantom ? 0.5 * (phantom_defaults.bone_hu + phantom_defaults.tissue_hu) : 300.0);
  ro.tiling.limits.max_vertices = a.max_vertices;
  Reconstruction rec;
  try {
    rec = reconstruct(*image, ro, progress.callback());
  } catch (const LimitError& e) {
    throw LimitError(source + ": " + e.what());
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(source + ": " + e.what());
  }
  const Mesh& mesh = rec.mesh;

  // 3. Smooth.
  t = std::chrono::steady_clock::now();
  config.options.progress = progress.callback();
  config.options.limits.max_vertices = a.max_vertices;
  SmoothResult smoothed;
  try {
    smoothed = smooth(mesh, method, config.options);
  } catch (const LimitError& e) {
    throw LimitError(source + ": " + e.what());
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(source + ": " + e.what());
  }
  const Mesh& result = smoothed.mesh;
  const double seconds_smooth = seconds_since(t);

  // 4. Export.
  t = std::chrono::steady_clock::now();
  progress.stage("write");
  write_mesh(result, out, write_options);
  if (!smoothed.labels.empty() && !a.labels_out.empty()) {
    MeshWriteOptions labels;
    labels.point_scalars = label_arrays({smoothed.labels, smoothed.detection, smoothed.creases, 0.0});
    write_mesh(mesh, a.labels_out, labels);
  }
  progress.finish();
  const double seconds_write = seconds_since(t);

  const TopologySummary topo = summarize_topology(result);
  const double v0 = enclosed_volume(mesh);
  const double v1 = enclosed_volume(result);
  nlohmann::json j;
  j["command"] = "run";
  j["source"] = source;
  j["output"] = a.output;
  if (!a.labels_out.empty()) j["labels_out"] = a.labels_out;
  j["method"] = std::string(to_string(method));
  if (const std::string p = preset_name(a.selection); !p.empty()) j["preset"] = p;
  j["iterations"] = smoothed.iterations;
  j["slices"] = rec.report.slices;
  j["contours"] = rec.report.contours;
  j["vertices"] = result.num_vertices();
  j["faces"] = result.num_faces();
  j["components"] = topo.components;
  j["is_closed"] = topo.closed;
  j["is_manifold"] = topo.manifold;
  j["euler_characteristic"] = topo.euler_characteristic;
  j["volume_before"] = v0;
  j["volume_after"] = v1;
  j["volume_change_percent"] = 100.0 * (v1 - v0) / v0;
  j["seconds_volume"] = seconds_volume;
  j["seconds_segment"] = rec.report.seconds_segment;
  j["seconds_tile"] = rec.report.seconds_tile;
  j["seconds_smooth"] = seconds_smooth;
  j["seconds_write"] = seconds_write;
  const LabelCounts counts = count_labels(smoothed.labels);
  if (!smoothed.labels.empty()) {
    j["edge_vertices"] = counts.edges;
    j["corner_vertices"] = counts.corners;
    j["noise_vertices"] = counts.noise;
    j["seconds_detect"] = smoothed.seconds.detect;
  }
  if (method == SmoothingMethod::FeaturePreserving) {
    j["subdivided_vertices"] = smoothed.subdivided_vertices;
    j["seconds_subdivide"] = smoothed.seconds.subdivide;
  }
  DistanceStats before, after, feature_before, feature_after;
  if (phantom) {
    std::vector<Index> feature_vertices;
    for (Index i = 0; i < mesh.num_vertices(); ++i) {
      if (distance_to_features(*phantom, mesh.positions.col(i)) < a.feature_radius) feature_vertices.push_back(i);
    }
    before = distance_to_surface(mesh.positions, phantom->sdf);
    after = distance_to_surface(result.positions, phantom->sdf);
    feature_before = distance_to_surface(mesh.positions, phantom->sdf, feature_vertices);
    feature_after = distance_to_surface(result.positions, phantom->sdf, feature_vertices);
    j["truth_volume"] = phantom->volume;
    j["rms_distance_before"] = before.rms;
    j["rms_distance_after"] = after.rms;
    j["feature_rms_distance_before"] = feature_before.rms;
    j["feature_rms_distance_after"] = feature_after.rms;
    j["feature_vertices"] = feature_vertices.size();
  }
  j["seconds"] = seconds_since(start);
  if (a.json) {
    print_json(j);
    return kOk;
  }
  if (a.common.quiet) return kOk;
  std::cout << std::fixed << std::setprecision(3) << "ContourMesh: " << source << "\n"
            << "  volume      " << image->GetLargestPossibleRegion().GetSize() << " voxels, threshold "
            << rec.report.threshold << " HU\n"
            << "  contours    " << rec.report.contours << " on " << rec.report.slices_with_contours << " slices ("
            << rec.report.hole_contours << " holes, " << rec.report.tiling.branchings << " branchings)\n"
            << "  mesh        " << result.num_vertices() << " vertices, " << result.num_faces() << " triangles, "
            << (topo.closed ? "closed" : "OPEN") << ", " << (topo.manifold ? "manifold" : "NOT manifold")
            << ", Euler characteristic " << topo.euler_characteristic << "\n";
  if (!smoothed.labels.empty()) {
    std::cout << "  features    " << counts.edges << " edge, " << counts.corners << " corner, " << counts.noise
              << " noise vertices";
    if (method == SmoothingMethod::FeaturePreserving) std::cout << "; " << smoothed.subdivided_vertices << " subdivided";
    std::cout << "\n";
  }
  std::cout << "  smoothing   " << describe_selection(a.selection, method) << ": volume " << std::setprecision(1) << v0 << " -> " << v1 << " mm^3 ("
            << std::setprecision(2) << 100.0 * (v1 - v0) / v0 << " %)\n";
  if (phantom) {
    std::cout << std::setprecision(3) << "  accuracy    RMS distance to the true surface " << before.rms << " -> "
              << after.rms << " mm; within " << a.feature_radius << " mm of sharp features " << feature_before.rms
              << " -> " << feature_after.rms << " mm\n";
  }
  std::cout << std::setprecision(2) << "  seconds     volume " << seconds_volume << ", segment "
            << rec.report.seconds_segment << ", tile " << rec.report.seconds_tile << ", smooth " << seconds_smooth
            << ", write " << seconds_write << ", total " << seconds_since(start) << "\n"
            << "  wrote       " << a.output << (a.labels_out.empty() ? "" : " and " + a.labels_out) << "\n";
  return kOk;
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand(
      "run", "The whole pipeline: volume (or a built-in phantom) -> contours -> mesh -> smoothing -> file");
  CLI::Option* input =
      cmd->add_option("input", args->input, "CT volume or DICOM directory; none: the built-in phantom --shape");
  cmd->add_option("-o,--output", args->output, "Output mesh (.stl .ply .vtp .obj); format from the extension unless --format")
      ->capture_default_str();
  cmd->add_option("--format", args->format, "Output format: auto | stl | stl-ascii | ply | vtp | obj")
      ->capture_default_str();
  cmd->add_option("--labels-out", args->labels_out,
                  "paper, cross-slice: also write the reconstructed mesh with per-vertex labels and curvatures (.vtp or .ply)");
  cmd->add_option("--shape", args->shape, "Phantom when no input: " + phantom_shape_names(" | "))
      ->capture_default_str();
  cmd->add_option("--spacing", args->spacing, "Phantom voxel size, mm: sx,sy,sz")->capture_default_str();
  cmd->add_option("--noise", args->noise, "Phantom Gaussian noise, HU")->capture_default_str();
  add_contour_noise_option(cmd, args->contour_noise)->excludes(input);
  cmd->add_option("--blur", args->blur, "Phantom Gaussian blur, mm")->capture_default_str();
  cmd->add_option("--seed", args->seed, "Phantom noise seed")->capture_default_str();
  cmd->add_option("--threshold", args->threshold,
                  "Bone threshold, HU (default: 300 for an input volume; 520 for a phantom, halfway between its "
                  "soft tissue and bone)");
  cmd->add_option("--end-caps", args->end_caps, "Where objects end: half-spacing | end-slice")->capture_default_str();
  add_method_options(cmd, args->selection);
  cmd->add_option("--feature-radius", args->feature_radius,
                  "Phantom: vertices this close to a sharp edge form the feature region, mm")
      ->capture_default_str();
  add_detection_options(cmd, args->detection);
  add_common_options(cmd, args->common);
  add_max_vertices_option(cmd, args->max_vertices);
  cmd->add_flag("--json", args->json, "Print one JSON object on stdout instead of the summary");
  cmd->callback([args] { set_exit_code(run_guarded("run", [&] { return run_run(*args); })); });
}

}  // namespace contourmesh::cli
