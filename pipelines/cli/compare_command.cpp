// SPDX-License-Identifier: BSD-3-Clause
// contourmesh compare [--phantom NAME|all | IN [--truth SURFACE]] --out DIR: every smoothing method, VTK's
// filters and 3D Slicer's voxel route on the same volume, measured against the truth over the surface,
// in one or several noise regimes and seeds, with tables, plots, renders, verdicts and report.html
// (the contourmesh_compare target does the work; the renders run in a child process here).
#include "cli_common.h"
#include "isolated_process.h"
#include "progress_display.h"
#include "volume_options.h"

#include <compare/comparison.h>
#include <compare/report.h>
#include <compare/series.h>
#include <compare/verdicts.h>
#include <contourmesh/vtk/atomic_file.h>
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/reconstruct/phantom.h>
#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/limits.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
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
  std::string seeds;
  std::string regimes;
  std::optional<double> threshold;
  double feature_radius = 1.5;
  double detection_radius = 1.5;
  int iterations = default_iterations(SmoothingMethod::Taubin);
  std::string methods;
  std::vector<std::string> variants;
  int repeat = 1;
  std::string render_size = "640x480";
  std::string render_methods;
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
    if (!a.regimes.empty()) s << " --regimes " << a.regimes;
    if (!a.seeds.empty()) s << " --seeds " << a.seeds;
    if (a.spacing != "0.7,0.7,2") s << " --spacing " << a.spacing;
    if (a.noise != 20.0) s << " --noise " << a.noise;
    if (a.contour_noise != 0.0) s << " --contour-noise " << a.contour_noise;
    if (a.blur != 0.5) s << " --blur " << a.blur;
    if (a.seed != 1) s << " --seed " << a.seed;
  }
  if (a.threshold) s << " --threshold " << *a.threshold;
  if (a.feature_radius != 1.5) s << " --feature-radius " << a.feature_radius;
  if (a.detection_radius != 1.5) s << " --detection-radius " << a.detection_radius;
  if (a.iterations != default_iterations(SmoothingMethod::Taubin)) s << " --iterations " << a.iterations;
  if (!a.methods.empty()) s << " --methods " << a.methods;
  for (const std::string& v : a.variants) s << " --variant " << v;
  if (a.repeat != 1) s << " --repeat " << a.repeat;
  if (a.render_size != "640x480") s << " --render-size " << a.render_size;
  if (!a.render_methods.empty()) s << " --render-methods " << a.render_methods;
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

// A comma-separated list.
std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream s(text);
  for (std::string item; std::getline(s, item, ',');) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
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

void print_summary(const Series& s, const ComparisonFiles& files, const fs::path& dir) {
  const Comparison& c = s.first();
  std::cout << s.name << " (" << s.regime.name << "): " << c.source;
  if (s.seeds.size() > 1) std::cout << ", means over " << s.seeds.size() << " seeds";
  std::cout << "\n  contour mesh " << c.contour_mesh.num_vertices() << " vertices; truth: "
            << (c.truth == TruthKind::None ? "none (no distance metrics)" : c.truth_description) << "\n";
  std::cout << "  " << std::left << std::setw(26) << "method" << std::right << std::setw(10) << "RMS mm"
            << std::setw(12) << "feature mm" << std::setw(10) << "normal" << std::setw(10) << "dV %" << std::setw(10)
            << "seconds\n";
  for (const MethodSummary& m : s.mean) {
    std::cout << "  " << std::left << std::setw(26) << m.spec.id << std::right << std::setw(10) << fixed(m.rms, 3)
              << std::setw(12) << fixed(m.feature_rms, 3) << std::setw(10) << fixed(m.normal_error, 2)
              << std::setw(10) << fixed(m.volume_change_percent, 2) << std::setw(10)
              << fixed(m.stage_seconds("total"), 3) << "\n";
  }
  if (!files.rendered) std::cout << "  no renders: " << files.render_note << "\n";
  std::cout << "  wrote " << (dir / "report.html").string() << " and " << files.files.size() - 1 << " other files\n";
}

// What to compare: the phantoms, regimes and seeds, or one input volume.
struct Plan {
  std::vector<PhantomShape> shapes;
  std::vector<Regime> regimes;
  std::vector<std::uint64_t> seeds;
};

