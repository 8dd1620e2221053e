// The evaluation harness (contourmesh_compare): run_comparison on small noisy phantoms, the method table
// and its variants, regimes, seeds and their means, the verdicts, the files it writes, a reference
// surface as truth, and `contourmesh compare` end to end with renders (under xvfb-run when there is no
// display), exit codes and bad input. Phantoms are coarse so that each test takes seconds.
#include <compare/comparison.h>
#include <compare/method_table.h>
#include <compare/report.h>
#include <compare/series.h>
#include <compare/verdicts.h>
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
                                           "cross-slice",
                                           "vtk-windowed-sinc",
                                           "vtk-smooth-feature-edges",
                                           "voxel-flying-edges",
                                           "voxel-windowed-sinc"};

// Coarse truth sampling and fewer samples per mm^2 than the default: the same code, a tenth of the work.
ComparisonTruth coarse_truth(const Phantom& phantom) { return phantom_truth(phantom, 0.8); }

ComparisonOptions fast_options() {
  ComparisonOptions o;
  o.reconstruction.segmentation.threshold = 520.0;
  o.metrics.density = 1.0;
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
    return run_comparison(*image, "small ridge-box", coarse_truth(phantom), fast_options());
  }();
  return c;
}

// A femur at coarse voxels with strong noise (200 HU against a 960 HU step), shared by the checks of one
// test.
const Comparison& femur_comparison() {
  static const Comparison c = [] {
    const Phantom phantom = make_phantom(PhantomShape::Femur);
    PhantomVolumeOptions v;
    v.spacing = {1.2, 1.2, 3.0};
    v.noise = 200.0;
    v.blur = 0.5;
    const CtImage::Pointer image = render_phantom(phantom, v);
    return run_comparison(*image, "femur test phantom", coarse_truth(phantom), fast_options());
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
    EXPECT_EQ(m.spec.id, kMethods[i]);
    SCOPED_TRACE(m.spec.id);
    if (m.spec.route == Route::Contour) {
      // Contour-route methods keep the reconstructed mesh's connectivity.
      EXPECT_EQ(m.mesh.num_vertices(), c.contour_mesh.num_vertices());
      EXPECT_EQ(m.mesh.triangles, c.contour_mesh.triangles);
    }
    EXPECT_TRUE(m.mesh.positions.allFinite());
    ASSERT_TRUE(m.accuracy.has_value());
    const SurfaceAccuracy& a = *m.accuracy;
    for (const RegionAccuracy* r : {&a.all, &a.feature, &a.smooth}) {
      EXPECT_TRUE(std::isfinite(r->rms) && r->rms > 0.0);
      EXPECT_LE(r->rms, r->hausdorff + 1e-12);
      EXPECT_TRUE(std::isfinite(r->normal_error_degrees));
      EXPECT_TRUE(std::isfinite(r->mean_signed));
      EXPECT_GT(r->mesh_area, 0.0);
    }
    EXPECT_NEAR(a.feature.mesh_area + a.smooth.mesh_area, a.all.mesh_area, 1e-6 * a.all.mesh_area);
    EXPECT_TRUE(std::isfinite(a.vertex_rms));
    EXPECT_TRUE(std::isfinite(m.volume_change_percent));
    ASSERT_TRUE(m.volume_error_percent.has_value());
    EXPECT_LT(std::abs(*m.volume_error_percent), 25.0) << "every mesh encloses roughly the femur's volume";
    EXPECT_GE(m.stage_seconds("total"), 0.0);
  }
}

void check_none_is_the_reconstructed_mesh(const Comparison& c) {
  const MethodResult& none = *c.find(SmoothingMethod::None);
  EXPECT_EQ(none.mesh.positions, c.contour_mesh.positions);
  EXPECT_EQ(none.volume_change_percent, 0.0);
  EXPECT_EQ(none.iterations, 0);
  EXPECT_TRUE(none.volume_curve.empty());
  EXPECT_EQ(c.find(ExternalMethod::VoxelFlyingEdges)->volume_change_percent, 0.0);
}

void check_the_metrics_see_what_smoothing_does(const Comparison& c) {
  const double none = c.find(SmoothingMethod::None)->accuracy->all.normal_error_degrees;
  // 200 HU of noise crumples the contours: smoothing straightens the faces.
  EXPECT_LT(c.find(SmoothingMethod::Taubin)->accuracy->all.normal_error_degrees, 0.9 * none);
  // Windowed sinc on the staircase of the voxel route also beats the raw flying-edges mesh.
  EXPECT_LT(c.find(ExternalMethod::VoxelWindowedSinc)->accuracy->all.normal_error_degrees,
            c.find(ExternalMethod::VoxelFlyingEdges)->accuracy->all.normal_error_degrees);
  // Laplacian shrinks, Taubin much less; the signed distance sees the shrinkage.
  const MethodResult& laplacian = *c.find(SmoothingMethod::Laplacian);
  EXPECT_LT(laplacian.volume_change_percent, -1.0);
  EXPECT_LT(laplacian.accuracy->all.mean_signed, c.find(SmoothingMethod::Taubin)->accuracy->all.mean_signed);
  EXPECT_LT(std::abs(c.find(SmoothingMethod::Taubin)->volume_change_percent), std::abs(laplacian.volume_change_percent));
}

