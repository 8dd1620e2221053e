// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/reconstruct/tiling.h>
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/mesh_quality.h>
#include <contourmesh/smooth/metrics.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <numbers>

#include "reconstruct/mesh_checks.h"

namespace contourmesh {
namespace {

Contour circle(double cx, double cy, double r, int n, bool hole = false, int parent = -1) {
  Contour c;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n;
    c.points.emplace_back(cx + r * std::cos(a), cy + r * std::sin(a));
  }
  if (hole) std::reverse(c.points.begin(), c.points.end());
  c.is_hole = hole;
  c.parent = parent;
  return c;
}

ContourStack stack_of(int slices, double spacing = 2.0) {
  ContourStack s;
  s.slices.resize(static_cast<std::size_t>(slices));
  for (int k = 0; k < slices; ++k) s.slices[k].w = k * spacing;
  return s;
}

void expect_sound(const Mesh& m, long euler, int components) {
  const test::Topology t = test::topology_of(m);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.manifold) << t.problems;
  EXPECT_EQ(t.euler, euler);
  EXPECT_EQ(t.components, components);
  EXPECT_GT(enclosed_volume(m), 0.0) << "outward orientation";
}

TEST(Tiling, CylinderIsClosedWithPrismVolumeAndIds) {
  ContourStack s = stack_of(8);
  for (auto& slice : s.slices) slice.contours.push_back(circle(0, 0, 10, 60));
  const double polygon_area = 0.5 * 60 * 100 * std::sin(2 * std::numbers::pi / 60);
  // Default: the ends extend half a spacing beyond the end slices (16 mm of prism).
  const TilingResult r = tile_contours(s);
  expect_sound(r.mesh, 2, 1);
  EXPECT_EQ(r.stats.one_to_one, 7u);
  EXPECT_EQ(r.stats.caps, 2u);
  EXPECT_NEAR(enclosed_volume(r.mesh), polygon_area * 16.0, 1e-6 * polygon_area);
  // In the end-slice planes, ear-clipped: 14 mm, and every vertex is on a slice.
  TilingOptions flat;
  flat.end_caps = EndCaps::AtEndSlice;
  flat.cap_refinement = CapRefinement::EarClipping;
  const TilingResult f = tile_contours(s, flat);
  expect_sound(f.mesh, 2, 1);
  EXPECT_NEAR(enclosed_volume(f.mesh), polygon_area * 14.0, 1e-6 * polygon_area);
  EXPECT_EQ(f.mesh.num_vertices(), 8 * 60);
  for (const Mesh* m : {&r.mesh, &f.mesh}) {
    ASSERT_TRUE(m->has_contour_ids());
    // Edges join vertices of one contour in a slice, or of adjacent slices; copies have no slice.
    const MeshAdjacency adj = build_adjacency(*m);
    int copies = 0;
    for (Index i = 0; i < m->num_vertices(); ++i) {
      if (m->slice_ids[i] == kNoId) {
        ++copies;
        continue;
      }
      EXPECT_EQ(m->slice_ids[i], i / 60);
      for (Index j : adj.ring(i)) {
        if (m->slice_ids[j] != kNoId) {
          EXPECT_LE(std::abs(m->slice_ids[i] - m->slice_ids[j]), 1);
        }
      }
    }
    EXPECT_EQ(copies, m == &r.mesh ? 120 + (r.mesh.num_vertices() - 8 * 60 - 120) : 0);  // end copies + cap interiors
  }
}

