// SPDX-License-Identifier: BSD-3-Clause
// The contour edges of every slice in a 2-D bucket grid, for cuts of a plane with the contours of a
// slice found by geometry alone: where the mesh's connectivity does not lead from one slice to the
// next (branchings and caps join contours through vertices off the slices).
#pragma once

#include "contourmesh/smooth/contour_structure.h"
#include "contourmesh/smooth/mesh.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace contourmesh::detail {

/// Where a plane crosses a contour edge.
struct EdgeCut {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Index a = -1, b = -1;  ///< the edge's ends
};

class SliceEdgeGrid {
 public:
  SliceEdgeGrid() = default;
  /// Indexes the edges between contour neighbours of the same slice (both ends flagged in
  /// `on_contour`), in buckets of `cell` (input units) in the slice planes (normal `axis`).
  SliceEdgeGrid(const Mesh& mesh, const ContourNeighbours& contour, const std::vector<std::uint8_t>& on_contour,
                const Eigen::Vector3d& axis, double cell);

  /// Of the edges of slice `slice` (on `positions`) crossing the plane through `origin` with normal
  /// `plane_normal`, whose ends' normals face `facing` (positive dot product of their sum), the crossing
  /// nearest to `near` in the slice plane, if within `radius`.
  [[nodiscard]] bool cut(std::int32_t slice, const Eigen::Matrix3Xd& positions, const Eigen::Matrix3Xd& normals,
                         const Eigen::Vector3d& origin, const Eigen::Vector3d& plane_normal,
                         const Eigen::Vector3d& near, const Eigen::Vector3d& facing, double radius, EdgeCut& out) const;

 private:
  // A slice's grid stores its non-empty cells only: a contour touches a few hundred of the tens of
  // thousands of cells of its slice's box (a dense CSR was hundreds of MB at a million vertices).
  struct Slice {
    double u0 = 0.0, v0 = 0.0;
    std::int64_t nu = 0, nv = 0;
    std::vector<std::int64_t> cells;  // ids (v * nu + u) of the non-empty cells, increasing
    std::vector<Index> start;         // CSR over `cells`: cell k's edges are edges[start[k], start[k + 1])
    std::vector<Index> edges;         // index into edge_a_ / edge_b_, increasing within a cell
  };
  Eigen::Vector3d e1_ = Eigen::Vector3d::UnitX(), e2_ = Eigen::Vector3d::UnitY();
  double cell_ = 1.0;
  std::int32_t first_slice_ = 0;
  std::vector<Slice> slices_;
  std::vector<Index> edge_a_, edge_b_;
};

}  // namespace contourmesh::detail
