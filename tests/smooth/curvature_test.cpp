// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/curvature.h>
#include <contourmesh/smooth/shapes.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace contourmesh {
namespace {

TEST(Curvature, IcosphereCurvatureIsOneOverRadiusAndUmbilic) {
  const double r = 2.5;
  const Mesh s = make_icosphere(5, r);
  const PrincipalCurvatures c = principal_curvatures(s.positions, s.triangles, build_adjacency(s));
  for (Index i = 0; i < s.num_vertices(); ++i) {
    EXPECT_NEAR(c.kappa_min[i] * r, 1.0, 0.05) << i;
    EXPECT_NEAR(c.kappa_max[i] * r, 1.0, 0.05) << i;
    EXPECT_EQ(c.umbilic[i], 1) << i;
  }
}

// A closed cylinder of radius r along z as a fine contour stack (caps far from the tested band).
Mesh fine_cylinder(double r) {
  ContourStackSpec spec;
  spec.curve = [r](double t) {
    return Eigen::Vector2d(r * std::cos(2 * std::numbers::pi * t), r * std::sin(2 * std::numbers::pi * t));
  };
  spec.slices = 60;
  spec.points_per_contour = 120;
  spec.slice_spacing = 2 * std::numbers::pi * r / 120;  // square-ish quads
  spec.z0 = -30 * spec.slice_spacing;
  return make_contour_stack(spec);
}

TEST(Curvature, CylinderHasZeroAndOneOverRadiusWithMinimumAlongTheAxis) {
  const double r = 4.0;
  const Mesh m = fine_cylinder(r);
  const PrincipalCurvatures c = principal_curvatures(m.positions, m.triangles, build_adjacency(m));
  int tested = 0;
  for (Index i = 0; i < m.num_vertices(); ++i) {
    if (m.slice_ids[i] < 10 || m.slice_ids[i] > 49) continue;  // away from the caps
    ++tested;
    EXPECT_NEAR(c.kappa_min[i] * r, 0.0, 0.05) << i;
    EXPECT_NEAR(c.kappa_max[i] * r, 1.0, 0.05) << i;
    EXPECT_EQ(c.umbilic[i], 0);
    EXPECT_GT(std::abs(c.direction_min.col(i).z()), 0.99) << "minimum curvature runs along the axis";
    EXPECT_LT(std::abs(c.direction_max.col(i).z()), 0.1);
  }
  EXPECT_GT(tested, 4000);
}

TEST(Curvature, ScaleInvariantUmbilicsAndSignOfConcaveCrease) {
  Mesh m = fine_cylinder(4.0);
  const MeshAdjacency adj = build_adjacency(m);
  const PrincipalCurvatures a = principal_curvatures(m.positions, m.triangles, adj);
  m.positions *= 1e-6;
  const PrincipalCurvatures b = principal_curvatures(m.positions, m.triangles, adj);
  EXPECT_EQ(a.umbilic, b.umbilic);
  for (Index i = 0; i < m.num_vertices(); i += 97)
    EXPECT_NEAR(b.kappa_max[i] * 1e-6, a.kappa_max[i], 1e-9 * std::abs(a.kappa_max[i]) + 1e-12);
  // Turn the cylinder inside out: the curvature across becomes negative.
  for (Triangle& t : m.triangles) std::swap(t[1], t[2]);
  const PrincipalCurvatures inv = principal_curvatures(m.positions, m.triangles, adj);
  const Index probe = 30 * 120 + 5;
  EXPECT_NEAR(inv.kappa_min[probe] * 4e-6, -1.0, 0.05);
}

TEST(Curvature, DegenerateRingsGiveFiniteResults) {
  // Valence-3 corner vertices of a coarse cube fall back to the 2-ring; everything stays finite.
  const Mesh cube = make_cube(1);
  const PrincipalCurvatures c = principal_curvatures(cube.positions, cube.triangles, build_adjacency(cube));
  EXPECT_TRUE(c.kappa_min.allFinite());
  EXPECT_TRUE(c.kappa_max.allFinite());
  EXPECT_TRUE(c.direction_min.allFinite());
}

}  // namespace
}  // namespace contourmesh
