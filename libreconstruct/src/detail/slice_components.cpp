// SPDX-License-Identifier: BSD-3-Clause
#include "detail/slice_components.h"

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstring>

namespace contourmesh::detail {

namespace {

// The first x in [x, nx) with (row[x] != 0) != on, else nx.
int next_change(const std::uint8_t* row, int x, int nx, bool on) {
  const std::uint64_t same = on ? 0x0101010101010101ull : 0;
  while (x + 8 <= nx) {
    std::uint64_t word;
    std::memcpy(&word, row + x, 8);
    if (const std::uint64_t diff = word ^ same) {
      if constexpr (std::endian::native == std::endian::little) return x + std::countr_zero(diff) / 8;
      else return x + std::countl_zero(diff) / 8;
    }
    x += 8;
  }
  while (x < nx && (row[x] != 0) == on) ++x;
  return x;
}

}  // namespace

void find_runs(const std::uint8_t* mask, int nx, int ny, std::vector<PixelRun>& runs) {
  runs.clear();
  for (int y = 0; y < ny; ++y) {
    const std::uint8_t* row = mask + static_cast<std::size_t>(y) * nx;
    int x = next_change(row, 0, nx, false);
    while (x < nx) {
      const int x1 = next_change(row, x, nx, true);
      runs.push_back({y, x, x1, 0});
      x = next_change(row, x1, nx, false);
    }
  }
}

void complement_runs(const std::vector<PixelRun>& runs, int nx, int ny, std::vector<PixelRun>& out) {
  out.clear();
  std::size_t k = 0;
  for (int y = 0; y < ny; ++y) {
    int x = 0;
    for (; k < runs.size() && runs[k].y == y; ++k) {
      if (runs[k].x0 > x) out.push_back({y, x, runs[k].x0, 0});
      x = runs[k].x1;
    }
    if (x < nx) out.push_back({y, x, nx, 0});
  }
}

int label_runs(std::vector<PixelRun>& runs, Connectivity connectivity, UnionFind<int>& labels) {
  // UnionFind keeps the smallest label as the root, so every root is the first label created in its
  // component.
  labels.reset(1);  // provisional labels start at 1
  const int reach = connectivity == Connectivity::Eight ? 1 : 0;
  std::size_t prev_begin = 0, prev_end = 0;  // the runs of the row above the current one
  for (std::size_t i = 0; i < runs.size();) {
    const int y = runs[i].y;
    if (prev_end > prev_begin && runs[prev_begin].y != y - 1) prev_begin = prev_end;  // a row without runs
    const std::size_t row_begin = i;
    std::size_t j = prev_begin;  // first run above that may touch the current run
    for (; i < runs.size() && runs[i].y == y; ++i) {
      // Runs above touching [x0 - reach, x1 + reach).
      const int lo = runs[i].x0 - reach, hi = runs[i].x1 + reach;
      while (j < prev_end && runs[j].x1 <= lo) ++j;
      int label = 0;
      for (std::size_t k = j; k < prev_end && runs[k].x0 < hi; ++k) {
        label = label == 0 ? labels.find(runs[k].label) : labels.unite(label, runs[k].label);
      }
      if (label == 0) label = labels.add();
      runs[i].label = label;
    }
    prev_begin = row_begin;
    prev_end = i;
  }
  // Final labels: the roots in creation order, which is the raster order of the first pixels. Labels
  // of the row above were stored before later unions: resolve every run through its root.
  std::vector<int> final_label(labels.size(), 0);
  int count = 0;
  for (std::size_t l = 1; l < labels.size(); ++l) {
    const int root = labels.find(static_cast<int>(l));
    final_label[l] = root == static_cast<int>(l) ? ++count : final_label[root];
  }
  for (PixelRun& r : runs) r.label = final_label[r.label];
  return count;
}

void keep_largest_component(std::vector<std::uint8_t>& mask, int nx, int ny, int nz) {
  const std::size_t slice = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  // Every run of the volume, slice by slice (runs are numbered in raster order), and where each row's
  // runs start.
  std::vector<PixelRun> runs, slice_runs;
  std::vector<std::size_t> row_begin(static_cast<std::size_t>(nz) * ny + 1, 0);
  for (int z = 0; z < nz; ++z) {
    find_runs(mask.data() + static_cast<std::size_t>(z) * slice, nx, ny, slice_runs);
    for (const PixelRun& r : slice_runs) {
      ++row_begin[static_cast<std::size_t>(z) * ny + r.y + 1];
      runs.push_back(r);
    }
  }
  for (std::size_t k = 1; k < row_begin.size(); ++k) row_begin[k] += row_begin[k - 1];
  UnionFind<int> components(runs.size());
  // Joins the overlapping runs of two rows (6-connectivity: runs share an edge when their x ranges
  // overlap).
  auto join_rows = [&](std::size_t a, std::size_t b) {
    std::size_t i = row_begin[a], j = row_begin[b];
    while (i < row_begin[a + 1] && j < row_begin[b + 1]) {
      if (runs[i].x0 < runs[j].x1 && runs[j].x0 < runs[i].x1)
        components.unite(static_cast<int>(i), static_cast<int>(j));
      if (runs[i].x1 < runs[j].x1) ++i;
      else ++j;
    }
  };
  for (int z = 0; z < nz; ++z) {
    for (int y = 0; y < ny; ++y) {
      const std::size_t row = static_cast<std::size_t>(z) * ny + y;
      if (y > 0) join_rows(row, row - 1);
      if (z > 0) join_rows(row, row - ny);
    }
  }
  // The largest component; its root is its first run (unite keeps the smaller index), so the first
  // root of the largest size is the first component in raster order.
  std::vector<std::size_t> size(runs.size(), 0);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    size[components.find(static_cast<int>(k))] += static_cast<std::size_t>(runs[k].x1 - runs[k].x0);
  }
  std::size_t best = runs.size();
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (size[k] > 0 && (best == runs.size() || size[k] > size[best])) best = k;
  }
  std::fill(mask.begin(), mask.end(), std::uint8_t{0});
  if (best == runs.size()) return;
  for (int z = 0, k = 0; z < nz; ++z) {
    for (int y = 0; y < ny; ++y) {
      const std::size_t row = static_cast<std::size_t>(z) * ny + y;
      for (; static_cast<std::size_t>(k) < row_begin[row + 1]; ++k) {
        if (components.find(k) != static_cast<int>(best)) continue;
        std::fill_n(mask.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(z) * slice +
                                                              static_cast<std::size_t>(y) * nx + runs[k].x0),
                    runs[k].x1 - runs[k].x0, std::uint8_t{1});
      }
    }
  }
}

}  // namespace contourmesh::detail