TEST(Tiling, RefinedCapsHaveWellShapedTrianglesOnTheirPlane) {
  ContourStack s = stack_of(4);
  for (auto& slice : s.slices) {
    slice.contours.push_back(circle(0, 0, 20, 180));  // 0.7 mm spacing
    slice.contours.push_back(circle(6, 0, 5, 45, true, 0));
  }
  const TilingResult r = tile_contours(s);
  expect_sound(r.mesh, 0, 1);
  const double top = 3 * 2.0 + 1.0;  // half a spacing above the last slice
  int cap_triangles = 0;
  double worst_edge = 0.0, worst_ratio = 0.0;
  for (const Triangle& t : r.mesh.triangles) {
    const Eigen::Vector3d a = r.mesh.positions.col(t[0]), b = r.mesh.positions.col(t[1]),
                          c = r.mesh.positions.col(t[2]);
    if (std::abs(a.z() - top) > 1e-9 || std::abs(b.z() - top) > 1e-9 || std::abs(c.z() - top) > 1e-9) continue;
    ++cap_triangles;
    const double e = std::max({(a - b).norm(), (b - c).norm(), (c - a).norm()});
    const double area = 0.5 * (b - a).cross(c - a).norm();
    worst_edge = std::max(worst_edge, e);
    worst_ratio = std::max(worst_ratio, e * e / area);  // 2.31 for an equilateral triangle
  }
  EXPECT_GT(cap_triangles, 1000);
  EXPECT_LT(worst_edge, 2.0) << "no long triangles across the cap";
  EXPECT_LT(worst_ratio, 20.0) << "no slivers";
}

TEST(Tiling, DifferentCountsAndShiftedContours) {
  ContourStack s = stack_of(6);
  for (int k = 0; k < 6; ++k) s.slices[k].contours.push_back(circle(0.5 * k, 0.3 * k, 8 + k, 30 + 7 * k));
  const TilingResult r = tile_contours(s);
  expect_sound(r.mesh, 2, 1);
}

TEST(Tiling, AThinWallThatSplitsInThreeHasFewSlivers) {
  // A flat wall (24 x 3 mm) 0.6 mm below three thin pieces of it and 0.6 mm below itself again: the
  // composites' bands fan long slivers across the nearly flat regions between the pieces (5.3 % of the
  // area before the slabs' faces were improved).
  auto ellipse = [](double cx, double cy, double rx, double ry, int n) {
    Contour c;
    for (int k = 0; k < n; ++k) {
      const double a = 2.0 * std::numbers::pi * k / n;
      c.points.emplace_back(cx + rx * std::cos(a), cy + ry * std::sin(a));
    }
    return c;
  };
  ContourStack s = stack_of(3, 0.6);
  s.slices[0].contours.push_back(ellipse(0, 0, 12, 1.5, 100));
  for (const double x : {-8.0, 0.0, 8.0}) s.slices[1].contours.push_back(ellipse(x, x == 0.0 ? -2.0 : 2.0, 3, 1, 24));
  s.slices[2].contours.push_back(ellipse(0, 0, 12, 1.5, 100));
  const TilingResult r = tile_contours(s);
  expect_sound(r.mesh, 2, 1);
  EXPECT_LT(sliver_area_share(r.mesh), 0.02);
}

TEST(Tiling, TinyContourNextToALargeOneKeepsTheBandManifold) {
  // The band between very different rings must stay an annulus (see RealScans for the case that broke).
  // Small rings near the rim of large ones, as where a bone process ends.
  ContourStack s = stack_of(4);
  s.slices[0].contours.push_back(circle(5.2, 0, 0.6, 3));
  s.slices[1].contours.push_back(circle(0, 0, 6, 40));
  s.slices[2].contours.push_back(circle(0, 0.4, 6, 40));
  s.slices[3].contours.push_back(circle(-5.0, 0.5, 0.5, 4));
  expect_sound(tile_contours(s).mesh, 2, 1);
}

TEST(Tiling, OrientationOfInputIsNormalised) {
  ContourStack s = stack_of(4);
  for (auto& slice : s.slices) {
    Contour c = circle(0, 0, 5, 20);
    std::reverse(c.points.begin(), c.points.end());  // clockwise outer: fixed by the tiler
    slice.contours.push_back(c);
  }
  expect_sound(tile_contours(s).mesh, 2, 1);
}

// Area of the faces (caps left out) within 10 degrees of the slice planes.
double shelf_area(const TilingResult& r) {
  std::vector<std::uint8_t> caps(r.face_roles.size());
  for (std::size_t f = 0; f < caps.size(); ++f) caps[f] = r.face_roles[f] == FaceRole::Cap;
  return area_facing_axis(r.mesh.positions, r.mesh.triangles, Eigen::Vector3d::UnitZ(), 10.0, caps);
}

