// SPDX-License-Identifier: BSD-3-Clause
// Small helpers shared by the libsmooth tests.
#pragma once

#include <contourmesh/smooth/mesh.h>
#include <contourmesh/smooth/shapes.h>

#include <cmath>

namespace contourmesh::test {

/// A regular hexagonal fan in the plane z = 0: centre vertex 0 and six neighbours at distance r.
inline Mesh hexagon_fan(double r = 1.0) {
  Mesh m;
  m.positions.resize(3, 7);
  m.positions.col(0).setZero();
  for (int k = 0; k < 6; ++k) {
    const double a = k * M_PI / 3.0;
    m.positions.col(k + 1) << r * std::cos(a), r * std::sin(a), 0.0;
  }
  for (int k = 0; k < 6; ++k) m.triangles.push_back({0, k + 1, (k + 1) % 6 + 1});
  return m;
}

/// A tetrahedron, the smallest closed manifold mesh (outward oriented).
inline Mesh tetrahedron() {
  Mesh m;
  m.positions.resize(3, 4);
  m.positions << 0, 1, 0, 0,  //
      0, 0, 1, 0,             //
      0, 0, 0, 1;
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

/// The contour-stack spec of a circular cylinder of `radius` mm: `slices` contours of 90 points,
/// 2 mm apart (make_contour_stack caps both ends).
inline ContourStackSpec cylinder_spec(double radius, int slices) {
  ContourStackSpec spec;
  spec.curve = [radius](double t) {
    return Eigen::Vector2d(radius * std::cos(2 * M_PI * t), radius * std::sin(2 * M_PI * t));
  };
  spec.slices = slices;
  spec.points_per_contour = 90;
  spec.slice_spacing = 2.0;
  return spec;
}

}  // namespace contourmesh::test
