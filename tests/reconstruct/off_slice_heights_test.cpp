// SPDX-License-Identifier: BSD-3-Clause
// Properties of fit_off_slice_heights against analytic volumes: end faces and domes between the
// slices, what it must not touch, and bad options.
#include <contourmesh/reconstruct/off_slice_heights.h>
#include <contourmesh/reconstruct/reconstruction.h>
#include <contourmesh/reconstruct/threads.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/metrics.h>

#include <gtest/gtest.h>

#include "reconstruct/partial_volume.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>

namespace contourmesh {
namespace {

using test::partial_volume;

ReconstructionOptions options_with(OffSlicePlacement placement) {
  ReconstructionOptions o;
  o.segmentation.threshold = 500.0;
  o.off_slice.placement = placement;
  return o;
}

// A cylinder of radius 8 about (16, 16) from z = 1 (a slab boundary) to z = 9.5: slices every 2 mm
// at z = 0, 2, ..., so the top lies a quarter spacing past the last slab the contours see.
double cylinder(const Eigen::Vector3d& p) {
  const double radial = std::hypot(p.x() - 16.0, p.y() - 16.0) - 8.0;
  const double axial = std::max(1.0 - p.z(), p.z() - 9.5);
  return std::max(radial, axial);
}

// Mean |z - 9.5| over the vertices without ids above the last contour (z > 8.5).
double top_error(const Mesh& mesh) {
  double sum = 0.0;
  int count = 0;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    if (mesh.slice_ids[v] >= 0 || mesh.positions(2, v) < 8.5) continue;
    sum += std::abs(mesh.positions(2, v) - 9.5);
    ++count;
  }
  EXPECT_GT(count, 20);
  return sum / std::max(count, 1);
}

TEST(OffSliceHeights, AnEndFaceBetweenTheSlicesIsFoundFromTheImage) {
  const CtImage::Pointer image = partial_volume({32, 32, 8}, {1.0, 1.0, 2.0}, cylinder);
  const double tiled = top_error(reconstruct(*image, options_with(OffSlicePlacement::Tiled)).mesh);
  const double fitted = top_error(reconstruct(*image, options_with(OffSlicePlacement::ImageCrossing)).mesh);
  EXPECT_NEAR(tiled, 0.5, 0.05);  // half a spacing beyond the last contour at z = 8
  EXPECT_LT(fitted, 0.2);         // the voxels' shares inside: exact for this box-profile volume
}

// The vertices without ids with z in (lo, hi): their mean |z - at| and their lowest and highest z.
struct Band {
  double error = 0.0, lowest = 1e9, highest = -1e9;
  int count = 0;
};
Band band_of(const Mesh& mesh, double lo, double hi, double at) {
  Band b;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    const double z = mesh.positions(2, v);
    if (mesh.slice_ids[v] >= 0 || z <= lo || z >= hi) continue;
    b.error += std::abs(z - at);
    b.lowest = std::min(b.lowest, z);
    b.highest = std::max(b.highest, z);
    ++b.count;
  }
  b.error /= std::max(b.count, 1);
  return b;
}

TEST(OffSliceHeights, AnEndFaceNearTheSliceBeyondIsLaidWhereItIsRead) {
  // The cylinder's ends 0.05 of a spacing from the slice beyond them: bottom z = 2.1 (the first contour
  // at z = 4), top z = 9.9 (the last at z = 8). Read there, not at the tenth of a spacing `min_fraction`
  // keeps elsewhere.
  const auto ends = [](const Eigen::Vector3d& p) {
    return std::max(std::hypot(p.x() - 16.0, p.y() - 16.0) - 8.0, std::max(2.1 - p.z(), p.z() - 9.9));
  };
  const CtImage::Pointer image = partial_volume({32, 32, 7}, {1.0, 1.0, 2.0}, ends, 64);
  ReconstructionOptions o = options_with(OffSlicePlacement::ImageCrossing);
  const Mesh near = reconstruct(*image, o).mesh;
  const Band top = band_of(near, 8.0, 10.0, 9.9), bottom = band_of(near, 2.0, 4.0, 2.1);
  ASSERT_GT(top.count, 20);
  ASSERT_GT(bottom.count, 20);
  EXPECT_LT(top.error, 0.06);
  EXPECT_LT(bottom.error, 0.06);
  EXPECT_LT(top.highest, 10.0 - 0.02 * 2.0 + 1e-9);  // never on the slice
  EXPECT_GT(bottom.lowest, 2.0 + 0.02 * 2.0 - 1e-9);
  o.off_slice.cap_far_fraction = o.off_slice.min_fraction;
  const Mesh clamped = reconstruct(*image, o).mesh;
  EXPECT_GT(band_of(clamped, 8.0, 10.0, 9.9).error, 0.08);  // held at 9.8
  EXPECT_GT(band_of(clamped, 2.0, 4.0, 2.1).error, 0.08);   // held at 2.2
}

