// SPDX-License-Identifier: BSD-3-Clause
// Private: connected components of a binary slice image, by runs and union-find (segmentation).
#pragma once

#include "contourmesh/internal/union_find.h"

#include <cstdint>
#include <vector>

namespace contourmesh::detail {

enum class Connectivity {
  Four,   ///< pixels sharing an edge
  Eight,  ///< pixels sharing an edge or a corner
};

/// A horizontal run of pixels: row y, columns [x0, x1), and the component it belongs to.
struct PixelRun {
  int y = 0;
  int x0 = 0;
  int x1 = 0;
  int label = 0;
};

/// Replaces `runs` by the maximal runs of the pixels with mask[p] != 0 in an nx x ny image (x fastest;
/// mask bytes 0 or 1), row by row, left to right. Reads eight pixels at a time where nothing changes.
void find_runs(const std::uint8_t* mask, int nx, int ny, std::vector<PixelRun>& runs);

/// Replaces `out` by the runs of the pixels that none of `runs` (ordered as find_runs orders them, not
/// overlapping) covers, in the same order.
void complement_runs(const std::vector<PixelRun>& runs, int nx, int ny, std::vector<PixelRun>& out);

/// Labels the connected components of the pixels that `runs` (ordered as find_runs orders them) cover:
/// sets every run's label to 1..count and returns count. Components are numbered in the raster order of
/// their first pixel (row by row, then x), the numbering of a flood fill started from each unlabelled
/// pixel in raster order. Union-find over the runs; `scratch` keeps its buffer between calls.
int label_runs(std::vector<PixelRun>& runs, Connectivity connectivity, UnionFind<int>& scratch);

/// Keeps, of a binary volume (nx x ny x nz, x fastest, bytes 0 or 1), only the largest 6-connected
/// component of the 1s; the first in raster order (z, then y, then x of its first voxel) among
/// equally large ones. Union-find over the runs of every row: linear in the voxels, fast when runs
/// are long.
void keep_largest_component(std::vector<std::uint8_t>& mask, int nx, int ny, int nz);

}  // namespace contourmesh::detail
