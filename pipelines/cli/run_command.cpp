// SPDX-License-Identifier: BSD-3-Clause
// contourmesh run [IN] -o OUT: the whole chain, read (or generate) -> segment -> contours -> tile ->
// smooth -> export. With no input it runs on a built-in phantom with noise, and reports accuracy
// against the phantom's analytic surface.
#include "cli_common.h"
#include "contour_input.h"
#include "feature_options.h"
#include "input_selection.h"
#include "method_options.h"
#include "progress_display.h"
#include "tiling_options.h"
#include "volume_options.h"

#include <contourmesh/vtk/atomic_file.h>
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/reconstruct/contour_deviation.h>
#include <contourmesh/reconstruct/contour_reconstruction.h>
#include <contourmesh/reconstruct/label_map.h>
#include <contourmesh/reconstruct/phantom.h>
#include <contourmesh/reconstruct/phantom_truth.h>
#include <contourmesh/reconstruct/reconstruction.h>
#include <contourmesh/reconstruct/threads.h>
#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/limits.h>
#include <contourmesh/smooth/metrics.h>
#include <contourmesh/smooth/smooth.h>
#include <contourmesh/smooth/surface_metrics.h>
#include <contourmesh/smooth/topology.h>

#include <CLI/CLI.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <future>
#include <limits>
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
  MethodArgs smoothing;
  double feature_radius = 1.5;
  TilingArgs tiling;
  std::string format = "auto";
  std::string labels_out;
  Index max_vertices = kDefaultMaxVertices;
  bool json = false;
  std::optional<double> sampling;
  FeatureArgs detection;
  ContourArgs contour;
  VolumeArgs volume;
  InputSelectionArgs selection;
  CommonArgs common;
};

// The method `run` smooths with (--method / --preset, the detection options), checked before the work.
MethodConfig run_method_config(const RunArgs& a, const std::string& labels_out) {
  MethodConfig config = method_config(a.smoothing, StepArgs{}, a.detection);
  if (!labels_out.empty() && !produces_labels(config.method)) {
    throw InvalidInputError("--labels-out needs a method that labels features (paper or cross-slice), not " +
                            std::string(to_string(config.method)));
  }
  config.options.limits.max_vertices = a.max_vertices;
  return config;
}

// The smoothing stage, the same for every input: the selected method through libsmooth's one entry
// point (cross-slice smoothing by default), which also guards against a diverging run. For drawn contours
// (run_one) the cross-slice stage keeps the volume of the vertices between the slices unless
// --off-slice-volume says otherwise (OffSliceVolume::Preserve): they are interpolated, not read from an
// image, so its normal filter has no noise to remove there and would only round thin structures inwards
// (docs/contours.md).
SmoothResult smooth_reconstruction(const Mesh& mesh, MethodConfig config, ProgressDisplay& progress,
                                   const std::string& source) {
  config.options.progress = progress.callback();
  try {
    return smooth(mesh, config.method, config.options);
  } catch (const InvalidInputError&) {
    rethrow_with_context(source);
  }
}

// The labels of the reconstructed mesh from a method that has them (paper, cross-slice), for --labels-out.
void write_labels(const Mesh& mesh, const SmoothResult& r, const std::string& path, ProgressDisplay& progress) {
  if (r.labels.empty() || path.empty()) return;
  MeshWriteOptions labels;
  labels.point_scalars = label_arrays({r.labels, r.detection, r.creases, 0.0});
  labels.progress = progress.callback();
  write_mesh(mesh, path, labels);
}

// The JSON fields of the method: its name, preset, iterations, and what its stages found.
void add_method_json(nlohmann::json& j, const RunArgs& a, const SmoothResult& r) {
  j["method"] = std::string(to_string(r.method));
  if (const std::string p = preset_name(a.smoothing); !p.empty()) j["preset"] = p;
  j["iterations"] = r.iterations;
  if (!r.labels.empty()) {
    const LabelCounts counts = count_labels(r.labels);
    j["edge_vertices"] = counts.edges;
    j["corner_vertices"] = counts.corners;
    j["noise_vertices"] = counts.noise;
    j["seconds_detect"] = r.seconds.detect;
  }
  if (r.method == SmoothingMethod::FeaturePreserving) {
    j["subdivided_vertices"] = r.subdivided_vertices;
    j["seconds_subdivide"] = r.seconds.subdivide;
  }
  if (r.method == SmoothingMethod::CrossSlice) j["profiles"] = r.profiles;
}

