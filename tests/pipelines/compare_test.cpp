// The evaluation harness (issue 6): run_comparison on a small noisy phantom, the tables and the plot it
// writes, a reference surface as truth, and `contourmesh compare` end to end with renders (under
// xvfb-run when there is no display), exit codes and bad input.
#include <pipelines/comparison.h>
#include <pipelines/comparison_report.h>
#include <pipelines/mesh_io.h>
#include <reconstruct/phantom.h>
#include <reconstruct/volume.h>
#include <smooth/errors.h>
#include <smooth/metrics.h>
#include <smooth/shapes.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.h"

namespace contourmesh {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kMethods = {"none",
                                           "laplacian",
                                           "taubin",
                                           "mcf",
                                           "mindist",
                                           "paper",
                                           "vtk-windowed-sinc",
                                           "vtk-smooth-feature-edges",
                                           "voxel-flying-edges",
                                           "voxel-windowed-sinc"};

// A femur at coarse voxels with strong noise (200 HU against a 960 HU step): small enough for a test,
// noisy enough that smoothing must pay off.
PhantomVolumeOptions noisy_volume() {
  PhantomVolumeOptions v;
  v.spacing = {1.2, 1.2, 3.0};
  v.noise = 200.0;
  v.blur = 0.5;
  return v;
}

ComparisonOptions fast_options() {
  ComparisonOptions o;
  o.reconstruction.segmentation.threshold = 520.0;
  return o;
}

// A ridge-box at coarse voxels: a fast comparison for the output tests.
const Comparison& small_comparison() {
  static const Comparison c = [] {
    const Phantom phantom = make_phantom(PhantomShape::RidgeBox);
    PhantomVolumeOptions v;
    v.spacing = {1.5, 1.5, 3.0};
    v.noise = 20.0;
    const CtImage::Pointer image = render_phantom(phantom, v);
    return run_comparison(*image, "small ridge-box", phantom_truth(phantom), fast_options());
  }();
  return c;
}

// The noisy femur, shared by the checks of one test (about a second; half a minute under ASan).
const Comparison& femur_comparison() {
  static const Comparison c = [] {
    const Phantom phantom = make_phantom(PhantomShape::Femur);
    const CtImage::Pointer image = render_phantom(phantom, noisy_volume());
    return run_comparison(*image, "femur test phantom", phantom_truth(phantom), fast_options());
  }();
  return c;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::string item;
  std::istringstream s(line);
  while (std::getline(s, item, sep)) out.push_back(item);
  if (!line.empty() && line.back() == sep) out.emplace_back();
  return out;
}

// Grey-level statistics of a PNG: the variance, and the fraction of pixels that are not the background
// (the colour of the corner pixel).
struct PngStats {
  int width = 0, height = 0;
  double variance = 0.0;
  double foreground = 0.0;
};

PngStats png_stats(const fs::path& path) {
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(path.string().c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  PngStats s;
  int dims[3];
  image->GetDimensions(dims);
  s.width = dims[0];
  s.height = dims[1];
  const int components = image->GetNumberOfScalarComponents();
  if (s.width <= 0 || s.height <= 0 || components < 3) return s;
  const auto* p = static_cast<const unsigned char*>(image->GetScalarPointer());
  const std::size_t n = static_cast<std::size_t>(s.width) * static_cast<std::size_t>(s.height);
  double sum = 0.0, sum_sq = 0.0;
  std::size_t foreground = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char* px = p + components * i;
    const double grey = (px[0] + px[1] + px[2]) / 3.0;
    sum += grey;
    sum_sq += grey * grey;
    if (px[0] != p[0] || px[1] != p[1] || px[2] != p[2]) ++foreground;
  }
  const double mean = sum / static_cast<double>(n);
  s.variance = sum_sq / static_cast<double>(n) - mean * mean;
  s.foreground = static_cast<double>(foreground) / static_cast<double>(n);
  return s;
}

// ---------------------------------------------------------------------------------------------------
// Library

void check_every_method_on_the_same_mesh_with_finite_metrics(const Comparison& c) {
  ASSERT_EQ(c.methods.size(), kMethods.size());
  for (std::size_t i = 0; i < kMethods.size(); ++i) {
    const MethodResult& m = c.methods[i];
    EXPECT_EQ(m.name, kMethods[i]);
    SCOPED_TRACE(m.name);
    if (m.route == "contour") {
      // Contour-route methods keep the reconstructed mesh's connectivity.
      EXPECT_EQ(m.mesh.num_vertices(), c.contour_mesh.num_vertices());
      EXPECT_EQ(m.mesh.triangles, c.contour_mesh.triangles);
    } else {
      EXPECT_EQ(m.route, "voxel");
    }
    EXPECT_TRUE(m.mesh.positions.allFinite());
    ASSERT_TRUE(m.all && m.feature && m.smooth);
    for (const RegionMetrics* r : {&*m.all, &*m.feature, &*m.smooth}) {
      EXPECT_TRUE(std::isfinite(r->distance.rms) && r->distance.rms > 0.0);
      EXPECT_LE(r->distance.mean, r->distance.rms + 1e-12);
      EXPECT_LE(r->distance.rms, r->distance.max + 1e-12);
      EXPECT_GT(r->distance.count, 0u);
      EXPECT_TRUE(std::isfinite(r->normals.mean_degrees));
      EXPECT_GT(r->normals.count, 0u);
    }
    EXPECT_EQ(m.feature->distance.count + m.smooth->distance.count, m.all->distance.count);
    EXPECT_TRUE(std::isfinite(m.volume_change_percent));
    ASSERT_TRUE(m.volume_error_percent.has_value());
    EXPECT_LT(std::abs(*m.volume_error_percent), 25.0) << "every mesh encloses roughly the femur's volume";
    EXPECT_GE(m.stage_seconds("total"), 0.0);
  }
}

void check_none_is_the_reconstructed_mesh(const Comparison& c) {
  const MethodResult& none = *c.find("none");
  EXPECT_EQ(none.mesh.positions, c.contour_mesh.positions);
  EXPECT_EQ(none.volume_change_percent, 0.0);
  EXPECT_EQ(none.volume_input, none.volume_output);
  EXPECT_TRUE(none.volume_curve.empty());
  EXPECT_EQ(c.find("voxel-flying-edges")->volume_change_percent, 0.0);
}

void check_smoothing_brings_the_mesh_closer_to_the_truth(const Comparison& c) {
  const double none = c.find("none")->all->distance.rms;
  EXPECT_LT(c.find("taubin")->all->distance.rms, 0.9 * none);
  EXPECT_LT(c.find("paper")->all->distance.rms, none);
  // 200 HU noise puts isolated voxels above the threshold; both routes drop such specks.
  EXPECT_LT(c.find("voxel-flying-edges")->all->distance.max, 6.0);
  // Windowed sinc on the staircase of the voxel route also beats the raw flying-edges mesh.
  EXPECT_LT(c.find("voxel-windowed-sinc")->all->distance.rms, c.find("voxel-flying-edges")->all->distance.rms);
  // Laplacian shrinks, Taubin much less.
  EXPECT_LT(c.find("laplacian")->volume_change_percent, -1.0);
  EXPECT_LT(std::abs(c.find("taubin")->volume_change_percent), std::abs(c.find("laplacian")->volume_change_percent));
}

void check_stages_labels_and_detection_scores(const Comparison& c) {
  const MethodResult& paper = *c.find("paper");
  for (const char* stage : {"detect", "subdivide", "smooth", "total"}) {
    EXPECT_GT(paper.stage_seconds(stage), 0.0) << stage;
  }
  EXPECT_NEAR(paper.stage_seconds("total"),
              paper.stage_seconds("detect") + paper.stage_seconds("subdivide") + paper.stage_seconds("smooth"), 1e-9);
  const MethodResult& voxel = *c.find("voxel-windowed-sinc");
  for (const char* stage : {"threshold", "surface", "smooth", "total"})
    EXPECT_GT(voxel.stage_seconds(stage), 0.0) << stage;

  ASSERT_TRUE(paper.labels.has_value());
  const LabelSummary& l = *paper.labels;
  EXPECT_EQ(l.edges + l.corners + l.noise, l.candidates);
  EXPECT_GT(l.candidates, 0u);
  ASSERT_TRUE(l.true_features && l.detected && l.true_positives);
  EXPECT_EQ(*l.detected, l.edges + l.corners);
  EXPECT_LE(*l.true_positives, std::min(*l.detected, *l.true_features));
  EXPECT_GT(*l.true_features, 0u);
  std::size_t truths = 0;
  for (std::uint8_t f : c.true_features) truths += f;
  EXPECT_EQ(truths, *l.true_features);
  EXPECT_DOUBLE_EQ(l.recall, static_cast<double>(*l.true_positives) / static_cast<double>(*l.true_features));
  EXPECT_EQ(c.labels.size(), static_cast<std::size_t>(c.contour_mesh.num_vertices()));
  for (const MethodResult& m : c.methods) {
    if (&m != &paper) {
      EXPECT_FALSE(m.labels.has_value()) << m.name;
    }
  }
}

void check_volume_curves_of_the_iterative_methods(const Comparison& c) {
  for (const char* name : {"laplacian", "taubin", "mcf", "mindist", "vtk-smooth-feature-edges"}) {
    const MethodResult& m = *c.find(name);
    ASSERT_EQ(m.volume_curve.size(), 21u) << name;
    EXPECT_EQ(m.volume_curve.front(), 0.0);
    // The last point is the method's result: the rate is minus the volume change.
    EXPECT_NEAR(100.0 * m.volume_curve.back(), -m.volume_change_percent, 1e-6) << name;
  }
  const MethodResult& paper = *c.find("paper");
  ASSERT_EQ(paper.volume_curve.size(), 41u);
  EXPECT_NEAR(100.0 * paper.volume_curve.back(), -paper.volume_change_percent, 1e-6);
  // Laplacian shrinks at every iteration.
  const auto& lap = c.find("laplacian")->volume_curve;
  for (std::size_t k = 1; k < lap.size(); ++k) EXPECT_GT(lap[k], lap[k - 1]);
  // Windowed sinc has no intermediate steps: no curve, its iteration count instead.
  EXPECT_TRUE(c.find("vtk-windowed-sinc")->volume_curve.empty());
  EXPECT_EQ(c.find("vtk-windowed-sinc")->iterations, 20);
}

// One noisy femur comparison, checked from several sides.
TEST(Comparison, NoisyFemurEveryMethodMeasured) {
  const Comparison& c = femur_comparison();
  {
    SCOPED_TRACE("every_method_on_the_same_mesh_with_finite_metrics");
    check_every_method_on_the_same_mesh_with_finite_metrics(c);
  }
  {
    SCOPED_TRACE("none_is_the_reconstructed_mesh");
    check_none_is_the_reconstructed_mesh(c);
  }
  {
    SCOPED_TRACE("smoothing_brings_the_mesh_closer_to_the_truth");
    check_smoothing_brings_the_mesh_closer_to_the_truth(c);
  }
  {
    SCOPED_TRACE("stages_labels_and_detection_scores");
    check_stages_labels_and_detection_scores(c);
  }
  {
    SCOPED_TRACE("volume_curves_of_the_iterative_methods");
    check_volume_curves_of_the_iterative_methods(c);
  }
}

TEST(Comparison, TablesHaveARowPerMethodAndParse) {
  const Comparison& c = small_comparison();
  std::istringstream csv(metrics_csv(c));
  std::string line;
  std::getline(csv, line);
  const std::size_t columns = split(line, ',').size();
  EXPECT_GT(columns, 30u);
  std::vector<std::string> names;
  while (std::getline(csv, line)) {
    const auto cells = split(line, ',');
    EXPECT_EQ(cells.size(), columns) << line;
    names.push_back(cells[0]);
  }
  EXPECT_EQ(names, kMethods);

  const auto j = nlohmann::json::parse(metrics_json(c));
  EXPECT_EQ(j["truth"], "phantom");
  ASSERT_EQ(j["methods"].size(), kMethods.size());
  for (const auto& m : j["methods"]) {
    for (const char* region : {"all", "feature", "smooth"}) {
      EXPECT_TRUE(m["distance_mm"][region]["rms"].is_number()) << m["name"] << region;
      EXPECT_TRUE(m["normal_error_degrees"][region]["mean"].is_number()) << m["name"] << region;
    }
    EXPECT_TRUE(m["volume_change_percent"].is_number());
    EXPECT_TRUE(m["seconds"]["total"].is_number());
  }

  std::istringstream curves(volume_curve_csv(c));
  std::getline(curves, line);
  EXPECT_EQ(line, "iteration,laplacian,taubin,mcf,mindist,paper,vtk-smooth-feature-edges");
  int rows = 0;
  while (std::getline(curves, line)) ++rows;
  EXPECT_EQ(rows, 41);
}

TEST(Comparison, VolumeCurvePlotIsDrawnWithoutADisplay) {
  test::ScopedTempDir tmp("contourmesh_compare");
  const fs::path png = tmp.path() / "curve.png";
  write_volume_curve_png(small_comparison(), png, 600, 400);
  const PngStats s = png_stats(png);
  EXPECT_EQ(s.width, 600);
  EXPECT_EQ(s.height, 400);
  EXPECT_GT(s.variance, 100.0);
  EXPECT_GT(s.foreground, 0.02);
}

TEST(Comparison, ReferenceSurfaceAsTruthGivesDistancesOnly) {
  // A ridge-box volume measured against a sphere: far apart, but every distance must be defined.
  const Phantom phantom = make_phantom(PhantomShape::RidgeBox);
  PhantomVolumeOptions v;
  v.spacing = {1.0, 1.0, 2.0};
  const CtImage::Pointer image = render_phantom(phantom, v);
  const Mesh sphere = make_icosphere(3, 30.0);
  const ComparisonTruth truth = reference_surface_truth(sphere, "a sphere of radius 30");
  // The distance to a sphere mesh from its centre is about its radius.
  EXPECT_NEAR(truth.distance(Eigen::Vector3d::Zero()), 30.0, 0.5);
  ComparisonOptions o = fast_options();
  o.volume_curves = false;
  const Comparison c = run_comparison(*image, "ridge-box volume", truth, o);
  EXPECT_EQ(c.truth, TruthKind::ReferenceSurface);
  for (const MethodResult& m : c.methods) {
    ASSERT_TRUE(m.all.has_value()) << m.name;
    EXPECT_GT(m.all->distance.rms, 1.0) << "a box is far from the sphere";
    EXPECT_EQ(m.all->normals.count, 0u) << "no normals without an analytic field";
    EXPECT_FALSE(m.feature || m.smooth || m.volume_error_percent) << m.name;
    EXPECT_TRUE(m.volume_curve.empty());
  }
  const MethodResult& paper = *c.find("paper");
  ASSERT_TRUE(paper.labels.has_value());
  EXPECT_FALSE(paper.labels->true_features.has_value());
  EXPECT_TRUE(std::isnan(paper.labels->recall));
  const auto j = nlohmann::json::parse(metrics_json(c));
  EXPECT_TRUE(j["methods"][0]["normal_error_degrees"].is_null());
  EXPECT_TRUE(j["methods"][0]["distance_mm"]["feature"].is_null());
  EXPECT_THROW((void)reference_surface_truth(Mesh{}, "empty"), InvalidInputError);
}

TEST(Comparison, WithoutTruthThereAreNoDistances) {
  const Phantom phantom = make_phantom(PhantomShape::RidgeBox);
  PhantomVolumeOptions v;
  v.spacing = {1.0, 1.0, 2.0};
  const CtImage::Pointer image = render_phantom(phantom, v);
  ComparisonOptions o = fast_options();
  o.volume_curves = false;
  const Comparison c = run_comparison(*image, "ridge-box volume", ComparisonTruth{}, o);
  EXPECT_EQ(c.truth, TruthKind::None);
  for (const MethodResult& m : c.methods) EXPECT_FALSE(m.all.has_value()) << m.name;
  EXPECT_TRUE(c.true_features.empty());
  const std::string csv = metrics_csv(c);
  EXPECT_NE(csv.find("none,contour,"), std::string::npos);
}

TEST(Comparison, OptionsOutOfRangeAndCancellation) {
  const Phantom phantom = make_phantom(PhantomShape::RidgeBox);
  PhantomVolumeOptions v;
  v.spacing = {1.5, 1.5, 3.0};
  const CtImage::Pointer image = render_phantom(phantom, v);
  for (const auto& change : std::vector<std::function<void(ComparisonOptions&)>>{
           [](ComparisonOptions& o) { o.timing_repeats = 0; },
           [](ComparisonOptions& o) { o.feature_radius = 0.0; },
           [](ComparisonOptions& o) { o.sinc_passband = 0.0; },
           [](ComparisonOptions& o) { o.laplace_relaxation = 2.0; },
       }) {
    ComparisonOptions o = fast_options();
    change(o);
    EXPECT_THROW((void)run_comparison(*image, "x", phantom_truth(phantom), o), InvalidInputError);
  }
  ComparisonOptions o = fast_options();
  o.progress = [](std::string_view stage, double) { return stage != "taubin"; };
  EXPECT_THROW((void)run_comparison(*image, "x", phantom_truth(phantom), o), CancelledError);
  // A threshold above every voxel: no contour, an error naming the source.
  o = fast_options();
  o.reconstruction.segmentation.threshold = 5000.0;
  try {
    (void)run_comparison(*image, "the test volume", phantom_truth(phantom), o);
    FAIL() << "expected InvalidInputError";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("the test volume"), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------------------
// The CLI

struct CliRun {
  int code = -1;
  std::string out;
  std::string err;
};

// Runs `contourmesh args`; with `display`, under xvfb-run when no X display is reachable (its own
// server number and authority file, so that parallel tests and other users' servers do not collide).
CliRun run_cli(const std::string& args, const fs::path& dir, bool display = false, const std::string& env = "") {
  std::string prefix = env.empty() ? "" : env + " ";
  if (display && !rendering_available()) {
    const int server = 200 + static_cast<int>(getpid() % 700);
    prefix += "xvfb-run -a -n " + std::to_string(server) + " -f " + (dir / "xauthority").string() + " ";
  }
  const fs::path err_file = dir / "stderr.txt";
  const std::string cmd = prefix + std::string(CONTOURMESH_CLI) + " " + args + " 2>" + err_file.string();
  CliRun r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = read_text(err_file);
  return r;
}

const char* kSmallPhantom = "--spacing 1.5,1.5,3 --noise 100 --repeat 1";

TEST(CompareCli, OnePhantomWritesEveryFileAndRendersTheMeshes) {
  test::ScopedTempDir tmp("contourmesh_compare");
  const fs::path out = tmp.path() / "out" / "ridge";  // parents are created
  const CliRun r = run_cli("compare --phantom ridge-box " + std::string(kSmallPhantom) +
                               " --render-size 320x240 --color-levels 32 --out " + out.string() + " --json",
                           tmp.path(), true);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["comparisons"].size(), 1u);
  const auto& item = j["comparisons"][0];
  EXPECT_EQ(item["name"], "ridge-box");
  ASSERT_TRUE(item["rendered"].get<bool>()) << item["render_note"];

  for (const char* file : {"metrics.csv", "metrics.json", "volume_curve.csv", "volume_curve.png", "report.html",
                           "labels.png", "detection.png"}) {
    EXPECT_TRUE(fs::is_regular_file(out / file)) << file;
  }
  // No temporary files are left behind.
  for (const auto& entry : fs::directory_iterator(out)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  }

  const auto metrics = nlohmann::json::parse(read_text(out / "metrics.json"));
  std::vector<std::string> names;
  for (const auto& m : metrics["methods"]) {
    names.push_back(m["name"]);
    for (const char* region : {"all", "feature", "smooth"}) {
      const auto& d = m["distance_mm"][region];
      for (const char* k : {"mean", "rms", "max"}) {
        EXPECT_TRUE(d[k].is_number() && std::isfinite(d[k].get<double>())) << m["name"] << " " << region << " " << k;
      }
      EXPECT_TRUE(m["normal_error_degrees"][region]["mean"].is_number());
    }
    EXPECT_TRUE(m["volume_change_percent"].is_number());
    if (m["name"] == "none") {
      EXPECT_EQ(m["volume_change_percent"].get<double>(), 0.0);
    }
  }
  EXPECT_EQ(names, kMethods);
  EXPECT_EQ(metrics, item["metrics"]) << "--json prints the same metrics as metrics.json";

  const std::string html = read_text(out / "report.html");
  for (const std::string& m : kMethods) {
    const std::string png = "render_" + m + ".png";
    EXPECT_NE(html.find("src=\"" + png + "\""), std::string::npos) << png;
    const PngStats s = png_stats(out / png);
    EXPECT_EQ(s.width, 320) << png;
    EXPECT_EQ(s.height, 240) << png;
    EXPECT_GT(s.variance, 50.0) << png << " is blank";
    EXPECT_GT(s.foreground, 0.10) << png << " shows no mesh";
  }
  for (const char* png : {"labels.png", "detection.png", "volume_curve.png"}) {
    const PngStats s = png_stats(out / png);
    EXPECT_GT(s.variance, 50.0) << png;
    EXPECT_GT(s.foreground, 0.02) << png;
  }
  EXPECT_NE(html.find("volume_curve.png"), std::string::npos);
  EXPECT_NE(html.find("metrics.csv"), std::string::npos);
}

TEST(CompareCli, WithoutADisplayTheRendersAreSkippedAndSaidSo) {
  test::ScopedTempDir tmp("contourmesh_compare");
  const fs::path out = tmp.path() / "out";
  const CliRun r =
      run_cli("compare --phantom ridge-box " + std::string(kSmallPhantom) + " --no-curves --out " + out.string(),
              tmp.path(), false, "env -u DISPLAY");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("no renders"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out / "render_paper.png"));
  EXPECT_TRUE(fs::is_regular_file(out / "volume_curve.png")) << "the plot needs no display";
  EXPECT_NE(read_text(out / "report.html").find("xvfb-run"), std::string::npos);
}

TEST(CompareCli, VolumeWithAndWithoutAReferenceSurface) {
  test::ScopedTempDir tmp("contourmesh_compare");
  const fs::path volume = tmp.path() / "scan.nrrd";
  PhantomVolumeOptions v;
  v.spacing = {1.5, 1.5, 3.0};
  write_volume(render_phantom(make_phantom(PhantomShape::RidgeBox), v), volume);
  const fs::path reference = tmp.path() / "reference.stl";
  write_mesh(make_icosphere(3, 20.0), reference);

  CliRun r = run_cli("compare " + volume.string() + " --truth " + reference.string() +
                         " --threshold 520 --no-render --no-curves --out " + (tmp.path() / "with").string() + " --json",
                     tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  auto m = nlohmann::json::parse(r.out)["comparisons"][0]["metrics"];
  EXPECT_EQ(m["truth"], "reference-surface");
  EXPECT_TRUE(m["methods"][0]["distance_mm"]["all"]["rms"].is_number());
  EXPECT_TRUE(m["methods"][0]["normal_error_degrees"].is_null());

  r = run_cli("compare " + volume.string() + " --threshold 520 --no-render --no-curves --out " +
                  (tmp.path() / "without").string() + " --json",
              tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  m = nlohmann::json::parse(r.out)["comparisons"][0]["metrics"];
  EXPECT_EQ(m["truth"], "none");
  EXPECT_TRUE(m["methods"][0]["distance_mm"].is_null());
  EXPECT_NE(read_text(tmp.path() / "without" / "report.html").find("no distance"), std::string::npos);
}

TEST(CompareCli, BadInputExitsWithTwoAndAClearMessage) {
  test::ScopedTempDir tmp("contourmesh_compare");
  const std::string out = " --out " + (tmp.path() / "out").string();
  CliRun r = run_cli("compare --phantom tibia" + out, tmp.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("tibia"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("femur"), std::string::npos) << "lists the valid names: " << r.err;

  const fs::path missing = tmp.path() / "no_such_scan.nrrd";
  r = run_cli("compare " + missing.string() + out, tmp.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("no_such_scan.nrrd"), std::string::npos) << r.err;

  // A regular file where the output directory should be, and a directory that cannot be created.
  const fs::path file = tmp.path() / "a_file";
  std::ofstream(file) << "x";
  r = run_cli("compare --phantom ridge-box --out " + file.string(), tmp.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("a_file"), std::string::npos) << r.err;
  r = run_cli("compare --phantom ridge-box --out " + (file / "sub").string(), tmp.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("a_file"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_regular_file(file));

  // The truth surface is checked before the volume is reconstructed.
  const fs::path volume = tmp.path() / "scan.nrrd";
  PhantomVolumeOptions v;
  v.spacing = {2.0, 2.0, 4.0};
  write_volume(render_phantom(make_phantom(PhantomShape::RidgeBox), v), volume);
  r = run_cli("compare " + volume.string() + " --truth " + (tmp.path() / "missing.stl").string() + out, tmp.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("missing.stl"), std::string::npos) << r.err;

  r = run_cli("compare --phantom ridge-box --render-size 10x10" + out, tmp.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--render-size"), std::string::npos) << r.err;
  r = run_cli("compare --phantom ridge-box --color-levels 1" + out, tmp.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--color-levels"), std::string::npos) << r.err;
}

TEST(CompareCli, ConflictingOptionsAreUsageErrors) {
  test::ScopedTempDir tmp("contourmesh_compare");
  const std::string out = " --out " + (tmp.path() / "out").string();
  EXPECT_EQ(run_cli("compare --phantom femur in.nrrd" + out, tmp.path()).code, 1);
  EXPECT_EQ(run_cli("compare --phantom femur --truth ref.stl" + out, tmp.path()).code, 1);
  EXPECT_EQ(run_cli("compare --phantom femur", tmp.path()).code, 1) << "--out is required";
  EXPECT_FALSE(fs::exists(tmp.path() / "out"));
}

}  // namespace
}  // namespace contourmesh