void check_stages_labels_and_detection_scores(const Comparison& c) {
  const MethodResult& paper = *c.find(SmoothingMethod::FeaturePreserving);
  for (const char* stage : {"detect", "subdivide", "smooth", "total"}) {
    EXPECT_GT(paper.stage_seconds(stage), 0.0) << stage;
  }
  EXPECT_NEAR(paper.stage_seconds("total"),
              paper.stage_seconds("detect") + paper.stage_seconds("subdivide") + paper.stage_seconds("smooth"), 1e-9);
  const MethodResult& voxel = *c.find(ExternalMethod::VoxelWindowedSinc);
  for (const char* stage : {"threshold", "surface", "smooth", "total"}) EXPECT_GT(voxel.stage_seconds(stage), 0.0) << stage;

  std::size_t truths = 0, examinable_truths = 0;
  for (std::size_t i = 0; i < c.true_features.size(); ++i) {
    truths += c.true_features[i];
    examinable_truths += c.true_features[i] && c.examinable[i];
    EXPECT_EQ(c.examinable[i] != 0, c.contour_mesh.slice_ids[i] >= 0);
  }
  EXPECT_GT(truths, examinable_truths) << "a femur's cap rims hold true features off the slices";
  for (const MethodResult* m : {&paper, c.find(SmoothingMethod::CrossSlice)}) {
    SCOPED_TRACE(m->spec.id);
    ASSERT_TRUE(m->labels.has_value());
    const LabelSummary& l = *m->labels;
    ASSERT_TRUE(l.true_features && l.detected && l.true_positives && l.examinable_true_features);
    EXPECT_EQ(*l.true_features, truths);
    EXPECT_EQ(*l.examinable_true_features, examinable_truths);
    EXPECT_EQ(*l.detected, l.edges + l.corners);
    EXPECT_LE(*l.true_positives, std::min(*l.detected, *l.true_features));
    EXPECT_LE(*l.examinable_true_positives, *l.true_positives);
    EXPECT_DOUBLE_EQ(l.recall, static_cast<double>(*l.true_positives) / static_cast<double>(truths));
    EXPECT_DOUBLE_EQ(l.recall_examinable,
                     static_cast<double>(*l.examinable_true_positives) / static_cast<double>(examinable_truths));
    EXPECT_EQ(m->vertex_labels.size(), static_cast<std::size_t>(c.contour_mesh.num_vertices()));
  }
  ASSERT_TRUE(paper.labels->candidates.has_value());
  EXPECT_EQ(paper.labels->edges + paper.labels->corners + paper.labels->noise, *paper.labels->candidates);
  for (const MethodResult& m : c.methods) {
    if (m.spec.key != MethodKey(SmoothingMethod::FeaturePreserving) &&
        m.spec.key != MethodKey(SmoothingMethod::CrossSlice)) {
      EXPECT_FALSE(m.labels.has_value()) << m.spec.id;
    }
  }
}

void check_iterations_and_volume_curves(const Comparison& c) {
  for (const char* id : {"laplacian", "taubin", "mcf", "mindist", "vtk-smooth-feature-edges"}) {
    const MethodResult& m = *c.find(id);
    EXPECT_EQ(m.iterations, 20) << id << ": the shared count";
    ASSERT_EQ(m.volume_curve.size(), 21u) << id;
    EXPECT_EQ(m.volume_curve.front(), 0.0);
    // The last point is the method's result: the rate is minus the volume change.
    EXPECT_NEAR(100.0 * m.volume_curve.back(), -m.volume_change_percent, 1e-6) << id;
  }
  const MethodResult& paper = *c.find("paper");
  EXPECT_EQ(paper.iterations, 40) << "the xu2006 preset keeps its own count";
  EXPECT_NE(paper.spec.title.find("40 iterations"), std::string::npos) << "and says so";
  ASSERT_EQ(paper.volume_curve.size(), 41u);
  EXPECT_NEAR(100.0 * paper.volume_curve.back(), -paper.volume_change_percent, 1e-6);
  const auto& lap = c.find("laplacian")->volume_curve;
  for (std::size_t k = 1; k < lap.size(); ++k) EXPECT_GT(lap[k], lap[k - 1]);
  // No intermediate steps: no curve.
  EXPECT_TRUE(c.find("vtk-windowed-sinc")->volume_curve.empty());
  EXPECT_EQ(c.find("vtk-windowed-sinc")->iterations, 20);
  EXPECT_TRUE(c.find("cross-slice")->volume_curve.empty());
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
    SCOPED_TRACE("the_metrics_see_what_smoothing_does");
    check_the_metrics_see_what_smoothing_does(c);
  }
  {
    SCOPED_TRACE("stages_labels_and_detection_scores");
    check_stages_labels_and_detection_scores(c);
  }
  {
    SCOPED_TRACE("iterations_and_volume_curves");
    check_iterations_and_volume_curves(c);
  }
}

