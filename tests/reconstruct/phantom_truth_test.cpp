// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/phantom_truth.h"

#include "reconstruct/phantom_cache.h"

#include <contourmesh/smooth/errors.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace contourmesh {
namespace {

TEST(PhantomTruth, SamplesLieOnTheAnalyticSurface) {
  const Phantom& femur = test::phantom_of(PhantomShape::Femur);
  const SurfaceTruth truth = phantom_surface_truth(femur);
  ASSERT_GT(truth.samples.size(), 1000);
  double worst = 0.0;
  for (Index k = 0; k < truth.samples.size(); ++k)
    worst = std::max(worst, std::abs(femur.sdf(truth.samples.points.col(k))));
  EXPECT_LT(worst, 0.01) << "mm off the zero set after the Newton step";
}

TEST(PhantomTruth, SampledAreaConvergesWithTheSpacing) {
  const Phantom& box = test::phantom_of(PhantomShape::RidgeBox);
  PhantomTruthOptions coarse, fine;
  coarse.sample_spacing = 0.4;
  fine.sample_spacing = 0.2;
  const double a = phantom_surface_truth(box, coarse).samples.area();
  const double b = phantom_surface_truth(box, fine).samples.area();
  EXPECT_NEAR(a / b, 1.0, 0.01);
}

TEST(PhantomTruth, FeatureDistanceLookupAgreesWithTheSearch) {
  const Phantom& box = test::phantom_of(PhantomShape::RidgeBox);
  const SurfaceTruth truth = phantom_surface_truth(box);
  ASSERT_TRUE(static_cast<bool>(truth.feature_distance));
  const Index step = std::max<Index>(1, truth.samples.size() / 200);
  for (Index k = 0; k < truth.samples.size(); k += step) {
    const Eigen::Vector3d p = truth.samples.points.col(k);
    EXPECT_DOUBLE_EQ(truth.feature_distance(p), distance_to_features(box, p));  // memoised
    const Eigen::Vector3d q = p + Eigen::Vector3d(0.1, -0.2, 0.3);
    EXPECT_DOUBLE_EQ(truth.feature_distance(q), distance_to_features(box, q));  // searched
  }
}

TEST(PhantomTruth, SmoothPhantomHasNoFeatureRegion) {
  Phantom smooth = test::phantom_of(PhantomShape::RidgeBox);
  smooth.feature_points.clear();
  EXPECT_FALSE(static_cast<bool>(phantom_surface_truth(smooth).feature_distance));
}

TEST(PhantomTruth, RefusesBadOptions) {
  const Phantom& box = test::phantom_of(PhantomShape::RidgeBox);
  PhantomTruthOptions o;
  o.sample_spacing = 0.0;
  EXPECT_THROW((void)phantom_surface_truth(box, o), InvalidInputError);
  o = {};
  o.margin = -1.0;
  EXPECT_THROW((void)phantom_surface_truth(box, o), InvalidInputError);
}

}  // namespace
}  // namespace contourmesh