// The summary line of the labels, when the method has them.
void print_features(const SmoothResult& r) {
  if (r.labels.empty()) return;
  const LabelCounts counts = count_labels(r.labels);
  std::cout << "  features    " << counts.edges << " edge, " << counts.corners << " corner, " << counts.noise
            << " noise vertices";
  if (r.method == SmoothingMethod::FeaturePreserving) std::cout << "; " << r.subdivided_vertices << " subdivided";
  std::cout << "\n";
}

// The vertices with distance_to_features(phantom, p) < radius, in order. The feature points are binned
// in a grid of cells at least `radius` wide, so each vertex looks at the points of the 27 cells around
// its own instead of all of them (on the skull phantom, 2138 points: 0.4 s -> a few ms). Any point
// closer than `radius` is in those cells, so the nearest one within reach, and the answer, are the
// same as a scan of every point gives.
std::vector<Index> vertices_near_features(const Phantom& phantom, const Eigen::Matrix3Xd& positions, double radius) {
  std::vector<Index> near;
  const auto& points = phantom.feature_points;
  if (points.empty() || !(radius > 0.0)) return near;
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& q : points) box.extend(q);
  const Eigen::Vector3d lo = box.min();
  Eigen::Array3i cells;
  double cell = radius;
  // At most ~ one cell per point (or 2^21 cells); larger cells are still at least `radius` wide.
  const double max_cells = std::max(static_cast<double>(points.size()), 64.0);
  for (;;) {
    const Eigen::Array3d n = ((box.max() - lo) / cell).array().floor() + 1.0;
    if (n.prod() <= max_cells && (n < 2e6).all()) {
      cells = n.cast<int>();
      break;
    }
    cell *= 2.0;
  }
  auto cell_of = [&](const Eigen::Vector3d& p) -> Eigen::Array3i {
    return (((p - lo) / cell).array().floor().max(-1.0).min((cells + 1).cast<double>())).cast<int>();
  };
  auto index = [&](const Eigen::Array3i& c) {
    return (static_cast<std::size_t>(c.z()) * cells.y() + c.y()) * cells.x() + c.x();
  };
  // Points per cell (CSR).
  std::vector<std::size_t> start(static_cast<std::size_t>(cells.prod()) + 1, 0), order(points.size());
  for (const Eigen::Vector3d& q : points) ++start[index(cell_of(q)) + 1];
  for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < points.size(); ++k) order[fill[index(cell_of(points[k]))]++] = k;
  }
  for (Index i = 0; i < positions.cols(); ++i) {
    const Eigen::Vector3d p = positions.col(i);
    if (!p.allFinite()) continue;  // no distance: never near
    const Eigen::Array3i c = cell_of(p);
    double best = std::numeric_limits<double>::infinity();
    for (int z = std::max(c.z() - 1, 0); z <= std::min(c.z() + 1, cells.z() - 1); ++z) {
      for (int y = std::max(c.y() - 1, 0); y <= std::min(c.y() + 1, cells.y() - 1); ++y) {
        for (int x = std::max(c.x() - 1, 0); x <= std::min(c.x() + 1, cells.x() - 1); ++x) {
          const std::size_t cc = index({x, y, z});
          for (std::size_t k = start[cc]; k < start[cc + 1]; ++k)
            best = std::min(best, (points[order[k]] - p).squaredNorm());
        }
      }
    }
    if (std::sqrt(best) < radius) near.push_back(i);
  }
  return near;
}

const std::vector<std::string> kVolumeOnly{"--shape",     "--spacing", "--noise",  "--contour-noise",
                                           "--blur",      "--seed",    "--threshold", "--feature-radius",
                                           "--label",     "--labels",  "--series", "--list-series"};

