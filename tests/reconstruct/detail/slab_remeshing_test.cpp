// SPDX-License-Identifier: BSD-3-Clause
// Removing slivers from a slab's tiling: fewer slivers, the same boundary, the same surface.
#include "detail/slab_remeshing.h"

#include "detail/band_tiling.h"

#include <contourmesh/smooth/mesh_quality.h>

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <utility>

#include "reconstruct/detail/level_helpers.h"

namespace contourmesh::detail {
namespace {

using test::circle_points;

double sliver_share(const SlabMesh& m) {
  double area = 0.0, sliver = 0.0;
  for (const Triangle& t : m.triangles) {
    const Eigen::Vector3d a = m.position(t[0]), b = m.position(t[1]), c = m.position(t[2]);
    const double A = 0.5 * (b - a).cross(c - a).norm();
    area += A;
    if (minimum_angle_degrees(a, b, c) < 10.0) sliver += A;
  }
  return sliver / area;
}

double area(const SlabMesh& m) {
  double total = 0.0;
  for (const Triangle& t : m.triangles) {
    total += 0.5 * (m.position(t[1]) - m.position(t[0])).cross(m.position(t[2]) - m.position(t[0])).norm();
  }
  return total;
}

// Directed edges and how often each occurs.
std::map<std::pair<VertexRef, VertexRef>, int> directed_edges(const SlabMesh& m) {
  std::map<std::pair<VertexRef, VertexRef>, int> edges;
  for (const Triangle& t : m.triangles) {
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  }
  return edges;
}

// A nearly flat band: a small contour 0.3 mm above a large one, off its centre (a wall that shrinks
// from one slice to the next): the least-area band fans long slivers across the gap.
struct FlatBand {
  test::TestStack stack;
  LevelContour lower, upper;
  SlabMesh mesh;
  FlatBand() {
    lower = stack.contour(circle_points(0, 0, 10, 64), 0.0);
    upper = stack.contour(circle_points(3, 1, 2, 14), 0.3);
    mesh = stack.slab();
    emit_band(lower, upper, minimum_area_band(lower.points, 0.0, upper.points, 0.3, TilingOptions{}), mesh);
  }
};

TEST(SlabRemeshing, AFlatFanLosesMostOfItsSliverArea) {
  FlatBand band;
  const double before = sliver_share(band.mesh);
  ASSERT_GT(before, 0.3);  // the fan is mostly slivers
  const SlabRemeshing done = improve_slab_faces(band.mesh, 0.1, 0.5);
  EXPECT_GT(done.flips + done.splits, 0u);
  EXPECT_LT(sliver_share(band.mesh), 0.25 * before);
}

TEST(SlabRemeshing, TheBoundaryAndTheContourVerticesStay) {
  FlatBand band;
  std::set<std::pair<VertexRef, VertexRef>> boundary;
  for (const auto& [e, n] : directed_edges(band.mesh)) {
    if (!directed_edges(band.mesh).count({e.second, e.first})) boundary.insert(e);
  }
  ASSERT_EQ(boundary.size(), 64u + 14u);
  const std::size_t stack_vertices = band.stack.positions.size();
  improve_slab_faces(band.mesh, 0.1, 0.5);
  const auto edges = directed_edges(band.mesh);
  std::set<std::pair<VertexRef, VertexRef>> after;
  for (const auto& [e, n] : edges) {
    EXPECT_EQ(n, 1) << "a directed edge used twice";
    if (!edges.count({e.second, e.first})) after.insert(e);
  }
  EXPECT_EQ(after, boundary);  // the contours' edges, nothing else, are still the slab's boundary
  EXPECT_EQ(band.stack.positions.size(), stack_vertices);
}

TEST(SlabRemeshing, TheSurfaceMovesByLessThanTheDeviationAllowed) {
  FlatBand band;
  const double before = area(band.mesh);
  improve_slab_faces(band.mesh, 0.05, 0.5);
  // Every face's corners are the old surface's points (splits) or its vertices (flips); flips across a
  // crease of a 0.3 mm high band can change the area only a little.
  EXPECT_NEAR(area(band.mesh), before, 0.02 * before);
  for (const Eigen::Vector3d& v : band.mesh.vertices) {
    EXPECT_GE(v.z(), 0.0);
    EXPECT_LE(v.z(), 0.3);
  }
}

TEST(SlabRemeshing, AWellShapedBandIsLeftAsItIs) {
  test::TestStack stack;
  const LevelContour lower = stack.contour(circle_points(0, 0, 10, 40), 0.0);
  const LevelContour upper = stack.contour(circle_points(0, 0, 10, 40), 2.0);
  SlabMesh mesh = stack.slab();
  emit_band(lower, upper, minimum_area_band(lower.points, 0.0, upper.points, 2.0, TilingOptions{}), mesh);
  const std::vector<Triangle> before = mesh.triangles;
  const SlabRemeshing done = improve_slab_faces(mesh, 0.5, 0.5);
  EXPECT_EQ(done.flips + done.splits, 0u);
  EXPECT_EQ(mesh.triangles, before);
}

}  // namespace
}  // namespace contourmesh::detail
