// contourmesh reconstruct IN -o mesh.vtp: CT volume (file or DICOM directory) -> contours -> tiled mesh.
#include "cli_common.h"
#include "input_selection.h"
#include "progress_display.h"

#include <pipelines/atomic_file.h>
#include <pipelines/mesh_io.h>
#include <reconstruct/label_map.h>
#include <reconstruct/reconstruction.h>
#include <reconstruct/threads.h>
#include <reconstruct/volume.h>
#include <smooth/errors.h>
#include <smooth/limits.h>
#include <smooth/metrics.h>
#include <smooth/topology.h>

#include <CLI/CLI.hpp>

#include <future>
#include <iomanip>
#include <iostream>
#include <memory>

namespace contourmesh::cli {

namespace {

struct ReconstructArgs {
  std::string input;
  std::string output;
  double threshold = 300.0;
  bool otsu = false;
  double sampling = 0.0;
  std::string smoothing = "none";
  std::string keep = "all";
  double min_area = 2.0;
  bool fill_holes = false;
  std::string end_caps = "half-spacing";
  std::string format = "auto";
  Index max_vertices = kDefaultMaxVertices;
  bool json = false;
  InputSelectionArgs selection;
  CommonArgs common;
};

ImageSmoothing parse_smoothing(const std::string& s) {
  if (s == "none") return ImageSmoothing::None;
  if (s == "median") return ImageSmoothing::Median;
  if (s == "anisotropic") return ImageSmoothing::CurvatureAnisotropic;
  throw InvalidInputError("--smoothing must be none, median or anisotropic, got '" + s + "'");
}

// The facts of one reconstructed mesh, for the JSON and the summary.
nlohmann::json mesh_facts(const Reconstruction& r, const TopologySummary& topo) {
  nlohmann::json j;
  j["threshold"] = r.report.threshold;
  j["slices"] = r.report.slices;
  j["slices_with_contours"] = r.report.slices_with_contours;
  j["contours"] = r.report.contours;
  j["hole_contours"] = r.report.hole_contours;
  j["branchings"] = r.report.tiling.branchings;
  j["caps"] = r.report.tiling.caps;
  j["dropped_contours"] = r.report.tiling.dropped_contours;
  j["dropped_components"] = r.report.dropped_components;
  j["vertices"] = r.mesh.num_vertices();
  j["faces"] = r.mesh.num_faces();
  j["components"] = topo.components;
  j["is_closed"] = topo.closed;
  j["is_manifold"] = topo.manifold;
  j["euler_characteristic"] = topo.euler_characteristic;
  j["volume"] = enclosed_volume(r.mesh);
  j["seconds_segment"] = r.report.seconds_segment;
  j["seconds_tile"] = r.report.seconds_tile;
  return j;
}

// Writes the mesh (its topology computed meanwhile when a second thread is allowed); returns its facts.
nlohmann::json write_reconstruction(const Reconstruction& r, const std::filesystem::path& output,
                                    const MeshWriteOptions& write_options, ProgressDisplay& progress) {
  std::future<TopologySummary> topology =
      std::async(available_threads() > 1 ? std::launch::async : std::launch::deferred,
                 [&r] { return summarize_topology(r.mesh); });
  progress.stage("write");
  write_mesh(r.mesh, output, write_options);
  nlohmann::json j = mesh_facts(r, topology.get());
  j["output"] = output.string();
  return j;
}

void print_mesh_summary(const nlohmann::json& j) {
  std::cout << std::fixed << std::setprecision(2) << "  contours   " << j["contours"].get<std::size_t>() << " ("
            << j["hole_contours"].get<std::size_t>() << " holes) on " << j["slices_with_contours"].get<std::size_t>()
            << " slices, " << j["branchings"].get<std::size_t>() << " branchings, " << j["caps"].get<std::size_t>()
            << " caps\n";
  const int components = j["components"].get<int>();
  std::cout << "  mesh       " << j["vertices"].get<Index>() << " vertices, " << j["faces"].get<Index>()
            << " triangles, " << components << " component" << (components == 1 ? "" : "s") << ", "
            << (j["is_closed"].get<bool>() ? "closed" : "OPEN") << ", "
            << (j["is_manifold"].get<bool>() ? "manifold" : "NOT manifold") << ", Euler characteristic "
            << j["euler_characteristic"].get<int>() << ", volume " << std::setprecision(1) << j["volume"].get<double>()
            << " mm^3\n";
}

int run_reconstruct(const ReconstructArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  if (a.selection.list_series) return print_series_list(a.input, a.json);
  if (a.output.empty()) {
    std::cerr << "contourmesh reconstruct: --output is required\n";
    return kUsage;
  }
  ReconstructionOptions options;
  auto& seg = options.segmentation;
  seg.threshold = a.threshold;
  seg.threshold_method = a.otsu ? ThresholdMethod::Otsu : ThresholdMethod::Fixed;
  seg.sampling = a.sampling;
  seg.smoothing = parse_smoothing(a.smoothing);
  if (a.keep == "all") seg.components = ComponentSelection::KeepAll;
  else if (a.keep == "largest") seg.components = ComponentSelection::KeepLargest;
  else throw InvalidInputError("--keep must be all or largest, got '" + a.keep + "'");
  seg.min_region_area = a.min_area;
  seg.fill_holes = a.fill_holes;
  if (a.end_caps == "half-spacing") options.tiling.end_caps = EndCaps::HalfSpacing;
  else if (a.end_caps == "end-slice") options.tiling.end_caps = EndCaps::AtEndSlice;
  else throw InvalidInputError("--end-caps must be half-spacing or end-slice, got '" + a.end_caps + "'");
  MeshWriteOptions write_options;
  write_options.format = parse_mesh_format(a.format);
  if (write_options.format == MeshFormat::Auto) (void)format_from_extension(a.output);  // fail before the work
  options.tiling.limits.max_vertices = a.max_vertices;

  apply_common_options(a.common);
  ProgressDisplay progress("reconstruct", a.common.quiet);
  progress.stage("read");
  if (labels_requested(a.selection)) {
    // One mesh per label of a label map or segmentation: every output is checked before any work.
    const SelectedLabels selected = read_selected_labels(a.input, a.selection);
    for (const Label& label : selected.labels) check_output_path(label_output_path(a.output, label, a.selection));
    nlohmann::json meshes = nlohmann::json::array();
    for (const Label& label : selected.labels) {
      Reconstruction r;
      try {
        r = reconstruct_label(selected.map, label, options, progress.callback());
      } catch (const LimitError& e) {
        throw LimitError(a.input + ": " + e.what());
      } catch (const InvalidInputError& e) {
        throw InvalidInputError(a.input + ": " + e.what());
      }
      nlohmann::json j = write_reconstruction(r, label_output_path(a.output, label, a.selection), write_options, progress);
      j["label"] = label.display_name();
      j["label_value"] = label.value;
      j["label_layer"] = label.layer;
      j["label_voxels"] = label.voxels;
      meshes.push_back(j);
    }
    progress.finish();
    if (a.json) {
      print_json({{"command", "reconstruct"}, {"input", a.input}, {"labels", meshes}, {"seconds", seconds_since(start)}});
      return kOk;
    }
    if (a.common.quiet) return kOk;
    std::cout << "reconstructed " << meshes.size() << " label" << (meshes.size() == 1 ? "" : "s") << " of " << a.input
              << "\n";
    for (const nlohmann::json& j : meshes) {
      std::cout << "label " << j["label"].get<std::string>() << " (value " << j["label_value"].get<int>() << ", "
                << j["label_voxels"].get<std::size_t>() << " voxels)\n";
      print_mesh_summary(j);
      std::cout << "  wrote      " << j["output"].get<std::string>() << "\n";
    }
    std::cout << "  in " << std::setprecision(2) << seconds_since(start) << " s\n";
    return kOk;
  }
  check_output_path(a.output);
  const CtImage::Pointer image = read_volume(a.input, read_options(a.selection));
  Reconstruction r;
  try {
    r = reconstruct(*image, options, progress.callback());
  } catch (const LimitError& e) {
    throw LimitError(a.input + ": " + e.what());
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(a.input + ": " + e.what());
  }
  nlohmann::json j = write_reconstruction(r, a.output, write_options, progress);
  progress.finish();
  const auto size = image->GetLargestPossibleRegion().GetSize();
  const auto spacing = image->GetSpacing();
  if (a.json) {
    j["command"] = "reconstruct";
    j["input"] = a.input;
    if (!a.selection.series.empty()) j["series"] = a.selection.series;
    j["size"] = {size[0], size[1], size[2]};
    j["spacing"] = {spacing[0], spacing[1], spacing[2]};
    j["seconds"] = seconds_since(start);
    print_json(j);
    return kOk;
  }
  if (a.common.quiet) return kOk;
  std::cout << std::fixed << std::setprecision(2) << "reconstructed " << a.input << "\n"
            << "  volume     " << size[0] << " x " << size[1] << " x " << size[2] << " voxels, " << spacing[0] << " x "
            << spacing[1] << " x " << spacing[2] << " mm, threshold " << r.report.threshold << "\n";
  print_mesh_summary(j);
  std::cout << "  wrote      " << a.output << " in " << std::setprecision(2) << seconds_since(start) << " s\n";
  return kOk;
}

}  // namespace

void add_reconstruct_command(CLI::App& app) {
  auto args = std::make_shared<ReconstructArgs>();
  CLI::App* cmd = app.add_subcommand("reconstruct", "Segment a CT volume and tile its contours into a closed mesh");
  cmd->add_option("input", args->input,
                  "CT volume (.mha .mhd .nrrd .nii .nii.gz), a DICOM series directory, or with --label(s) a label "
                  "map or 3D Slicer segmentation (.seg.nrrd)")
      ->required();
  cmd->add_option("-o,--output", args->output, "Output mesh (.vtp or .ply keep the contour ids)");
  CLI::Option* threshold =
      cmd->add_option("--threshold", args->threshold, "Foreground threshold, HU (bone: 300)")->capture_default_str();
  CLI::Option* otsu = cmd->add_flag("--otsu", args->otsu, "Use Otsu's threshold instead of --threshold");
  add_input_selection_options(cmd, args->selection, {threshold, otsu});
  cmd->add_option("--sampling", args->sampling, "Distance between contour points, mm (0: the pixel spacing, at most 1 mm)")
      ->capture_default_str();
  cmd->add_option("--smoothing", args->smoothing, "Image denoising: none | median | anisotropic")->capture_default_str();
  cmd->add_option("--keep", args->keep, "Components: all | largest (3-D)")->capture_default_str();
  cmd->add_option("--min-area", args->min_area, "Drop regions and fill holes smaller than this, mm^2")
      ->capture_default_str();
  cmd->add_flag("--fill-holes", args->fill_holes, "Fill every hole in every slice");
  cmd->add_option("--end-caps", args->end_caps,
                  "Where objects end: half-spacing (half a slice beyond the last contour) | end-slice")
      ->capture_default_str();
  cmd->add_option("--format", args->format, "Output format: auto | stl | stl-ascii | ply | vtp | obj")
      ->capture_default_str();
  add_max_vertices_option(cmd, args->max_vertices);
  cmd->add_flag("--json", args->json, "Print one JSON object on stdout instead of the summary");
  add_common_options(cmd, args->common);
  cmd->callback([args] { set_exit_code(run_guarded("reconstruct", [&] { return run_reconstruct(*args); })); });
}

}  // namespace contourmesh::cli