// One label of a label map that `run` meshes instead of thresholding the input.
struct LabelJob {
  const LabelMap* map = nullptr;
  Label label;
};
const std::vector<std::string> kContourOnly{"--roi", "--align", "--slab-thickness",
                                            "--planarity-tolerance", "--sampling-tolerance", "--sampling"};

// The chain on one volume, or on one label when `job` is set, written to `output` (and `labels_out`).
// With `collect`, the JSON summary is appended to it instead of being printed.
int run_run(const RunArgs& a, const std::string& output, const std::string& labels_out, const LabelJob* job,
            nlohmann::json* collect) {
  const auto start = std::chrono::steady_clock::now();
  const MethodConfig config = run_method_config(a, labels_out);
  // Fail on bad options and output paths before the work.
  MeshWriteOptions write_options;
  write_options.format = parse_mesh_format(a.format);
  if (write_options.format == MeshFormat::Auto) (void)format_from_extension(output);
  if (!labels_out.empty()) {
    if (!format_keeps_contour_ids(format_from_extension(labels_out))) {
      throw InvalidInputError(labels_out + ": labels need a .vtp or .ply file");
    }
  }
  if (!(a.feature_radius > 0.0)) throw InvalidInputError("--feature-radius must be > 0 mm");
  check_contour_noise(a.contour_noise);
  apply_common_options(a.common);
  ProgressDisplay progress("run", a.common.quiet);
  // The default output goes to out/: create the directory, then check it can take the file.
  const std::filesystem::path out(output);
  if (!out.parent_path().empty() && !std::filesystem::exists(out.parent_path())) {
    std::error_code ec;
    std::filesystem::create_directories(out.parent_path(), ec);
    if (ec) {
      throw InvalidInputError(output + ": cannot create the directory '" + out.parent_path().string() +
                              "': " + ec.message());
    }
  }
  check_output_path(out);
  if (!labels_out.empty()) check_output_path(labels_out);
  check_distinct_outputs({{"-o", output}, {"--labels-out", labels_out}});

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
  } else if (job) {
    image = label_mask(*job->map, job->label);
    source = a.input + " label '" + job->label.display_name() + "'";
  } else {
    VolumeReadOptions read = volume_read_options(a.volume, "run");
    read.series_uid = a.selection.series;
    image = read_volume(a.input, read);
    source = a.input;
  }
  const double seconds_volume = seconds_since(t);

  // 2. Reconstruct.
  ReconstructionOptions ro;
  ro.tiling = tiling_options(a.tiling);
  ro.single_slice = parse_single_slice(a.contour.single_slice);
  ro.off_slice.placement = off_slice_placement(a.volume);
  ro.segmentation.flat_crossings = flat_crossings(a.volume);
  // A phantom is segmented at its partial-volume iso-level, real CT at the bone default.
  const PhantomVolumeOptions phantom_defaults;
  ro.segmentation.threshold =
      a.threshold.value_or(phantom ? 0.5 * (phantom_defaults.bone_hu + phantom_defaults.tissue_hu) : 300.0);
  if (job) ro.segmentation.threshold = 0.5 * kLabelMaskInside;  // the label's voxels (label_map.h)
  ro.tiling.limits.max_vertices = a.max_vertices;
  ro.segmentation.limits.max_vertices = a.max_vertices;
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
  const SmoothResult smoothed = smooth_reconstruction(mesh, config, progress, source);
  const Mesh& result = smoothed.mesh;
  const double seconds_smooth = seconds_since(t);

  // 4. Export. The summary's topology is computed meanwhile when a second thread is allowed.
  std::future<TopologySummary> topology =
      std::async(available_threads() > 1 ? std::launch::async : std::launch::deferred,
                 [&result] { return summarize_topology(result); });
  t = std::chrono::steady_clock::now();
  progress.stage("write");
  write_options.progress = progress.callback();
  write_mesh(result, out, write_options);
  write_labels(mesh, smoothed, labels_out, progress);
  progress.finish();
  const double seconds_write = seconds_since(t);

  const TopologySummary topo = topology.get();
  const double v0 = enclosed_volume(mesh);
  const double v1 = enclosed_volume(result);
  nlohmann::json j;
  j["command"] = "run";
  j["source"] = source;
  j["output"] = output;
  if (!labels_out.empty()) j["labels_out"] = labels_out;
  add_method_json(j, a, smoothed);
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
  // Against a phantom: accuracy over the surfaces (samples on the mesh and on the truth), as `compare`
  // measures it; the distances at vertices stay in the JSON as a secondary figure (they flatter the
  // unsmoothed mesh, whose vertices lie on the contours by construction).
  SurfaceAccuracy surface_before, surface_after;
  if (phantom) {
    const std::vector<Index> feature_vertices = vertices_near_features(*phantom, mesh.positions, a.feature_radius);
    const DistanceStats before = distance_to_surface(mesh.positions, phantom->sdf);
    const DistanceStats after = distance_to_surface(result.positions, phantom->sdf);
    const DistanceStats feature_before = distance_to_surface(mesh.positions, phantom->sdf, feature_vertices);
    const DistanceStats feature_after = distance_to_surface(result.positions, phantom->sdf, feature_vertices);
    const SurfaceTruth truth = phantom_surface_truth(*phantom);
    SurfaceMetricsOptions mo;
    mo.feature_radius = a.feature_radius;
    surface_before = surface_accuracy(mesh.positions, mesh.triangles, truth, mo);
    surface_after = surface_accuracy(result.positions, result.triangles, truth, mo);
    j["truth_volume"] = phantom->volume;
    j["surface_rms_before"] = surface_before.all.rms;
    j["surface_rms_after"] = surface_after.all.rms;
    j["surface_feature_rms_before"] = surface_before.feature.rms;
    j["surface_feature_rms_after"] = surface_after.feature.rms;
    j["surface_hausdorff_before"] = surface_before.all.hausdorff;
    j["surface_hausdorff_after"] = surface_after.all.hausdorff;
    j["normal_error_degrees_before"] = surface_before.all.normal_error_degrees;
    j["normal_error_degrees_after"] = surface_after.all.normal_error_degrees;
    j["rms_distance_before"] = before.rms;
    j["rms_distance_after"] = after.rms;
    j["feature_rms_distance_before"] = feature_before.rms;
    j["feature_rms_distance_after"] = feature_after.rms;
    j["feature_vertices"] = feature_vertices.size();
  }
  j["seconds"] = seconds_since(start);
  if (job) {
    j["label"] = job->label.display_name();
    j["label_value"] = job->label.value;
    j["label_voxels"] = job->label.voxels;
  }
  if (collect) {
    collect->push_back(j);
    if (a.json) return kOk;
  }
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
  print_features(smoothed);
  std::cout << "  smoothing   " << describe_selection(a.smoothing, smoothed.method) << ": volume "
            << std::setprecision(1) << v0 << " -> " << v1 << " mm^3 (" << std::setprecision(2) << 100.0 * (v1 - v0) / v0
            << " %)\n";
  if (phantom) {
    std::cout << std::setprecision(3) << "  accuracy    over the surface, unsmoothed -> smoothed: two-sided RMS "
              << surface_before.all.rms << " -> " << surface_after.all.rms << " mm; within " << std::setprecision(1)
              << a.feature_radius << std::setprecision(3) << " mm of sharp features "
              << fixed(surface_before.feature.rms, 3) << " -> " << fixed(surface_after.feature.rms, 3)
              << " mm; normal error " << std::setprecision(2) << surface_before.all.normal_error_degrees << " -> "
              << surface_after.all.normal_error_degrees << " deg\n";
  }
  std::cout << std::setprecision(2) << "  seconds     volume " << seconds_volume << ", segment "
            << rec.report.seconds_segment << ", tile " << rec.report.seconds_tile << ", smooth " << seconds_smooth
            << ", write " << seconds_write << ", total " << seconds_since(start) << "\n"
            << "  wrote       " << output << (labels_out.empty() ? "" : " and " + labels_out) << "\n";
  return kOk;
}