TEST(Tiling, OneToTwoBranchIsOneClosedSurface) {
  ContourStack s = stack_of(10);
  for (int k = 0; k < 10; ++k) {
    if (k < 5) s.slices[k].contours.push_back(circle(0, 0, 10, 64));
    else {
      s.slices[k].contours.push_back(circle(-6, 0, 5, 32));
      s.slices[k].contours.push_back(circle(6, 0, 5, 32));
    }
  }
  // The mid-plane composite alone: the two circles copied onto the mid-plane, bridged, and flat faces
  // under the bridge (no band refinement: no face split afterwards).
  TilingOptions meyers;
  meyers.cap_refinement = CapRefinement::EarClipping;
  meyers.branching = Branching::MidPlaneComposite;
  meyers.band_refinement = BandRefinement::None;
  const TilingResult m = tile_contours(s, meyers);
  EXPECT_EQ(m.stats.branchings, 1u);
  expect_sound(m.mesh, 2, 1);
  int mid = 0;
  for (Index i = 0; i < m.mesh.num_vertices(); ++i) mid += m.mesh.slice_ids[i] == kNoId;
  EXPECT_EQ(mid, 64 + 64 + 64);  // the two copies on the mid-plane, and the two end copies
  // Interpolated (default): intermediate contours carry no ids, and the flat area left is a fraction of
  // the composite's.
  const TilingResult r = tile_contours(s);
  EXPECT_EQ(r.stats.branchings, 1u);
  EXPECT_GT(r.stats.intermediate_contours, 0u);
  expect_sound(r.mesh, 2, 1);
  ASSERT_EQ(r.face_roles.size(), r.mesh.triangles.size());
  for (Index i = 0; i < r.mesh.num_vertices(); ++i) {
    EXPECT_EQ(r.mesh.slice_ids[i] == kNoId, r.mesh.contour_ids[i] == kNoId);
  }
  EXPECT_LT(shelf_area(r), 0.5 * shelf_area(m)) << shelf_area(r) << " vs " << shelf_area(m);
}

TEST(Tiling, TwoToOneAndThreeWayBranches) {
  ContourStack s = stack_of(9);
  for (int k = 0; k < 9; ++k) {
    if (k < 3) {
      s.slices[k].contours.push_back(circle(-7, 0, 4, 24));
      s.slices[k].contours.push_back(circle(7, 0, 4, 24));
    } else if (k < 6) {
      s.slices[k].contours.push_back(circle(0, 0, 12, 70));
    } else {
      s.slices[k].contours.push_back(circle(-7, -4, 3.5, 20));
      s.slices[k].contours.push_back(circle(7, -4, 3.5, 20));
      s.slices[k].contours.push_back(circle(0, 7, 3.5, 20));
    }
  }
  const TilingResult r = tile_contours(s);
  EXPECT_EQ(r.stats.branchings, 2u);
  expect_sound(r.mesh, 2, 1);
}

TEST(Tiling, ManyToManyGroup) {
  // Two circles side by side below two circles one behind the other above: the four overlap around an
  // empty middle that is background on both slices.
  ContourStack s = stack_of(6);
  for (int k = 0; k < 6; ++k) {
    if (k < 3) {
      s.slices[k].contours.push_back(circle(-6, 0, 5, 30));
      s.slices[k].contours.push_back(circle(6, 0, 5, 30));
    } else {
      s.slices[k].contours.push_back(circle(0, -6, 5, 30));
      s.slices[k].contours.push_back(circle(0, 6, 5, 30));
    }
  }
  // Composites on the thirds bridge the middle over: a sphere.
  TilingOptions meyers;
  meyers.branching = Branching::MidPlaneComposite;
  const TilingResult m = tile_contours(s, meyers);
  EXPECT_EQ(m.stats.branchings, 1u);
  expect_sound(m.mesh, 2, 1);
  // The interpolated mid-level keeps the middle open (it is outside every circle, so outside the
  // interpolated region too): a ring of four lobes, and the surface is a torus.
  const TilingResult r = tile_contours(s);
  EXPECT_EQ(r.stats.branchings, 1u);
  expect_sound(r.mesh, 0, 1);
}