Plan make_plan(const CompareArgs& a) {
  Plan p;
  if (!a.input.empty()) {
    p.regimes = {Regime{"input", 0.0, 0.0}};
    return p;
  }
  const std::string name = a.phantom.empty() ? "femur" : a.phantom;
  p.shapes = name == "all" ? all_phantom_shapes() : std::vector<PhantomShape>{parse_phantom_shape(name)};
  if (!a.regimes.empty()) {
    p.regimes = parse_regimes(a.regimes);
  } else if (name == "all") {
    p.regimes = default_regimes();
  } else {
    // One regime from --noise and --contour-noise.
    if (!(a.noise >= 0.0)) throw InvalidInputError("--noise must be a sigma >= 0 in HU");
    check_contour_noise(a.contour_noise);
    std::ostringstream regime;
    if (a.contour_noise > 0.0) regime << "contour" << a.contour_noise << "-";
    regime << "ct" << a.noise;
    p.regimes = {parse_regime(regime.str())};
  }
  p.seeds = a.seeds.empty() ? std::vector<std::uint64_t>{a.seed} : parse_seeds(a.seeds);
  return p;
}

nlohmann::json verdicts_json(const Verdicts& v) {
  nlohmann::json rows = nlohmann::json::array();
  for (const VerdictRow& r : v.rows) {
    nlohmann::json row = {{"phantom", r.phantom}, {"regime", r.regime}};
    const std::pair<const char*, const BarVerdict*> bars[] = {
        {"do_no_harm", &r.harm}, {"beat_voxel_route", &r.voxel}, {"denoise", &r.denoise}, {"detection", &r.detection}};
    for (const auto& [name, bar] : bars) row[name] = std::string(to_string(bar->state));
    rows.push_back(row);
  }
  return rows;
}

// The options of the comparison and of its reports, checked before any work (exit 2).
struct Setup {
  Plan plan;
  ComparisonOptions options;
  ComparisonReportOptions report;
};

Setup make_setup(const CompareArgs& a) {
  if (a.repeat < 1) throw InvalidInputError("--repeat must be >= 1");
  if (!(a.feature_radius > 0.0)) throw InvalidInputError("--feature-radius must be > 0 mm");
  if (!(a.detection_radius > 0.0)) throw InvalidInputError("--detection-radius must be > 0 mm");
  if (a.iterations < 1) throw InvalidInputError("--iterations must be >= 1");
  if (a.color_levels < 2 || a.color_levels > 256) throw InvalidInputError("--color-levels must be in [2, 256]");
  if (!(a.blur >= 0.0)) throw InvalidInputError("--blur must be a sigma >= 0 in mm");
  Setup s;
  s.plan = make_plan(a);
  ComparisonOptions& o = s.options;
  o.metrics.feature_radius = a.feature_radius;
  o.detection_radius = a.detection_radius;
  o.timing_repeats = a.repeat;
  o.reconstruction.tiling.limits.max_vertices = a.max_vertices;
  o.reconstruction.off_slice.placement = off_slice_placement(a.volume);
  o.reconstruction.segmentation.flat_crossings = flat_crossings(a.volume);
  o.limits.max_vertices = a.max_vertices;
  o.methods.iterations = a.iterations;
  o.methods.only = split_list(a.methods);
  for (const std::string& v : a.variants) o.methods.variants.push_back(parse_variant(v));
  const std::vector<MethodSpec> table = method_table(o.methods);  // unknown names and bad settings throw here
  ComparisonReportOptions& r = s.report;
  r.renders = !a.no_render;
  std::tie(r.render_width, r.render_height) = parse_render_size(a.render_size);
  r.color_levels = a.color_levels;
  r.render_methods = split_list(a.render_methods);
  for (const std::string& id : r.render_methods) {
    if (std::none_of(table.begin(), table.end(), [&](const MethodSpec& m) { return m.id == id; })) {
      throw InvalidInputError("--render-methods: '" + id + "' is not a method of this comparison");
    }
  }
  r.isolate = [](const std::function<void()>& render) { return run_isolated("rendering", render); };
  r.command_line = command_line(a);
  r.note = a.note;
  return s;
}

// The series written so far, kept for the summary (numbers only: the meshes are dropped once written).
class Results {
 public:
  Results(const ComparisonReportOptions& report, ProgressDisplay& progress) : report_(report), progress_(progress) {}

  void add(Series s, const fs::path& dir) {
    progress_.stage("write");
    ComparisonFiles files = write_series(s, dir, report_);
    progress_.finish();
    for (Comparison& run : s.runs) {
      for (MethodResult& m : run.methods) {
        m.mesh = {};
        m.vertex_labels.clear();
      }
    }
    series_.push_back(std::make_unique<Series>(std::move(s)));
    entries_.push_back({series_.back().get(), dir, std::move(files)});
  }
  [[nodiscard]] const std::vector<SeriesEntry>& entries() const { return entries_; }
  [[nodiscard]] std::vector<const Series*> series() const {
    std::vector<const Series*> all;
    for (const auto& s : series_) all.push_back(s.get());
    return all;
  }

 private:
  const ComparisonReportOptions& report_;
  ProgressDisplay& progress_;
  std::vector<std::unique_ptr<Series>> series_;
  std::vector<SeriesEntry> entries_;
};

