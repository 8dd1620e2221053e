// SPDX-License-Identifier: BSD-3-Clause
#include "detail/slice_edge_grid.h"

#include "contourmesh/internal/huge_pages.h"
#include "detail/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace contourmesh::detail {

SliceEdgeGrid::SliceEdgeGrid(const Mesh& mesh, const ContourNeighbours& contour,
                             const std::vector<std::uint8_t>& on_contour, const Eigen::Vector3d& axis, double cell)
    : cell_(std::max(cell, 1e-9)) {
  e1_ = axis.unitOrthogonal();
  e2_ = axis.cross(e1_);
  const Index n = mesh.num_vertices();
  std::int32_t lo = std::numeric_limits<std::int32_t>::max(), hi = std::numeric_limits<std::int32_t>::min();
  // At most one edge per contour vertex (each joins it to the next one along its contour).
  const auto on = static_cast<std::size_t>(std::count(on_contour.begin(), on_contour.end(), std::uint8_t{1}));
  reserve_huge(edge_a_, on);
  reserve_huge(edge_b_, on);
  for (Index i = 0; i < n; ++i) {
    if (!on_contour[static_cast<std::size_t>(i)]) continue;
    for (Index j : contour.of[static_cast<std::size_t>(i)]) {
      if (j > i && on_contour[static_cast<std::size_t>(j)] &&
          mesh.slice_ids[static_cast<std::size_t>(j)] == mesh.slice_ids[static_cast<std::size_t>(i)]) {
        edge_a_.push_back(i);
        edge_b_.push_back(j);
        lo = std::min(lo, mesh.slice_ids[static_cast<std::size_t>(i)]);
        hi = std::max(hi, mesh.slice_ids[static_cast<std::size_t>(i)]);
      }
    }
  }
  if (edge_a_.empty()) return;
  first_slice_ = lo;
  slices_.resize(static_cast<std::size_t>(hi - lo + 1));
  const auto uv = [&](Index v) {
    return Eigen::Vector2d(mesh.positions.col(v).dot(e1_), mesh.positions.col(v).dot(e2_));
  };
  // Bounds per slice, then each slice's edges (in increasing index), then per slice the cells every
  // edge's box touches, counted in a dense scratch array that is reused from slice to slice, and the
  // non-empty ones kept as a CSR (an edge goes into every cell its box touches).
  std::vector<Eigen::AlignedBox2d> bounds(slices_.size());
  std::vector<Index> slice_start(slices_.size() + 1, 0);
  const auto slice_of = [&](std::size_t e) {
    return static_cast<std::size_t>(mesh.slice_ids[static_cast<std::size_t>(edge_a_[e])] - lo);
  };
  for (std::size_t e = 0; e < edge_a_.size(); ++e) {
    const std::size_t s = slice_of(e);
    bounds[s].extend(uv(edge_a_[e]));
    bounds[s].extend(uv(edge_b_[e]));
    ++slice_start[s + 1];
  }
  for (std::size_t s = 0; s < slices_.size(); ++s) slice_start[s + 1] += slice_start[s];
  std::vector<Index> by_slice;
  resize_huge(by_slice, edge_a_.size());
  {
    std::vector<Index> fill(slice_start.begin(), slice_start.end() - 1);
    for (std::size_t e = 0; e < edge_a_.size(); ++e) {
      by_slice[static_cast<std::size_t>(fill[slice_of(e)]++)] = static_cast<Index>(e);
    }
  }
  // The slices are independent: a few at a time on every core, each chunk with its own count scratch.
  parallel_chunks(slices_.size(), 4, [&](std::size_t, std::size_t chunk_begin, std::size_t chunk_end) {
    std::vector<Index> count;  // per cell of the current slice: edges, then the next free slot
    for (std::size_t s = chunk_begin; s < chunk_end; ++s) {
      Slice& sl = slices_[s];
      if (bounds[s].isEmpty()) continue;
      sl.u0 = bounds[s].min().x();
      sl.v0 = bounds[s].min().y();
      sl.nu = static_cast<std::int64_t>(std::floor(bounds[s].sizes().x() / cell_)) + 1;
      sl.nv = static_cast<std::int64_t>(std::floor(bounds[s].sizes().y() / cell_)) + 1;
      const auto cells_of = [&](std::size_t e, auto&& visit) {
        const Eigen::Vector2d a = uv(edge_a_[e]), b = uv(edge_b_[e]);
        const auto cu = [&](double u) {
          return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((u - sl.u0) / cell_)), 0, sl.nu - 1);
        };
        const auto cv = [&](double v) {
          return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((v - sl.v0) / cell_)), 0, sl.nv - 1);
        };
        for (std::int64_t y = cv(std::min(a.y(), b.y())); y <= cv(std::max(a.y(), b.y())); ++y) {
          for (std::int64_t x = cu(std::min(a.x(), b.x())); x <= cu(std::max(a.x(), b.x())); ++x) {
            visit(static_cast<std::size_t>(y * sl.nu + x));
          }
        }
      };
      const auto first = static_cast<std::size_t>(slice_start[s]), last = static_cast<std::size_t>(slice_start[s + 1]);
      count.assign(static_cast<std::size_t>(sl.nu * sl.nv), 0);
      Index total = 0;
      for (std::size_t k = first; k < last; ++k) {
        cells_of(static_cast<std::size_t>(by_slice[k]), [&](std::size_t c) {
          ++count[c];
          ++total;
        });
      }
      sl.start.push_back(0);
      for (std::size_t c = 0; c < count.size(); ++c) {
        if (count[c] == 0) continue;
        const Index begin = sl.start.back();
        sl.cells.push_back(static_cast<std::int64_t>(c));
        sl.start.push_back(begin + count[c]);
        count[c] = begin;
      }
      sl.edges.resize(static_cast<std::size_t>(total));
      for (std::size_t k = first; k < last; ++k) {
        cells_of(static_cast<std::size_t>(by_slice[k]),
                 [&](std::size_t c) { sl.edges[static_cast<std::size_t>(count[c]++)] = by_slice[k]; });
      }
    }
  });
}