TEST(Tiling, AnnulusStackIsATorus) {
  ContourStack s = stack_of(6);
  for (auto& slice : s.slices) {
    slice.contours.push_back(circle(0, 0, 12, 60));
    slice.contours.push_back(circle(0, 0, 6, 30, /*hole=*/true, 0));
  }
  const TilingResult r = tile_contours(s);
  EXPECT_EQ(r.stats.hole_contours, 6u);
  expect_sound(r.mesh, 0, 1);
}

TEST(Tiling, InternalCavityIsASecondSurface) {
  ContourStack s = stack_of(10);
  for (int k = 0; k < 10; ++k) {
    s.slices[k].contours.push_back(circle(0, 0, 12, 60));
    if (k >= 3 && k <= 6) s.slices[k].contours.push_back(circle(1, 0, 5, 30, true));  // parent found by the tiler
  }
  const TilingResult r = tile_contours(s);
  expect_sound(r.mesh, 4, 2);
  // Ends extend half a spacing: the solid is 20 mm tall and the cavity 8 mm.
  const double outer = 0.5 * 60 * 144 * std::sin(2 * std::numbers::pi / 60) * 20.0;
  const double cavity = 0.5 * 30 * 25 * std::sin(2 * std::numbers::pi / 30) * 8.0;
  EXPECT_NEAR(enclosed_volume(r.mesh), outer - cavity, 1e-6 * outer);
}

TEST(Tiling, TwoObjectsAndAHoleThatSplits) {
  ContourStack s = stack_of(8);
  for (int k = 0; k < 8; ++k) {
    s.slices[k].contours.push_back(circle(-30, 0, 8, 40));
    s.slices[k].contours.push_back(circle(30, 0, 20, 90));
    // A hole in the second object that splits into two holes halfway up.
    if (k >= 2 && k < 4) s.slices[k].contours.push_back(circle(30, 0, 10, 50, true, 1));
    if (k >= 4 && k < 6) {
      s.slices[k].contours.push_back(circle(24, 0, 4, 24, true, 1));
      s.slices[k].contours.push_back(circle(36, 0, 4, 24, true, 1));
    }
  }
  const TilingResult r = tile_contours(s);
  expect_sound(r.mesh, 6, 3);  // a cylinder, and a solid with a Y-shaped cavity (two surfaces)
}

// An annulus arc from angle a0 to a1 (counter-clockwise), radii r0 < r1.
Contour arc(double a0, double a1, double r0, double r1, int n) {
  Contour c;
  for (int k = 0; k <= n; ++k) {
    const double a = a0 + (a1 - a0) * k / n;
    c.points.emplace_back(r1 * std::cos(a), r1 * std::sin(a));
  }
  for (int k = n; k >= 0; --k) {
    const double a = a0 + (a1 - a0) * k / n;
    c.points.emplace_back(r0 * std::cos(a), r0 * std::sin(a));
  }
  return c;
}

TEST(Tiling, HolesThatOpenToTheOutsideJoinTheOuterBoundary) {
  // A thick tube (ring slices) whose wall is cut by two windows in the middle slices, like the orbits
  // of a skull: the inside and outside surfaces join there.
  ContourStack s = stack_of(9);
  for (int k = 0; k < 9; ++k) {
    if (k >= 3 && k <= 5) {
      s.slices[k].contours.push_back(arc(0.3, std::numbers::pi - 0.3, 8, 12, 30));
      s.slices[k].contours.push_back(arc(std::numbers::pi + 0.3, 2 * std::numbers::pi - 0.3, 8, 12, 30));
    } else {
      s.slices[k].contours.push_back(circle(0, 0, 12, 80));
      s.slices[k].contours.push_back(circle(0, 0, 8, 60, true, 0));
    }
  }
  const TilingResult r = tile_contours(s);
  const test::Topology t = test::topology_of(r.mesh);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.manifold) << t.problems;
  EXPECT_EQ(t.components, 1);
  // A lower ring and an upper ring (genus 1 each) joined by two pillars: genus 3, chi = 2 - 2 * 3.
  EXPECT_EQ(t.euler, -4);
  EXPECT_GT(enclosed_volume(r.mesh), 0.0);
  EXPECT_EQ(r.stats.caps, 2u);  // only the two annulus ends: the holes open, they are not capped
}

