// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/reconstruct/contours.h>
#include <contourmesh/reconstruct/reconstruction.h>
#include <contourmesh/reconstruct/segmentation.h>
#include <contourmesh/reconstruct/tiling.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/metrics.h>

#include <gtest/gtest.h>

#include "reconstruct/partial_volume.h"

#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "reconstruct/mesh_checks.h"

namespace contourmesh {
namespace {

// A volume whose voxels hold `inside_hu` where sdf < 0 (4x4 in-plane supersampling for partial
// volume) and `outside_hu` elsewhere; physical point of index (i, j, k) = origin + spacing * index.
CtImage::Pointer make_volume(const std::array<int, 3>& n, const Eigen::Vector3d& spacing, const Eigen::Vector3d& origin,
                             const std::function<double(const Eigen::Vector3d&)>& sdf, float inside_hu = 1000.0f,
                             float outside_hu = 0.0f) {
  const auto image = test::pixel_volume(n, spacing, [&](int i, int j, int k) {
    int inside = 0;
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) {
        const Eigen::Vector3d p = origin + Eigen::Vector3d((i - 0.375 + 0.25 * a) * spacing.x(),
                                                          (j - 0.375 + 0.25 * b) * spacing.y(), k * spacing.z());
        inside += sdf(p) < 0.0;
      }
    }
    return outside_hu + (inside_hu - outside_hu) * static_cast<float>(inside) / 16.0f;
  });
  image->SetOrigin(origin.data());
  return image;
}

double cylinder(const Eigen::Vector3d& p, double cx, double cy, double r) {
  return std::hypot(p.x() - cx, p.y() - cy) - r;
}

TEST(Segmentation, CylinderGivesOneAccurateCounterClockwiseContourPerSlice) {
  const auto image = make_volume({60, 60, 5}, {0.5, 0.5, 2.0}, {-15, -15, 0},
                                 [](const Eigen::Vector3d& p) { return cylinder(p, 0, 0, 10); });
  SegmentationOptions o;
  o.threshold = 500;
  o.sampling = 0.4;
  const SegmentationResult r = segment_contours(*image, o);
  ASSERT_EQ(r.stack.slices.size(), 5u);
  for (std::size_t k = 0; k < 5; ++k) {
    const SliceContours& s = r.stack.slices[k];
    EXPECT_DOUBLE_EQ(s.w, 2.0 * k);
    ASSERT_EQ(s.contours.size(), 1u);
    const Contour& c = s.contours[0];
    EXPECT_FALSE(c.is_hole);
    EXPECT_GT(signed_area(c.points), 0.0);
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      const Eigen::Vector3d p = r.stack.to_physical(c.points[i], s.w);
      EXPECT_NEAR(std::hypot(p.x(), p.y()), 10.0, 0.1);  // sub-pixel: well under the 0.5 mm pixel
      EXPECT_NEAR((c.points[(i + 1) % c.points.size()] - c.points[i]).norm(), 0.4, 0.05);
    }
  }
}

TEST(Segmentation, HolesAreClockwiseWithParentsAndSmallOnesAreFilled) {
  // A ring (hole radius 5) with a tiny pit (radius 0.4 mm) in its wall, and a speck far away.
  const auto image = make_volume({80, 80, 3}, {0.5, 0.5, 1.0}, {-20, -20, 0}, [](const Eigen::Vector3d& p) {
    const double ring = std::max(cylinder(p, 0, 0, 12), -cylinder(p, 0, 0, 5));
    const double pit = -cylinder(p, 8.5, 0, 0.4);
    const double speck = cylinder(p, -17, -17, 0.5);
    return std::min(std::max(ring, pit), speck);
  });
  SegmentationOptions o;
  o.threshold = 500;
  const SegmentationResult r = segment_contours(*image, o);
  for (const SliceContours& s : r.stack.slices) {
    ASSERT_EQ(s.contours.size(), 2u);  // outer + hole; speck dropped, pit filled
    EXPECT_FALSE(s.contours[0].is_hole);
    EXPECT_TRUE(s.contours[1].is_hole);
    EXPECT_EQ(s.contours[1].parent, 0);
    EXPECT_LT(signed_area(s.contours[1].points), 0.0);
    EXPECT_NEAR(-signed_area(s.contours[1].points), std::numbers::pi * 25.0, 2.0);
  }
  EXPECT_GE(r.dropped_regions, 3u);
  o.fill_holes = true;
  for (const SliceContours& s : segment_contours(*image, o).stack.slices) EXPECT_EQ(s.contours.size(), 1u);
}

