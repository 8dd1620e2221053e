// SPDX-License-Identifier: BSD-3-Clause
// The evaluation harness's comparison (contourmesh_compare): run_comparison on small noisy phantoms, with
// a phantom, a reference surface or no truth; what it measures, the tables and the plot it writes.
#include <compare/comparison.h>
#include <compare/report.h>
#include <compare/series.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/metrics.h>
#include <contourmesh/smooth/shapes.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "compare_support.h"
#include "test_support.h"

namespace contourmesh {
namespace {

using namespace compare_test;
namespace fs = std::filesystem;

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
  EXPECT_LT(std::abs(c.find(SmoothingMethod::Taubin)->volume_change_percent),
            std::abs(laplacian.volume_change_percent));
}

void check_stages_labels_and_detection_scores(const Comparison& c) {
  const MethodResult& paper = *c.find(SmoothingMethod::FeaturePreserving);
  for (const char* stage : {"detect", "subdivide", "smooth", "total"}) {
    EXPECT_GT(paper.stage_seconds(stage), 0.0) << stage;
  }
  EXPECT_NEAR(paper.stage_seconds("total"),
              paper.stage_seconds("detect") + paper.stage_seconds("subdivide") + paper.stage_seconds("smooth"), 1e-9);
  const MethodResult& voxel = *c.find(ExternalMethod::VoxelWindowedSinc);
  for (const char* stage : {"threshold", "surface", "smooth", "total"})
    EXPECT_GT(voxel.stage_seconds(stage), 0.0) << stage;

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

}  // namespace
}  // namespace contourmesh