TEST(OffSliceHeights, ACavitysRoofKeepsItsDistanceFromItsOwnSlice) {
  // A block with a cylindrical cavity from z = 3 to z = 8.1, 0.05 of a spacing above the cavity's last
  // contour at z = 8: its roof's cap faces down, towards its own slice, and stays a tenth of a spacing
  // from it, where the faces of the band between them keep their area.
  const auto cavity = [](const Eigen::Vector3d& p) {
    const double block =
        std::max({std::abs(p.x() - 16.0) - 12.0, std::abs(p.y() - 16.0) - 12.0, std::abs(p.z() - 7.0) - 6.0});
    const double hole = std::max(std::hypot(p.x() - 16.0, p.y() - 16.0) - 6.0, std::max(3.0 - p.z(), p.z() - 8.1));
    return std::max(block, -hole);
  };
  const CtImage::Pointer image = partial_volume({32, 32, 8}, {1.0, 1.0, 2.0}, cavity, 64);
  const Mesh mesh = reconstruct(*image, options_with(OffSlicePlacement::ImageCrossing)).mesh;
  // The roof's vertices: inside the hole's radius, between slices 4 and 5.
  double lowest = 1e9;
  int count = 0;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector3d p = mesh.positions.col(v);
    const bool roof = p.z() > 8.0 && p.z() < 10.0 && std::hypot(p.x() - 16.0, p.y() - 16.0) <= 7.0;
    if (mesh.slice_ids[v] >= 0 || !roof) continue;
    lowest = std::min(lowest, p.z());
    ++count;
  }
  ASSERT_GT(count, 20);
  EXPECT_GT(lowest, 8.0 + 0.1 * 2.0 - 1e-9);
}

TEST(OffSliceHeights, ADomeComesCloserToTheSphere) {
  auto sphere = [](const Eigen::Vector3d& p) { return (p - Eigen::Vector3d(16.0, 16.0, 14.7)).norm() - 9.0; };
  const CtImage::Pointer image = partial_volume({32, 32, 16}, {1.0, 1.0, 2.0}, sphere);
  auto rms_off_slice = [&](const Mesh& mesh) {
    double sum = 0.0;
    int count = 0;
    for (Index v = 0; v < mesh.num_vertices(); ++v) {
      if (mesh.slice_ids[v] >= 0) continue;
      sum += std::pow(sphere(mesh.positions.col(v)), 2);
      ++count;
    }
    EXPECT_GT(count, 10);
    return std::sqrt(sum / std::max(count, 1));
  };
  const double tiled = rms_off_slice(reconstruct(*image, options_with(OffSlicePlacement::Tiled)).mesh);
  const double fitted = rms_off_slice(reconstruct(*image, options_with(OffSlicePlacement::ImageCrossing)).mesh);
  EXPECT_LT(fitted, 0.6 * tiled) << "tiled " << tiled << " fitted " << fitted;
}

// A block whose top rises 18 degrees off the slices, from z = 5 at x = 4 to z = 18 at x = 44: each
// slab holds a strip of the top about 6 mm wide, tiled through intermediate contours without ids.
double tilted_top(double x) { return 5.0 + (x - 4.0) * std::tan(18.0 * std::numbers::pi / 180.0); }

CtImage::Pointer tilted_block() {
  return partial_volume({48, 32, 12}, {1.0, 1.0, 2.0}, [](const Eigen::Vector3d& p) {
    return std::max({4.0 - p.x(), p.x() - 44.0, 4.0 - p.y(), p.y() - 28.0, 1.0 - p.z(), p.z() - tilted_top(p.x())});
  });
}

// Mean |z - top| over the vertices without ids on the tilted top, away from its edges and from the
// slices' ends of the block.
double tilted_top_error(const Mesh& mesh) {
  double sum = 0.0;
  int count = 0;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector3d p = mesh.positions.col(v);
    if (mesh.slice_ids[v] >= 0 || p.x() < 10.0 || p.x() > 38.0 || p.y() < 8.0 || p.y() > 24.0) continue;
    if (std::abs(p.z() - tilted_top(p.x())) > 1.0) continue;
    sum += std::abs(p.z() - tilted_top(p.x()));
    ++count;
  }
  EXPECT_GT(count, 50);
  return sum / std::max(count, 1);
}

TEST(OffSliceHeights, AGentlyTiltedFaceIsNotReadAsTerraces) {
  // A voxel value is the mean over the slice's thickness, so linear interpolation of the threshold
  // between slice centres reads a height s (in spacings above slice k) as s / (s + 1/2) below the
  // mid-plane and 1/2 / (3/2 - s) above it: up to 0.09 spacing off, flat around the mid-plane
  // (0.10 mm mean error here; the voxels' shares: 0.05 mm). By default vertices off the end caps read
  // a step inwards scaled by sqrt(1 - |n_w|): a fifth of a pixel on this top.
  const Mesh mesh = reconstruct(*tilted_block(), options_with(OffSlicePlacement::ImageCrossing)).mesh;
  EXPECT_LT(tilted_top_error(mesh), 0.07) << "mean height error, mm";
}