// A tube with a 0.7 mm wall sampled every 8 mm: the outer contour's chords (sagitta 0.8 mm) would
// cut through the hole. The contours of a slice must not meet (the tiler rejects them), so both are
// resampled more finely until they do not.
TEST(Segmentation, ResamplingNeverMakesTheContoursOfASliceMeet) {
  const auto image = make_volume({100, 100, 3}, {0.25, 0.25, 1.0}, {-12.5, -12.5, 0}, [](const Eigen::Vector3d& p) {
    return std::max(cylinder(p, 0, 0, 10.0), -cylinder(p, 0, 0, 9.3));
  });
  SegmentationOptions o;
  o.threshold = 500;
  o.sampling = 8.0;
  const auto r = segment_contours(*image, o);
  for (const SliceContours& slice : r.stack.slices) {
    ASSERT_EQ(slice.contours.size(), 2u);
    std::vector<std::vector<Eigen::Vector2d>> outlines;
    for (const Contour& c : slice.contours) outlines.push_back(c.points);
    EXPECT_FALSE(find_polygon_crossing(outlines));
    // 2 pi 10 / 8 = 8 points at the asked spacing; the outer contour needed more.
    EXPECT_GT(slice.contours[0].points.size(), 8u);
  }
  EXPECT_NO_THROW(tile_contours(r.stack));
}

using test::pixel_volume;

// Sub-pixel position: on a ramp of 100 HU per pixel, the contour crosses each row where the linear
// interpolation of the two pixel values meets the threshold.
TEST(Segmentation, ContoursCrossPixelEdgesWhereTheValuesMeetTheThreshold) {
  const Eigen::Vector3d spacing(0.5, 0.7, 1.0);
  const auto image = pixel_volume({12, 8, 2}, spacing, [](int i, int, int) { return 100.0f * i + 7.0f; });
  SegmentationOptions o;
  o.threshold = 550;  // between pixel 5 (507) and pixel 6 (607): 0.43 of the way
  o.sampling = 0.1;
  const auto r = segment_contours(*image, o);
  for (const SliceContours& s : r.stack.slices) {
    ASSERT_EQ(s.contours.size(), 1u);
    double min_x = 1e9;
    for (const Eigen::Vector2d& p : s.contours[0].points) min_x = std::min(min_x, p.x());
    EXPECT_NEAR(min_x, 5.43 * spacing.x(), 1e-9);
    EXPECT_GT(signed_area(s.contours[0].points), 0.0);
  }
}

// Regions are 4-connected: two pixel blocks touching at one corner are two contours, each around its
// own block (at a threshold halfway between bone and background a k x k block's contour passes
// through the pixel edges' midpoints: area k^2 - 1/2 pixels).
TEST(Segmentation, BlocksTouchingAtACornerStayTwoRegions) {
  const auto image = pixel_volume({14, 14, 2}, {1.0, 1.0, 1.0}, [](int i, int j, int) {
    const bool a = i >= 2 && i < 6 && j >= 2 && j < 6, b = i >= 6 && i < 10 && j >= 6 && j < 10;
    return a || b ? 1000.0f : 0.0f;
  });
  SegmentationOptions o;
  o.threshold = 500;
  o.sampling = 0.05;
  const auto r = segment_contours(*image, o);
  for (const SliceContours& s : r.stack.slices) {
    ASSERT_EQ(s.contours.size(), 2u);
    for (const Contour& c : s.contours) {
      EXPECT_FALSE(c.is_hole);
      EXPECT_NEAR(signed_area(c.points), 15.5, 0.01);
    }
    std::vector<std::vector<Eigen::Vector2d>> outlines{s.contours[0].points, s.contours[1].points};
    EXPECT_FALSE(find_polygon_crossing(outlines));
  }
}

TEST(Segmentation, KeepLargestDropsTheSmallerObject) {
  const auto image = make_volume({80, 40, 3}, {0.5, 0.5, 1.0}, {-20, -10, 0}, [](const Eigen::Vector3d& p) {
    return std::min(cylinder(p, -10, 0, 6), cylinder(p, 10, 0, 4));
  });
  SegmentationOptions o;
  o.threshold = 500;
  EXPECT_EQ(segment_contours(*image, o).stack.slices[1].contours.size(), 2u);
  o.components = ComponentSelection::KeepLargest;
  const auto r = segment_contours(*image, o);
  ASSERT_EQ(r.stack.slices[1].contours.size(), 1u);
  EXPECT_LT(r.stack.to_physical(r.stack.slices[1].contours[0].points[0], 0).x(), 0.0);
}

// A square prism (20 x 20 mm, 0.5 mm pixels, 2 mm slices) whose end face lies exactly at slice 3's centre:
// slices 0-2 inside, slice 3 half inside (the iso-level) with 20 HU of noise, slice 4 outside.
CtImage::Pointer end_face_on_slice() {
  auto image = make_volume({60, 60, 5}, {0.5, 0.5, 2.0}, {-15, -15, 0}, [](const Eigen::Vector3d& p) {
    return p.z() < 5.0 ? std::max(std::abs(p.x()), std::abs(p.y())) - 10.0 : 1.0;
  });
  std::mt19937 rng(3);
  std::normal_distribution<float> noise(0.0f, 20.0f);
  for (int j = 0; j < 60; ++j) {
    for (int i = 0; i < 60; ++i) {
      const float below = image->GetPixel({{i, j, 2}});
      image->SetPixel({{i, j, 3}}, 0.5f * below + noise(rng));
    }
  }
  return image;
}

