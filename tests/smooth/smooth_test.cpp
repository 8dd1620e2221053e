// SPDX-License-Identifier: BSD-3-Clause
// smooth(mesh, method, options): one entry point that gives each method's own result, its default
// iteration count, labels where the method has them, and the presets.
#include "contourmesh/smooth/cross_slice.h"
#include "contourmesh/smooth/errors.h"
#include "contourmesh/smooth/feature_smoothing.h"
#include "contourmesh/smooth/shapes.h"
#include "contourmesh/smooth/smooth.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "test_support.h"

namespace contourmesh {
namespace {

Mesh small_stack() { return test::noisy_ridge_stack(10, 48, 3.0, 5); }

TEST(SmoothEntryPoint, BaselinesGiveTheBaselineResult) {
  const Mesh m = small_stack();
  for (SmoothingMethod method : {SmoothingMethod::None, SmoothingMethod::Laplacian, SmoothingMethod::Taubin,
                                 SmoothingMethod::MeanCurvatureFlow, SmoothingMethod::MinDistFlow}) {
    SCOPED_TRACE(std::string(to_string(method)));
    SmoothingOptions direct;
    direct.method = method;
    const SmoothResult r = smooth(m, method);
    EXPECT_EQ(r.method, method);
    EXPECT_EQ(r.mesh.positions, smooth(m, direct));
    EXPECT_EQ(r.mesh.triangles, m.triangles);
    EXPECT_EQ(r.mesh.slice_ids, m.slice_ids);
    EXPECT_TRUE(r.labels.empty());
    EXPECT_FALSE(r.detection.has_value());
    EXPECT_EQ(r.iterations, method == SmoothingMethod::None ? 0 : 20);
    EXPECT_GE(r.seconds.total, r.seconds.smooth);
  }
}

TEST(SmoothEntryPoint, ThePapersMethodGivesItsOwnResultAndLabels) {
  const Mesh m = small_stack();
  const FeatureSmoothingResult direct = feature_preserving_smooth(m);
  const SmoothResult r = smooth(m, SmoothingMethod::FeaturePreserving);
  EXPECT_EQ(r.mesh.positions, direct.mesh.positions);
  EXPECT_EQ(r.labels, direct.detection.labels);
  ASSERT_TRUE(r.detection.has_value());
  EXPECT_EQ(r.detection->edges, direct.detection.edges);
  EXPECT_EQ(r.iterations, 40);
  EXPECT_EQ(r.subdivided_vertices, direct.subdivided_vertices);
  EXPECT_EQ(r.adaptive_vertices, direct.adaptive_vertices);
  EXPECT_GT(r.seconds.detect, 0.0);
  EXPECT_GE(r.seconds.total, r.seconds.detect + r.seconds.subdivide + r.seconds.smooth);
}

TEST(SmoothEntryPoint, CrossSliceGivesItsOwnResultAndLabels) {
  const Mesh m = small_stack();
  const CrossSliceResult direct = cross_slice_smooth(m);
  const SmoothResult r = smooth(m, SmoothingMethod::CrossSlice);
  EXPECT_EQ(r.mesh.positions, direct.mesh.positions);
  EXPECT_EQ(r.labels, direct.labels);
  EXPECT_EQ(r.labels.size(), static_cast<std::size_t>(m.num_vertices()));
  ASSERT_TRUE(r.creases.has_value());
  EXPECT_EQ(r.creases->labels, direct.features.labels);
  EXPECT_FALSE(r.detection.has_value());
  EXPECT_EQ(r.profiles, direct.profiles);
  EXPECT_EQ(r.noise_across, direct.noise_across);
  EXPECT_EQ(r.iterations, 0);
}

TEST(SmoothEntryPoint, LabelsAloneAreTheLabelsOfTheMethod) {
  const Mesh m = small_stack();
  SmoothOptions o;
  o.paper.detection.in_slice = InSliceFeatures::AlongFeatureLine;
  o.cross_slice.features.band = 0.5;
  for (SmoothingMethod method : {SmoothingMethod::FeaturePreserving, SmoothingMethod::CrossSlice}) {
    const FeatureLabels f = label_features(m, method, o);
    EXPECT_EQ(f.labels, smooth(m, method, o).labels) << to_string(method);
    EXPECT_EQ(f.detection.has_value(), method == SmoothingMethod::FeaturePreserving);
    EXPECT_EQ(f.creases.has_value(), method == SmoothingMethod::CrossSlice);
  }
  EXPECT_THROW((void)label_features(m, SmoothingMethod::Taubin), InvalidInputError);
}

TEST(SmoothEntryPoint, DefaultIterationCountsLiveInTheLibrary) {
  EXPECT_EQ(default_iterations(SmoothingMethod::None), 0);
  for (SmoothingMethod m : {SmoothingMethod::Laplacian, SmoothingMethod::Taubin, SmoothingMethod::MeanCurvatureFlow,
                            SmoothingMethod::MinDistFlow}) {
    EXPECT_EQ(default_iterations(m), SmoothingOptions{}.iterations);
    EXPECT_EQ(default_iterations(m), 20);
  }
  EXPECT_EQ(default_iterations(SmoothingMethod::FeaturePreserving), FeatureSmoothingOptions{}.iterations);
  EXPECT_EQ(default_iterations(SmoothingMethod::FeaturePreserving), 40);
  EXPECT_EQ(default_iterations(SmoothingMethod::CrossSlice), 0);
  EXPECT_TRUE(produces_labels(SmoothingMethod::FeaturePreserving));
  EXPECT_TRUE(produces_labels(SmoothingMethod::CrossSlice));
  EXPECT_FALSE(produces_labels(SmoothingMethod::Taubin));
}

TEST(SmoothEntryPoint, ASharedIterationCountOverridesEachFamily) {
  const Mesh m = small_stack();
  SmoothOptions o;
  o.iterations = 7;
  EXPECT_EQ(iterations_of(SmoothingMethod::Taubin, o), 7);
  EXPECT_EQ(iterations_of(SmoothingMethod::FeaturePreserving, o), 7);
  EXPECT_EQ(iterations_of(SmoothingMethod::CrossSlice, o), 0);
  SmoothingOptions taubin;
  taubin.iterations = 7;
  EXPECT_EQ(smooth(m, SmoothingMethod::Taubin, o).mesh.positions, smooth(m, taubin));
  FeatureSmoothingOptions paper;
  paper.iterations = 7;
  EXPECT_EQ(smooth(m, SmoothingMethod::FeaturePreserving, o).mesh.positions,
            feature_preserving_smooth(m, paper).mesh.positions);
  o.iterations = -1;
  EXPECT_THROW((void)smooth(m, SmoothingMethod::Taubin, o), InvalidInputError);
}

TEST(SmoothEntryPoint, DetectionOptionsOfTheMethodThatRuns) {
  SmoothOptions o;
  EXPECT_EQ(detection_options_of(SmoothingMethod::FeaturePreserving, o), &o.paper.detection);
  EXPECT_EQ(detection_options_of(SmoothingMethod::CrossSlice, o), nullptr) << "it labels creases";
  EXPECT_EQ(detection_options_of(SmoothingMethod::Taubin, o), nullptr);
}

TEST(SmoothEntryPoint, ProgressLimitsAndCancellation) {
  const Mesh m = small_stack();
  for (SmoothingMethod method : all_smoothing_methods()) {
    SCOPED_TRACE(std::string(to_string(method)));
    SmoothOptions o;
    std::vector<std::string> stages;
    o.progress = [&](std::string_view stage, double) {
      stages.emplace_back(stage);
      return true;
    };
    (void)smooth(m, method, o);
    o.progress = [](std::string_view, double) { return false; };
    if (method != SmoothingMethod::None) {
      EXPECT_FALSE(stages.empty());
      EXPECT_THROW((void)smooth(m, method, o), CancelledError);
    }
    o = {};
    o.limits.max_vertices = m.num_vertices() - 1;
    EXPECT_THROW((void)smooth(m, method, o), LimitError);
  }
  // The families' own progress members are replaced by the common one.
  SmoothOptions o;
  o.paper.progress = [](std::string_view, double) { return false; };
  o.paper.detection.progress = [](std::string_view, double) { return false; };
  o.cross_slice.progress = [](std::string_view, double) { return false; };
  EXPECT_NO_THROW((void)smooth(m, SmoothingMethod::FeaturePreserving, o));
  EXPECT_NO_THROW((void)smooth(m, SmoothingMethod::CrossSlice, o));
}

TEST(SmoothEntryPoint, ADivergingRunIsAnErrorAndTheFamilysObserverStillRuns) {
  const Mesh m = small_stack();
  for (SmoothingMethod method : {SmoothingMethod::Taubin, SmoothingMethod::FeaturePreserving}) {
    SCOPED_TRACE(std::string(to_string(method)));
    SmoothOptions o;
    o.iterations = 1'000'000;  // amplifies the high frequencies until they overflow
    int seen = 0;
    o.baseline.on_iteration = o.paper.on_iteration = [&seen](int, const Eigen::Matrix3Xd&) { ++seen; };
    try {
      (void)smooth(m, method, o);
      ADD_FAILURE() << "no DivergenceError";
    } catch (const DivergenceError& e) {
      EXPECT_NE(std::string(e.what()).find("smoothing diverged at iteration"), std::string::npos) << e.what();
    }
    EXPECT_GT(seen, 0);
    EXPECT_LT(seen, 1'000'000);  // stopped at once, not at the end
  }
}

TEST(SmoothEntryPoint, MethodsThatNeedIdsSaySo) {
  const Mesh sphere = make_icosphere(2);
  EXPECT_THROW((void)smooth(sphere, SmoothingMethod::FeaturePreserving), InvalidInputError);
  EXPECT_THROW((void)smooth(sphere, SmoothingMethod::CrossSlice), InvalidInputError);
  EXPECT_NO_THROW((void)smooth(sphere, SmoothingMethod::Taubin));
}

TEST(Presets, NamesAndTheDefault) {
  for (Preset p : {Preset::Default, Preset::Xu2006}) EXPECT_EQ(parse_preset(to_string(p)), p);
  EXPECT_THROW((void)parse_preset("slicer"), InvalidInputError);
  const MethodConfig d = preset(Preset::Default);
  EXPECT_EQ(d.method, SmoothingMethod::CrossSlice);
  const Mesh m = small_stack();
  EXPECT_EQ(smooth(m, d.method, d.options).mesh.positions, cross_slice_smooth(m).mesh.positions)
      << "the default preset is cross-slice smoothing with its defaults";
}

}  // namespace
}  // namespace contourmesh
