// SPDX-License-Identifier: BSD-3-Clause
// Removing slivers from a slab's tiling: fewer slivers, the same boundary, the same surface.
#include "detail/slab_remeshing.h"

#include "detail/band_tiling.h"

#include <contourmesh/smooth/mesh_quality.h>

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <utility>
#include <vector>

#include "reconstruct/detail/level_helpers.h"

namespace contourmesh::detail {
namespace {

using test::circle_points;
using test::directed_edges;
using test::local_contour;

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

// The same nearly flat band between two rings of vertices without ids (two composites of a branching,
// 0.4 mm apart): a fan from the small ring's vertices across the whole gap.
struct FlatCompositeBand {
  test::TestStack stack;
  LevelContour lower, upper;
  SlabMesh mesh;
  FlatCompositeBand() {
    mesh = stack.slab();
    lower = local_contour(circle_points(0, 0, 10, 64), 0.0, mesh);
    upper = local_contour(circle_points(4, 1, 2, 14), 0.4, mesh);
    emit_band(lower, upper, minimum_area_band(lower.points, 0.0, upper.points, 0.4, TilingOptions{}), mesh);
  }
};

TEST(SlabRemeshing, AFanBetweenCompositesGetsPointsInsideAndNoSliversAreLeft) {
  FlatCompositeBand band;
  const double before = sliver_share(band.mesh);
  ASSERT_GT(before, 0.3);
  const std::size_t vertices = band.mesh.vertices.size();
  const SlabRemeshing done = improve_slab_faces(band.mesh, 0.1, 0.5);
  EXPECT_GT(done.insertions, 0u);
  EXPECT_GT(band.mesh.vertices.size(), vertices);
  EXPECT_LT(sliver_share(band.mesh), 0.02);
}

// Interior edges whose two faces lie within 30 degrees of the slice planes, one facing up, one down.
int folds(const SlabMesh& m) {
  std::map<std::pair<VertexRef, VertexRef>, int> face_of;
  auto side = [&](std::size_t f) {
    const Triangle& t = m.triangles[f];
    const Eigen::Vector3d n = (m.position(t[1]) - m.position(t[0])).cross(m.position(t[2]) - m.position(t[0]));
    const double c = std::cos(30.0 * std::numbers::pi / 180.0) * n.norm();
    return n.z() >= c ? 1 : n.z() <= -c ? -1 : 0;
  };
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    for (int k = 0; k < 3; ++k) face_of[{m.triangles[f][k], m.triangles[f][(k + 1) % 3]}] = static_cast<int>(f);
  }
  int count = 0;
  for (const auto& [e, f] : face_of) {
    const auto it = face_of.find({e.second, e.first});
    const int s = side(static_cast<std::size_t>(f));
    if (it != face_of.end() && s != 0 && side(static_cast<std::size_t>(it->second)) == -s) ++count;
  }
  return count / 2;
}

TEST(SlabRemeshing, AFanBetweenCompositesKeepsItsRingsAndGainsNoFolds) {
  FlatCompositeBand band;
  const auto edges_before = directed_edges(band.mesh);
  std::set<std::pair<VertexRef, VertexRef>> rings;
  for (const auto& [e, n] : edges_before) {
    if (!edges_before.count({e.second, e.first})) rings.insert(e);
  }
  ASSERT_EQ(rings.size(), 64u + 14u);
  const std::vector<Eigen::Vector3d> ring_points(band.mesh.vertices.begin(), band.mesh.vertices.end());
  const int folds_before = folds(band.mesh);
  improve_slab_faces(band.mesh, 0.1, 0.5);
  EXPECT_LE(folds(band.mesh), folds_before);  // no flip folds the surface
  const auto edges = directed_edges(band.mesh);
  std::set<std::pair<VertexRef, VertexRef>> after;
  for (const auto& [e, n] : edges) {
    EXPECT_EQ(n, 1) << "a directed edge used twice";
    if (!edges.count({e.second, e.first})) after.insert(e);
  }
  EXPECT_EQ(after, rings);
  for (std::size_t v = 0; v < ring_points.size(); ++v) EXPECT_EQ(band.mesh.vertices[v], ring_points[v]);
  // New vertices lie on the band, between the two planes.
  for (std::size_t v = ring_points.size(); v < band.mesh.vertices.size(); ++v) {
    EXPECT_GE(band.mesh.vertices[v].z(), 0.0);
    EXPECT_LE(band.mesh.vertices[v].z(), 0.4);
  }
}

TEST(SlabRemeshing, AFlatFanLosesMostOfItsSliverArea) {
  FlatBand band;
  const double before = sliver_share(band.mesh);
  ASSERT_GT(before, 0.3);  // the fan is mostly slivers
  const SlabRemeshing done = improve_slab_faces(band.mesh, 0.1, 0.5);
  EXPECT_GT(done.flips + done.splits + done.insertions, 0u);
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