// `run` on a volume: --list-series, one label after the other with --label / --labels, or the volume.
int run_volume(const RunArgs& a) {
  if (a.selection.list_series) return print_series_list(a.input, a.json);
  (void)tiling_options(a.tiling);  // refuse bad tiling options before any work
  if (!labels_requested(a.selection)) return run_run(a, a.output, a.labels_out, nullptr, nullptr);
  if (a.input.empty()) throw InvalidInputError("--label and --labels need an input label map");
  const auto start = std::chrono::steady_clock::now();
  const SelectedLabels selected = read_selected_labels(a.input, a.selection);
  for (const Label& label : selected.labels) {
    check_output_path(label_output_path(a.output, label, a.selection));
    if (!a.labels_out.empty()) check_output_path(label_output_path(a.labels_out, label, a.selection));
  }
  nlohmann::json meshes = nlohmann::json::array();
  for (const Label& label : selected.labels) {
    const LabelJob job{&selected.map, label};
    const std::string labels_out =
        a.labels_out.empty() ? std::string() : label_output_path(a.labels_out, label, a.selection).string();
    const int code = run_run(a, label_output_path(a.output, label, a.selection).string(), labels_out, &job, &meshes);
    if (code != kOk) return code;
  }
  if (a.json)
    print_json({{"command", "run"}, {"input", a.input}, {"labels", meshes}, {"seconds", seconds_since(start)}});
  return kOk;
}