TEST(Tiling, SingleSliceContoursAreDroppedAndLeftHandedFramesStayOutward) {
  ContourStack s = stack_of(5);
  for (auto& slice : s.slices) slice.contours.push_back(circle(0, 0, 5, 24));
  s.slices[2].contours.push_back(circle(40, 0, 3, 12));  // exists in one slice only
  s.axis_w = -Eigen::Vector3d::UnitZ();                   // a left-handed frame
  const TilingResult r = tile_contours(s);
  EXPECT_EQ(r.stats.dropped_contours, 1u);
  expect_sound(r.mesh, 2, 1);
}

TEST(Tiling, BadStacksAreRejected) {
  ContourStack s = stack_of(3);
  for (auto& slice : s.slices) slice.contours.push_back(circle(0, 0, 5, 24));
  ContourStack unordered = s;
  unordered.slices[2].w = 1.0;
  EXPECT_THROW((void)tile_contours(unordered), InvalidInputError);
  ContourStack tiny = s;
  tiny.slices[1].contours[0].points.resize(2);
  EXPECT_THROW((void)tile_contours(tiny), InvalidInputError);
  ContourStack orphan = s;
  orphan.slices[1].contours.push_back(circle(50, 0, 1, 10, true));
  EXPECT_THROW((void)tile_contours(orphan), InvalidInputError);
}