TEST(Comparison, TablesHaveARowPerMethodAndParse) {
  const Series s = make_series("ridge-box", parse_regime("ct20"), {1}, {small_comparison()});
  std::istringstream csv(metrics_csv(s));
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

  const auto j = nlohmann::json::parse(metrics_json(s));
  EXPECT_EQ(j["truth"], "phantom");
  EXPECT_EQ(j["regime"]["name"], "ct20");
  ASSERT_EQ(j["runs"].size(), 1u);
  EXPECT_EQ(j["runs"][0]["seed"], 1);
  ASSERT_EQ(j["mean"].size(), kMethods.size());
  for (const auto& m : j["mean"]) {
    for (const char* key : {"rms_mm", "hausdorff_mm", "feature_rms_mm", "smooth_rms_mm", "normal_error_degrees",
                            "vertex_rms_mm", "volume_error_percent"}) {
      EXPECT_TRUE(m[key].is_number()) << m["id"] << " " << key;
    }
    EXPECT_TRUE(m["seconds"]["total"].is_number());
  }
  for (const auto& m : j["runs"][0]["methods"]) {
    for (const char* region : {"all", "feature", "smooth"}) {
      EXPECT_TRUE(m["accuracy"][region]["rms"].is_number()) << m["id"] << region;
      EXPECT_TRUE(m["accuracy"][region]["hausdorff"].is_number()) << m["id"] << region;
    }
  }
  EXPECT_TRUE(j["mean"][6]["labels"]["recall_on_contours"].is_number()) << "cross-slice's labels";

  std::istringstream curves(volume_curve_csv(small_comparison()));
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
  v.spacing = {1.5, 1.5, 3.0};
  const CtImage::Pointer image = render_phantom(phantom, v);
  const Mesh sphere = make_icosphere(3, 30.0);
  const ComparisonTruth truth = reference_surface_truth(sphere, "a sphere of radius 30");
  // The distance to a sphere mesh from its centre is about its radius.
  EXPECT_NEAR(truth.surface->distance(Eigen::Vector3d::Zero()), 30.0, 0.5);
  EXPECT_NEAR(truth.surface->samples.area(), surface_area(sphere), 0.05 * surface_area(sphere));
  ComparisonOptions o = fast_options();
  o.volume_curves = false;
  o.methods.only = {"none", "taubin", "cross-slice", "voxel-windowed-sinc"};
  const Comparison c = run_comparison(*image, "ridge-box volume", truth, o);
  EXPECT_EQ(c.truth, TruthKind::ReferenceSurface);
  ASSERT_EQ(c.methods.size(), 4u);
  for (const MethodResult& m : c.methods) {
    ASSERT_TRUE(m.accuracy.has_value()) << m.spec.id;
    EXPECT_GT(m.accuracy->all.rms, 1.0) << "a box is far from the sphere";
    EXPECT_TRUE(std::isnan(m.accuracy->all.normal_error_degrees)) << "no normals without an analytic field";
    EXPECT_TRUE(std::isnan(m.accuracy->all.mean_signed)) << "the distance to a mesh is unsigned";
    EXPECT_TRUE(std::isnan(m.accuracy->feature.rms)) << "no features known";
    EXPECT_FALSE(m.volume_error_percent.has_value());
  }
  ASSERT_TRUE(c.find("cross-slice")->labels.has_value());
  EXPECT_FALSE(c.find("cross-slice")->labels->true_features.has_value());
  EXPECT_TRUE(std::isnan(c.find("cross-slice")->labels->recall));
  EXPECT_THROW((void)reference_surface_truth(Mesh{}, "empty"), InvalidInputError);
}