// One ROI (or contour file): tiled, smoothed by the same stage as a CT volume, written, and measured
// against its drawn contours before and after smoothing; its JSON object.
nlohmann::json run_one(const RunArgs& a, const MethodConfig& config, InputKind kind, const ContourInput& in,
                       const std::filesystem::path& output, const std::filesystem::path& labels,
                       const MeshWriteOptions& write_options, ProgressDisplay& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const ContourReconstruction rec = reconstruct_from_contours(
      in.stack, in.what, contour_options(a.contour, in, a.sampling, tiling_options(a.tiling), a.max_vertices),
      progress.callback());
  print_warnings("run", rec.report.warnings);
  auto t = std::chrono::steady_clock::now();
  MethodConfig drawn = config;
  if (!a.smoothing.off_slice_volume) drawn.options.cross_slice.off_slice.volume = OffSliceVolume::Preserve;
  const SmoothResult smoothed = smooth_reconstruction(rec.mesh, drawn, progress, in.what);
  const double seconds_smooth = seconds_since(t);
  t = std::chrono::steady_clock::now();
  progress.stage("write");
  write_mesh(smoothed.mesh, output, write_options);
  write_labels(rec.mesh, smoothed, labels.string(), progress);
  const double seconds_write = seconds_since(t);
  const TopologySummary topo = summarize_topology(smoothed.mesh);
  const double v0 = enclosed_volume(rec.mesh);
  const double v1 = enclosed_volume(smoothed.mesh);
  const ContourDeviation before = contour_deviation(rec.mesh, in.stack);
  const ContourDeviation after = contour_deviation(smoothed.mesh, in.stack);
  nlohmann::json j;
  j["status"] = "ok";
  describe_input(j, in);
  j["output"] = output.string();
  if (!labels.empty()) j["labels_out"] = labels.string();
  add_method_json(j, a, smoothed);
  j["slices"] = rec.report.slices;
  j["contours"] = rec.report.contours;
  j["hole_contours"] = rec.report.hole_contours;
  j["points_drawn"] = rec.report.points_drawn;
  j["slabs"] = rec.report.slabs;
  j["vertices"] = smoothed.mesh.num_vertices();
  j["faces"] = smoothed.mesh.num_faces();
  j["components"] = topo.components;
  j["is_closed"] = topo.closed;
  j["is_manifold"] = topo.manifold;
  j["euler_characteristic"] = topo.euler_characteristic;
  j["slicewise_volume"] = rec.report.slicewise_volume;
  j["volume_before"] = v0;
  j["volume_after"] = v1;
  j["volume_change_percent"] = 100.0 * (v1 - v0) / v0;
  j["contour_deviation_before_mean"] = before.mean;
  j["contour_deviation_before_max"] = before.max;
  j["contour_deviation_after_mean"] = after.mean;
  j["contour_deviation_after_rms"] = after.rms;
  j["contour_deviation_after_max"] = after.max;
  j["slices_without_section_after"] = after.slices_without_section;
  j["seconds_tile"] = rec.report.seconds_tile;
  j["seconds_smooth"] = seconds_smooth;
  j["seconds_write"] = seconds_write;
  j["seconds"] = seconds_since(t0);
  if (a.json || a.common.quiet) return j;
  std::cout << std::fixed << std::setprecision(2) << "ContourMesh: " << in.what
            << (kind == InputKind::StructureSet ? " of " + a.input : "") << "\n"
            << "  contours    " << rec.report.contours << " on " << rec.report.slices << " slices ("
            << rec.report.hole_contours << (rec.report.hole_contours == 1 ? " hole, " : " holes, ")
            << rec.report.tiling.branchings << " branchings, " << rec.report.slabs << " single-slice slabs)\n"
            << "  mesh        " << smoothed.mesh.num_vertices() << " vertices, " << smoothed.mesh.num_faces()
            << " triangles, " << (topo.closed ? "closed" : "OPEN") << ", "
            << (topo.manifold ? "manifold" : "NOT manifold") << ", Euler characteristic " << topo.euler_characteristic
            << "\n";
  print_features(smoothed);
  std::cout << "  smoothing   " << describe_selection(a.smoothing, smoothed.method) << ": volume "
            << std::setprecision(1) << v0 << " -> " << v1 << " mm^3 (" << std::setprecision(2) << 100.0 * (v1 - v0) / v0
            << " %; slice-wise " << std::setprecision(1) << rec.report.slicewise_volume << ")\n"
            << std::setprecision(3) << "  contours    in-plane distance to the drawn contours: mean " << before.mean
            << " -> " << after.mean << " mm, largest " << before.max << " -> " << after.max << " mm\n"
            << std::setprecision(2) << "  seconds     tile " << rec.report.seconds_tile << ", smooth " << seconds_smooth
            << ", write " << seconds_write << ", total " << seconds_since(t0) << "\n"
            << "  wrote       " << output.string() << (labels.empty() ? "" : " and " + labels.string()) << "\n";
  return j;
}

