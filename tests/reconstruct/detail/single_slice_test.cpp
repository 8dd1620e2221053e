// SPDX-License-Identifier: BSD-3-Clause
// Contours found on one slice only by the image route (detail/single_slice.h through reconstruct()):
// a cavity or a plate thinner than the slice spacing is kept as a (hollow) slab; a small tongue of a piece
// that continues is not made a floating slab; Drop leaves them all out.
#include <contourmesh/reconstruct/phantom.h>
#include <contourmesh/reconstruct/reconstruction.h>
#include <contourmesh/smooth/metrics.h>

#include <gtest/gtest.h>

#include "reconstruct/mesh_checks.h"
#include "reconstruct/partial_volume.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace contourmesh {
namespace {

using test::partial_volume;

// Slices every 2 mm at z = 0, 2, 4, ...; pixels of 1 mm. A slice's voxel spans z +- 1.
const Eigen::Vector3d kSpacing(1.0, 1.0, 2.0);

double box(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const Eigen::Vector3d d = (lo - p).cwiseMax(p - hi);
  return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
}

// A flat disc of radius r about (cx, cy) between heights z0 and z1.
double disc(const Eigen::Vector3d& p, double cx, double cy, double r, double z0, double z1) {
  return std::max(std::hypot(p.x() - cx, p.y() - cy) - r, std::max(z0 - p.z(), p.z() - z1));
}

ReconstructionOptions options(SingleSliceContours single_slice) {
  ReconstructionOptions o;
  o.segmentation.threshold = 500.0;
  o.single_slice = single_slice;
  return o;
}

// A block from z = 1 to 13 holding a disc-shaped cavity 1.6 mm thick (z 5.2 to 6.8): only the slice at
// z = 6 sees the hole.
double block_with_cavity(const Eigen::Vector3d& p) {
  const double block = box(p, {4.0, 4.0, 1.0}, {28.0, 28.0, 13.0});
  return std::max(block, -disc(p, 16.0, 16.0, 5.0, 5.2, 6.8));
}

TEST(SingleSliceContours, ACavitySeenOnOneSliceStaysHollow) {
  const auto image = partial_volume({32, 32, 8}, kSpacing, block_with_cavity);
  const Reconstruction kept = reconstruct(*image, options(SingleSliceContours::Slab));
  const Reconstruction dropped = reconstruct(*image, options(SingleSliceContours::Drop));
  const test::Topology t = test::topology_of(kept.mesh);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.manifold) << t.problems;
  EXPECT_EQ(t.components, 2);  // the block and its cavity
  EXPECT_EQ(t.euler, 4);
  EXPECT_EQ(kept.report.single_slice_cavities, 1u);
  EXPECT_EQ(test::topology_of(dropped.mesh).components, 1);
  // The hollow slab reaches half-way to the adjacent slices: 2 mm thick, where the cavity is 1.6 mm.
  const double cavity = std::numbers::pi * 25.0 * 1.6;
  const double removed = enclosed_volume(dropped.mesh) - enclosed_volume(kept.mesh);
  EXPECT_GT(removed, 0.8 * cavity);
  EXPECT_LT(removed, 1.4 * cavity);
}

// A block on the slices z = 2 to 10, and apart from it a plate 1.4 mm thick (z 5.3 to 6.7) that only the
// slice at z = 6 sees.
double block_and_plate(const Eigen::Vector3d& p) {
  return std::min(box(p, {3.0, 3.0, 1.0}, {12.0, 28.0, 11.0}), disc(p, 22.0, 16.0, 5.0, 5.3, 6.7));
}

TEST(SingleSliceContours, APlateSeenOnOneSliceBecomesASlab) {
  const auto image = partial_volume({32, 32, 8}, kSpacing, block_and_plate);
  const Reconstruction kept = reconstruct(*image, options(SingleSliceContours::Slab));
  const test::Topology t = test::topology_of(kept.mesh);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.manifold) << t.problems;
  EXPECT_EQ(t.components, 2);
  EXPECT_EQ(kept.report.single_slice_slabs, 1u);
  const Reconstruction dropped = reconstruct(*image, options(SingleSliceContours::Drop));
  EXPECT_EQ(test::topology_of(dropped.mesh).components, 1);
  EXPECT_EQ(dropped.report.single_slice_left_out, 1u);
  EXPECT_EQ(kept.report.single_slice_left_out, 0u);
  // The plate's part: every vertex with x > 15 lies between the slab's faces, z in [5, 7].
  for (Index v = 0; v < kept.mesh.num_vertices(); ++v) {
    if (kept.mesh.positions(0, v) < 15.0) continue;
    EXPECT_GE(kept.mesh.positions(2, v), 5.0 - 1e-9);
    EXPECT_LE(kept.mesh.positions(2, v), 7.0 + 1e-9);
  }
}

// A block from z = 1 to 11.2 (slices 2 to 10) with a small knob on top (radius 1.5, up to z = 12.8): the
// slice at z = 12 sees the knob alone, inside the block's outline at z = 10 but under 1 % of it, so the
// tiler does not join them.
double block_with_knob(const Eigen::Vector3d& p) {
  return std::min(box(p, {1.0, 1.0, 1.0}, {31.0, 31.0, 11.2}), disc(p, 16.0, 16.0, 1.5, 11.0, 12.8));
}

TEST(SingleSliceContours, AKnobOnAPieceIsNotMadeAFloatingSlab) {
  const auto image = partial_volume({32, 32, 8}, kSpacing, block_with_knob);
  const Reconstruction r = reconstruct(*image, options(SingleSliceContours::Slab));
  ASSERT_GT(r.report.tiling.dropped_contours, 0u) << "the knob's contour must be one the tiler leaves out";
  EXPECT_EQ(r.report.single_slice_slabs, 0u);
  EXPECT_EQ(r.report.single_slice_left_out, r.report.tiling.dropped_contours)
      << "the report must say it left the knob out";
  EXPECT_EQ(test::topology_of(r.mesh).components, 1);
}

// The skull with a diploe (120 cavities 3 mm across in its wall, slices 2 mm apart): most cavities lie on
// one slice only, and all but those the pixels cannot resolve are kept.
TEST(SingleSliceContours, TheDiploesCavitiesAreKept) {
  const Phantom phantom = make_phantom(PhantomShape::SkullDiploe);
  PhantomVolumeOptions vo;  // 0.7 x 0.7 x 2 mm, no blur, no noise
  const auto image = render_phantom(phantom, vo);
  ReconstructionOptions ro;
  ro.segmentation.threshold = 0.5 * (vo.bone_hu + vo.tissue_hu);
  const Reconstruction r = reconstruct(*image, ro);
  const test::Topology t = test::topology_of(r.mesh);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.manifold) << t.problems;
  EXPECT_GE(r.report.single_slice_cavities, 60u);
  EXPECT_GE(t.components, phantom.surface_components - 3);
  EXPECT_LE(t.components, phantom.surface_components);
}

}  // namespace
}  // namespace contourmesh
