// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/mesh_quality.h>
#include <contourmesh/smooth/shapes.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace contourmesh {
namespace {

using std::numbers::pi;

TEST(MeshQuality, MinimumAngleOfKnownTriangles) {
  const Eigen::Vector3d o(1, 2, 3);
  EXPECT_NEAR(minimum_angle_degrees(o, o + Eigen::Vector3d(1, 0, 0), o + Eigen::Vector3d(0.5, std::sqrt(3.0) / 2, 0)),
              60.0, 1e-9);
  EXPECT_NEAR(minimum_angle_degrees(o, o + Eigen::Vector3d(1, 0, 0), o + Eigen::Vector3d(0, 1, 0)), 45.0, 1e-9);
  // A right triangle with legs 1 and tan(5 degrees): its smallest angle is 5 degrees.
  EXPECT_NEAR(
      minimum_angle_degrees(o, o + Eigen::Vector3d(0, 0, 1), o + Eigen::Vector3d(std::tan(5 * pi / 180), 0, 1)), 5.0,
      1e-9);
  EXPECT_EQ(minimum_angle_degrees(o, o, o + Eigen::Vector3d(1, 0, 0)), 0.0);
  EXPECT_EQ(minimum_angle_degrees(o, o + Eigen::Vector3d(1, 0, 0), o + Eigen::Vector3d(2, 0, 0)), 0.0);
}

// Two triangles: a unit right isosceles one (area 0.5, 45 degrees) and a thin one of area 1.5 whose
// smallest angle is below 10 degrees.
Mesh good_and_thin() {
  Mesh m;
  m.positions.resize(3, 6);
  m.positions.col(0) << 0, 0, 0;
  m.positions.col(1) << 1, 0, 0;
  m.positions.col(2) << 0, 1, 0;
  m.positions.col(3) << 10, 0, 0;
  m.positions.col(4) << 40, 0, 0;
  m.positions.col(5) << 25, 0.1, 0;  // base 30, height 0.1: angles of atan(0.1 / 15)
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  return m;
}

TEST(MeshQuality, SliverShareIsTheAreaOfThinFacesOverTheTotal) {
  const Mesh m = good_and_thin();
  EXPECT_NEAR(sliver_area_share(m, 10.0), 1.5 / 2.0, 1e-12);
  EXPECT_NEAR(sliver_area_share(m, 0.1), 0.0, 1e-12);  // the thin face's angles are 0.38 degrees
  EXPECT_NEAR(sliver_area_share(m, 50.0), 1.0, 1e-12);
  EXPECT_EQ(sliver_area_share(make_cube(4)), 0.0);  // right isosceles faces: 45 degrees
  EXPECT_EQ(sliver_area_share(Mesh{}), 0.0);
  EXPECT_THROW((void)sliver_area_share(m, 61.0), InvalidInputError);
  Mesh bad = m;
  bad.triangles.push_back({0, 1, 9});
  EXPECT_THROW((void)sliver_area_share(bad), InvalidInputError);
}

TEST(MeshQuality, AreaFacingTheAxisCountsFacesParallelToTheSlices) {
  // A cube of edge 2: its top and bottom (area 4 each) face +-z, the sides face x and y.
  const Mesh cube = make_cube(3, 1.0);
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(area_facing_axis(cube.positions, cube.triangles, z, 10.0), 8.0, 1e-9);
  EXPECT_NEAR(area_facing_axis(cube.positions, cube.triangles, 5.0 * z, 10.0), 8.0, 1e-9);  // any length
  // Skipping the faces above z = 0.99 leaves the bottom.
  std::vector<std::uint8_t> skip(cube.triangles.size(), 0);
  for (std::size_t f = 0; f < cube.triangles.size(); ++f) {
    bool top = true;
    for (Index v : cube.triangles[f]) top = top && cube.positions(2, v) > 0.99;
    skip[f] = top ? 1 : 0;
  }
  EXPECT_NEAR(area_facing_axis(cube.positions, cube.triangles, z, 10.0, skip), 4.0, 1e-9);
  // Tilted by 7 degrees about x, top and bottom are still within 10 degrees, not within 5.
  const Eigen::Vector3d tilted(0.0, std::sin(7 * pi / 180), std::cos(7 * pi / 180));
  EXPECT_NEAR(area_facing_axis(cube.positions, cube.triangles, tilted, 10.0), 8.0, 1e-9);
  EXPECT_NEAR(area_facing_axis(cube.positions, cube.triangles, tilted, 5.0), 0.0, 1e-9);
  EXPECT_THROW((void)area_facing_axis(cube.positions, cube.triangles, Eigen::Vector3d::Zero(), 10.0),
               InvalidInputError);
  EXPECT_THROW((void)area_facing_axis(cube.positions, cube.triangles, z, 10.0, std::vector<std::uint8_t>(3, 0)),
               InvalidInputError);
}

TEST(MeshQuality, AreaFacingTheAxisOfASphereIsItsPolarCaps) {
  // Faces within a degrees of z on a unit sphere: two caps of area 2 pi (1 - cos a).
  const Mesh s = make_icosphere(6);
  const double a = 20.0;
  const double expected = 2.0 * 2.0 * pi * (1.0 - std::cos(a * pi / 180));
  EXPECT_NEAR(area_facing_axis(s.positions, s.triangles, Eigen::Vector3d::UnitZ(), a) / expected, 1.0, 0.03);
}

// A roof of two unit squares (four triangles) meeting along a ridge: each half folded `turn` degrees from
// the plane, so the surface turns by 2 turn across the ridge. Area 4 x 0.5 = 2, all at the ridge.
Mesh roof(double turn_degrees) {
  const double h = std::sin(turn_degrees * pi / 360.0), w = std::cos(turn_degrees * pi / 360.0);
  Mesh m;
  m.positions.resize(3, 6);
  m.positions.col(0) << 0, 0, 0;  // the ridge: vertices 0 and 1
  m.positions.col(1) << 0, 1, 0;
  m.positions.col(2) << -w, 0, -h;
  m.positions.col(3) << -w, 1, -h;
  m.positions.col(4) << w, 0, -h;
  m.positions.col(5) << w, 1, -h;
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {0, 1, 5}, {0, 5, 4}};
  return m;
}