// The contour route: drawn contours (an RT Structure Set ROI, or all of them, or a contour file) ->
// tiling -> the same smoothing -> export.
int run_contours(const RunArgs& a, InputKind kind, bool output_given) {
  const auto start = std::chrono::steady_clock::now();
  const MethodConfig config = run_method_config(a, a.labels_out);
  (void)tiling_options(a.tiling);
  MeshWriteOptions write_options;
  write_options.format = parse_mesh_format(a.format);
  apply_common_options(a.common);
  ProgressDisplay progress("run", a.common.quiet);
  progress.stage("read");
  const ContourInputs loaded = load_contour_inputs(a.input, kind, a.contour);
  print_warnings("run", loaded.warnings);
  print_warnings("run", loaded.skipped);
  // Without -o: out/<ROI>.stl, or the directory out/ for --roi all.
  const std::string output =
      output_given ? a.output : (loaded.all ? std::string("out") : "out/" + loaded.inputs[0].stem + ".stl");
  const MeshFormat f = write_options.format;
  const std::string extension = f == MeshFormat::Auto || f == MeshFormat::StlBinary || f == MeshFormat::StlAscii
                                    ? ".stl"
                                    : "." + std::string(to_string(f));
  const auto outputs = roi_outputs(output, loaded, extension);
  const auto labels = roi_outputs(a.labels_out, loaded, "_labels.vtp");
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    if (f == MeshFormat::Auto) (void)format_from_extension(outputs[i]);
    if (!labels[i].empty() && !format_keeps_contour_ids(format_from_extension(labels[i]))) {
      throw InvalidInputError(labels[i].string() + ": labels need a .vtp or .ply file");
    }
  }
  std::size_t failed = 0;
  nlohmann::json rois = for_each_roi(
      "run", a.input, loaded,
      [&](const ContourInput& in, std::size_t i) {
        return run_one(a, config, kind, in, outputs[i], labels[i], write_options, progress);
      },
      failed);
  progress.finish();
  if (a.json) print_json(roi_results_json("run", a.input, loaded, std::move(rois), failed, start));
  if (failed > 0 && !a.json)
    std::cerr << "contourmesh run: " << failed << " of " << loaded.inputs.size() << " ROIs failed\n";
  return failed > 0 ? kBadInput : kOk;
}