bool SliceEdgeGrid::cut(std::int32_t slice, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& normals,
                        const Eigen::Vector3d& origin, const Eigen::Vector3d& plane_normal, const Eigen::Vector3d& near,
                        const Eigen::Vector3d& facing, double radius, EdgeCut& out) const {
  const std::int64_t s = static_cast<std::int64_t>(slice) - first_slice_;
  if (s < 0 || s >= static_cast<std::int64_t>(slices_.size())) return false;
  const Slice& sl = slices_[static_cast<std::size_t>(s)];
  if (sl.nu == 0) return false;
  // The plane contains the slice axis, so it meets the slice in a line L, and `near` (a point of the
  // plane) projects onto L. A crossing lies on L, in the cell that holds it (every edge is listed in
  // each cell its box touches): walk the cells L passes through, outwards from `near` both ways.
  const Eigen::Vector2d q(near.dot(e1_) - sl.u0, near.dot(e2_) - sl.v0);
  Eigen::Vector2d dir(plane_normal.dot(e2_), -plane_normal.dot(e1_));  // L's direction in the slice plane
  if (!(dir.norm() > 0.0)) return false;
  dir.normalize();
  double best = radius;
  bool found = false;
  const auto test_cell = [&](std::int64_t cu, std::int64_t cv) {
    if (cu < 0 || cv < 0 || cu >= sl.nu || cv >= sl.nv) return;
    const auto cell = std::lower_bound(sl.cells.begin(), sl.cells.end(), cv * sl.nu + cu);
    if (cell == sl.cells.end() || *cell != cv * sl.nu + cu) return;
    const auto c = static_cast<std::size_t>(cell - sl.cells.begin());
    for (Index k = sl.start[c]; k < sl.start[c + 1]; ++k) {
      const Index e = sl.edges[static_cast<std::size_t>(k)];
      const Index a = edge_a_[static_cast<std::size_t>(e)], b = edge_b_[static_cast<std::size_t>(e)];
      const double sa = (x.col(a) - origin).dot(plane_normal), sb = (x.col(b) - origin).dot(plane_normal);
      if ((sa <= 0.0) == (sb <= 0.0)) continue;
      if ((normals.col(a) + normals.col(b)).dot(facing) <= 0.0) continue;
      const Eigen::Vector3d p = x.col(a) + (sa / (sa - sb)) * (x.col(b) - x.col(a));
      const double du = p.dot(e1_) - sl.u0 - q.x(), dv = p.dot(e2_) - sl.v0 - q.y();
      const double d2 = du * du + dv * dv;
      if (d2 < best * best) {
        best = std::sqrt(d2);
        out.point = p;
        out.a = a;
        out.b = b;
        found = true;
      }
    }
  };
  // Amanatides-Woo traversal from q along +dir and -dir up to `best`.
  for (const double sign : {1.0, -1.0}) {
    const Eigen::Vector2d d = sign * dir;
    std::int64_t cu = static_cast<std::int64_t>(std::floor(q.x() / cell_));
    std::int64_t cv = static_cast<std::int64_t>(std::floor(q.y() / cell_));
    const std::int64_t step_u = d.x() >= 0.0 ? 1 : -1, step_v = d.y() >= 0.0 ? 1 : -1;
    const double inf = std::numeric_limits<double>::infinity();
    const double delta_u = d.x() != 0.0 ? cell_ / std::abs(d.x()) : inf;
    const double delta_v = d.y() != 0.0 ? cell_ / std::abs(d.y()) : inf;
    double next_u = d.x() != 0.0 ? ((static_cast<double>(cu) + (step_u > 0 ? 1.0 : 0.0)) * cell_ - q.x()) / d.x() : inf;
    double next_v = d.y() != 0.0 ? ((static_cast<double>(cv) + (step_v > 0 ? 1.0 : 0.0)) * cell_ - q.y()) / d.y() : inf;
    double travelled = 0.0;
    for (int guard = 0; guard < 100000; ++guard) {
      test_cell(cu, cv);
      // Anything in later cells lies at least `travelled` from q along L.
      if (travelled > best) break;
      if (next_u < next_v) {
        travelled = next_u;
        next_u += delta_u;
        cu += step_u;
      } else {
        travelled = next_v;
        next_v += delta_v;
        cv += step_v;
      }
      if (travelled > best) break;
    }
  }
  return found;
}

}  // namespace contourmesh::detail
