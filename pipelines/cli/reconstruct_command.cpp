// SPDX-License-Identifier: BSD-3-Clause
// contourmesh reconstruct IN -o mesh.vtp: CT volume (file or DICOM directory) -> contours -> tiled mesh;
// or drawn contours (an RT Structure Set with --roi, a contour-stack file) -> tiled mesh.
#include "cli_common.h"
#include "contour_input.h"
#include "input_selection.h"
#include "progress_display.h"
#include "tiling_options.h"
#include "volume_options.h"

#include <contourmesh/vtk/atomic_file.h>
#include <contourmesh/vtk/contour_stack_io.h>
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/reconstruct/contour_deviation.h>
#include <contourmesh/reconstruct/contour_reconstruction.h>
#include <contourmesh/reconstruct/label_map.h>
#include <contourmesh/reconstruct/reconstruction.h>
#include <contourmesh/reconstruct/threads.h>
#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/limits.h>
#include <contourmesh/smooth/mesh_quality.h>
#include <contourmesh/smooth/metrics.h>
#include <contourmesh/smooth/topology.h>

#include <CLI/CLI.hpp>

#include <filesystem>
#include <future>
#include <iomanip>
#include <optional>
#include <vector>
#include <iostream>
#include <memory>

namespace contourmesh::cli {

namespace {

struct ReconstructArgs {
  std::string input;
  std::string output;
  double threshold = 300.0;
  bool otsu = false;
  std::optional<double> sampling;
  std::string smoothing = "none";
  std::string keep = "all";
  double min_area = 2.0;
  bool fill_holes = false;
  TilingArgs tiling;
  std::string format = "auto";
  std::string contours_out;
  Index max_vertices = kDefaultMaxVertices;
  bool json = false;
  ContourArgs contour;
  VolumeArgs volume;
  InputSelectionArgs selection;
  CommonArgs common;
};

// Options of one route, refused on the other's input.
const std::vector<std::string> kVolumeOptions{"--threshold", "--otsu",   "--smoothing", "--keep",       "--min-area",
                                              "--fill-holes", "--label", "--labels",    "--series",     "--list-series",
                                              "--off-slice",  "--flat-crossings"};
const std::vector<std::string> kContourOptions{"--roi", "--align", "--slab-thickness",
                                               "--planarity-tolerance", "--sampling-tolerance"};

ImageSmoothing parse_smoothing(const std::string& s) {
  if (s == "none") return ImageSmoothing::None;
  if (s == "median") return ImageSmoothing::Median;
  if (s == "anisotropic") return ImageSmoothing::CurvatureAnisotropic;
  throw InvalidInputError("--smoothing must be none, median or anisotropic, got '" + s + "'");
}

// --label / --labels: one mesh per label of a label map or a 3D Slicer segmentation; every output is
// checked before any work.
int run_reconstruct_labels(const ReconstructArgs& a, const ReconstructionOptions& options,
                           const MeshWriteOptions& write_options, std::chrono::steady_clock::time_point start) {
  apply_common_options(a.common);
  ProgressDisplay progress("reconstruct", a.common.quiet);
  progress.stage("read");
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
    const std::filesystem::path output = label_output_path(a.output, label, a.selection);
    progress.stage("write");
    write_mesh(r.mesh, output, write_options);
    const TopologySummary topo = summarize_topology(r.mesh);
    nlohmann::json j;
    j["label"] = label.display_name();
    j["label_value"] = label.value;
    j["label_layer"] = label.layer;
    j["label_voxels"] = label.voxels;
    j["output"] = output.string();
    j["slices_with_contours"] = r.report.slices_with_contours;
    j["contours"] = r.report.contours;
    j["hole_contours"] = r.report.hole_contours;
    j["branchings"] = r.report.tiling.branchings;
    j["caps"] = r.report.tiling.caps;
    j["vertices"] = r.mesh.num_vertices();
    j["faces"] = r.mesh.num_faces();
    j["components"] = topo.components;
    j["is_closed"] = topo.closed;
    j["is_manifold"] = topo.manifold;
    j["euler_characteristic"] = topo.euler_characteristic;
    j["volume"] = enclosed_volume(r.mesh);
    const auto spacing = selected.map.layers[static_cast<std::size_t>(label.layer)]->GetSpacing();
    j["voxel_volume"] = static_cast<double>(label.voxels) * spacing[0] * spacing[1] * spacing[2];
    j["seconds_segment"] = r.report.seconds_segment;
    j["seconds_tile"] = r.report.seconds_tile;
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
    const int components = j["components"].get<int>();
    std::cout << std::fixed << std::setprecision(1) << "label " << j["label"].get<std::string>() << " (value "
              << j["label_value"].get<int>() << ", " << j["label_voxels"].get<std::size_t>() << " voxels, "
              << j["voxel_volume"].get<double>() << " mm^3)\n"
              << "  mesh       " << j["vertices"].get<Index>() << " vertices, " << j["faces"].get<Index>()
              << " triangles, " << components << " component" << (components == 1 ? "" : "s") << ", "
              << (j["is_closed"].get<bool>() ? "closed" : "OPEN") << ", volume " << j["volume"].get<double>()
              << " mm^3\n"
              << "  wrote      " << j["output"].get<std::string>() << "\n";
  }
  return kOk;
}

int run_reconstruct(const ReconstructArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  if (a.selection.list_series) return print_series_list(a.input, a.json);
  if (a.output.empty()) {
    std::cerr << "contourmesh reconstruct: --output is required\n";
    return kUsage;
  }
  ReconstructionOptions options;
  options.single_slice = parse_single_slice(a.contour.single_slice);
  auto& seg = options.segmentation;
  seg.threshold = a.threshold;
  seg.threshold_method = a.otsu ? ThresholdMethod::Otsu : ThresholdMethod::Fixed;
  seg.sampling = a.sampling.value_or(0.0);
  seg.smoothing = parse_smoothing(a.smoothing);
  if (a.keep == "all") seg.components = ComponentSelection::KeepAll;
  else if (a.keep == "largest") seg.components = ComponentSelection::KeepLargest;
  else throw InvalidInputError("--keep must be all or largest, got '" + a.keep + "'");
  seg.min_region_area = a.min_area;
  seg.fill_holes = a.fill_holes;
  options.tiling = tiling_options(a.tiling);
  options.off_slice.placement = off_slice_placement(a.volume);
  options.segmentation.flat_crossings = flat_crossings(a.volume);
  MeshWriteOptions write_options;
  write_options.format = parse_mesh_format(a.format);
  if (write_options.format == MeshFormat::Auto) (void)format_from_extension(a.output);  // fail before the work
  options.tiling.limits.max_vertices = a.max_vertices;
  if (labels_requested(a.selection)) {
    if (!a.contours_out.empty()) throw InvalidInputError("--contours-out is not available with --label or --labels");
    return run_reconstruct_labels(a, options, write_options, start);
  }
  check_output_path(a.output);
  if (!a.contours_out.empty()) {
    if (!is_contour_stack_path(a.contours_out))
      throw InvalidInputError(a.contours_out + ": contour files end in .json");
    check_output_path(a.contours_out);
  }
  options.tiling.limits.max_vertices = a.max_vertices;
  options.segmentation.limits.max_vertices = a.max_vertices;

  apply_common_options(a.common);
  ProgressDisplay progress("reconstruct", a.common.quiet);
  progress.stage("read");
  VolumeReadOptions read = volume_read_options(a.volume, "reconstruct");
  read.series_uid = a.selection.series;
  const CtImage::Pointer image = read_volume(a.input, read);
  Reconstruction r;
  try {
    r = reconstruct(*image, options, progress.callback());
  } catch (const LimitError& e) {
    throw LimitError(a.input + ": " + e.what());
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(a.input + ": " + e.what());
  }
  // The summary's topology is computed while the file is written, when a second thread is allowed.
  std::future<TopologySummary> topology =
      std::async(available_threads() > 1 ? std::launch::async : std::launch::deferred,
                 [&r] { return summarize_topology(r.mesh); });
  progress.stage("write");
  write_options.progress = progress.callback();
  write_mesh(r.mesh, a.output, write_options);
  if (!a.contours_out.empty()) {
    ContourStackFile contours;
    contours.stack = r.contours;
    write_contour_stack(contours, a.contours_out);
  }
  progress.finish();
  const TopologySummary topo = topology.get();
  const double volume = enclosed_volume(r.mesh);
  // Caps are flat by construction: the shelf measure counts the other faces parallel to the slices.
  std::vector<std::uint8_t> caps(r.face_roles.size(), 0);
  for (std::size_t f = 0; f < caps.size(); ++f) caps[f] = r.face_roles[f] == FaceRole::Cap ? 1 : 0;
  MeshQualityOptions quality_options;
  quality_options.slice_axis = r.contours.axis_w;
  const MeshQuality quality = mesh_quality(r.mesh, quality_options, caps);
  const auto size = image->GetLargestPossibleRegion().GetSize();
  const auto spacing = image->GetSpacing();
  if (a.json) {
    nlohmann::json j;
    j["command"] = "reconstruct";
    j["input"] = a.input;
    j["output"] = a.output;
    if (!a.selection.series.empty()) j["series"] = a.selection.series;
    j["size"] = {size[0], size[1], size[2]};
    j["spacing"] = {spacing[0], spacing[1], spacing[2]};
    j["threshold"] = r.report.threshold;
    j["slices"] = r.report.slices;
    j["slices_with_contours"] = r.report.slices_with_contours;
    j["contours"] = r.report.contours;
    j["hole_contours"] = r.report.hole_contours;
    j["branchings"] = r.report.tiling.branchings;
    j["one_to_one"] = r.report.tiling.one_to_one;
    j["refined_bands"] = r.report.tiling.refined_bands;
    j["intermediate_contours"] = r.report.tiling.intermediate_contours;
    j["composites"] = r.report.tiling.composites;
    j["partings"] = r.report.tiling.partings;
    j["caps"] = r.report.tiling.caps;
    j["dropped_contours"] = r.report.tiling.dropped_contours;
    j["dropped_components"] = r.report.dropped_components;
    j["single_slice_slabs"] = r.report.single_slice_slabs;
    j["single_slice_cavities"] = r.report.single_slice_cavities;
    j["single_slice_thinned"] = r.report.single_slice_thinned;
    j["single_slice_filled"] = r.report.single_slice_filled;
    j["single_slice_left_out"] = r.report.single_slice_left_out;
    j["vertices"] = r.mesh.num_vertices();
    j["faces"] = r.mesh.num_faces();
    j["components"] = topo.components;
    j["is_closed"] = topo.closed;
    j["is_manifold"] = topo.manifold;
    j["euler_characteristic"] = topo.euler_characteristic;
    j["volume"] = volume;
    j["area"] = quality.area;
    j["sliver_area_share"] = quality.sliver_area_share;
    j["min_angle_degrees"] = quality.min_angle_degrees;
    j["shelf_area"] = quality.shelf_area;
    j["shelf_area_share"] = quality.shelf_area_share;
    j["share_without_ids"] = quality.share_without_ids;
    if (!a.contours_out.empty()) j["contours_out"] = a.contours_out;
    j["off_slice_candidates"] = r.report.off_slice.candidates;
    j["off_slice_fitted"] = r.report.off_slice.fitted;
    j["off_slice_damped"] = r.report.off_slice.damped;
    j["seconds_segment"] = r.report.seconds_segment;
    j["seconds_tile"] = r.report.seconds_tile;
    j["seconds_off_slice"] = r.report.seconds_off_slice;
    j["seconds"] = seconds_since(start);
    print_json(j);
    return kOk;
  }
  if (a.common.quiet) return kOk;
  std::cout << std::fixed << std::setprecision(2) << "reconstructed " << a.input << "\n"
            << "  volume     " << size[0] << " x " << size[1] << " x " << size[2] << " voxels, " << spacing[0] << " x "
            << spacing[1] << " x " << spacing[2] << " mm, threshold " << r.report.threshold << "\n"
            << "  contours   " << r.report.contours << " (" << r.report.hole_contours << " holes) on "
            << r.report.slices_with_contours << " slices, " << r.report.tiling.branchings << " branchings, "
            << r.report.tiling.caps << " caps\n"
            << "  tiling     " << r.report.tiling.intermediate_contours << " intermediate contours, "
            << r.report.tiling.refined_bands << " bands refined, " << r.report.tiling.composites << " composites, "
            << r.report.tiling.partings << " partings\n"
            << "  one slice  " << r.report.tiling.dropped_contours
            << " contours with no partner on an adjacent slice: " << r.report.single_slice_slabs << " slabs, "
            << r.report.single_slice_cavities << " hollow (" << r.report.single_slice_thinned << " thinner), "
            << r.report.single_slice_filled << " holes filled, " << r.report.single_slice_left_out
            << " left out; " << r.report.dropped_components
            << " specks dropped\n"
            << "  off-slice  " << r.report.off_slice.fitted << " of " << r.report.off_slice.candidates
            << " vertices between the slices placed from the image (" << r.report.off_slice.damped << " damped)\n"
            << "  mesh       " << r.mesh.num_vertices() << " vertices, " << r.mesh.num_faces() << " triangles, "
            << topo.components << " component" << (topo.components == 1 ? "" : "s") << ", "
            << (topo.closed ? "closed" : "OPEN") << ", " << (topo.manifold ? "manifold" : "NOT manifold")
            << ", Euler characteristic " << topo.euler_characteristic << ", volume " << std::setprecision(1) << volume
            << " mm^3\n"
            << "  quality    " << std::setprecision(1) << 100.0 * quality.sliver_area_share
            << " % of the area in faces with an angle under 10 degrees, " << 100.0 * quality.shelf_area_share
            << " % in faces within 10 degrees of the slices (caps left out), " << 100.0 * quality.share_without_ids
            << " % of the vertices without ids\n"
            << "  wrote      " << a.output << (a.contours_out.empty() ? "" : " and " + a.contours_out) << " in "
            << std::setprecision(2) << seconds_since(start) << " s\n";
  return kOk;
}

// The file extension of a mesh format (".vtp" for Auto: it keeps the contour ids).
std::string mesh_extension(MeshFormat format) {
  switch (format) {
    case MeshFormat::StlBinary:
    case MeshFormat::StlAscii: return ".stl";
    case MeshFormat::Ply: return ".ply";
    case MeshFormat::Obj: return ".obj";
    case MeshFormat::Vtp:
    case MeshFormat::Auto: break;
  }
  return ".vtp";
}

// One ROI (or contour file): tiled, written, checked against its drawn contours; its JSON object.
nlohmann::json reconstruct_one(const ReconstructArgs& a, InputKind kind, const ContourInput& in,
                               const std::filesystem::path& output, const std::filesystem::path& contours_out,
                               const MeshWriteOptions& write_options, ProgressDisplay& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const ContourReconstruction r = reconstruct_from_contours(
      in.stack, in.what, contour_options(a.contour, in, a.sampling, tiling_options(a.tiling), a.max_vertices),
      progress.callback());
  print_warnings("reconstruct", r.report.warnings);
  progress.stage("write");
  write_mesh(r.mesh, output, write_options);
  if (!contours_out.empty()) write_input_contours(in, contours_out);
  const TopologySummary topo = summarize_topology(r.mesh);
  const double volume = enclosed_volume(r.mesh);
  const ContourDeviation deviation = contour_deviation(r.mesh, in.stack);
  const double difference = 100.0 * (volume - r.report.slicewise_volume) / r.report.slicewise_volume;
  const double seconds = seconds_since(t0);
  nlohmann::json j;
  j["status"] = "ok";
  describe_input(j, in);
  j["output"] = output.string();
  if (!contours_out.empty()) j["contours_out"] = contours_out.string();
  j["slices"] = r.report.slices;
  j["contours"] = r.report.contours;
  j["hole_contours"] = r.report.hole_contours;
  j["points_drawn"] = r.report.points_drawn;
  j["points_tiled"] = r.report.points_tiled;
  j["branchings"] = r.report.tiling.branchings;
  j["caps"] = r.report.tiling.caps;
  j["slabs"] = r.report.slabs;
  j["aligned_gaps"] = r.report.aligned_gaps;
  j["vertices"] = r.mesh.num_vertices();
  j["faces"] = r.mesh.num_faces();
  j["components"] = topo.components;
  j["is_closed"] = topo.closed;
  j["is_manifold"] = topo.manifold;
  j["euler_characteristic"] = topo.euler_characteristic;
  j["volume"] = volume;
  j["slicewise_volume"] = r.report.slicewise_volume;
  j["volume_difference_percent"] = difference;
  j["contour_deviation_mean"] = deviation.mean;
  j["contour_deviation_max"] = deviation.max;
  j["slices_without_section"] = deviation.slices_without_section;
  j["seconds_tile"] = r.report.seconds_tile;
  j["seconds"] = seconds;
  if (a.json || a.common.quiet) return j;
  std::cout << std::fixed << std::setprecision(2) << "reconstructed " << in.what
            << (kind == InputKind::StructureSet ? " of " + a.input : "") << "\n"
            << "  contours   " << r.report.contours << " (" << r.report.hole_contours
            << (r.report.hole_contours == 1 ? " hole) on " : " holes) on ") << r.report.slices << " slices, "
            << r.report.points_drawn << " points drawn, " << r.report.points_tiled << " tiled; "
            << r.report.tiling.branchings << " branchings, " << r.report.tiling.caps << " caps, " << r.report.slabs
            << " single-slice slabs\n"
            << "  mesh       " << r.mesh.num_vertices() << " vertices, " << r.mesh.num_faces() << " triangles, "
            << topo.components << " component" << (topo.components == 1 ? "" : "s") << ", "
            << (topo.closed ? "closed" : "OPEN") << ", " << (topo.manifold ? "manifold" : "NOT manifold")
            << ", Euler characteristic " << topo.euler_characteristic << "\n"
            << "  volume     " << std::setprecision(1) << volume << " mm^3; slice-wise " << r.report.slicewise_volume
            << " mm^3 (" << std::showpos << std::setprecision(2) << difference << std::noshowpos << " %)\n"
            << std::setprecision(3) << "  contours   reproduced in their slice planes within " << deviation.max
            << " mm (mean " << deviation.mean << " mm)\n"
            << "  wrote      " << output.string() << (contours_out.empty() ? "" : " and " + contours_out.string())
            << " in " << std::setprecision(2) << seconds << " s\n";
  return j;
}

int run_reconstruct_contours(const ReconstructArgs& a, InputKind kind) {
  const auto start = std::chrono::steady_clock::now();
  MeshWriteOptions write_options;
  write_options.format = parse_mesh_format(a.format);
  (void)tiling_options(a.tiling);
  apply_common_options(a.common);
  ProgressDisplay progress("reconstruct", a.common.quiet);
  progress.stage("read");
  const ContourInputs loaded = load_contour_inputs(a.input, kind, a.contour);
  print_warnings("reconstruct", loaded.warnings);
  print_warnings("reconstruct", loaded.skipped);
  const auto outputs = roi_outputs(a.output, loaded, mesh_extension(write_options.format));
  const auto contour_outputs = roi_outputs(a.contours_out, loaded, ".json", true);
  if (write_options.format == MeshFormat::Auto) {
    for (const auto& p : outputs) (void)format_from_extension(p);
  }
  std::size_t failed = 0;
  nlohmann::json rois = for_each_roi(
      "reconstruct", a.input, loaded,
      [&](const ContourInput& in, std::size_t i) {
        return reconstruct_one(a, kind, in, outputs[i], contour_outputs[i], write_options, progress);
      },
      failed);
  progress.finish();
  if (a.json) print_json(roi_results_json("reconstruct", a.input, loaded, std::move(rois), failed, start));
  if (failed > 0 && !a.json) {
    std::cerr << "contourmesh reconstruct: " << failed << " of " << loaded.inputs.size() << " ROIs failed\n";
  }
  return failed > 0 ? kBadInput : kOk;
}

int run_reconstruct_any(const ReconstructArgs& a, const CLI::App* cmd) {
  const InputKind kind = input_kind(a.input);
  if (kind == InputKind::Volume) {
    reject_options(cmd, kContourOptions, "applies to contours (an RT Structure Set or a .json contour file)");
    return run_reconstruct(a);
  }
  reject_options(cmd, kVolumeOptions, "applies to CT volumes, not to contours");
  if (a.output.empty()) {
    std::cerr << "contourmesh reconstruct: --output is required\n";
    return kUsage;
  }
  return run_reconstruct_contours(a, kind);
}

}  // namespace

