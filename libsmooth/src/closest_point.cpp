// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/closest_point.h"

#include "detail/bucket_grid.h"
#include "contourmesh/smooth/errors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace contourmesh {

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c) {
  // Voronoi regions of the vertices, edges and face (Ericson, Real-Time Collision Detection, 5.1.5).
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double denom = d1 - d3;
    return denom > 0.0 ? Eigen::Vector3d(a + (d1 / denom) * ab) : a;
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double denom = d2 - d6;
    return denom > 0.0 ? Eigen::Vector3d(a + (d2 / denom) * ac) : a;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double denom = (d4 - d3) + (d5 - d6);
    return denom > 0.0 ? Eigen::Vector3d(b + ((d4 - d3) / denom) * (c - b)) : b;
  }
  const double sum = va + vb + vc;
  if (!(std::abs(sum) > 0.0)) {
    // Degenerate (collinear) triangle that fell through: the nearest of its three edges.
    Eigen::Vector3d best = a;
    for (const auto& [s, t] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
      const Eigen::Vector3d e = t - s;
      const double len2 = e.squaredNorm();
      const double u = len2 > 0.0 ? std::clamp((p - s).dot(e) / len2, 0.0, 1.0) : 0.0;
      const Eigen::Vector3d q = s + u * e;
      if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
    }
    return best;
  }
  const double v = vb / sum, w = vc / sum;
  return a + v * ab + w * ac;
}

namespace {

// Counts, then fills, the items of each cell (an item may lie in several cells).
template <typename CellsOf>
void fill_csr(std::int64_t cells, std::size_t items, const CellsOf& cells_of, std::vector<std::int64_t>& start,
              std::vector<Index>& out) {
  start.assign(static_cast<std::size_t>(cells) + 1, 0);
  for (std::size_t i = 0; i < items; ++i) {
    cells_of(i, [&](std::int64_t c) { ++start[static_cast<std::size_t>(c) + 1]; });
  }
  for (std::size_t c = 0; c < static_cast<std::size_t>(cells); ++c) start[c + 1] += start[c];
  out.resize(static_cast<std::size_t>(start.back()));
  std::vector<std::int64_t> next(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < items; ++i) {
    cells_of(i, [&](std::int64_t c) {
      out[static_cast<std::size_t>(next[static_cast<std::size_t>(c)]++)] = static_cast<Index>(i);
    });
  }
}

detail::BucketGrid make_grid(const Eigen::Vector3d& origin, double cell, const std::array<std::int64_t, 3>& dims) {
  detail::BucketGrid g;
  g.origin = origin;
  g.cell = cell;
  g.dims = dims;
  return g;
}

// Visits shells around p until `best` (a distance) cannot improve; `visit_cell(x, y, z)` updates best.
template <typename VisitCell>
void search(const detail::BucketGrid& grid, const Eigen::Vector3d& p, const double& best, VisitCell&& visit_cell) {
  const auto c = grid.cell_of(p);
  const double outside = grid.distance_to_box(p);
  for (std::int64_t r = 0; r <= grid.max_shell(); ++r) {
    grid.shell(c, r, visit_cell);
    // Every cell not yet visited is at least r cells away from p's (clamped) cell.
    const double bound = std::hypot(outside, static_cast<double>(r) * grid.cell);
    if (best <= bound) break;
  }
}

}  // namespace

TriangleLocator::TriangleLocator(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles) {
  const Index n = static_cast<Index>(positions.cols());
  corners_.resize(triangles.size() * 9);
  boxes_.resize(triangles.size() * 6);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  double area = 0.0;
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Index v = triangles[f][static_cast<std::size_t>(k)];
      if (v < 0 || v >= n) {
        throw InvalidInputError("closest point: face " + std::to_string(f) + " names vertex " + std::to_string(v) +
                                " of " + std::to_string(n));
      }
      const Eigen::Vector3d q = positions.col(v);
      if (!q.allFinite()) {
        throw InvalidInputError("closest point: vertex " + std::to_string(v) + " is not finite");
      }
      for (int a = 0; a < 3; ++a) corners_[f * 9 + static_cast<std::size_t>(3 * k + a)] = q[a];
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    const Eigen::Map<const Eigen::Vector3d> a(&corners_[f * 9]), b(&corners_[f * 9 + 3]), c(&corners_[f * 9 + 6]);
    area += 0.5 * (b - a).cross(c - a).norm();
    Eigen::Map<Eigen::Vector3d> box_lo(&boxes_[f * 6]), box_hi(&boxes_[f * 6 + 3]);
    box_lo = a.cwiseMin(b).cwiseMin(c);
    box_hi = a.cwiseMax(b).cwiseMax(c);
  }
  if (triangles.empty()) return;
  // Cells about twice the typical edge: a face touches few cells, a cell holds few faces.
  const double edge = std::sqrt(2.0 * area / static_cast<double>(triangles.size()));
  const double target = 4.0 * static_cast<double>(triangles.size());
  const detail::BucketGrid grid = detail::BucketGrid::over(lo, hi, target, 2.0 * edge);
  origin_ = grid.origin;
  cell_ = grid.cell;
  dims_ = grid.dims;
  fill_csr(grid.count(), triangles.size(),
           [&](std::size_t f, auto&& emit) {
             const Eigen::Map<const Eigen::Vector3d> a(&corners_[f * 9]), b(&corners_[f * 9 + 3]),
                 c(&corners_[f * 9 + 6]);
             const auto c0 = grid.cell_of(a.cwiseMin(b).cwiseMin(c));
             const auto c1 = grid.cell_of(a.cwiseMax(b).cwiseMax(c));
             for (std::int64_t z = c0[2]; z <= c1[2]; ++z) {
               for (std::int64_t y = c0[1]; y <= c1[1]; ++y) {
                 for (std::int64_t x = c0[0]; x <= c1[0]; ++x) emit(grid.index(x, y, z));
               }
             }
           },
           start_, faces_);
}

