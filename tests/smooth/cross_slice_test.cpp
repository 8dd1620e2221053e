// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/cross_slice.h"
#include "contourmesh/smooth/errors.h"
#include "contourmesh/smooth/shapes.h"
#include "smooth/test_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace contourmesh {
namespace {

// Largest |distance from the axis - radius| over the vertices of slice s.
double radial_error(const Mesh& mesh, int s, double radius) {
  double worst = 0.0;
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.slice_ids[i] != s) continue;
    worst = std::max(worst, std::abs(mesh.positions.col(i).head<2>().norm() - radius));
  }
  return worst;
}

TEST(CrossSlice, LeavesAnExactCylinderInPlace) {
  const Mesh mesh = make_contour_stack(test::cylinder_spec(10.0, 20));
  CrossSliceOptions options;
  options.off_slice.filter = OffSliceFilter::None;
  const CrossSliceResult r = cross_slice_smooth(mesh, options);
  // Only the fourth-order deviation of the polygon from its local parabolas is left to correct.
  EXPECT_LT((r.mesh.positions - mesh.positions).cwiseAbs().maxCoeff(), 1e-4);
  EXPECT_GT(r.profiles, 0u);
  // The normal filter of the default moves the caps' rims a little: the facets' normals of a polygonal
  // cylinder are not a fixed point of the filter.
  const CrossSliceResult filtered = cross_slice_smooth(mesh);
  EXPECT_LT((filtered.mesh.positions - mesh.positions).cwiseAbs().maxCoeff(), 0.02);
}

TEST(CrossSlice, PullsAContourDisplacedAloneBackTowardsItsNeighbours) {
  // Contour 10 is segmented 0.5 mm too large; its neighbours are right. The noise level is given (the
  // estimate from this mesh, whose other contours are exact, would be zero).
  Mesh mesh = make_contour_stack(test::cylinder_spec(10.0, 20));
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.slice_ids[i] == 10) mesh.positions.col(i).head<2>() *= 10.5 / 10.0;
  }
  CrossSliceOptions options;
  options.noise_across = 0.3;
  const CrossSliceResult r = cross_slice_smooth(mesh, options);
  EXPECT_LT(radial_error(r.mesh, 10, 10.0), 0.15);
}

TEST(CrossSlice, KinkBoundWindowsKeepAJunctionBetweenParts) {
  // A cylinder of 10 mm up to slice 10, then a cone flaring by 0.8 mm per slice: a concave junction,
  // noise-free, smoothed as if the contours had 0.25 mm of noise (the windows that noise lets grow).
  // Two-sided windows reaching across the junction pull its neighbours off both parts; the kink test
  // finds it (at 0.25 mm from every vertex within six slices; at 0.4 mm from three to five slices
  // away only) and each side is fitted alone.
  Mesh mesh = make_contour_stack(test::cylinder_spec(10.0, 24));
  const auto radius = [](int s) { return 10.0 + 0.8 * std::max(0, s - 10); };
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    const int s = mesh.slice_ids[i];
    if (s >= 0) mesh.positions.col(i).head<2>() *= radius(s) / 10.0;
  }
  CrossSliceOptions options;
  options.noise_across = 0.25;
  options.off_slice.filter = OffSliceFilter::None;
  options.across_kinks = ProfileKinks::Ignore;
  const CrossSliceResult ignore = cross_slice_smooth(mesh, options);
  options.across_kinks = ProfileKinks::Bound;
  const CrossSliceResult bound = cross_slice_smooth(mesh, options);
  double worst_ignore = 0.0, worst_bound = 0.0;
  for (int s = 4; s <= 18; ++s) {
    worst_ignore = std::max(worst_ignore, radial_error(ignore.mesh, s, radius(s)));
    worst_bound = std::max(worst_bound, radial_error(bound.mesh, s, radius(s)));
  }
  EXPECT_GT(worst_ignore, 0.3);
  EXPECT_LT(worst_bound, 0.1 * worst_ignore);
}