TEST(Comparison, WithoutTruthThereAreNoDistances) {
  const Phantom phantom = make_phantom(PhantomShape::RidgeBox);
  PhantomVolumeOptions v;
  v.spacing = {1.5, 1.5, 3.0};
  const CtImage::Pointer image = render_phantom(phantom, v);
  ComparisonOptions o = fast_options();
  o.volume_curves = false;
  o.methods.only = {"none", "taubin"};
  const Comparison c = run_comparison(*image, "ridge-box volume", ComparisonTruth{}, o);
  EXPECT_EQ(c.truth, TruthKind::None);
  for (const MethodResult& m : c.methods) EXPECT_FALSE(m.accuracy.has_value()) << m.spec.id;
  EXPECT_TRUE(c.true_features.empty());
  const Series s = make_series("volume", Regime{"input", 0.0, 0.0}, {}, {c});
  EXPECT_NE(metrics_csv(s).find("\nnone,contour,"), std::string::npos);
}

TEST(Comparison, OptionsOutOfRangeAndCancellation) {
  const Phantom phantom = make_phantom(PhantomShape::RidgeBox);
  PhantomVolumeOptions v;
  v.spacing = {2.0, 2.0, 4.0};
  const CtImage::Pointer image = render_phantom(phantom, v);
  const ComparisonTruth truth = coarse_truth(phantom);
  for (const auto& change : std::vector<std::function<void(ComparisonOptions&)>>{
           [](ComparisonOptions& o) { o.timing_repeats = 0; },
           [](ComparisonOptions& o) { o.metrics.feature_radius = 0.0; },
           [](ComparisonOptions& o) { o.detection_radius = -1.0; },
           [](ComparisonOptions& o) { o.methods.sinc_passband = 0.0; },
           [](ComparisonOptions& o) { o.methods.laplace_relaxation = 2.0; },
           [](ComparisonOptions& o) { o.methods.iterations = 0; },
           [](ComparisonOptions& o) { o.methods.only = {"bilateral"}; },
       }) {
    ComparisonOptions o = fast_options();
    change(o);
    EXPECT_THROW((void)run_comparison(*image, "x", truth, o), InvalidInputError);
  }
  ComparisonOptions o = fast_options();
  o.progress = [](std::string_view stage, double) { return stage != "taubin"; };
  EXPECT_THROW((void)run_comparison(*image, "x", truth, o), CancelledError);
  // A threshold above every voxel: no contour, an error naming the source.
  o = fast_options();
  o.reconstruction.segmentation.threshold = 5000.0;
  try {
    (void)run_comparison(*image, "the test volume", truth, o);
    FAIL() << "expected InvalidInputError";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("the test volume"), std::string::npos) << e.what();
  }
}

TEST(Comparison, PhantomTruthSamplesTheSurfaceAndKnowsItsFeatures) {
  const Phantom phantom = make_phantom(PhantomShape::RidgeBox);
  const ComparisonTruth t = coarse_truth(phantom);
  EXPECT_EQ(t.kind, TruthKind::Phantom);
  EXPECT_EQ(t.volume, phantom.volume);
  ASSERT_TRUE(t.surface && t.surface->feature_distance && t.surface->normal);
  EXPECT_GT(t.surface->samples.size(), 1000);
  for (Index k = 0; k < t.surface->samples.size(); k += 97) {
    EXPECT_LT(std::abs(phantom.sdf(t.surface->samples.points.col(k))), 0.05) << "samples lie on the surface";
  }
  for (std::size_t k = 0; k < phantom.feature_points.size(); k += 50) {
    EXPECT_DOUBLE_EQ(t.surface->feature_distance(phantom.feature_points[k]), 0.0);
    EXPECT_NEAR(t.surface->feature_distance(phantom.feature_points[k] + Eigen::Vector3d(0, 0, 0.0)), 0.0, 1e-12);
  }
  EXPECT_NEAR(t.surface->feature_distance(phantom.feature_points[0] + Eigen::Vector3d(100.0, 0, 0)), 100.0, 60.0);
}

// ---------------------------------------------------------------------------------------------------
// The method table and its variants

TEST(MethodTable, StandardMethodsKeyedByEnumAndTheSharedIterationCount) {
  EXPECT_EQ(standard_method_ids(), kMethods);
  MethodTableOptions o;
  o.iterations = 12;
  const std::vector<MethodSpec> table = method_table(o);
  ASSERT_EQ(table.size(), kMethods.size());
  for (const MethodSpec& s : table) {
    EXPECT_FALSE(s.variant);
    EXPECT_TRUE(static_cast<bool>(s.run)) << s.id;
    EXPECT_FALSE(s.title.empty() || s.legend.empty() || s.settings.empty()) << s.id;
    if (const auto* m = std::get_if<SmoothingMethod>(&s.key)) {
      EXPECT_EQ(s.id, std::string(to_string(*m)));
      EXPECT_EQ(s.route, Route::Contour);
      const int want = *m == SmoothingMethod::None ? 0 : (*m == SmoothingMethod::FeaturePreserving ? 40 : 12);
      if (*m != SmoothingMethod::CrossSlice) EXPECT_EQ(iterations_of(*m, s.options), want) << s.id;
    } else {
      EXPECT_EQ(s.id, std::string(to_string(std::get<ExternalMethod>(s.key))));
    }
  }
  EXPECT_EQ(table[5].preset, "xu2006");
  EXPECT_EQ(table[6].preset, "default");
  EXPECT_EQ(table[6].key, MethodKey(preset(Preset::Default).method));
  EXPECT_NE(table[7].settings.find("12 iterations"), std::string::npos) << "VTK's filters share the count";
  o.only = {"none", "cross-slice"};
  ASSERT_EQ(method_table(o).size(), 2u);
  o.only = {"none", "slicer"};
  EXPECT_THROW((void)method_table(o), InvalidInputError);
}