// Every phantom of the plan in every regime, once per seed; the truth of a phantom is built once.
void run_phantoms(const CompareArgs& a, const Setup& setup, ComparisonOptions options, ProgressDisplay& progress,
                  const std::function<fs::path(const Regime&, const std::string&)>& directory, Results& results) {
  const Plan& plan = setup.plan;
  PhantomVolumeOptions volume;
  volume.spacing = parse_spacing(a.spacing);
  volume.blur = a.blur;
  for (PhantomShape shape : plan.shapes) {
    const std::string name(to_string(shape));
    progress.stage("phantom");
    const Phantom phantom = make_phantom(shape);
    const ComparisonTruth truth = phantom_truth(phantom);
    options.reconstruction.segmentation.threshold = a.threshold.value_or(0.5 * (volume.bone_hu + volume.tissue_hu));
    for (const Regime& regime : plan.regimes) {
      apply_regime(regime, volume);
      std::vector<Comparison> runs;
      for (std::size_t k = 0; k < plan.seeds.size(); ++k) {
        volume.seed = plan.seeds[k];
        progress.stage("phantom");
        const CtImage::Pointer image = render_phantom(phantom, volume);
        std::ostringstream source;
        source << "phantom '" << name << "' (" << volume.spacing.x() << " x " << volume.spacing.y() << " x "
               << volume.spacing.z() << " mm voxels, " << regime.ct_noise_hu << " HU noise, ";
        if (regime.contour()) source << regime.contour_noise_mm << " mm contour noise, ";
        source << volume.blur << " mm blur, seed " << volume.seed << ")";
        options.volume_curves = !a.no_curves && k == 0;  // the plot shows the first seed's
        runs.push_back(run_comparison(*image, source.str(), truth, options));
      }
      results.add(make_series(name, regime, plan.seeds, std::move(runs)), directory(regime, name));
    }
  }
}

// One input volume, against a reference surface or no truth.
void run_volume(const CompareArgs& a, const Setup& setup, ComparisonOptions options, ProgressDisplay& progress,
                const fs::path& out, Results& results) {
  std::optional<Mesh> reference;
  if (!a.truth.empty()) {
    MeshReadOptions ro;
    ro.max_vertices = a.max_vertices;
    reference = read_mesh(a.truth, ro);
  }
  progress.stage("read");
  const CtImage::Pointer image = read_volume(a.input, volume_read_options(a.volume, "compare"));
  options.reconstruction.segmentation.threshold = a.threshold.value_or(300.0);
  options.volume_curves = !a.no_curves;
  const ComparisonTruth truth =
      reference ? reference_surface_truth(*reference, "reference surface " + a.truth) : ComparisonTruth{};
  std::vector<Comparison> runs;
  runs.push_back(run_comparison(*image, a.input, truth, options));
  results.add(make_series(fs::path(a.input).filename().string(), setup.plan.regimes.front(), {}, std::move(runs)), out);
}

void print_json_result(const CompareArgs& a, const Results& results, const Verdicts& verdicts,
                       const std::vector<fs::path>& summary_files, double seconds) {
  nlohmann::json j;
  j["command"] = "compare";
  j["output"] = a.out;
  nlohmann::json list = nlohmann::json::array();
  for (const SeriesEntry& e : results.entries()) {
    nlohmann::json item;
    item["name"] = e.series->name;
    item["regime"] = e.series->regime.name;
    item["directory"] = e.directory.string();
    item["rendered"] = e.files.rendered;
    item["render_note"] = e.files.render_note;
    nlohmann::json files = nlohmann::json::array();
    for (const fs::path& f : e.files.files) files.push_back(f.string());
    item["files"] = files;
    item["metrics"] = nlohmann::json::parse(std::ifstream(e.directory / "metrics.json"));
    list.push_back(item);
  }
  j["comparisons"] = list;
  j["verdicts"] = verdicts_json(verdicts);
  if (!summary_files.empty()) {
    nlohmann::json files = nlohmann::json::array();
    for (const fs::path& f : summary_files) files.push_back(f.string());
    j["summary_files"] = files;
  }
  if (!a.markdown.empty()) j["markdown"] = a.markdown;
  j["seconds"] = seconds;
  print_json(j);
}

