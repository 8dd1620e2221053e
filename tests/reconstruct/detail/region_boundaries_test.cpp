// SPDX-License-Identifier: BSD-3-Clause
// Boundary tracing of segmentation: the same loops, in the same order and from the same first point, as
// itk::ContourExtractor2DImageFilter run on each region on its own (region pixels above the contour
// value, the rest below), and the marching-squares orientation.
#include "detail/region_boundaries.h"

#include <itkContourExtractor2DImageFilter.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace contourmesh::detail {
namespace {

using Image2D = itk::Image<float, 2>;
using Loop = std::vector<std::array<double, 2>>;

RegionImage region_image(const std::vector<int>& labels, int nx, int ny, std::vector<PixelRun>& owned) {
  RegionImage image;
  image.reset(nx, ny);
  owned.clear();
  for (int y = 0; y < ny; ++y) {
    for (int x = 0; x < nx;) {
      const int l = labels[static_cast<std::size_t>(y) * nx + x];
      int end = x + 1;
      while (end < nx && labels[static_cast<std::size_t>(y) * nx + end] == l) ++end;
      if (l > 0) {
        owned.push_back({y, x, end, l});
        image.paint(owned.back(), l);
      }
      x = end;
    }
  }
  return image;
}

// ITK's loops of region l: the region's pixels 1, everything else 0, contour value 0.5, on a crop two
// pixels around the region; points in image pixel coordinates, the closing repeat dropped.
std::vector<Loop> itk_loops(const std::vector<int>& labels, int nx, int ny, int l) {
  int x0 = nx, y0 = ny, x1 = -1, y1 = -1;
  for (int y = 0; y < ny; ++y) {
    for (int x = 0; x < nx; ++x) {
      if (labels[static_cast<std::size_t>(y) * nx + x] != l) continue;
      x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
    }
  }
  if (x1 < 0) return {};
  x0 -= 2, y0 -= 2;
  const int w = x1 - x0 + 3, h = y1 - y0 + 3;
  auto crop = Image2D::New();
  Image2D::RegionType r;
  r.SetSize({{static_cast<itk::SizeValueType>(w), static_cast<itk::SizeValueType>(h)}});
  crop->SetRegions(r);
  crop->Allocate();
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int gx = x0 + x, gy = y0 + y;
      const bool in = gx >= 0 && gy >= 0 && gx < nx && gy < ny && labels[static_cast<std::size_t>(gy) * nx + gx] == l;
      crop->SetPixel({{x, y}}, in ? 1.0f : 0.0f);
    }
  }
  auto extractor = itk::ContourExtractor2DImageFilter<Image2D>::New();
  extractor->SetInput(crop);
  extractor->SetContourValue(0.5);
  extractor->Update();
  std::vector<Loop> loops;
  for (unsigned k = 0; k < extractor->GetNumberOfIndexedOutputs(); ++k) {
    const auto* vertices = extractor->GetOutput(k)->GetVertexList();
    Loop loop;
    for (unsigned i = 0; i + 1 < vertices->Size(); ++i) {
      loop.push_back({vertices->ElementAt(i)[0] + x0, vertices->ElementAt(i)[1] + y0});
    }
    loops.push_back(loop);
  }
  return loops;
}

Loop midpoints(const RegionLoop& loop) {
  Loop out;
  for (const EdgeCrossing& c : loop.crossings) {
    out.push_back({c.x + (c.horizontal ? 0.5 : 0.0), c.y + (c.horizontal ? 0.0 : 0.5)});
  }
  return out;
}

double shoelace(const Loop& loop) {
  double a = 0.0;
  for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
    a += loop[j][0] * loop[i][1] - loop[i][0] * loop[j][1];
  }
  return a / 2.0;
}

// Random labels 0..3 per pixel: scattered regions with many saddles, holes and loops at the border.
TEST(RegionBoundaries, SameLoopsOrderAndStartAsItkContourExtractorPerRegion) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 40; ++trial) {
    const int nx = 3 + trial % 19, ny = 2 + trial % 13, regions = 1 + trial % 3;
    std::uniform_int_distribution<int> pick(0, regions);
    std::vector<int> labels(static_cast<std::size_t>(nx) * ny);
    for (int& l : labels) l = pick(rng);
    std::vector<PixelRun> owned;
    const RegionImage image = region_image(labels, nx, ny, owned);
    std::vector<std::uint8_t> visited;
    std::vector<RegionLoop> loops;
    trace_region_boundaries(image, owned, visited, loops);
    std::size_t k = 0;
    for (int l = 1; l <= regions; ++l) {
      for (const Loop& expected : itk_loops(labels, nx, ny, l)) {
        ASSERT_LT(k, loops.size()) << "trial " << trial;
        EXPECT_EQ(loops[k].region, l);
        EXPECT_EQ(midpoints(loops[k]), expected) << "trial " << trial << ", region " << l;
        ++k;
      }
    }
    EXPECT_EQ(k, loops.size()) << "trial " << trial;
  }
}

// Outer boundaries have positive area in (x, y) pixel coordinates (counter-clockwise with y up), holes
// negative; pixels touching only at a corner are separate loops (4-connected regions).
TEST(RegionBoundaries, OrientationHolesAndSaddles) {
  const int nx = 7, ny = 5;
  const std::vector<int> labels = {0, 0, 0, 0, 0, 0, 0,  //
                                   0, 1, 1, 1, 0, 0, 0,  //
                                   0, 1, 0, 1, 0, 2, 0,  //
                                   0, 1, 1, 1, 2, 0, 0,  //
                                   0, 0, 0, 0, 0, 0, 0};
  std::vector<PixelRun> owned;
  const RegionImage image = region_image(labels, nx, ny, owned);
  std::vector<std::uint8_t> visited;
  std::vector<RegionLoop> loops;
  trace_region_boundaries(image, owned, visited, loops);
  ASSERT_EQ(loops.size(), 4u);  // ring: outer + hole; region 2: two diagonal pixels, two loops
  EXPECT_EQ(loops[0].region, 1);
  EXPECT_DOUBLE_EQ(shoelace(midpoints(loops[0])), 9.0 - 0.5);  // 3 x 3 square, corners cut by half a pixel
  EXPECT_DOUBLE_EQ(shoelace(midpoints(loops[1])), -0.5);       // the hole: a diamond around one pixel
  for (std::size_t k : {2u, 3u}) {
    EXPECT_EQ(loops[k].region, 2);
    EXPECT_DOUBLE_EQ(shoelace(midpoints(loops[k])), 0.5);
  }
}

}  // namespace
}  // namespace contourmesh::detail
