// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/feature_smoothing.h>
#include <contourmesh/smooth/metrics.h>
#include <contourmesh/smooth/shapes.h>
#include <contourmesh/smooth/topology.h>

#include <gtest/gtest.h>

namespace contourmesh {
namespace {

TEST(FeatureSmoothing, KeepsTheRidgeSharperThanTaubinWithoutShrinking) {
  ContourStackSpec spec;
  spec.curve = ridge_circle_curve(20.0, 6.0, 0.35);
  spec.slices = 24;
  spec.points_per_contour = 180;
  Mesh m = make_contour_stack(spec);
  add_noise(m, {0.15, 11, NoiseDirection::InPlane});
  const ScalarField sdf = contour_stack_sdf(spec);
  std::vector<Index> tips;
  for (int k = 2; k < spec.slices - 2; ++k) tips.push_back(k * spec.points_per_contour);

  const FeatureSmoothingResult paper = feature_preserving_smooth(m);
  EXPECT_EQ(paper.mesh.triangles, m.triangles) << "the original connectivity is resumed";
  EXPECT_EQ(paper.mesh.slice_ids, m.slice_ids);
  EXPECT_GT(paper.detection.edges, tips.size() / 2);
  EXPECT_GT(paper.subdivided_vertices, 0u);
  EXPECT_GT(paper.adaptive_vertices, m.num_vertices());
  EXPECT_GE(paper.seconds.total, paper.seconds.smooth);

  SmoothingOptions taubin;
  taubin.method = SmoothingMethod::Taubin;
  const Eigen::Matrix3Xd tb = smooth(m, taubin);
  const double paper_tip = distance_to_surface(paper.mesh.positions, sdf, tips).rms;
  const double taubin_tip = distance_to_surface(tb, sdf, tips).rms;
  EXPECT_LT(paper_tip, 0.8 * taubin_tip) << "paper " << paper_tip << " taubin " << taubin_tip;
  const double v0 = enclosed_volume(m);
  // Subdividing around features does not add volume change over plain Taubin with the same 40 iterations.
  taubin.iterations = 40;
  const double taubin40_change = std::abs(enclosed_volume(smooth(m, taubin), m.triangles) - v0) / v0;
  const double paper_change = std::abs(enclosed_volume(paper.mesh) - v0) / v0;
  EXPECT_LE(paper_change, taubin40_change + 0.002);

  FeatureSmoothingOptions keep;
  keep.output = OutputResolution::Adaptive;
  const FeatureSmoothingResult adaptive = feature_preserving_smooth(m, keep);
  EXPECT_EQ(adaptive.mesh.num_vertices(), adaptive.adaptive_vertices);
  const TopologySummary t = summarize_topology(adaptive.mesh);
  EXPECT_TRUE(t.closed && t.manifold) << t.first_problems;
  // The adaptive mesh's first vertices are the resumed result.
  EXPECT_TRUE(adaptive.mesh.positions.leftCols(m.num_vertices()).isApprox(paper.mesh.positions));
}

TEST(FeatureSmoothing, OptionsAndCancellation) {
  ContourStackSpec spec;
  spec.curve = ridge_circle_curve(10.0, 3.0, 0.4);
  spec.slices = 6;
  spec.points_per_contour = 60;
  const Mesh m = make_contour_stack(spec);
  FeatureSmoothingOptions o;
  o.diffusion = SmoothingMethod::MeanCurvatureFlow;
  EXPECT_THROW((void)feature_preserving_smooth(m, o), InvalidInputError);
  o = {};
  o.progress = [](std::string_view stage, double) { return stage != "smooth"; };
  EXPECT_THROW((void)feature_preserving_smooth(m, o), CancelledError);
  EXPECT_THROW((void)feature_preserving_smooth(make_icosphere(1)), InvalidInputError);  // no ids
}

}  // namespace
}  // namespace contourmesh