TEST(CrossSlice, KinkTestMovesNothingWithoutNoise) {
  // The noise-free guarantee holds with the kink test: at a noise level of zero no kink is reported, the
  // result is the one without the test (which moves a vertex by at most 1e-4 mm here: the windows of
  // zero width still fuse the polygon's fourth-order deviation, as on the exact cylinder above).
  Mesh mesh = make_contour_stack(test::cylinder_spec(10.0, 24));
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    const int s = mesh.slice_ids[i];
    if (s > 10) mesh.positions.col(i).head<2>() *= (10.0 + 0.8 * (s - 10)) / 10.0;
  }
  CrossSliceOptions options;
  options.noise_across = 0.0;
  options.noise_along = 0.0;
  options.off_slice.filter = OffSliceFilter::None;
  options.across_kinks = ProfileKinks::Ignore;
  const CrossSliceResult ignore = cross_slice_smooth(mesh, options);
  options.across_kinks = ProfileKinks::Bound;
  const CrossSliceResult bound = cross_slice_smooth(mesh, options);
  EXPECT_TRUE(bound.mesh.positions == ignore.mesh.positions);
  EXPECT_LT((bound.mesh.positions - mesh.positions).cwiseAbs().maxCoeff(), 1e-4);
}

TEST(CrossSlice, RejectsAKinkRateOutOfRange) {
  const Mesh mesh = make_contour_stack(test::cylinder_spec(10.0, 8));
  CrossSliceOptions options;
  options.kink_false_rate = 1.0;
  EXPECT_THROW((void)cross_slice_smooth(mesh, options), InvalidInputError);
  options.kink_false_rate = 0.0;
  EXPECT_THROW((void)cross_slice_smooth(mesh, options), InvalidInputError);
}

TEST(CrossSlice, KeepsContourVerticesInTheirSlicePlanes) {
  Mesh mesh = make_contour_stack(test::cylinder_spec(10.0, 20));
  add_noise(mesh, {.sigma = 0.2, .seed = 3, .direction = NoiseDirection::InPlane});
  const CrossSliceResult r = cross_slice_smooth(mesh);
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.slice_ids[i] >= 0) {
      EXPECT_DOUBLE_EQ(r.mesh.positions(2, i), mesh.positions(2, i));
    }
  }
}

// A vertex without ids inside a contour (as a repaired file may hold) breaks that contour open: its ends
// have one contour neighbour each. Profiles that reach such an end stop there instead of walking off it.
TEST(CrossSlice, ContoursBrokenOpenByAVertexWithoutIdsAreSmoothedToo) {
  Mesh mesh = make_contour_stack(test::cylinder_spec(10.0, 20));
  add_noise(mesh, {.sigma = 0.2, .seed = 3, .direction = NoiseDirection::InPlane});
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.slice_ids[i] >= 0 && i % 97 == 0) mesh.slice_ids[i] = mesh.contour_ids[i] = kNoId;
  }
  const CrossSliceResult r = cross_slice_smooth(mesh);
  ASSERT_EQ(r.mesh.num_vertices(), mesh.num_vertices());
  EXPECT_TRUE(r.mesh.positions.allFinite());
  EXPECT_GT(r.profiles, 0u);
  EXPECT_LT(radial_error(r.mesh, 10, 10.0), radial_error(mesh, 10, 10.0));
}

// A tiler that refines bands joins each contour to an intermediate contour (vertices without ids)
// instead of to the next slice: no edge joins two contour vertices of different slices. The slice
// spacing used to come from such edges, and smoothing refused the mesh.
TEST(CrossSlice, ContoursJoinedOnlyThroughIntermediateContoursAreSmoothed) {
  Mesh mesh = make_contour_stack(test::cylinder_spec(10.0, 21));
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.slice_ids[i] < 0) continue;
    if (mesh.slice_ids[i] % 2 == 1) mesh.slice_ids[i] = mesh.contour_ids[i] = kNoId;
    else mesh.slice_ids[i] /= 2;  // contour slices stay consecutive: 10 slices, 4 mm apart
  }
  Mesh noisy = mesh;
  add_noise(noisy, {.sigma = 0.2, .seed = 5, .direction = NoiseDirection::InPlane});
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.slice_ids[i] < 0) noisy.positions.col(i) = mesh.positions.col(i);
  }
  const CrossSliceResult r = cross_slice_smooth(noisy);
  EXPECT_TRUE(r.mesh.positions.allFinite());
  EXPECT_GT(r.profiles, 0u);  // the cuts are found among the next slice's contour edges
  EXPECT_LT(radial_error(r.mesh, 5, 10.0), radial_error(noisy, 5, 10.0));
}

