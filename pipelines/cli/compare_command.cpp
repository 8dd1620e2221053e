// contourmesh compare [--phantom NAME|all | IN [--truth SURFACE]] --out DIR: every smoothing method, VTK's
// filters and 3D Slicer's voxel route on the same volume, measured against the truth, with tables,
// plots, renders and report.html (pipelines/comparison_report.h does the work).
#include "cli_common.h"
#include "progress_display.h"
#include "volume_options.h"

#include <pipelines/atomic_file.h>
#include <pipelines/comparison.h>
#include <pipelines/comparison_report.h>
#include <pipelines/mesh_io.h>
#include <reconstruct/phantom.h>
#include <reconstruct/volume.h>
#include <smooth/errors.h>
#include <smooth/limits.h>

#include <CLI/CLI.hpp>

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace contourmesh::cli {

namespace {

namespace fs = std::filesystem;

struct CompareArgs {
  std::string input;
  std::string phantom;
  std::string truth;
  std::string out;
  std::string markdown;
  std::string note;
  std::string spacing = "0.7,0.7,2";
  double noise = 20.0;
  double contour_noise = 0.0;
  double blur = 0.5;
  std::uint64_t seed = 1;
  std::optional<double> threshold;
  double feature_radius = 2.0;
  double detection_radius = 0.8;
  int repeat = 1;
  std::string render_size = "640x480";
  int color_levels = 256;
  bool no_render = false;
  bool no_curves = false;
  Index max_vertices = kDefaultMaxVertices;
  bool json = false;
  VolumeArgs volume;
  CommonArgs common;
};

// The command as typed, for the reports (options at their defaults left out, and the --note that the
// reports print anyway).
std::string command_line(const CompareArgs& a) {
  std::ostringstream s;
  s << "contourmesh compare";
  if (!a.input.empty()) s << " " << a.input;
  if (!a.truth.empty()) s << " --truth " << a.truth;
  if (!a.phantom.empty()) s << " --phantom " << a.phantom;
  s << " --out " << a.out;
  if (a.input.empty()) {
    if (a.spacing != "0.7,0.7,2") s << " --spacing " << a.spacing;
    if (a.noise != 20.0) s << " --noise " << a.noise;
    if (a.contour_noise != 0.0) s << " --contour-noise " << a.contour_noise;
    if (a.blur != 0.5) s << " --blur " << a.blur;
    if (a.seed != 1) s << " --seed " << a.seed;
  }
  if (a.threshold) s << " --threshold " << *a.threshold;
  if (a.feature_radius != 2.0) s << " --feature-radius " << a.feature_radius;
  if (a.detection_radius != 0.8) s << " --detection-radius " << a.detection_radius;
  if (a.repeat != 1) s << " --repeat " << a.repeat;
  if (a.render_size != "640x480") s << " --render-size " << a.render_size;
  if (a.color_levels != 256) s << " --color-levels " << a.color_levels;
  if (a.no_render) s << " --no-render";
  if (a.no_curves) s << " --no-curves";
  if (!a.markdown.empty()) s << " --markdown " << a.markdown;
  return s.str();
}

// "WxH", each in [16, 4096].
std::pair<int, int> parse_render_size(const std::string& text) {
  const std::size_t x = text.find('x');
  int w = 0, h = 0;
  try {
    std::size_t used_w = 0, used_h = 0;
    if (x == std::string::npos) throw std::invalid_argument("no x");
    w = std::stoi(text.substr(0, x), &used_w);
    h = std::stoi(text.substr(x + 1), &used_h);
    if (used_w != x || used_h != text.size() - x - 1) throw std::invalid_argument("trailing text");
  } catch (const std::exception&) {
    w = h = 0;
  }
  if (w < 16 || h < 16 || w > 4096 || h > 4096) {
    throw InvalidInputError("--render-size must be WIDTHxHEIGHT in pixels, 16 to 4096 each (e.g. 640x480), got '" +
                            text + "'");
  }
  return {w, h};
}

// Creates `dir` (and parents) and checks that files can be written in it: exit 2 before any work.
void prepare_directory(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) {
    throw InvalidInputError(dir.string() + ": exists and is not a directory");
  }
  fs::create_directories(dir, ec);
  if (ec) throw InvalidInputError(dir.string() + ": cannot create the output directory: " + ec.message());
  check_output_path(dir / "report.html");
}

void print_summary(const std::string& name, const Comparison& c, const ComparisonFiles& files, const fs::path& dir) {
  std::cout << std::fixed << name << ": " << c.source << "\n  contour mesh " << c.contour_mesh.num_vertices()
            << " vertices; truth: " << (c.truth == TruthKind::None ? "none (no distance metrics)" : c.truth_description)
            << "\n";
  std::cout << "  " << std::left << std::setw(26) << "method" << std::right << std::setw(10) << "RMS mm"
            << std::setw(12) << "feature mm" << std::setw(10) << "dV %" << std::setw(10) << "seconds"
            << "\n";
  for (const MethodResult& m : c.methods) {
    std::cout << "  " << std::left << std::setw(26) << m.name << std::right << std::setprecision(3) << std::setw(10);
    if (m.all)
      std::cout << m.all->distance.rms;
    else
      std::cout << "-";
    std::cout << std::setw(12);
    if (m.feature)
      std::cout << m.feature->distance.rms;
    else
      std::cout << "-";
    std::cout << std::setprecision(2) << std::setw(10) << m.volume_change_percent << std::setprecision(3)
              << std::setw(10) << m.stage_seconds("total") << "\n";
  }
  if (!files.rendered) std::cout << "  no renders: " << files.render_note << "\n";
  std::cout << "  wrote " << (dir / "report.html").string() << " and " << files.files.size() - 1 << " other files\n";
}

int run_compare(const CompareArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  apply_common_options(a.common);
  if (a.repeat < 1) throw InvalidInputError("--repeat must be >= 1");
  if (!(a.feature_radius > 0.0)) throw InvalidInputError("--feature-radius must be > 0 mm");
  if (!(a.detection_radius > 0.0)) throw InvalidInputError("--detection-radius must be > 0 mm");
  (void)parse_render_size(a.render_size);
  if (a.color_levels < 2 || a.color_levels > 256) throw InvalidInputError("--color-levels must be in [2, 256]");

  // What to compare: phantoms (one or all) or one volume.
  std::vector<PhantomShape> shapes;
  if (a.input.empty()) {
    const std::string name = a.phantom.empty() ? "femur" : a.phantom;
    if (name == "all")
      shapes = all_phantom_shapes();
    else
      shapes.push_back(parse_phantom_shape(name));
  }
  const bool several = shapes.size() > 1;
  PhantomVolumeOptions volume_options;
  volume_options.spacing = parse_spacing(a.spacing);
  volume_options.noise = a.noise;
  volume_options.contour_noise = a.contour_noise;
  volume_options.blur = a.blur;
  volume_options.seed = a.seed;
  if (!(a.noise >= 0.0)) throw InvalidInputError("--noise must be a sigma >= 0 in HU");
  if (!(a.blur >= 0.0)) throw InvalidInputError("--blur must be a sigma >= 0 in mm");
  check_contour_noise(a.contour_noise);

  // Outputs are checked before the work.
  const fs::path out(a.out);
  prepare_directory(out);
  for (PhantomShape s : shapes) {
    if (several) prepare_directory(out / std::string(to_string(s)));
  }
  if (!a.markdown.empty()) check_output_path(a.markdown);

  ComparisonOptions options;
  options.feature_radius = a.feature_radius;
  options.detection_radius = a.detection_radius;
  options.timing_repeats = a.repeat;
  options.volume_curves = !a.no_curves;
  options.reconstruction.tiling.limits.max_vertices = a.max_vertices;
  options.paper.limits.max_vertices = a.max_vertices;
  ComparisonReportOptions report;
  report.renders = !a.no_render;
  std::tie(report.render_width, report.render_height) = parse_render_size(a.render_size);
  report.color_levels = a.color_levels;
  report.command_line = command_line(a);
  report.note = a.note;

  ProgressDisplay progress("compare", a.common.quiet);
  options.progress = progress.callback();

  // Each comparison is kept for the summary.
  std::vector<std::unique_ptr<Comparison>> comparisons;
  std::vector<ComparisonEntry> entries;
  const auto compare_one = [&](const std::string& name, const CtImage& image, const std::string& source,
                               const ComparisonTruth& truth, const fs::path& dir) {
    auto c = std::make_unique<Comparison>(run_comparison(image, source, truth, options));
    progress.stage("write");
    ComparisonFiles files = write_comparison(*c, dir, report);
    progress.finish();
    entries.push_back({name, dir, c.get(), std::move(files)});
    comparisons.push_back(std::move(c));
  };

  if (a.input.empty()) {
    for (PhantomShape shape : shapes) {
      const std::string name(to_string(shape));
      progress.stage("phantom");
      const Phantom phantom = make_phantom(shape);
      const CtImage::Pointer image = render_phantom(phantom, volume_options);
      std::ostringstream source;
      source << "phantom '" << name << "' (" << volume_options.spacing.x() << " x " << volume_options.spacing.y()
             << " x " << volume_options.spacing.z() << " mm voxels, " << volume_options.noise << " HU noise, ";
      if (volume_options.contour_noise > 0.0) source << volume_options.contour_noise << " mm contour noise, ";
      source << volume_options.blur << " mm blur, seed " << volume_options.seed << ")";
      options.reconstruction.segmentation.threshold =
          a.threshold.value_or(0.5 * (volume_options.bone_hu + volume_options.tissue_hu));
      compare_one(name, *image, source.str(), phantom_truth(phantom), several ? out / name : out);
    }
  } else {
    std::optional<Mesh> reference;
    if (!a.truth.empty()) {
      MeshReadOptions ro;
      ro.max_vertices = a.max_vertices;
      reference = read_mesh(a.truth, ro);
    }
    progress.stage("read");
    const CtImage::Pointer image = read_volume(a.input, volume_read_options(a.volume, "compare"));
    options.reconstruction.segmentation.threshold = a.threshold.value_or(300.0);
    const ComparisonTruth truth =
        reference ? reference_surface_truth(*reference, "reference surface " + a.truth) : ComparisonTruth{};
    compare_one(fs::path(a.input).filename().string(), *image, a.input, truth, out);
  }

  std::vector<fs::path> summary_files;
  if (several) summary_files = write_comparison_summary(entries, out, report);
  if (!a.markdown.empty()) write_comparison_markdown(entries, a.markdown, report);

  if (a.json) {
    nlohmann::json j;
    j["command"] = "compare";
    j["output"] = a.out;
    nlohmann::json list = nlohmann::json::array();
    for (const ComparisonEntry& e : entries) {
      nlohmann::json item;
      item["name"] = e.name;
      item["directory"] = e.directory.string();
      item["rendered"] = e.files.rendered;
      item["render_note"] = e.files.render_note;
      nlohmann::json files = nlohmann::json::array();
      for (const fs::path& f : e.files.files) files.push_back(f.string());
      item["files"] = files;
      item["metrics"] = nlohmann::json::parse(metrics_json(*e.comparison));
      list.push_back(item);
    }
    j["comparisons"] = list;
    if (several) {
      nlohmann::json files = nlohmann::json::array();
      for (const fs::path& f : summary_files) files.push_back(f.string());
      j["summary_files"] = files;
    }
    if (!a.markdown.empty()) j["markdown"] = a.markdown;
    j["seconds"] = seconds_since(start);
    print_json(j);
    return kOk;
  }
  if (a.common.quiet) return kOk;
  for (const ComparisonEntry& e : entries) print_summary(e.name, *e.comparison, e.files, e.directory);
  if (several) std::cout << "summary: " << (out / "report.html").string() << "\n";
  if (!a.markdown.empty()) std::cout << "markdown: " << a.markdown << "\n";
  std::cout << std::setprecision(1) << "total " << seconds_since(start) << " s\n";
  return kOk;
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Every smoothing method, VTK's filters and 3D Slicer's voxel route on one volume, measured against the truth: "
      "metrics.csv/json, volume curves, renders, report.html");
  CLI::Option* input =
      cmd->add_option("input", args->input, "CT volume or DICOM directory (default: the phantom --phantom)");
  CLI::Option* phantom = cmd->add_option("--phantom", args->phantom,
                                         "Phantom to compare on, or 'all' (one subdirectory each, plus a summary): " +
                                             phantom_shape_names(" | ") + " | all (default femur)");
  CLI::Option* truth = cmd->add_option("--truth", args->truth,
                                       "With an input volume: reference surface mesh to measure distances against");
  phantom->excludes(input);
  truth->needs(input);
  truth->excludes(phantom);
  cmd->add_option("-o,--out", args->out, "Output directory (created if missing)")->required();
  cmd->add_option("--markdown", args->markdown, "Also write a Markdown page of the results (links relative to it)");
  cmd->add_option("--note", args->note, "A paragraph to add under the title of the reports");
  cmd->add_option("--spacing", args->spacing, "Phantom voxel size, mm: sx,sy,sz")->capture_default_str();
  cmd->add_option("--noise", args->noise, "Phantom Gaussian noise, HU")->capture_default_str();
  add_contour_noise_option(cmd, args->contour_noise)->excludes(input);
  cmd->add_option("--blur", args->blur, "Phantom Gaussian blur, mm")->capture_default_str();
  cmd->add_option("--seed", args->seed, "Phantom noise seed")->capture_default_str();
  cmd->add_option("--threshold", args->threshold,
                  "Bone threshold of both routes, HU (default: 520 for a phantom, 300 for an input volume)");
  cmd->add_option("--feature-radius", args->feature_radius,
                  "Phantom: vertices this close to a sharp edge or corner form the feature region, mm")
      ->capture_default_str();
  cmd->add_option("--detection-radius", args->detection_radius,
                  "Phantom: vertices this close to a sharp edge or corner are the true features that detection is "
                  "scored against, mm")
      ->capture_default_str();
  cmd->add_option("--repeat", args->repeat, "Time each method this many times and report the fastest")
      ->capture_default_str();
  cmd->add_option("--render-size", args->render_size, "Size of the renders in pixels, WIDTHxHEIGHT")
      ->capture_default_str();
  cmd->add_option("--color-levels", args->color_levels,
                  "Levels per colour channel in the renders (2-256): 32 halves the PNG files")
      ->capture_default_str();
  cmd->add_flag("--no-render", args->no_render, "Skip the PNG renders of the meshes (they need an X display)");
  cmd->add_flag("--no-curves", args->no_curves, "Skip the volume-shrinking curves (saves the extra runs)");
  add_volume_options(cmd, args->volume);
  add_common_options(cmd, args->common);
  add_max_vertices_option(cmd, args->max_vertices);
  cmd->add_flag("--json", args->json, "Print one JSON object on stdout instead of the summary");
  cmd->callback([args] { set_exit_code(run_guarded("compare", [&] { return run_compare(*args); })); });
}

}  // namespace contourmesh::cli