ClosestPoint TriangleLocator::closest(const Eigen::Vector3d& p) const {
  ClosestPoint best;
  best.distance = std::numeric_limits<double>::infinity();
  if (corners_.empty()) return best;
  const detail::BucketGrid grid = make_grid(origin_, cell_, dims_);
  double best2 = std::numeric_limits<double>::infinity();
  search(grid, p, best.distance, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    // A cell no nearer than the best so far holds nothing nearer (a cell holds a dozen faces or more).
    if (grid.distance2_to_cell(p, x, y, z) >= best2) return;
    const std::int64_t cell = grid.index(x, y, z);
    for (std::int64_t k = start_[static_cast<std::size_t>(cell)]; k < start_[static_cast<std::size_t>(cell) + 1]; ++k) {
      const Index f = faces_[static_cast<std::size_t>(k)];
      // The face's box first: most faces of a bucket are farther than the best so far (and a face that
      // spans several buckets is met again in each).
      const double* box = &boxes_[static_cast<std::size_t>(f) * 6];
      const Eigen::Map<const Eigen::Vector3d> box_lo(box), box_hi(box + 3);
      if (detail::squared_distance_to_box(p, box_lo, box_hi) >= best2) continue;
      const std::size_t o = static_cast<std::size_t>(f) * 9;
      const Eigen::Map<const Eigen::Vector3d> a(&corners_[o]), b(&corners_[o + 3]), c(&corners_[o + 6]);
      const Eigen::Vector3d q = closest_point_on_triangle(p, a, b, c);
      const double d2 = (q - p).squaredNorm();
      if (d2 < best2) {
        best2 = d2;
        best.distance = std::sqrt(d2);
        best.face = f;
        best.point = q;
      }
    }
  });
  return best;
}

PointLocator::PointLocator(const Eigen::Matrix3Xd& points) {
  if (points.cols() == 0) return;
  if (!points.allFinite()) throw InvalidInputError("point locator: a point is not finite");
  const Eigen::Vector3d lo = points.rowwise().minCoeff(), hi = points.rowwise().maxCoeff();
  const detail::BucketGrid grid = detail::BucketGrid::over(lo, hi, 2.0 * static_cast<double>(points.cols()), 1e-9);
  origin_ = grid.origin;
  cell_ = grid.cell;
  dims_ = grid.dims;
  std::vector<Index> order;
  fill_csr(grid.count(), static_cast<std::size_t>(points.cols()),
           [&](std::size_t i, auto&& emit) { emit([&] {
             const auto c = grid.cell_of(points.col(static_cast<Index>(i)));
             return grid.index(c[0], c[1], c[2]);
           }()); },
           start_, order);
  points_.resize(3, points.cols());
  for (std::size_t k = 0; k < order.size(); ++k) points_.col(static_cast<Index>(k)) = points.col(order[k]);
}

double PointLocator::distance(const Eigen::Vector3d& p) const {
  double best = std::numeric_limits<double>::infinity();
  if (points_.cols() == 0) return best;
  const detail::BucketGrid grid = make_grid(origin_, cell_, dims_);
  double best2 = best;
  search(grid, p, best, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    const std::int64_t cell = grid.index(x, y, z);
    for (std::int64_t k = start_[static_cast<std::size_t>(cell)]; k < start_[static_cast<std::size_t>(cell) + 1]; ++k) {
      const double d2 = (points_.col(static_cast<Index>(k)) - p).squaredNorm();
      if (d2 < best2) {
        best2 = d2;
        best = std::sqrt(d2);
      }
    }
  });
  return best;
}

}  // namespace contourmesh
