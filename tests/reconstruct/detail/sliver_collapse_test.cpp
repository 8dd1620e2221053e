// SPDX-License-Identifier: BSD-3-Clause
// Collapsing needles in a slab's tiling: the thin band between two nearly coincident levels goes, the
// slab's boundary and its contour vertices stay, and the surface stays an oriented manifold.
#include "detail/sliver_collapse.h"

#include "detail/band_tiling.h"

#include <contourmesh/smooth/closest_point.h>
#include <contourmesh/smooth/mesh_quality.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "reconstruct/detail/level_helpers.h"

namespace contourmesh::detail {
namespace {

using test::circle_points;
using test::directed_edges;
using test::local_contour;

double sliver_area(const SlabMesh& m) {
  double sliver = 0.0;
  for (const Triangle& t : m.triangles) {
    const Eigen::Vector3d a = m.position(t[0]), b = m.position(t[1]), c = m.position(t[2]);
    if (minimum_angle_degrees(a, b, c) < 10.0) sliver += 0.5 * (b - a).cross(c - a).norm();
  }
  return sliver;
}

// Edges with no twin: the slab's boundary.
std::set<std::pair<VertexRef, VertexRef>> boundary(const SlabMesh& m) {
  const auto edges = directed_edges(m);
  std::set<std::pair<VertexRef, VertexRef>> out;
  for (const auto& [e, n] : edges) {
    if (!edges.count({e.second, e.first})) out.insert(e);
  }
  return out;
}

// A slab of 2 mm halved into a sub-slab of 0.1 mm and the rest: the intermediate level (vertices
// without ids) lies 0.1 mm above the lower contour, a little inside it, with a third more points (a
// wall: the levels nearly coincide). The thin band is all needles.
struct ThinSubSlab {
  test::TestStack stack;
  SlabMesh mesh;
  LevelContour lower, middle, upper;
  explicit ThinSubSlab(bool middle_has_ids = false) {
    mesh = stack.slab();
    lower = stack.contour(circle_points(0, 0, 10, 63), 0.0);
    upper = stack.contour(circle_points(0, 0, 9, 57), 2.0);
    const Polygon m = circle_points(0, 0, 9.98, 84);
    middle = middle_has_ids ? stack.contour(m, 0.1) : local_contour(m, 0.1, mesh);
    TilingOptions options;
    emit_band(lower, middle, minimum_area_band(lower.points, 0.0, middle.points, 0.1, options), mesh);
    emit_band(middle, upper, minimum_area_band(middle.points, 0.1, upper.points, 2.0, options), mesh);
  }
};

TEST(SliverCollapse, AThinSubSlabLosesItsNeedles) {
  ThinSubSlab slab;
  const double before = sliver_area(slab.mesh);
  ASSERT_GT(before, 0.5);  // the band of 0.1 mm: about 63 mm long
  const std::size_t collapses = collapse_slivers(slab.mesh, 1.0, 0.1);
  EXPECT_GT(collapses, 40u);
  EXPECT_LT(sliver_area(slab.mesh), 0.2 * before);
}

TEST(SliverCollapse, TheBoundaryAndTheContourVerticesStay) {
  ThinSubSlab slab;
  const auto ring_edges = boundary(slab.mesh);
  ASSERT_EQ(ring_edges.size(), 63u + 57u);
  (void)collapse_slivers(slab.mesh, 1.0, 0.1);
  EXPECT_EQ(boundary(slab.mesh), ring_edges);
  // Every contour vertex is still a corner of some face.
  std::set<VertexRef> used;
  for (const Triangle& t : slab.mesh.triangles) used.insert(t.begin(), t.end());
  for (const LevelContour* c : {&slab.lower, &slab.upper}) {
    for (VertexRef v : c->ids) EXPECT_TRUE(used.count(v)) << "contour vertex " << v << " lost";
  }
}

TEST(SliverCollapse, TheSlabStaysAnOrientedManifoldWithItsLocalVerticesRenumbered) {
  ThinSubSlab slab;
  (void)collapse_slivers(slab.mesh, 1.0, 0.1);
  for (const auto& [e, n] : directed_edges(slab.mesh)) EXPECT_EQ(n, 1) << "a directed edge used twice";
  // Every local vertex is used, and no reference points past the local vertices.
  std::vector<int> uses(slab.mesh.vertices.size(), 0);
  for (const Triangle& t : slab.mesh.triangles) {
    for (VertexRef v : t) {
      if (!is_local(v)) continue;
      ASSERT_LT(local_index(v), slab.mesh.vertices.size());
      ++uses[local_index(v)];
    }
    EXPECT_NE(t[0], t[1]);
    EXPECT_NE(t[1], t[2]);
    EXPECT_NE(t[0], t[2]);
  }
  for (int u : uses) EXPECT_GT(u, 0);
  EXPECT_EQ(slab.mesh.roles.size(), slab.mesh.triangles.size());
}

TEST(SliverCollapse, VerticesOnlyGoNeverMove) {
  ThinSubSlab slab;
  (void)collapse_slivers(slab.mesh, 1.0, 0.1);
  // Every vertex that remains is where it was: on the lower circle, the middle one or the upper one.
  for (const Triangle& t : slab.mesh.triangles) {
    for (VertexRef v : t) {
      const Eigen::Vector3d p = slab.mesh.position(v);
      const double r = p.head<2>().norm();
      const bool on_a_level = (std::abs(p.z()) < 1e-12 && std::abs(r - 10.0) < 1e-9) ||
                              (std::abs(p.z() - 0.1) < 1e-12 && std::abs(r - 9.98) < 1e-9) ||
                              (std::abs(p.z() - 2.0) < 1e-12 && std::abs(r - 9.0) < 1e-9);
      EXPECT_TRUE(on_a_level) << p.transpose();
    }
  }
}

TEST(SliverCollapse, NeedlesBetweenContourVerticesStay) {
  // The same levels, all three with ids: nothing may go.
  ThinSubSlab slab(true);
  const auto before = slab.mesh.triangles;
  EXPECT_EQ(collapse_slivers(slab.mesh, 1.0, 0.1), 0u);
  EXPECT_EQ(slab.mesh.triangles, before);
}

TEST(SliverCollapse, NothingCollapsesThatWouldMoveTheSurfaceMoreThanTheBound) {
  ThinSubSlab slab;
  const auto before = slab.mesh.triangles;
  // Every collapse in the thin band moves a corner 0.1 mm down a wall that bends into a slope there.
  EXPECT_EQ(collapse_slivers(slab.mesh, 1.0, 0.001), 0u);
  EXPECT_EQ(slab.mesh.triangles, before);
}

TEST(SliverCollapse, NothingCollapsesOntoANeighbourBeyondTheLengthBound) {
  ThinSubSlab slab;
  const auto before = slab.mesh.triangles;
  EXPECT_EQ(collapse_slivers(slab.mesh, 0.09, 0.1), 0u);  // every edge of the thin band is longer
  EXPECT_EQ(slab.mesh.triangles, before);
}

TEST(SliverCollapse, EveryVertexThatGoesStaysNearTheSurface) {
  ThinSubSlab slab;
  const std::vector<Eigen::Vector3d> middle(slab.mesh.vertices.begin(), slab.mesh.vertices.end());
  ASSERT_GT(collapse_slivers(slab.mesh, 1.0, 0.1), 0u);
  for (const Eigen::Vector3d& p : middle) {
    double nearest = 1e9;
    for (const Triangle& t : slab.mesh.triangles) {
      const Eigen::Vector3d q =
          closest_point_on_triangle(p, slab.mesh.position(t[0]), slab.mesh.position(t[1]), slab.mesh.position(t[2]));
      nearest = std::min(nearest, (q - p).norm());
    }
    EXPECT_LE(nearest, 0.1) << p.transpose();
  }
}

}  // namespace
}  // namespace contourmesh::detail