std::string tiling_error(const ContourStack& s, const TilingOptions& o = {}) {
  try {
    (void)tile_contours(s, o);
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return {};
}

TEST(Tiling, ContoursWithFewerThanThreeDistinctPointsAreNamed) {
  ContourStack s = stack_of(3);
  for (auto& slice : s.slices) slice.contours.push_back(circle(0, 0, 5, 24));
  s.slices[1].contours[0].points = {{0, 0}, {1, 0}};
  EXPECT_EQ(tiling_error(s), "tiling: contour 0 of slice 1 has 2 distinct points (at least 3 needed)");
  s.slices[1].contours[0].points = {{0, 0}, {1, 0}, {1, 0}, {0, 0}};  // four points, two distinct
  EXPECT_EQ(tiling_error(s), "tiling: contour 0 of slice 1 has 2 distinct points (at least 3 needed)");
  s.slices[1].contours[0].points = {};
  EXPECT_NE(tiling_error(s).find("has 0 distinct points"), std::string::npos);
  s.slices[1].contours[0] = circle(0, 0, 5, 24);
  s.slices[1].contours[0].points[4].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(tiling_error(s), "tiling: contour 0 of slice 1: point 4 is not finite");
}

TEST(Tiling, ARepeatedClosingPointIsDropped) {
  ContourStack s = stack_of(3);
  for (auto& slice : s.slices) {
    slice.contours.push_back(circle(0, 0, 5, 24));
    slice.contours.back().points.push_back(slice.contours.back().points.front());  // closed explicitly
  }
  const TilingResult r = tile_contours(s);
  expect_sound(r.mesh, 2, 1);
  EXPECT_EQ(std::count(r.mesh.slice_ids.begin(), r.mesh.slice_ids.end(), 1), 24);
}

TEST(Tiling, SelfIntersectingContourIsRejectedNamingItsEdges) {
  ContourStack s = stack_of(3);
  for (auto& slice : s.slices) slice.contours.push_back(circle(0, 0, 5, 24));
  // A spike that folds back across the contour: edges 2 and 5 cross.
  s.slices[2].contours[0].points = {{-5, -5}, {5, -5}, {5, 5}, {-2, 0}, {-2, 6}, {6, 2}, {-5, 5}};
  const std::string e = tiling_error(s);
  EXPECT_EQ(e.rfind("tiling: contour 0 of slice 2 intersects itself: its edges ", 0), 0u) << e;
  EXPECT_NE(e.find(" meet at ("), std::string::npos) << e;
  // A plain bow tie.
  s.slices[2].contours[0].points = {{-5, -5}, {5, -5}, {-5, 5}, {5, 5}};
  EXPECT_EQ(tiling_error(s), "tiling: contour 0 of slice 2 intersects itself: its edges 1 and 3 meet at (0, 0) mm");
}

// fuzz_tiling found a slice whose two holes overlapped (one inside the other): the tiler returned a
// non-manifold mesh (tests/fuzz/regressions/fuzz_tiling). The contours of a slice must not meet, and a
// region inside a hole is an outer contour, not another hole.
TEST(Tiling, ContoursOfASliceThatMeetAreRejectedNamingBoth) {
  ContourStack s = stack_of(3);
  for (auto& slice : s.slices) slice.contours.push_back(circle(0, 0, 10, 48));
  s.slices[1].contours.push_back(circle(8, 0, 5, 24));  // crosses contour 0
  const std::string e = tiling_error(s);
  EXPECT_EQ(e.rfind("tiling: contours 0 and 1 of slice 1 meet: edge ", 0), 0u) << e;
  EXPECT_NE(e.find(" mm"), std::string::npos) << e;
  // Two holes of one outer contour that overlap.
  s.slices[1].contours.back() = circle(-2, 0, 4, 24, true, 0);
  s.slices[1].contours.push_back(circle(2, 0, 4, 24, true, 0));
  EXPECT_EQ(tiling_error(s).rfind("tiling: contours 1 and 2 of slice 1 meet", 0), 0u) << tiling_error(s);
}

TEST(Tiling, AHoleInsideAHoleIsRejected) {
  ContourStack s = stack_of(3);
  for (auto& slice : s.slices) slice.contours.push_back(circle(0, 0, 10, 48));
  s.slices[1].contours.push_back(circle(0, 0, 6, 36, true, 0));
  s.slices[1].contours.push_back(circle(0, 0, 3, 24, true, 0));
  EXPECT_EQ(tiling_error(s),
            "tiling: hole contour 2 of slice 1 lies inside hole contour 1 (a region inside a hole is an "
            "outer contour)");
  // An island inside the hole, given as an outer contour, is a valid slice.
  s.slices[1].contours[2] = circle(0, 0, 3, 24);
  EXPECT_EQ(tiling_error(s), "");
}

TEST(Tiling, AHoleParentThatDoesNotContainItIsIgnored) {
  ContourStack s = stack_of(3);
  for (auto& slice : s.slices) {
    slice.contours.push_back(circle(-20, 0, 8, 48));
    slice.contours.push_back(circle(20, 0, 8, 48));
  }
  // A hole through outer 1; in the middle slice it names outer 0, which does not contain it: it is
  // tiled as a hole of outer 1 there too.
  for (int k = 0; k < 3; ++k) s.slices[k].contours.push_back(circle(20, 0, 3, 24, true, k == 1 ? 0 : 1));
  const TilingResult r = tile_contours(s);
  const test::Topology t = test::topology_of(r.mesh);
  EXPECT_TRUE(t.closed && t.manifold) << t.problems;
  EXPECT_EQ(r.stats.hole_contours, 3u);
  EXPECT_EQ(r.stats.dropped_contours, 0u);
}

// The contours of a convex polyhedron (its vertices and edges) cut by the planes z = z0 + k dz,
// resampled to `spacing`.
ContourStack slices_of(const std::vector<Eigen::Vector3d>& corners, const std::vector<std::array<int, 2>>& edges,
                       double z0, double dz, int count, double spacing) {
  ContourStack s;
  for (int k = 0; k < count; ++k) {
    const double z = z0 + k * dz;
    std::vector<Eigen::Vector2d> pts;
    for (const auto& e : edges) {
      const Eigen::Vector3d a = corners[e[0]], b = corners[e[1]];
      if ((a.z() - z) * (b.z() - z) >= 0.0) continue;
      const double t = (z - a.z()) / (b.z() - a.z());
      pts.push_back((a + t * (b - a)).head<2>());
    }
    if (pts.size() < 3) continue;
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (const auto& p : pts) c += p / static_cast<double>(pts.size());
    std::sort(pts.begin(), pts.end(), [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
      return std::atan2(p.y() - c.y(), p.x() - c.x()) < std::atan2(q.y() - c.y(), q.x() - c.x());
    });
    SliceContours slice;
    slice.w = z;
    Contour contour;
    contour.points = resample_closed(pts, spacing);
    slice.contours.push_back(contour);
    s.slices.push_back(slice);
  }
  return s;
}

// A box (half sizes hx, hy, hz) turned by `degrees` about the x axis, then moved by `shear` * z along x.
ContourStack box_stack(double hx, double hy, double hz, double degrees, double shear, double dz, double spacing) {
  const double a = degrees * std::numbers::pi / 180.0;
  std::vector<Eigen::Vector3d> corners;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d p((k & 1) ? hx : -hx, (k & 2) ? hy : -hy, (k & 4) ? hz : -hz);
    Eigen::Vector3d q(p.x(), std::cos(a) * p.y() - std::sin(a) * p.z(), std::sin(a) * p.y() + std::cos(a) * p.z());
    q.x() += shear * q.z();
    corners.push_back(q);
  }
  std::vector<std::array<int, 2>> edges;
  for (int i = 0; i < 8; ++i) {
    for (int b : {1, 2, 4}) {
      if (!(i & b)) edges.push_back({i, i | b});
    }
  }
  double lo = 1e9, hi = -1e9;
  for (const auto& c : corners) {
    lo = std::min(lo, c.z());
    hi = std::max(hi, c.z());
  }
  const int count = static_cast<int>(std::floor((hi - lo) / dz));
  return slices_of(corners, edges, lo + 0.5 * (hi - lo - (count - 1) * dz), dz, count, spacing);
}

