// SPDX-License-Identifier: BSD-3-Clause
// Private: the boundary loops of labelled regions in a slice, in the order and orientation of marching
// squares (segmentation).
#pragma once

#include "detail/slice_components.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace contourmesh::detail {

/// The region of every pixel of an nx x ny slice (0: none), with one pixel of "none" around it, so
/// that every square and edge a boundary passes through is inside.
class RegionImage {
 public:
  /// nx x ny pixels, all in no region.
  void reset(int nx, int ny) {
    nx_ = nx;
    ny_ = ny;
    padded_.assign(static_cast<std::size_t>(nx + 2) * static_cast<std::size_t>(ny + 2), 0);
  }
  void paint(const PixelRun& run, int region) {
    std::fill_n(padded_.begin() + static_cast<std::ptrdiff_t>(index(run.x0, run.y)), run.x1 - run.x0, region);
  }
  /// The region of pixel (x, y); x in [-1, nx], y in [-1, ny].
  [[nodiscard]] int at(int x, int y) const { return padded_[index(x, y)]; }
  [[nodiscard]] int nx() const { return nx_; }
  [[nodiscard]] int ny() const { return ny_; }
  [[nodiscard]] const std::vector<int>& padded() const { return padded_; }

 private:
  [[nodiscard]] std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y + 1) * static_cast<std::size_t>(nx_ + 2) + static_cast<std::size_t>(x + 1);
  }
  int nx_ = 0, ny_ = 0;
  std::vector<int> padded_;
};

/// A pixel edge crossed by a region's boundary. Horizontal: between pixels (x, y) and (x + 1, y);
/// vertical: between (x, y) and (x, y + 1). x and y may be -1 (the pixels just outside the image).
struct EdgeCrossing {
  int x = 0;
  int y = 0;
  bool horizontal = false;
};

/// One closed boundary of one region.
struct RegionLoop {
  int region = 0;
  /// Marching-squares order of its first segment: the raster index of its square in the padded image.
  /// Loops of a region are listed by increasing first_key.
  std::int64_t first_key = 0;
  std::vector<EdgeCrossing> crossings;
};

/// Traces every boundary of every region of `regions`. A region is 4-connected: where two of its
/// pixels touch only at a corner (a marching-squares saddle) the boundary passes between them. Each
/// loop runs with its region on the right in image coordinates (x right, y down; counter-clockwise
/// around the region seen with y up) and starts at the crossing that its last segment in
/// marching-squares order reaches: where the loop closes when segments are joined square by square
/// in raster order. Loops are returned sorted by region, then first_key.
///
/// `owned` must hold runs covering every pixel that belongs to a region (each run inside one region):
/// their ends seed the tracing, so the time is linear in the runs and the crossings (plus clearing
/// `visited`, one byte per pixel).
void trace_region_boundaries(const RegionImage& regions, std::span<const PixelRun> owned,
                             std::vector<std::uint8_t>& visited, std::vector<RegionLoop>& loops);

}  // namespace contourmesh::detail