TEST(MethodTable, VariantsParseIntoRowsOfTheirOwn) {
  MethodVariant v = parse_variant("across:stages=across-only,reach=4");
  EXPECT_EQ(v.id, "across");
  EXPECT_EQ(v.method, SmoothingMethod::CrossSlice);
  EXPECT_EQ(v.options.cross_slice.stages, CrossSliceStages::AcrossOnly);
  EXPECT_EQ(v.options.cross_slice.reach, 4);
  v = parse_variant("paper-normal:preset=xu2006,measure=normal,in-slice=along-line");
  EXPECT_EQ(v.method, SmoothingMethod::FeaturePreserving);
  EXPECT_EQ(v.options.paper.detection.measure, UmbrellaMeasure::NormalComponent);
  EXPECT_GT(v.options.paper.detection.corner_spread, 1.0 / 3.0) << "the rest is the preset's";
  v = parse_variant("taubin40:method=taubin,iterations=40");
  EXPECT_EQ(v.method, SmoothingMethod::Taubin);
  EXPECT_EQ(v.options.iterations, 40);
  EXPECT_EQ(parse_variant("plain").method, preset(Preset::Default).method);

  for (const char* bad : {":reach=3", "a b:reach=3", "x:reach", "x:reach=three", "x:colour=red", "x:measure=normal",
                          "x:method=taubin,reach=3", "x:stages=sideways", "x:method=bilateral"}) {
    EXPECT_THROW((void)parse_variant(bad), InvalidInputError) << bad;
  }
  try {
    (void)parse_variant("x:method=taubin,reach=3");
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("'reach' is not an option of taubin"), std::string::npos) << e.what();
  }

  MethodTableOptions o;
  o.only = {"none"};
  o.variants = {parse_variant("across:stages=across-only"), parse_variant("xu-normal:preset=xu2006,measure=normal"),
                parse_variant("lap:method=laplacian")};
  const std::vector<MethodSpec> table = method_table(o);
  ASSERT_EQ(table.size(), 4u);
  EXPECT_TRUE(table[1].variant);
  EXPECT_NE(table[1].settings.find("stages=across-only"), std::string::npos) << table[1].settings;
  EXPECT_EQ(iterations_of(SmoothingMethod::FeaturePreserving, table[2].options), 40) << "a preset keeps its count";
  EXPECT_EQ(iterations_of(SmoothingMethod::Laplacian, table[3].options), 20) << "others share the table's";
  o.variants.push_back(parse_variant("taubin:method=taubin"));
  EXPECT_THROW((void)method_table(o), InvalidInputError) << "a standard method's id";
  o.variants.back() = parse_variant("across:reach=2");
  EXPECT_THROW((void)method_table(o), InvalidInputError) << "twice";
}

// ---------------------------------------------------------------------------------------------------
// Regimes, seeds, means and verdicts

TEST(Series, RegimesAndSeedsParse) {
  const Regime ct = parse_regime("ct60");
  EXPECT_EQ(ct.ct_noise_hu, 60.0);
  EXPECT_FALSE(ct.contour());
  const Regime contour = parse_regime("contour0.4");
  EXPECT_EQ(contour.contour_noise_mm, 0.4);
  EXPECT_EQ(contour.ct_noise_hu, 20.0);
  EXPECT_TRUE(contour.contour());
  EXPECT_EQ(parse_regime("contour1-ct60").ct_noise_hu, 60.0);
  const std::vector<Regime> all = parse_regimes("all");
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].name, "ct20");
  EXPECT_EQ(all[1].name, "ct60");
  EXPECT_EQ(all[2].name, "contour0.4");
  for (const char* bad : {"ct", "ct-5", "mri20", "contour0", "contourx", "ct20,ct20"}) {
    EXPECT_THROW((void)parse_regimes(bad), InvalidInputError) << bad;
  }
  EXPECT_EQ(parse_seeds("1-3"), (std::vector<std::uint64_t>{1, 2, 3}));
  EXPECT_EQ(parse_seeds("7,1-2"), (std::vector<std::uint64_t>{7, 1, 2}));
  for (const char* bad : {"", "3-1", "1,1", "a", "1-", "0-200"}) EXPECT_THROW((void)parse_seeds(bad), InvalidInputError) << bad;
}

