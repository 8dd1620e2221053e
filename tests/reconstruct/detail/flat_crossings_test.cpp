// SPDX-License-Identifier: BSD-3-Clause
// The sides of the pixels whose column the boundary crosses near the slice's centre (segmentation).
#include "detail/flat_crossings.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <random>
#include <vector>

namespace contourmesh::detail {
namespace {

constexpr int kN = 30;                   // pixels per side
constexpr float kThreshold = 500.0f;     // between the outside (0) and the inside (1000)
constexpr float kAbove = 501.0f, kBelow = 499.999f;

// Three slices of kN x kN: inside (1000) below, outside (0) above, and in the middle slice the values
// `middle(x, y)` plus Gaussian noise of `noise` (fixed seed) over the square [5, 25) x [5, 25); outside
// that square every slice is outside.
std::vector<float> three_slices(float (*middle)(int, int), float noise, unsigned seed = 7) {
  std::vector<float> v(3 * kN * kN, 0.0f);
  std::mt19937 rng(seed);
  std::normal_distribution<float> gauss(0.0f, noise);
  for (int y = 5; y < 25; ++y) {
    for (int x = 5; x < 25; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * kN + x;
      v[p] = 1000.0f;
      v[kN * kN + p] = middle(x, y) + gauss(rng);
    }
  }
  return v;
}

// The middle slice after the listed changes: how many of the square's pixels are at or above the
// threshold.
int inside_count(const std::vector<float>& volume, const std::vector<PixelValue>& changes) {
  std::vector<float> slice(volume.begin() + kN * kN, volume.begin() + 2 * kN * kN);
  for (const PixelValue& c : changes) slice[c.pixel] = c.value;
  int inside = 0;
  for (int y = 5; y < 25; ++y) {
    for (int x = 5; x < 25; ++x) inside += slice[static_cast<std::size_t>(y) * kN + x] >= kThreshold;
  }
  return inside;
}

TEST(FlatCrossings, AnEndFaceOnTheSliceIsDecidedAsAWhole) {
  // The face lies exactly at the middle slice's centre: every pixel is half inside, and 20 HU of noise
  // put about half of them on either side.
  const std::vector<float> v = three_slices([](int, int) { return 500.0f; }, 20.0f);
  ASSERT_GT(inside_count(v, {}), 100);
  ASSERT_LT(inside_count(v, {}), 300);
  const std::vector<PixelValue> changes = flat_crossing_values(v.data(), kN, kN, 3, 1, kThreshold, kAbove, kBelow);
  const int inside = inside_count(v, changes);
  EXPECT_TRUE(inside == 0 || inside == 400) << inside;
}

TEST(FlatCrossings, ThePatchsMedianChoosesTheSide) {
  // The face 0.06 of a spacing beyond the slice's centre (the pixels 56 % inside): all inside.
  const std::vector<float> up = three_slices([](int, int) { return 560.0f; }, 20.0f);
  EXPECT_EQ(inside_count(up, flat_crossing_values(up.data(), kN, kN, 3, 1, kThreshold, kAbove, kBelow)), 400);
  const std::vector<float> down = three_slices([](int, int) { return 480.0f; }, 20.0f);
  EXPECT_EQ(inside_count(down, flat_crossing_values(down.data(), kN, kN, 3, 1, kThreshold, kAbove, kBelow)), 0);
  // 0.02 beyond: outside, where the off-slice heights lay the cap nearer the face than inside.
  const std::vector<float> near = three_slices([](int, int) { return 520.0f; }, 20.0f);
  EXPECT_EQ(inside_count(near, flat_crossing_values(near.data(), kN, kN, 3, 1, kThreshold, kAbove, kBelow)), 0);
}

TEST(FlatCrossings, TheSideIsWhereTheFaceLiesNotTheThresholds) {
  // Segmented at 450 HU, pixels 47 % inside are above the threshold one by one; the face they show
  // lies just before the slice's centre, so the patch is outside (the cap then goes between this slice
  // and the one before, where the off-slice heights read it).
  const std::vector<float> v = three_slices([](int, int) { return 470.0f; }, 20.0f);
  std::vector<float> slice(v.begin() + kN * kN, v.begin() + 2 * kN * kN);
  EXPECT_GT(std::count_if(slice.begin(), slice.end(), [](float x) { return x >= 450.0f; }), 300);
  for (const PixelValue& c : flat_crossing_values(v.data(), kN, kN, 3, 1, 450.0f, 451.0f, 449.999f)) {
    slice[c.pixel] = c.value;
  }
  for (float x : slice) EXPECT_LT(x, 450.0f);
}

TEST(FlatCrossings, TheInsideAboveIsMirrored) {
  // The same end face upside down: outside below, inside above.
  std::vector<float> v = three_slices([](int, int) { return 560.0f; }, 20.0f);
  for (std::size_t p = 0; p < static_cast<std::size_t>(kN * kN); ++p) std::swap(v[p], v[2 * kN * kN + p]);
  EXPECT_EQ(inside_count(v, flat_crossing_values(v.data(), kN, kN, 3, 1, kThreshold, kAbove, kBelow)), 400);
}

TEST(FlatCrossings, ASurfaceTiltedAcrossTheBandKeepsEachPixelsSide) {
  // The crossing's height rises across the square by 0.3 of the slice spacing (a face a few degrees off
  // the slices): not flat, nothing changes.
  const std::vector<float> v =
      three_slices([](int x, int) { return 350.0f + 15.0f * static_cast<float>(x - 5); }, 20.0f);
  EXPECT_TRUE(flat_crossing_values(v.data(), kN, kN, 3, 1, kThreshold, kAbove, kBelow).empty());
}

TEST(FlatCrossings, NoiseThatFillsTheBandKeepsEachPixelsSide) {
  // 120 HU of noise on a 1000 HU contrast: the band of +-0.2 cannot tell a flat patch from any other.
  const std::vector<float> v = three_slices([](int, int) { return 500.0f; }, 120.0f);
  EXPECT_TRUE(flat_crossing_values(v.data(), kN, kN, 3, 1, kThreshold, kAbove, kBelow).empty());
}

TEST(FlatCrossings, SmallPatchesAndTheEndSlicesAreLeftAlone) {
  FlatCrossingOptions o;
  o.min_pixels = 401;  // more than the square
  const std::vector<float> v = three_slices([](int, int) { return 500.0f; }, 20.0f);
  EXPECT_TRUE(flat_crossing_values(v.data(), kN, kN, 3, 1, kThreshold, kAbove, kBelow, o).empty());
  EXPECT_TRUE(flat_crossing_values(v.data(), kN, kN, 3, 0, kThreshold, kAbove, kBelow).empty());
  EXPECT_TRUE(flat_crossing_values(v.data(), kN, kN, 3, 2, kThreshold, kAbove, kBelow).empty());
}

}  // namespace
}  // namespace contourmesh::detail