int run_any(const RunArgs& a, const CLI::App* cmd) {
  const InputKind kind = a.input.empty() ? InputKind::Volume : input_kind(a.input);
  if (kind == InputKind::Volume) {
    reject_options(cmd, kContourOnly, "applies to contours (an RT Structure Set or a .json contour file)");
    return run_volume(a);
  }
  reject_options(cmd, kVolumeOnly, "applies to CT volumes and phantoms, not to contours");
  return run_contours(a, kind, cmd->count("--output") > 0);
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand(
      "run",
      "The whole pipeline: volume (or a built-in phantom, or drawn contours) -> contours -> mesh -> smoothing -> file");
  CLI::Option* input = cmd->add_option("input", args->input,
                  "CT volume or DICOM directory, RT Structure Set (with --roi) or contour file (.json); none: the "
                  "built-in phantom --shape");
  cmd->add_option("-o,--output", args->output,
                  "Output mesh (.stl .ply .vtp .obj); format from the extension unless --format")
      ->capture_default_str();
  cmd->add_option("--format", args->format, "Output format: auto | stl | stl-ascii | ply | vtp | obj")
      ->capture_default_str();
  cmd->add_option(
      "--labels-out", args->labels_out,
      "paper, cross-slice: also write the reconstructed mesh with per-vertex labels and curvatures (.vtp or .ply)");
  cmd->add_option("--shape", args->shape, "Phantom when no input: " + phantom_shape_names(" | "))
      ->capture_default_str();
  cmd->add_option("--spacing", args->spacing, "Phantom voxel size, mm: sx,sy,sz")->capture_default_str();
  cmd->add_option("--noise", args->noise, "Phantom Gaussian noise, HU")->capture_default_str();
  add_contour_noise_option(cmd, args->contour_noise)->excludes(input);
  cmd->add_option("--blur", args->blur, "Phantom Gaussian blur, mm")->capture_default_str();
  cmd->add_option("--seed", args->seed, "Phantom noise seed")->capture_default_str();
  CLI::Option* threshold = cmd->add_option("--threshold", args->threshold,
                  "Bone threshold, HU (default: 300 for an input volume; 520 for a phantom, halfway between its "
                  "soft tissue and bone)");
  add_tiling_options(cmd, args->tiling);
  add_method_options(cmd, args->smoothing);
  cmd->add_option("--feature-radius", args->feature_radius,
                  "Phantom: the surface this close to a sharp edge or corner forms the feature region, mm")
      ->capture_default_str();
  cmd->add_option("--sampling", args->sampling, "Contours: largest distance between contour points, mm (0: as drawn)")
      ->default_str("1");
  add_contour_options(cmd, args->contour);
  add_detection_options(cmd, args->detection);
  add_volume_options(cmd, args->volume);
  add_input_selection_options(cmd, args->selection, {threshold});
  add_common_options(cmd, args->common);
  add_max_vertices_option(cmd, args->max_vertices);
  cmd->add_flag("--json", args->json, "Print one JSON object on stdout instead of the summary");
  cmd->callback([args, cmd] { set_exit_code(run_guarded("run", [&] { return run_any(*args, cmd); })); });
}

}  // namespace contourmesh::cli