TEST(Series, MeansAreOverTheSeeds) {
  const Phantom phantom = make_phantom(PhantomShape::RidgeBox);
  const ComparisonTruth truth = coarse_truth(phantom);
  ComparisonOptions o = fast_options();
  o.methods.only = {"none", "taubin"};
  o.volume_curves = false;
  std::vector<Comparison> runs;
  for (std::uint64_t seed : {1u, 2u}) {
    PhantomVolumeOptions v;
    v.spacing = {2.0, 2.0, 4.0};
    v.noise = 150.0;
    v.seed = seed;
    runs.push_back(run_comparison(*render_phantom(phantom, v), "seed " + std::to_string(seed), truth, o));
  }
  const double a = runs[0].find("taubin")->accuracy->all.rms, b = runs[1].find("taubin")->accuracy->all.rms;
  EXPECT_NE(a, b) << "different noise, different results";
  const Series s = make_series("ridge-box", parse_regime("ct150"), {1, 2}, std::move(runs));
  ASSERT_EQ(s.mean.size(), 2u);
  EXPECT_EQ(s.find("taubin")->runs, 2u);
  EXPECT_DOUBLE_EQ(s.find("taubin")->rms, 0.5 * (a + b));
  EXPECT_EQ(s.find(SmoothingMethod::Taubin), s.find("taubin"));
  const auto j = nlohmann::json::parse(metrics_json(s));
  ASSERT_EQ(j["runs"].size(), 2u);
  EXPECT_EQ(j["runs"][1]["seed"], 2);
  EXPECT_DOUBLE_EQ(j["runs"][1]["methods"][1]["accuracy"]["all"]["rms"].get<double>(), b);
  EXPECT_THROW((void)make_series("x", parse_regime("ct20"), {}, {}), InvalidInputError);
}

// A series with the given numbers of the default, the unsmoothed mesh and the voxel route.
Series synthetic(const std::string& name, const std::string& regime, double d_rms, double d_feature, double d_normal,
                 double n_rms, double n_feature, double n_normal, double voxel_rms) {
  Series s;
  s.name = name;
  s.regime = parse_regime(regime);
  s.runs.resize(1);
  s.runs[0].truth = TruthKind::Phantom;
  const auto summary = [](MethodKey key, double rms, double feature, double normal) {
    MethodSummary m;
    m.spec.key = key;
    m.spec.id = std::visit([](auto k) { return std::string(to_string(k)); }, key);
    m.rms = rms;
    m.feature_rms = feature;
    m.normal_error = normal;
    m.volume_error_percent = 0.1;
    return m;
  };
  s.mean.push_back(summary(SmoothingMethod::None, n_rms, n_feature, n_normal));
  MethodSummary d = summary(preset(Preset::Default).method, d_rms, d_feature, d_normal);
  d.has_labels = true;
  d.precision = 0.85;
  d.recall = 0.69;
  d.recall_examinable = 0.9;
  s.mean.push_back(d);
  s.mean.push_back(summary(ExternalMethod::VoxelWindowedSinc, voxel_rms, 1.0, 5.0));
  return s;
}

