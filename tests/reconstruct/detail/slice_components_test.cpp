// SPDX-License-Identifier: BSD-3-Clause
// The run-based labelling of segmentation against a plain flood fill (the definition of the numbering).
#include "detail/slice_components.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

namespace contourmesh::detail {
namespace {

// Flood fill from each unlabelled selected pixel in raster order: the reference numbering.
std::vector<int> flood_labels(const std::vector<std::uint8_t>& mask, int nx, int ny, bool selected, bool eight) {
  std::vector<int> label(mask.size(), 0), stack;
  int next = 0;
  for (int start = 0; start < nx * ny; ++start) {
    if ((mask[start] != 0) != selected || label[start]) continue;
    label[start] = ++next;
    stack.push_back(start);
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          if ((dx == 0 && dy == 0) || (!eight && dx != 0 && dy != 0)) continue;
          const int x = v % nx + dx, y = v / nx + dy;
          if (x < 0 || y < 0 || x >= nx || y >= ny) continue;
          const int w = y * nx + x;
          if ((mask[w] != 0) == selected && !label[w]) {
            label[w] = next;
            stack.push_back(w);
          }
        }
      }
    }
  }
  return label;
}

std::vector<int> painted(const std::vector<PixelRun>& runs, int nx, int ny) {
  std::vector<int> label(static_cast<std::size_t>(nx) * ny, 0);
  for (const PixelRun& r : runs) {
    for (int x = r.x0; x < r.x1; ++x) label[static_cast<std::size_t>(r.y) * nx + x] = r.label;
  }
  return label;
}

std::vector<std::uint8_t> random_mask(std::mt19937& rng, int nx, int ny, double density) {
  std::bernoulli_distribution on(density);
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(nx) * ny);
  for (auto& m : mask) m = on(rng) ? 1 : 0;
  return mask;
}

TEST(SliceComponents, RunsCoverExactlyTheSelectedPixelsAndTheirComplement) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const int nx = 1 + trial % 23, ny = 1 + trial % 17;  // widths below, at and above one 8-byte word
    const auto mask = random_mask(rng, nx, ny, 0.2 + 0.6 * (trial % 5) / 4.0);
    std::vector<PixelRun> runs, rest;
    find_runs(mask.data(), nx, ny, runs);
    complement_runs(runs, nx, ny, rest);
    std::vector<int> covered(mask.size(), 0);
    for (const auto* list : {&runs, &rest}) {
      for (std::size_t k = 0; k < list->size(); ++k) {
        const PixelRun& r = (*list)[k];
        ASSERT_LT(r.x0, r.x1);
        for (int x = r.x0; x < r.x1; ++x) {
          const std::size_t p = static_cast<std::size_t>(r.y) * nx + x;
          EXPECT_EQ(mask[p] != 0, list == &runs);
          ++covered[p];
        }
        if (k > 0) {  // ordered, maximal: two runs of a row never touch
          const PixelRun& q = (*list)[k - 1];
          EXPECT_TRUE(q.y < r.y || q.x1 < r.x0);
        }
      }
    }
    for (int c : covered) EXPECT_EQ(c, 1);
  }
}

TEST(SliceComponents, LabelsAndNumberingMatchAFloodFill) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 60; ++trial) {
    const int nx = 5 + trial % 41, ny = 3 + trial % 29;
    const auto mask = random_mask(rng, nx, ny, 0.3 + 0.4 * (trial % 3) / 2.0);
    for (const bool eight : {false, true}) {
      for (const bool selected : {true, false}) {
        std::vector<PixelRun> runs, selected_runs;
        UnionFind<int> scratch;
        find_runs(mask.data(), nx, ny, runs);
        if (selected) selected_runs = runs;
        else complement_runs(runs, nx, ny, selected_runs);
        const int count = label_runs(selected_runs, eight ? Connectivity::Eight : Connectivity::Four, scratch);
        const std::vector<int> reference = flood_labels(mask, nx, ny, selected, eight);
        ASSERT_EQ(painted(selected_runs, nx, ny), reference) << "trial " << trial << (eight ? " 8" : " 4");
        EXPECT_EQ(count, *std::max_element(reference.begin(), reference.end()));
      }
    }
  }
}

// Diagonal neighbours: one component with 8-connectivity, two with 4; a row without runs between.
TEST(SliceComponents, DiagonalPixelsAndEmptyRows) {
  const std::vector<std::uint8_t> mask = {1, 0, 0,  //
                                          0, 1, 0,  //
                                          0, 0, 0,  //
                                          0, 1, 1};
  std::vector<PixelRun> runs;
  UnionFind<int> scratch;
  find_runs(mask.data(), 3, 4, runs);
  auto four = runs, eight = runs;
  EXPECT_EQ(label_runs(four, Connectivity::Four, scratch), 3);
  EXPECT_EQ(label_runs(eight, Connectivity::Eight, scratch), 2);
  EXPECT_EQ(eight[0].label, eight[1].label);
  EXPECT_NE(eight[1].label, eight[2].label);
}

// The reference: 6-connected flood fill in raster order, the first of the largest components kept.
std::vector<std::uint8_t> largest_by_flood(const std::vector<std::uint8_t>& mask, int nx, int ny, int nz) {
  std::vector<int> label(mask.size(), 0), stack;
  int next = 0, best = 0;
  std::size_t best_size = 0;
  for (int start = 0; start < nx * ny * nz; ++start) {
    if (!mask[start] || label[start]) continue;
    label[start] = ++next;
    stack.push_back(start);
    std::size_t count = 0;
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      ++count;
      const int x = v % nx, y = (v / nx) % ny, z = v / (nx * ny);
      const int d[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
      for (const auto& o : d) {
        const int xx = x + o[0], yy = y + o[1], zz = z + o[2];
        if (xx < 0 || yy < 0 || zz < 0 || xx >= nx || yy >= ny || zz >= nz) continue;
        const int w = (zz * ny + yy) * nx + xx;
        if (mask[w] && !label[w]) {
          label[w] = next;
          stack.push_back(w);
        }
      }
    }
    if (count > best_size) best_size = count, best = next;
  }
  std::vector<std::uint8_t> out(mask.size(), 0);
  for (std::size_t v = 0; v < mask.size(); ++v) out[v] = best != 0 && label[v] == best;
  return out;
}

TEST(SliceComponents, KeepLargestComponentMatchesAFloodFillTiesIncluded) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 40; ++trial) {
    const int nx = 2 + trial % 13, ny = 1 + trial % 7, nz = 1 + trial % 5;
    auto mask = random_mask(rng, nx, ny * nz, 0.25 + 0.1 * (trial % 4));
    const auto expected = largest_by_flood(mask, nx, ny, nz);
    keep_largest_component(mask, nx, ny, nz);
    EXPECT_EQ(mask, expected) << "trial " << trial;
  }
  // Two single voxels: equally large, the first in raster order stays.
  std::vector<std::uint8_t> two = {0, 1, 0, 0, 0, 0, 0, 1};
  keep_largest_component(two, 2, 2, 2);
  EXPECT_EQ(two, (std::vector<std::uint8_t>{0, 1, 0, 0, 0, 0, 0, 0}));
  std::vector<std::uint8_t> none(8, 0);
  keep_largest_component(none, 2, 2, 2);
  EXPECT_EQ(none, std::vector<std::uint8_t>(8, 0));
}

}  // namespace
}  // namespace contourmesh::detail