TEST(Tiling, ABoxTiltedOffTheSlicesHasNoSliverFans) {
  // Its top and bottom lie 5 degrees off the slices: from slice to slice the contours grow by 23 mm.
  // One least-area band per slab put 39 % of the area in slivers.
  const ContourStack s = box_stack(20, 15, 10, 5.0, 0.0, 2.0, 0.7);
  TilingOptions plain;
  plain.band_refinement = BandRefinement::None;
  EXPECT_GT(sliver_area_share(tile_contours(s, plain).mesh), 0.2);
  const TilingResult r = tile_contours(s);
  expect_sound(r.mesh, 2, 1);
  EXPECT_LT(sliver_area_share(r.mesh), 0.02);
  EXPECT_GT(r.stats.refined_bands, 0u);
}

TEST(Tiling, AnObliquePrismHasNoSliverFans) {
  // A square prism leaning 60 degrees: each contour is the last one moved 3.5 mm sideways.
  const ContourStack s = box_stack(10, 10, 15, 0.0, std::tan(60.0 * std::numbers::pi / 180.0), 2.0, 0.7);
  const TilingResult r = tile_contours(s);
  expect_sound(r.mesh, 2, 1);
  EXPECT_LT(sliver_area_share(r.mesh), 0.02);
}

TEST(Tiling, TheMeshDoesNotDependOnTheThreadCount) {
  // Branchings, a hole that opens, refinement: every kind of slab.
  ContourStack s = stack_of(9);
  for (int k = 0; k < 9; ++k) {
    if (k < 3) {
      s.slices[k].contours.push_back(circle(0, 0, 12, 80));
      s.slices[k].contours.push_back(circle(0, 0, 8, 60, true, 0));
    } else if (k < 6) {
      s.slices[k].contours.push_back(arc(0.3, std::numbers::pi - 0.3, 8, 12, 30));
      s.slices[k].contours.push_back(arc(std::numbers::pi + 0.3, 2 * std::numbers::pi - 0.3, 8, 12, 30));
    } else {
      s.slices[k].contours.push_back(circle(-5, 0, 4 + k - 6, 30));
      s.slices[k].contours.push_back(circle(6, 0, 3, 24));
    }
  }
  TilingOptions one;
  one.threads = 1;
  const TilingResult reference = tile_contours(s, one);
  for (const int threads : {2, 3, 8}) {
    TilingOptions o;
    o.threads = threads;
    const TilingResult r = tile_contours(s, o);
    EXPECT_TRUE(r.mesh.positions == reference.mesh.positions) << threads;
    EXPECT_EQ(r.mesh.triangles, reference.mesh.triangles) << threads;
    EXPECT_EQ(r.mesh.slice_ids, reference.mesh.slice_ids) << threads;
    EXPECT_EQ(r.mesh.contour_ids, reference.mesh.contour_ids) << threads;
    EXPECT_EQ(r.face_roles, reference.face_roles) << threads;
  }
  const test::Topology t = test::topology_of(reference.mesh);
  EXPECT_TRUE(t.closed && t.manifold) << t.problems;
}