TEST(Verdicts, TheBarsAtTheirBounds) {
  // Do no harm: 1.05 x + 0.01 mm; normals 0.7 x. Beat the voxel route at 20 HU.
  const Series pass = synthetic("femur", "ct20", 0.2200, 0.1, 3.5, 0.2, 0.1, 5.0, 0.25);
  const Series fail = synthetic("pelvis", "ct20", 0.2201, 0.1, 3.5, 0.2, 0.1, 5.0, 0.21);
  const Series ct60 = synthetic("femur", "ct60", 0.2, 0.2, 3.6, 0.2, 0.2, 5.0, 0.1);
  // Denoise: 0.6 x, feature 0.7 x, lowest of all, volume.
  const Series denoise = synthetic("femur", "contour0.4", 0.239, 0.279, 3.0, 0.4, 0.4, 5.0, 0.3);
  const Series noisy = synthetic("skull", "contour0.4", 0.25, 0.28, 3.0, 0.4, 0.4, 5.0, 0.2);
  const std::vector<const Series*> all = {&pass, &fail, &ct60, &denoise, &noisy};
  const Verdicts v = judge(all);
  ASSERT_EQ(v.rows.size(), 5u);
  EXPECT_EQ(v.rows[0].harm.state, BarState::Pass) << v.rows[0].harm.detail;
  EXPECT_EQ(v.rows[0].voxel.state, BarState::Pass);
  EXPECT_EQ(v.rows[1].harm.state, BarState::Fail) << "0.2201 > 1.05 x 0.2 + 0.01";
  EXPECT_EQ(v.rows[1].voxel.state, BarState::Fail);
  EXPECT_EQ(v.rows[2].harm.state, BarState::Fail) << "normals 3.6 > 0.7 x 5";
  EXPECT_EQ(v.rows[2].voxel.state, BarState::NotApplicable) << "only at 20 HU";
  EXPECT_EQ(v.rows[3].denoise.state, BarState::Pass) << v.rows[3].denoise.detail;
  EXPECT_EQ(v.rows[3].harm.state, BarState::NotApplicable);
  EXPECT_EQ(v.rows[4].denoise.state, BarState::Fail) << "above 0.6 x, and the voxel route is lower";
  EXPECT_NE(v.rows[4].denoise.detail.find("not lowest"), std::string::npos) << v.rows[4].denoise.detail;
  for (const VerdictRow& r : v.rows) EXPECT_EQ(r.detection.state, BarState::Fail) << "recall 0.69 < 0.7";
  EXPECT_TRUE(v.rows[0].original);
  // Totals: bar 2 needs 5 of the 7 original phantoms.
  const auto total = [&](const std::string& bar, const std::string& regime) {
    for (const BarTotal& t : v.totals) {
      if (t.bar == bar && t.regime == regime) return t;
    }
    return BarTotal{};
  };
  const BarTotal voxel = total("2. beat the voxel route", "ct20");
  EXPECT_EQ(voxel.passed, 1);
  EXPECT_EQ(voxel.rows, 2);
  EXPECT_EQ(voxel.required, 5);
  EXPECT_FALSE(voxel.met());
  EXPECT_FALSE(total("1. do no harm", "ct20").met());
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
  EXPECT_EQ(item["regime"], "ct100");
  ASSERT_TRUE(item["rendered"].get<bool>()) << item["render_note"];
  ASSERT_EQ(j["verdicts"].size(), 1u);
  EXPECT_EQ(j["verdicts"][0]["denoise"], "-") << "a CT regime";

  for (const char* file : {"metrics.csv", "metrics.json", "volume_curve.csv", "volume_curve.png", "report.html",
                           "labels_cross-slice.png", "detection_cross-slice.png", "labels_paper.png"}) {
    EXPECT_TRUE(fs::is_regular_file(out / file)) << file;
  }
  // No temporary files are left behind.
  for (const auto& entry : fs::directory_iterator(out)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  }

  const auto metrics = nlohmann::json::parse(read_text(out / "metrics.json"));
  std::vector<std::string> names;
  for (const auto& m : metrics["mean"]) {
    names.push_back(m["id"]);
    for (const char* key : {"rms_mm", "hausdorff_mm", "feature_rms_mm", "smooth_rms_mm"}) {
      EXPECT_TRUE(m[key].is_number() && std::isfinite(m[key].get<double>())) << m["id"] << " " << key;
    }
    EXPECT_TRUE(m["normal_error_degrees"].is_number());
    if (m["id"] == "none") {
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
  for (const char* png : {"labels_cross-slice.png", "detection_cross-slice.png", "volume_curve.png"}) {
    const PngStats s = png_stats(out / png);
    EXPECT_GT(s.variance, 50.0) << png;
    EXPECT_GT(s.foreground, 0.02) << png;
  }
  EXPECT_NE(html.find("volume_curve.png"), std::string::npos);
  EXPECT_NE(html.find("metrics.csv"), std::string::npos);
}

// Two regimes, two seeds, a few methods and a variant: one directory per regime, means over the seeds,
// the summary with the verdicts, and the Markdown page.
TEST(CompareCli, RegimesSeedsVariantsAndTheSummary) {
  test::ScopedTempDir tmp("contourmesh_compare");
  const fs::path out = tmp.path() / "out";
  const fs::path md = tmp.path() / "results.md";
  const CliRun r = run_cli("compare --phantom ridge-box --spacing 2,2,4 --regimes ct20,ct60 --seeds 1-2 --methods "
                           "none,cross-slice,voxel-windowed-sinc --variant along-off:stages=across-only --no-render "
                           "--no-curves --out " +
                               out.string() + " --markdown " + md.string() + " --json",
                           tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["comparisons"].size(), 2u);
  for (const auto& item : j["comparisons"]) {
    const fs::path dir = item["directory"].get<std::string>();
    EXPECT_EQ(dir.parent_path(), out);
    EXPECT_EQ(dir.filename(), item["regime"].get<std::string>());
    const auto& m = item["metrics"];
    EXPECT_EQ(m["seeds"], nlohmann::json::array({1, 2}));
    ASSERT_EQ(m["runs"].size(), 2u);
    ASSERT_EQ(m["mean"].size(), 4u);
    EXPECT_EQ(m["mean"][3]["id"], "along-off");
    EXPECT_TRUE(m["mean"][3]["variant"].get<bool>());
    const double a = m["runs"][0]["methods"][1]["accuracy"]["all"]["rms"], b = m["runs"][1]["methods"][1]["accuracy"]["all"]["rms"];
    EXPECT_NEAR(m["mean"][1]["rms_mm"].get<double>(), 0.5 * (a + b), 1e-12);
    EXPECT_EQ(m["mean"][1]["runs"], 2);
  }
  for (const char* file : {"summary.csv", "summary.json", "report.html"}) EXPECT_TRUE(fs::exists(out / file)) << file;
  const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary["series"].size(), 2u);
  EXPECT_EQ(summary["verdicts"].size(), 2u);
  EXPECT_FALSE(summary["verdicts"][0]["do_no_harm"].is_null());
  EXPECT_TRUE(summary["verdicts"][1]["beat_voxel_route"].is_null()) << "ct60: bar 2 does not apply";
  const std::string page = read_text(md);
  for (const char* text : {"## Verdicts of the default", "## ct20", "## ct60", "## Feature labels", "along-off",
                           "the mean over the noise seeds 1, 2"}) {
    EXPECT_NE(page.find(text), std::string::npos) << text;
  }
  EXPECT_NE(r.out.find("\"verdicts\""), std::string::npos);
}

TEST(CompareCli, WithoutADisplayTheRendersAreSkippedAndSaidSo) {
  test::ScopedTempDir tmp("contourmesh_compare");
  const fs::path out = tmp.path() / "out";
  const CliRun r = run_cli("compare --phantom ridge-box " + std::string(kSmallPhantom) +
                               " --methods none,cross-slice --no-curves --out " + out.string(),
                           tmp.path(), false, "env -u DISPLAY");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("no renders"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out / "render_cross-slice.png"));
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
                         " --threshold 520 --methods none,taubin --no-render --no-curves --out " +
                         (tmp.path() / "with").string() + " --json",
                     tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  auto m = nlohmann::json::parse(r.out)["comparisons"][0]["metrics"];
  EXPECT_EQ(m["truth"], "reference-surface");
  EXPECT_TRUE(m["mean"][0]["rms_mm"].is_number());
  EXPECT_TRUE(m["mean"][0]["normal_error_degrees"].is_null());
  EXPECT_EQ(m["regime"]["name"], "input");

  r = run_cli("compare " + volume.string() + " --threshold 520 --methods none,taubin --no-render --no-curves --out " +
                  (tmp.path() / "without").string() + " --json",
              tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  m = nlohmann::json::parse(r.out)["comparisons"][0]["metrics"];
  EXPECT_EQ(m["truth"], "none");
  EXPECT_TRUE(m["runs"][0]["methods"][0]["accuracy"].is_null());
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

  // Options checked before any work.
  for (const auto& [option, fragment] : std::vector<std::pair<std::string, std::string>>{
           {"--render-size 10x10", "--render-size"},
           {"--color-levels 1", "--color-levels"},
           {"--regimes ct20,mri", "mri"},
           {"--seeds 3-1", "--seeds"},
           {"--methods none,slicer", "slicer"},
           {"--variant x:colour=red", "colour"},
           {"--render-methods cross-slice,foo", "foo"},
           {"--iterations 0", "--iterations"}}) {
    r = run_cli("compare --phantom ridge-box " + option + out, tmp.path());
    EXPECT_EQ(r.code, 2) << option;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << option << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(tmp.path() / "out" / "report.html"));
}

TEST(CompareCli, ConflictingOptionsAreUsageErrors) {
  test::ScopedTempDir tmp("contourmesh_compare");
  const std::string out = " --out " + (tmp.path() / "out").string();
  EXPECT_EQ(run_cli("compare --phantom femur in.nrrd" + out, tmp.path()).code, 1);
  EXPECT_EQ(run_cli("compare --phantom femur --truth ref.stl" + out, tmp.path()).code, 1);
  EXPECT_EQ(run_cli("compare --phantom femur --regimes ct20 --noise 60" + out, tmp.path()).code, 1);
  EXPECT_EQ(run_cli("compare --phantom femur --seeds 1-3 --seed 2" + out, tmp.path()).code, 1);
  EXPECT_EQ(run_cli("compare --phantom femur", tmp.path()).code, 1) << "--out is required";
  EXPECT_FALSE(fs::exists(tmp.path() / "out"));
}

}  // namespace
}  // namespace contourmesh