TEST(OffSliceHeights, ReadingInwardsOnATiltedFaceIsABias) {
  // A step of one pixel inwards along the in-plane normal reads a column where the top is higher or
  // lower by the step times the slope: every vertex's height carries that offset (0.126 mm mean
  // error with the whole step; 0.057 mm reading the vertices' own columns).
  ReconstructionOptions all = options_with(OffSlicePlacement::ImageCrossing);
  all.off_slice.inward_read = InwardRead::Whole;
  const CtImage::Pointer image = tilted_block();
  const double scaled = tilted_top_error(reconstruct(*image, options_with(OffSlicePlacement::ImageCrossing)).mesh);
  const double whole = tilted_top_error(reconstruct(*image, all).mesh);
  EXPECT_LT(scaled, 0.8 * whole) << "scaled step " << scaled << " mm, whole step " << whole << " mm";
}

TEST(OffSliceHeights, EndCapsStillReadInwards) {
  // The end face of the cylinder: its vertices are caps' (and their rims'), which read a step inwards
  // by default as with InwardRead::Whole.
  const CtImage::Pointer image = partial_volume({32, 32, 8}, {1.0, 1.0, 2.0}, cylinder);
  ReconstructionOptions all = options_with(OffSlicePlacement::ImageCrossing);
  all.off_slice.inward_read = InwardRead::Whole;
  const Reconstruction by_default = reconstruct(*image, options_with(OffSlicePlacement::ImageCrossing));
  const Reconstruction everywhere = reconstruct(*image, all);
  EXPECT_NEAR(top_error(by_default.mesh), top_error(everywhere.mesh), 0.01);
}

TEST(OffSliceHeights, VerticesWithIdsAndTheConnectivityStay) {
  const CtImage::Pointer image = partial_volume({32, 32, 8}, {1.0, 1.0, 2.0}, cylinder);
  const Mesh tiled = reconstruct(*image, options_with(OffSlicePlacement::Tiled)).mesh;
  const OffSliceResult fitted = fit_off_slice_heights(tiled, *image, 500.0);
  ASSERT_EQ(fitted.mesh.num_vertices(), tiled.num_vertices());
  EXPECT_EQ(fitted.mesh.triangles, tiled.triangles);
  EXPECT_EQ(fitted.mesh.slice_ids, tiled.slice_ids);
  EXPECT_GT(fitted.report.fitted, 0u);
  std::size_t moved = 0;
  for (Index v = 0; v < tiled.num_vertices(); ++v) {
    const Eigen::Vector3d d = fitted.mesh.positions.col(v) - tiled.positions.col(v);
    if (tiled.slice_ids[v] >= 0) {
      EXPECT_EQ(d.norm(), 0.0) << "vertex " << v;
    }
    EXPECT_EQ(d.head<2>().norm(), 0.0) << "vertex " << v << " moved off the slice axis";
    moved += d.norm() > 0.0;
  }
  EXPECT_GT(moved, 0u);
}

TEST(OffSliceHeights, TiledPlacementChangesNothing) {
  const CtImage::Pointer image = partial_volume({32, 32, 8}, {1.0, 1.0, 2.0}, cylinder);
  const Mesh tiled = reconstruct(*image, options_with(OffSlicePlacement::Tiled)).mesh;
  OffSliceOptions o;
  o.placement = OffSlicePlacement::Tiled;
  const OffSliceResult same = fit_off_slice_heights(tiled, *image, 500.0, o);
  EXPECT_EQ(same.mesh.positions, tiled.positions);
  EXPECT_EQ(same.report.fitted, 0u);
}

// A needle 1 mm across on 0.01 mm pixels, slices 50 mm apart: a quarter of the slice spacing is twelve
// times the needle's width, so the flips after the heights must be held to the pixels, or they cut
// chords through it (before they were: 4 % of the volume).
TEST(OffSliceHeights, FlipsOnThickSlicesKeepANeedlesVolume) {
  const CtImage::Pointer image = partial_volume({110, 110, 3}, {0.01, 0.01, 50.0}, [](const Eigen::Vector3d& p) {
    return std::hypot(p.x() - 0.545, p.y() - 0.545) - 0.5;
  });
  ReconstructionOptions tiled_options = options_with(OffSlicePlacement::Tiled);
  tiled_options.segmentation.min_region_area = 0.01;
  tiled_options.segmentation.min_contour_length = 0.1;
  ReconstructionOptions image_options = tiled_options;
  image_options.off_slice.placement = OffSlicePlacement::ImageCrossing;
  const double tiled = enclosed_volume(reconstruct(*image, tiled_options).mesh);
  const double placed = enclosed_volume(reconstruct(*image, image_options).mesh);
  ASSERT_GT(tiled, 0.0);
  EXPECT_NEAR(placed, tiled, 0.02 * tiled);
}