TEST(Tiling, OptionsOutOfRangeAreRejected) {
  ContourStack s = stack_of(3);
  for (auto& slice : s.slices) slice.contours.push_back(circle(0, 0, 5, 24));
  TilingOptions o;
  o.max_branching_depth = -1;
  EXPECT_EQ(tiling_error(s, o), "tiling: max_branching_depth must be >= 0");
  o = {};
  o.interpolation_grid = 0.0;
  EXPECT_EQ(tiling_error(s, o), "tiling: interpolation_grid must be in (0, 1]");
  o = {};
  o.threads = -2;
  EXPECT_EQ(tiling_error(s, o), "tiling: threads must be >= 0");
  o = {};
  o.max_band_aspect = 0.0;
  EXPECT_EQ(tiling_error(s, o), "tiling: max_band_aspect must be > 0");
}

TEST(Tiling, LimitsStopTheTilingBeforeItAllocates) {
  ContourStack s = stack_of(3);
  for (auto& slice : s.slices) slice.contours.push_back(circle(0, 0, 50, 2000));
  TilingOptions o;
  o.cap_refinement = CapRefinement::EarClipping;
  o.limits.max_vertices = 5000;  // 6000 contour points
  try {
    (void)tile_contours(s, o);
    FAIL();
  } catch (const LimitError& e) {
    EXPECT_EQ(std::string(e.what()), "tiling: 6000 vertices exceed the limit of 5000 vertices");
  }
  o.limits.max_vertices = 6100;  // the points fit, the end-cap copies do not
  EXPECT_NE(tiling_error(s, o).find("the mesh would have more than 6100 vertices"), std::string::npos);
  o.limits.max_vertices = kDefaultMaxVertices;
  // Two slices of 6000 points: the mesh (about 3 MB) fits in 5 MB, the programme of the pair does not
  // (coarse to fine: a corridor of about 10 MB; the full grid would need 324 MB), and is refused before
  // it is allocated.
  ContourStack big = stack_of(2);
  for (auto& slice : big.slices) slice.contours.push_back(circle(0, 0, 100, 6000));
  o.limits.max_memory_bytes = 5'000'000;
  const std::string e = tiling_error(big, o);
  EXPECT_EQ(e.rfind("tiling: contours of 6000 and 6000 points: needs about ", 0), 0u) << e;
  EXPECT_NE(e.find(" MB of memory, more than the 5 MB allowed"), std::string::npos) << e;
  o.limits.max_memory_bytes = 0;
  EXPECT_EQ(tiling_error(s, o), "");
}

TEST(Tiling, LargeContoursAreTiledCoarseToFine) {
  // 2500 x 2500 point pairs: the full grid needs 56 MB, the band of +/- 15 % around the diagonal 17 MB;
  // the coarse-to-fine corridor fits in 3 MB whatever full_dp_limit says.
  ContourStack s = stack_of(3);
  for (auto& slice : s.slices) slice.contours.push_back(circle(0, 0, 100, 2500));
  TilingOptions o;
  o.full_dp_limit = 1000;
  o.limits.max_memory_bytes = 3'000'000;
  o.cap_refinement = CapRefinement::EarClipping;  // the bands are under test, not the 31000 mm^2 caps
  expect_sound(tile_contours(s, o).mesh, 2, 1);
}

}  // namespace
}  // namespace contourmesh
