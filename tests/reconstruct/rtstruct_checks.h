// SPDX-License-Identifier: BSD-3-Clause
// The checks every ROI with contours must pass: a closed, manifold, outward-oriented mesh, its volume
// within 5 % of the slice-wise volume, and its unsmoothed cross-section with every slice plane within
// 0.1 mm of the drawn contours.
#pragma once

#include <contourmesh/reconstruct/contour_deviation.h>
#include <contourmesh/reconstruct/contour_reconstruction.h>
#include <contourmesh/reconstruct/rtstruct.h>
#include <contourmesh/smooth/metrics.h>
#include <contourmesh/smooth/topology.h>

#include <gtest/gtest.h>

#include "reconstruct/mesh_checks.h"

namespace contourmesh::test {

/// Whether `p` is inside the surface formed by the triangles of components other than `skip`: the
/// parity of their crossings with a ray from `p` in a fixed generic direction.
inline bool inside_other_components(const Mesh& mesh, const ComponentLabels& labels, Index skip,
                                    const Eigen::Vector3d& p) {
  const Eigen::Vector3d dir = Eigen::Vector3d(0.5773, 0.6123, 0.5402).normalized();
  int crossings = 0;
  for (const Triangle& f : mesh.triangles) {
    if (labels.of_vertex[f[0]] == skip) continue;
    const Eigen::Vector3d a = mesh.positions.col(f[0]), b = mesh.positions.col(f[1]), c = mesh.positions.col(f[2]);
    const Eigen::Vector3d e1 = b - a, e2 = c - a, h = dir.cross(e2);
    const double det = e1.dot(h);
    if (std::abs(det) < 1e-14) continue;
    const Eigen::Vector3d s = p - a;
    const double u = s.dot(h) / det;
    if (u < 0.0 || u > 1.0) continue;
    const Eigen::Vector3d q = s.cross(e1);
    const double v = dir.dot(q) / det;
    if (v < 0.0 || u + v > 1.0) continue;
    if (e2.dot(q) / det > 0.0) ++crossings;
  }
  return crossings % 2 == 1;
}

/// Outward orientation: every component encloses a positive volume, except cavities (negative volume,
/// inside another component).
inline void expect_outward(const Mesh& mesh) {
  const ComponentLabels labels = component_labels(mesh);
  std::vector<double> volume(static_cast<std::size_t>(labels.count), 0.0);
  std::vector<Index> some_vertex(static_cast<std::size_t>(labels.count), -1);
  for (const Triangle& f : mesh.triangles) {
    const Index c = labels.of_vertex[f[0]];
    volume[c] += mesh.positions.col(f[0]).dot(mesh.positions.col(f[1]).cross(mesh.positions.col(f[2]))) / 6.0;
    some_vertex[c] = f[0];
  }
  for (Index c = 0; c < labels.count; ++c) {
    if (volume[c] > 0.0) continue;
    EXPECT_TRUE(inside_other_components(mesh, labels, c, mesh.positions.col(some_vertex[c])))
        << "component " << c << " encloses " << volume[c] << " mm^3 and is not a cavity";
  }
}

inline void expect_roi_reconstructs(const RtRoi& roi) {
  SCOPED_TRACE(roi.label());
  const RoiStack drawn = roi_contour_stack(roi);
  const ContourReconstruction r = reconstruct_from_contours(drawn.planar.stack, roi.label());
  const Topology t = topology_of(r.mesh);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.manifold) << t.problems;
  expect_outward(r.mesh);
  const double v = enclosed_volume(r.mesh);
  EXPECT_NEAR(v / slicewise_volume(drawn.planar.stack), 1.0, 0.05)
      << v << " vs " << slicewise_volume(drawn.planar.stack);
  const ContourDeviation d = contour_deviation(r.mesh, drawn.planar.stack);
  EXPECT_LT(d.max, 0.1);
  EXPECT_EQ(d.slices, drawn.planar.stack.slices.size());
  EXPECT_EQ(d.slices_without_section, 0u);
}

}  // namespace contourmesh::test