// An unset reach follows the noise level across the slices: 4 slices for precise contours, about 24 mm
// (12 slices 2 mm apart) for noisy ones; a reach given is kept.
TEST(CrossSlice, ReachFromTheNoiseLevelUnlessGiven) {
  const Mesh precise = make_contour_stack(test::cylinder_spec(10.0, 20));
  Mesh noisy = precise;
  add_noise(noisy, {.sigma = 0.4, .seed = 2, .direction = NoiseDirection::InPlane});
  const CrossSliceResult a = cross_slice_smooth(precise), b = cross_slice_smooth(noisy);
  EXPECT_LT(a.noise_across, 0.2);
  EXPECT_EQ(a.reach, 4);
  EXPECT_GT(b.noise_across, 0.2);
  EXPECT_EQ(b.reach, 12);
  CrossSliceOptions o;
  o.reach = 6;
  EXPECT_EQ(cross_slice_smooth(noisy, o).reach, 6);
  o.reach.reset();
  o.precise_noise = 1.0;  // a threshold above the noisy mesh's level
  EXPECT_EQ(cross_slice_smooth(noisy, o).reach, 4);
  o.precise_noise = -1.0;
  EXPECT_THROW((void)cross_slice_smooth(noisy, o), InvalidInputError);
}

// On noisy contours the reach is a length across the slices, at least 8 slices and at most 30: 24 mm is
// 24 slices 1 mm apart, 8 slices (not 5) 5 mm apart; a length of 0 keeps 8 at any spacing.
TEST(CrossSlice, NoisyReachIsALengthOfAtLeastEightSlices) {
  const auto noisy_cylinder = [](double spacing) {
    ContourStackSpec spec = test::cylinder_spec(10.0, 20);
    spec.slice_spacing = spacing;
    Mesh m = make_contour_stack(spec);
    add_noise(m, {.sigma = 0.4, .seed = 2, .direction = NoiseDirection::InPlane});
    return m;
  };
  const Mesh fine = noisy_cylinder(1.0);
  const CrossSliceResult thick = cross_slice_smooth(noisy_cylinder(5.0));
  ASSERT_GT(thick.noise_across, 0.2);  // noisy: the long reach applies
  EXPECT_EQ(thick.reach, 8);
  const std::pair<double, int> length_and_slices[] = {{24.0, 24}, {12.0, 12}, {100.0, 30}, {0.0, 8}};
  for (const auto& [length, slices] : length_and_slices) {
    CrossSliceOptions o;
    o.noisy_reach_length = length;
    EXPECT_EQ(cross_slice_smooth(fine, o).reach, slices) << length << " mm";
  }
  CrossSliceOptions negative;
  negative.noisy_reach_length = -1.0;
  EXPECT_THROW((void)cross_slice_smooth(fine, negative), InvalidInputError);
}

// The noise across the slices is estimated from five-slice profiles; on a stack too short to give them
// (thick slices through a small object) the noise along the contours stands in for it.
TEST(CrossSlice, TooFewProfilesAcrossTakeTheNoiseAlongTheContours) {
  Mesh tall = make_contour_stack(test::cylinder_spec(10.0, 20));
  Mesh short_stack = make_contour_stack(test::cylinder_spec(10.0, 4));
  add_noise(tall, {.sigma = 0.1, .seed = 3, .direction = NoiseDirection::InPlane});
  add_noise(short_stack, {.sigma = 0.1, .seed = 3, .direction = NoiseDirection::InPlane});
  const CrossSliceResult a = cross_slice_smooth(tall), b = cross_slice_smooth(short_stack);
  EXPECT_EQ(a.noise_across_source, NoiseSource::AcrossProfiles);
  EXPECT_NEAR(a.noise_across, 0.1, 0.04);
  EXPECT_EQ(b.noise_across_source, NoiseSource::AlongProfiles);
  EXPECT_NEAR(b.noise_across, 0.1, 0.04);
  CrossSliceOptions o;
  o.noise_across = 0.3;
  const CrossSliceResult given = cross_slice_smooth(short_stack, o);
  EXPECT_EQ(given.noise_across_source, NoiseSource::Given);
  EXPECT_EQ(given.noise_across, 0.3);
  o.noise_across.reset();
  o.min_profile_share = 1.5;
  EXPECT_THROW((void)cross_slice_smooth(short_stack, o), InvalidInputError);
}

TEST(CrossSlice, NeedsContourIds) {
  EXPECT_THROW((void)cross_slice_smooth(make_icosphere(2)), InvalidInputError);
}

}  // namespace
}  // namespace contourmesh