TEST(Segmentation, AnEndFaceOnASliceCentreGivesOneCleanContourOrNone) {
  const auto image = end_face_on_slice();
  SegmentationOptions o;
  o.threshold = 500;
  // Pixel by pixel, the noise splits the half-bone slice into specks and holes.
  o.flat_crossings = FlatCrossings::PerPixel;
  EXPECT_GT(segment_contours(*image, o).stack.slices[3].contours.size(), 2u);
  // Decided as one patch: the whole section or nothing, and the slices around as they were.
  o.flat_crossings = FlatCrossings::Patches;
  const SegmentationResult r = segment_contours(*image, o);
  const std::vector<Contour>& end = r.stack.slices[3].contours;
  ASSERT_LE(end.size(), 1u);
  if (!end.empty()) {
    EXPECT_NEAR(signed_area(end[0].points), 400.0, 10.0);
  }
  ASSERT_EQ(r.stack.slices[2].contours.size(), 1u);
  EXPECT_NEAR(signed_area(r.stack.slices[2].contours[0].points), 400.0, 2.0);
  EXPECT_TRUE(r.stack.slices[4].contours.empty());
}

TEST(Segmentation, OtsuFindsAThresholdBetweenTheTwoClasses) {
  const auto image = make_volume({40, 40, 2}, {1, 1, 1}, {-20, -20, 0},
                                 [](const Eigen::Vector3d& p) { return cylinder(p, 0, 0, 9); }, 900.0f, 100.0f);
  SegmentationOptions o;
  o.threshold_method = ThresholdMethod::Otsu;
  o.smoothing = ImageSmoothing::Median;
  const SegmentationResult r = segment_contours(*image, o);
  EXPECT_GT(r.threshold, 150.0);
  EXPECT_LT(r.threshold, 850.0);
  EXPECT_EQ(r.stack.slices[0].contours.size(), 1u);
}

TEST(Segmentation, CylinderReconstructsToAClosedMeshWithTheRightVolume) {
  const auto image = make_volume({70, 70, 12}, {0.5, 0.5, 2.0}, {-17.5, -17.5, -2}, [](const Eigen::Vector3d& p) {
    return std::max(cylinder(p, 0, 0, 12), std::abs(p.z() - 10.0) - 8.9);  // z in [1.1, 18.9]
  });
  SegmentationOptions o;
  o.threshold = 500;
  o.smoothing = ImageSmoothing::CurvatureAnisotropic;
  const auto seg = segment_contours(*image, o);
  const TilingResult tiled = tile_contours(seg.stack);
  const test::Topology t = test::topology_of(tiled.mesh);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.manifold) << t.problems;
  EXPECT_EQ(t.euler, 2);
  // Slices at z = 2, 4, ..., 18 hold the disc; with the half-spacing ends the mesh spans z = 1 .. 19,
  // the solid z = 1.1 .. 18.9.
  EXPECT_NEAR(enclosed_volume(tiled.mesh), std::numbers::pi * 144.0 * 17.8, 0.02 * std::numbers::pi * 144.0 * 17.8);
}

TEST(Segmentation, BadOptionsAndEmptyResultsAreReported) {
  const auto image = make_volume({10, 10, 2}, {1, 1, 1}, {0, 0, 0}, [](const Eigen::Vector3d&) { return 1.0; });
  SegmentationOptions o;
  o.sampling = -1;
  EXPECT_THROW((void)segment_contours(*image, o), InvalidInputError);
  const auto r = segment_contours(*image);  // all below threshold: no contours, not an error here
  EXPECT_EQ(r.stack.num_contours(), 0u);
  int calls = 0;
  EXPECT_THROW((void)segment_contours(*image, {}, [&](std::string_view, double) { return ++calls < 1; }),
               CancelledError);
}

TEST(Segmentation, AllBoneAndAllAirVolumesAreRejectedSayingWhich) {
  auto message = [](const CtImage::Pointer& image) {
    try {
      (void)reconstruct(*image);
    } catch (const InvalidInputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const auto bone = make_volume({10, 10, 3}, {1, 1, 1}, {0, 0, 0}, [](const Eigen::Vector3d&) { return -1.0; });
  EXPECT_NE(message(bone).find("every voxel is at or above the threshold 300 (all bone"), std::string::npos);
  const auto air = make_volume({10, 10, 3}, {1, 1, 1}, {0, 0, 0}, [](const Eigen::Vector3d&) { return 1.0; });
  EXPECT_NE(message(air).find("no region at or above the threshold 300 in any of the 3 slices"), std::string::npos);
  // One bone voxel per slice: dropped as too small, and said so.
  const auto specks = make_volume({10, 10, 3}, {1, 1, 1}, {0, 0, 0}, [](const Eigen::Vector3d& p) {
    return std::abs(p.x() - 5) < 0.6 && std::abs(p.y() - 5) < 0.6 ? -1.0 : 1.0;
  });
  EXPECT_NE(message(specks).find("3 regions were smaller than the minimum area"), std::string::npos)
      << message(specks);
}

}  // namespace
}  // namespace contourmesh