int run_compare(const CompareArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  apply_common_options(a.common);
  Setup setup = make_setup(a);
  const Plan& plan = setup.plan;

  // Outputs are checked before the work: one directory per regime (when several) and object (when several).
  const fs::path out(a.out);
  const auto directory = [&](const Regime& regime, const std::string& name) {
    fs::path d = out;
    if (plan.regimes.size() > 1) d /= regime.name;
    if (plan.shapes.size() > 1) d /= name;
    return d;
  };
  prepare_directory(out);
  for (const Regime& r : plan.regimes) {
    for (PhantomShape s : plan.shapes) prepare_directory(directory(r, std::string(to_string(s))));
  }
  if (!a.markdown.empty()) check_output_path(a.markdown);

  ProgressDisplay progress("compare", a.common.quiet);
  setup.options.progress = progress.callback();
  Results results(setup.report, progress);
  if (a.input.empty()) {
    run_phantoms(a, setup, setup.options, progress, directory, results);
  } else {
    run_volume(a, setup, setup.options, progress, out, results);
  }

  std::vector<fs::path> summary_files;
  if (results.entries().size() > 1) summary_files = write_summary(results.entries(), out, setup.report);
  if (!a.markdown.empty()) write_markdown(results.entries(), a.markdown, setup.report);
  const Verdicts verdicts = judge(results.series());
  if (a.json) {
    print_json_result(a, results, verdicts, summary_files, seconds_since(start));
    return kOk;
  }
  if (a.common.quiet) return kOk;
  for (const SeriesEntry& e : results.entries()) print_summary(*e.series, e.files, e.directory);
  for (const BarTotal& t : verdicts.totals) {
    std::cout << "verdict " << t.bar << " (" << t.regime << "): " << t.passed << " of " << t.rows << " pass"
              << (t.required > 0 ? ", " + std::to_string(t.original_passed) + " of the 7 original phantoms" : "")
              << (t.met() ? ": met" : ": missed") << "\n";
  }
  if (!summary_files.empty()) std::cout << "summary: " << (out / "report.html").string() << "\n";
  if (!a.markdown.empty()) std::cout << "markdown: " << a.markdown << "\n";
  std::cout << std::setprecision(1) << std::fixed << "total " << seconds_since(start) << " s\n";
  return kOk;
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Every smoothing method, VTK's filters and 3D Slicer's voxel route on one volume, measured against the truth "
      "over the surface, in noise regimes and over seeds: metrics.csv/json, volume curves, renders, verdicts, "
      "report.html");
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
  CLI::Option* regimes = cmd->add_option(
      "--regimes", args->regimes,
      "Noise regimes, comma-separated: ct<HU> (CT noise), contour<MM> (per-slice contour noise at 20 HU), "
      "contour<MM>-ct<HU>, or all = ct20,ct60,contour0.4 (default for --phantom all; otherwise ct<--noise>)");
  CLI::Option* seeds =
      cmd->add_option("--seeds", args->seeds, "Noise seeds, e.g. 1-3 or 1,4,7: numbers are means over them");
  cmd->add_option("--spacing", args->spacing, "Phantom voxel size, mm: sx,sy,sz")->capture_default_str();
  cmd->add_option("--noise", args->noise, "Phantom Gaussian noise, HU (one regime)")
      ->capture_default_str()
      ->excludes(regimes);
  add_contour_noise_option(cmd, args->contour_noise)->excludes(input)->excludes(regimes);
  cmd->add_option("--blur", args->blur, "Phantom Gaussian blur, mm")->capture_default_str();
  cmd->add_option("--seed", args->seed, "Phantom noise seed (one run)")->capture_default_str()->excludes(seeds);
  cmd->add_option("--threshold", args->threshold,
                  "Bone threshold of both routes, HU (default: 520 for a phantom, 300 for an input volume)");
  cmd->add_option("--feature-radius", args->feature_radius,
                  "Phantom: the surface this close to a sharp edge or corner is the feature region, mm")
      ->capture_default_str();
  cmd->add_option("--detection-radius", args->detection_radius,
                  "Phantom: contour-mesh vertices this close to a sharp edge or corner are the true features that "
                  "labels are scored against, mm")
      ->capture_default_str();
  cmd->add_option("--iterations", args->iterations,
                  "Iterations of every iterative method (the default, the baselines, VTK's filters on the contour "
                  "mesh); the xu2006 preset keeps its 40, the voxel route 3D Slicer's 20")
      ->capture_default_str();
  cmd->add_option("--methods", args->methods,
                  "Run only these methods, comma-separated ids (none, laplacian, taubin, mcf, mindist, paper, "
                  "cross-slice, vtk-windowed-sinc, vtk-smooth-feature-edges, voxel-flying-edges, voxel-windowed-sinc)");
  cmd->add_option("--variant", args->variants,
                  "Also run a variant, NAME:key=value,... (repeatable): method=M or preset=P, then that method's "
                  "options, e.g. no-along:stages=across-only or reach4:reach=4 (docs/cli.md lists the keys)");
  cmd->add_option("--repeat", args->repeat, "Time each method this many times and report the fastest")
      ->capture_default_str();
  cmd->add_option("--render-size", args->render_size, "Size of the renders in pixels, WIDTHxHEIGHT")
      ->capture_default_str();
  cmd->add_option("--render-methods", args->render_methods,
                  "Render only these methods (comma-separated ids; default: every method)");
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