void add_reconstruct_command(CLI::App& app) {
  auto args = std::make_shared<ReconstructArgs>();
  CLI::App* cmd = app.add_subcommand(
      "reconstruct", "Segment a CT volume, or take drawn contours, and tile the contours into a closed mesh");
  cmd->add_option("input", args->input,
                  "CT volume (.mha .mhd .nrrd .nii .nii.gz), DICOM series directory, RT Structure Set (with "
                  "--roi), contour file (.json), or with --label(s) a label map or 3D Slicer segmentation (.seg.nrrd)")
      ->required();
  cmd->add_option("-o,--output", args->output,
                  "Output mesh (.vtp or .ply keep the contour ids); with --roi all a directory, or a path with {roi}; "
                  "with --labels a path whose stem gets _<label>, or with {label}");
  CLI::Option* threshold =
      cmd->add_option("--threshold", args->threshold, "Foreground threshold, HU (bone: 300)")->capture_default_str();
  CLI::Option* otsu = cmd->add_flag("--otsu", args->otsu, "Use Otsu's threshold instead of --threshold");
  add_input_selection_options(cmd, args->selection, {threshold, otsu});
  cmd->add_option("--sampling", args->sampling,
                  "Distance between contour points, mm (CT default 0: the pixel spacing, at most 1 mm; contours "
                  "default 1, 0: as drawn)");
  cmd->add_option("--smoothing", args->smoothing, "Image denoising: none | median | anisotropic")
      ->capture_default_str();
  cmd->add_option("--keep", args->keep, "Components: all | largest (3-D)")->capture_default_str();
  cmd->add_option("--min-area", args->min_area, "Drop regions and fill holes smaller than this, mm^2")
      ->capture_default_str();
  cmd->add_flag("--fill-holes", args->fill_holes, "Fill every hole in every slice");
  add_tiling_options(cmd, args->tiling);
  cmd->add_option("--format", args->format, "Output format: auto | stl | stl-ascii | ply | vtp | obj")
      ->capture_default_str();
  cmd->add_option("--contours-out", args->contours_out,
                  "Also write the contours (found in the CT, or as normalised from the input) to this .json file");
  add_contour_options(cmd, args->contour);
  add_volume_options(cmd, args->volume);
  add_max_vertices_option(cmd, args->max_vertices);
  cmd->add_flag("--json", args->json, "Print one JSON object on stdout instead of the summary");
  add_common_options(cmd, args->common);
  cmd->callback(
      [args, cmd] { set_exit_code(run_guarded("reconstruct", [&] { return run_reconstruct_any(*args, cmd); })); });
}

}  // namespace contourmesh::cli