TEST(MeshQuality, FoldShareIsTheAreaOfFacesAtSharpTurns) {
  // Across the ridge the surface turns by 2 x 70 = 140 degrees: the two faces at the ridge's edge fold (the
  // diagonals inside each half are flat); at 2 x 50 = 100 degrees nothing does.
  const Mesh sharp = roof(140.0), blunt = roof(100.0);
  EXPECT_NEAR(fold_area_share(sharp.positions, sharp.triangles), 0.5, 1e-12);
  EXPECT_EQ(fold_area_share(blunt.positions, blunt.triangles), 0.0);
  EXPECT_NEAR(fold_area_share(blunt.positions, blunt.triangles, 90.0), 0.5, 1e-12);
  // A cube turns by 90 degrees at its edges, a fine sphere by almost nothing.
  const Mesh cube = make_cube(3, 1.0), sphere = make_icosphere(3);
  EXPECT_EQ(fold_area_share(cube.positions, cube.triangles), 0.0);
  const double edges = fold_area_share(cube.positions, cube.triangles, 89.0);  // the faces along the cube's edges
  EXPECT_GT(edges, 0.2);
  EXPECT_LT(edges, 0.8);
  EXPECT_EQ(fold_area_share(sphere.positions, sphere.triangles, 30.0), 0.0);
  EXPECT_EQ(fold_area_share(Eigen::Matrix3Xd(3, 0), {}), 0.0);
  EXPECT_THROW((void)fold_area_share(cube.positions, cube.triangles, 181.0), InvalidInputError);
  std::vector<Triangle> bad = cube.triangles;
  bad.push_back({0, 1, 999});
  EXPECT_THROW((void)fold_area_share(cube.positions, bad), InvalidInputError);
}

TEST(MeshQuality, ShareWithoutIds) {
  Mesh m = good_and_thin();
  EXPECT_EQ(share_without_ids(m), 1.0);  // no ids at all
  m.slice_ids = {0, 0, kNoId, 1, kNoId, kNoId};
  m.contour_ids = {0, 0, kNoId, 0, kNoId, kNoId};
  EXPECT_NEAR(share_without_ids(m), 0.5, 1e-12);
  EXPECT_EQ(share_without_ids(Mesh{}), 0.0);
}

TEST(MeshQuality, SummaryAgreesWithTheSingleMeasures) {
  Mesh m = good_and_thin();
  m.slice_ids = {0, 0, 0, kNoId, kNoId, kNoId};
  m.contour_ids = m.slice_ids;
  const std::vector<std::uint8_t> skip = {0, 1};
  const MeshQuality q = mesh_quality(m, {}, skip);
  EXPECT_NEAR(q.area, 2.0, 1e-12);
  EXPECT_NEAR(q.sliver_area_share, sliver_area_share(m), 1e-12);
  EXPECT_NEAR(q.min_angle_degrees, std::atan(0.1 / 15) * 180 / pi, 1e-9);
  EXPECT_NEAR(q.shelf_area, 0.5, 1e-12);  // both faces lie in z = 0; the thin one is skipped
  EXPECT_NEAR(q.shelf_area_share, 0.25, 1e-12);
  EXPECT_NEAR(q.share_without_ids, 0.5, 1e-12);
  MeshQualityOptions sideways;
  sideways.slice_axis = Eigen::Vector3d::UnitX();
  EXPECT_EQ(mesh_quality(m, sideways).shelf_area, 0.0);
}

}  // namespace
}  // namespace contourmesh