// Two spheres of radius r about a and b that merge between slices, with a ripple of 0.3 mm: intermediate
// contours, caps and steep faces together.
std::function<double(const Eigen::Vector3d&)> merging_spheres(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                              double r) {
  return [a, b, r](const Eigen::Vector3d& p) {
    return std::min((p - a).norm(), (p - b).norm()) - r + 0.3 * std::sin(1.7 * p.x()) * std::sin(2.3 * p.y());
  };
}

TEST(OffSliceHeights, NoFaceTurnsOverOnANoisyBranchingShape) {
  const CtImage::Pointer image =
      partial_volume({32, 32, 16}, {1.0, 1.0, 2.0}, merging_spheres({11.0, 16.0, 13.0}, {21.0, 16.0, 17.0}, 6.5));
  const Mesh tiled = reconstruct(*image, options_with(OffSlicePlacement::Tiled)).mesh;
  const OffSliceResult fitted = fit_off_slice_heights(tiled, *image, 500.0);
  for (const Triangle& t : tiled.triangles) {
    auto normal = [&](const Mesh& m) {
      return Eigen::Vector3d(
          (m.positions.col(t[1]) - m.positions.col(t[0])).cross(m.positions.col(t[2]) - m.positions.col(t[0])));
    };
    const Eigen::Vector3d before = normal(tiled), after = normal(fitted.mesh);
    if (before.norm() < 1e-12) continue;
    EXPECT_GT(before.dot(after), 0.0);
  }
}

// The data term and the membrane fit run in blocks of vertices on every core; each vertex writes only
// its own entries, so the heights are the same, bit for bit, on one thread and on several. The mesh
// (merging spheres, a few blocks of vertices) has intermediate contours, caps and damped faces.
TEST(OffSliceHeights, TheSameHeightsOnOneThreadAndOnSeveral) {
  const CtImage::Pointer image =
      partial_volume({60, 60, 20}, {1.0, 1.0, 2.0}, merging_spheres({22.0, 30.0, 17.0}, {40.0, 30.0, 23.0}, 13.0));
  const Mesh tiled = reconstruct(*image, options_with(OffSlicePlacement::Tiled)).mesh;
  ASSERT_GT(tiled.num_vertices(), 2 * 1024) << "several blocks of vertices";
  auto fit = [&](int threads) {
    const ThreadLimit limit(threads);
    return fit_off_slice_heights(tiled, *image, 500.0);
  };
  const OffSliceResult one = fit(1), several = fit(3);
  EXPECT_GT(one.report.fitted, 1000u);
  EXPECT_EQ(one.report.candidates, several.report.candidates);
  EXPECT_EQ(one.report.fitted, several.report.fitted);
  EXPECT_EQ(one.report.damped, several.report.damped);
  EXPECT_TRUE(one.mesh.positions == several.mesh.positions);
  EXPECT_FALSE(one.mesh.positions == tiled.positions) << "the heights must move something";
}

TEST(OffSliceHeights, OptionsOutOfRangeAndMeshesWithoutIdsAreRefused) {
  const CtImage::Pointer image = partial_volume({8, 8, 4}, {1.0, 1.0, 2.0}, cylinder);
  Mesh no_ids;
  no_ids.positions = Eigen::Matrix3Xd::Zero(3, 3);
  no_ids.triangles = {{0, 1, 2}};
  EXPECT_THROW((void)fit_off_slice_heights(no_ids, *image, 500.0), InvalidInputError);
  Mesh ok = no_ids;
  ok.slice_ids = {0, 0, 1};
  ok.contour_ids = {0, 0, 0};
  for (auto bad : std::initializer_list<std::function<void(OffSliceOptions&)>>{
           [](OffSliceOptions& o) { o.smoothness = 0.0; }, [](OffSliceOptions& o) { o.iterations = 0; },
           [](OffSliceOptions& o) { o.min_fraction = 0.5; }, [](OffSliceOptions& o) { o.inward_pixels = -1.0; },
           [](OffSliceOptions& o) { o.cap_far_fraction = -0.01; }}) {
    OffSliceOptions o;
    bad(o);
    EXPECT_THROW((void)fit_off_slice_heights(ok, *image, 500.0, o), InvalidInputError);
  }
  // Face roles, when given, are one per face.
  EXPECT_THROW((void)fit_off_slice_heights(ok, *image, 500.0, {}, {FaceRole::Band, FaceRole::Cap}), InvalidInputError);
}

}  // namespace
}  // namespace contourmesh
