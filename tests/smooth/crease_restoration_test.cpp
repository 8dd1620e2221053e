// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/crease_restoration.h"
#include "contourmesh/smooth/errors.h"
#include "contourmesh/smooth/shapes.h"

#include "detail/parallel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace contourmesh {
namespace {

constexpr double kHalf = 10.0;  // the cube [-10, 10]^3
constexpr double kRound = 0.8;  // radius of the rounded edges, mm

// Signed distance to the sharp cube's surface, for points near it (max of the six planes).
double to_sharp_cube(const Eigen::Vector3d& p) { return p.cwiseAbs().maxCoeff() - kHalf; }

// Distance from a point on the cube's surface to its nearest edge, and to its nearest corner.
double to_edge(const Eigen::Vector3d& p) {
  Eigen::Vector3d gaps = (Eigen::Vector3d::Constant(kHalf) - p.cwiseAbs()).cwiseMax(0.0);
  std::sort(gaps.data(), gaps.data() + 3);
  return gaps[1];  // gaps[0] is the face the point lies on
}
double to_corner(const Eigen::Vector3d& p) { return (p.cwiseAbs() - Eigen::Vector3d::Constant(kHalf)).norm(); }

// A 0.5 mm cube whose edges and corners are rounded with radius kRound, as thresholding a blurred image
// rounds them: each vertex moved onto the rounded box, along the direction from its clamped core point.
Mesh rounded_cube(double radius = kRound) {
  Mesh cube = make_cube(40, kHalf);
  const double core = kHalf - radius;
  for (Index i = 0; i < cube.num_vertices(); ++i) {
    const Eigen::Vector3d p = cube.positions.col(i);
    const Eigen::Vector3d c = p.cwiseMax(-core).cwiseMin(core);
    cube.positions.col(i) = c + radius * (p - c).normalized();
  }
  return cube;
}

// Edge labels within 1.5 mm of an edge and 3 mm from every corner (where two planes meet, not three).
std::vector<VertexLabel> edge_labels(const Mesh& mesh) {
  std::vector<VertexLabel> labels(static_cast<std::size_t>(mesh.num_vertices()), VertexLabel::Smooth);
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::Vector3d p = mesh.positions.col(i);
    if (to_edge(p) < 1.5 && to_corner(p) > 3.0) labels[static_cast<std::size_t>(i)] = VertexLabel::Edge;
  }
  return labels;
}

// The largest distance to the sharp cube of the vertices within 0.6 mm of an edge and 4 mm from the
// corners (new vertices included).
double worst_near_edges(const Mesh& mesh) {
  double worst = 0.0;
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::Vector3d p = mesh.positions.col(i);
    if (to_edge(p) < 0.6 && to_corner(p) > 4.0) worst = std::max(worst, std::abs(to_sharp_cube(p)));
  }
  return worst;
}

TEST(CreaseRestoration, RoundedCubeEdgesComeBackSharp) {
  const Mesh rounded = rounded_cube();
  ASSERT_GT(worst_near_edges(rounded), 0.2);  // the rounding: 0.8 (sqrt(2) - 1) = 0.33 mm at an edge
  const RestoredCreases r = restore_creases(rounded, edge_labels(rounded));
  EXPECT_GT(r.mesh.num_vertices(), rounded.num_vertices());  // the spokes were bisected
  EXPECT_EQ(r.original_vertices, rounded.num_vertices());
  EXPECT_GT(r.moved, 0u);
  EXPECT_LT(worst_near_edges(r.mesh), 0.05);  // within a seventh of the rounding
}

TEST(CreaseRestoration, VerticesOnTheBisectorMoveOntoTheCreaseLine) {
  // The cube's edge vertices lie on the bisector of their two faces once rounded (as deep below each):
  // they land on the edge line, not on one of the faces (with line_ratio 1 they would, 0.2 mm from it).
  const Mesh cube = make_cube(40, kHalf);
  const Mesh rounded = rounded_cube();
  const RestoredCreases r = restore_creases(rounded, edge_labels(rounded));
  CreaseRestorationOptions plane_only;
  plane_only.line_ratio = 1.0;
  const RestoredCreases p = restore_creases(rounded, edge_labels(rounded), plane_only);
  std::size_t checked = 0;
  double worst = 0.0, worst_plane_only = 0.0;
  for (Index i = 0; i < cube.num_vertices(); ++i) {
    const Eigen::Vector3d c = cube.positions.col(i);
    if (to_edge(c) > 1e-9 || to_corner(c) < 4.0) continue;  // on an edge, away from the corners
    worst = std::max(worst, to_edge(r.mesh.positions.col(i)));
    worst_plane_only = std::max(worst_plane_only, to_edge(p.mesh.positions.col(i)));
    ++checked;
  }
  ASSERT_GT(checked, 100u);
  EXPECT_LT(worst, 0.05);
  EXPECT_GT(worst_plane_only, 0.1);
}

TEST(CreaseRestoration, CornersWhereThreePlanesMeetDoNotMove) {
  // Every vertex within 1.5 mm of an edge labelled, corners included: a ball there holds three planes,
  // and a two-plane fit would throw its vertices onto one of them. None within 1.5 mm of a corner moves.
  const Mesh rounded = rounded_cube();
  std::vector<VertexLabel> labels(static_cast<std::size_t>(rounded.num_vertices()), VertexLabel::Smooth);
  for (Index i = 0; i < rounded.num_vertices(); ++i) {
    if (to_edge(rounded.positions.col(i)) < 1.5) labels[static_cast<std::size_t>(i)] = VertexLabel::Edge;
  }
  CreaseRestorationOptions no_subdivision;
  no_subdivision.levels = 0;
  const RestoredCreases r = restore_creases(rounded, labels, no_subdivision);
  ASSERT_GT(r.moved, 0u);
  for (Index i = 0; i < rounded.num_vertices(); ++i) {
    if (to_corner(rounded.positions.col(i)) < 1.5) {
      EXPECT_TRUE(r.mesh.positions.col(i) == rounded.positions.col(i)) << "vertex " << i;
    }
  }
}

TEST(CreaseRestoration, TheInputsVerticesComeFirstAndFacesOnlyGrow) {
  const Mesh rounded = rounded_cube();
  CreaseRestorationOptions no_moves;
  no_moves.max_move = 1e-12;  // subdivision alone
  const RestoredCreases r = restore_creases(rounded, edge_labels(rounded), no_moves);
  ASSERT_GT(r.mesh.num_vertices(), rounded.num_vertices());
  EXPECT_EQ(r.moved, 0u);
  EXPECT_TRUE(r.mesh.positions.leftCols(rounded.num_vertices()) == rounded.positions);
}

TEST(CreaseRestoration, FlatFacesAwayFromTheEdgesDoNotMove) {
  const Mesh rounded = rounded_cube();
  const RestoredCreases r = restore_creases(rounded, edge_labels(rounded));
  for (Index i = 0; i < rounded.num_vertices(); ++i) {
    if (to_edge(rounded.positions.col(i)) > 2.6) {
      EXPECT_TRUE(r.mesh.positions.col(i) == rounded.positions.col(i)) << "vertex " << i;
    }
  }
}

TEST(CreaseRestoration, ContourVerticesStayOnTheirSlicePlanes) {
  // The rounded cube's side walls as a contour stack: every vertex with |z| < 10 lies on a 0.5 mm grid
  // plane and gets that plane as its slice; the caps' vertices have no ids. The vertical edges are
  // restored by moves within the slice planes.
  Mesh rounded = rounded_cube();
  const Index n = rounded.num_vertices();
  rounded.slice_ids.assign(static_cast<std::size_t>(n), -1);
  rounded.contour_ids.assign(static_cast<std::size_t>(n), -1);
  for (Index i = 0; i < n; ++i) {
    const double z = rounded.positions(2, i);
    if (std::abs(z) < kHalf - kRound) {
      rounded.slice_ids[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(std::lround((z + kHalf) / 0.5));
      rounded.contour_ids[static_cast<std::size_t>(i)] = 0;
    }
  }
  const RestoredCreases r = restore_creases(rounded, edge_labels(rounded));
  double worst_vertical = 0.0;
  for (Index i = 0; i < r.mesh.num_vertices(); ++i) {
    if (r.mesh.slice_ids[static_cast<std::size_t>(i)] < 0) continue;
    const Eigen::Vector3d before = i < n ? Eigen::Vector3d(rounded.positions.col(i)) : r.mesh.positions.col(i);
    if (i < n) {
      EXPECT_EQ(r.mesh.positions(2, i), before.z()) << "vertex " << i << " left its slice plane";
    }
    const Eigen::Vector3d p = r.mesh.positions.col(i);
    const bool vertical_edge = std::abs(p.z()) < kHalf - 4.0 && to_edge(p) < 0.6;
    if (vertical_edge) worst_vertical = std::max(worst_vertical, std::abs(to_sharp_cube(p)));
  }
  EXPECT_LT(worst_vertical, 0.05);
}

TEST(CreaseRestoration, NothingChangesWithoutEdgeLabels) {
  const Mesh rounded = rounded_cube();
  const std::vector<VertexLabel> smooth(static_cast<std::size_t>(rounded.num_vertices()), VertexLabel::Smooth);
  const RestoredCreases r = restore_creases(rounded, smooth);
  EXPECT_EQ(r.moved, 0u);
  EXPECT_TRUE(r.mesh.positions == rounded.positions);
  EXPECT_EQ(r.mesh.triangles, rounded.triangles);
}

TEST(CreaseRestoration, ASmoothSphereLabelledEverywhereDoesNotMove) {
  // A sphere has no two planes anywhere: every ball fails the angle or the residual test.
  const Mesh sphere = make_icosphere(4, 10.0);
  const std::vector<VertexLabel> all(static_cast<std::size_t>(sphere.num_vertices()), VertexLabel::Edge);
  CreaseRestorationOptions no_subdivision;
  no_subdivision.levels = 0;
  const RestoredCreases r = restore_creases(sphere, all, no_subdivision);
  EXPECT_EQ(r.moved, 0u);
}

TEST(CreaseRestoration, LabelsWithoutTwoPlanesAreNotRefined) {
  // Only edge vertices whose ball fits two planes get their spokes bisected: a sphere labelled
  // everywhere keeps its mesh, vertex for vertex and face for face.
  const Mesh sphere = make_icosphere(4, 10.0);
  const std::vector<VertexLabel> all(static_cast<std::size_t>(sphere.num_vertices()), VertexLabel::Edge);
  const RestoredCreases r = restore_creases(sphere, all);
  EXPECT_EQ(r.mesh.num_vertices(), sphere.num_vertices());
  EXPECT_EQ(r.mesh.triangles, sphere.triangles);
  EXPECT_TRUE(r.mesh.positions == sphere.positions);
}

TEST(CreaseRestoration, EdgesThatAreAlreadySharpAreNotRefined) {
  // The sharp cube: every ball near an edge fits its two planes, but no vertex lies inside them, so
  // there is nothing to restore and the mesh stays as it is.
  const Mesh sharp = make_cube(40, kHalf);
  const RestoredCreases r = restore_creases(sharp, edge_labels(sharp));
  EXPECT_EQ(r.mesh.num_vertices(), sharp.num_vertices());
  EXPECT_EQ(r.moved, 0u);
}

TEST(CreaseRestoration, RoundingUnderMinRoundingIsLeftAlone) {
  // Edges rounded with r = 0.05 mm lie at most 0.02 mm inside their planes: under the default
  // min_rounding (0.03 mm) nothing is refined or moved; with min_rounding 0 they are restored.
  const Mesh slight = rounded_cube(0.05);
  const std::vector<VertexLabel> labels = edge_labels(slight);
  const RestoredCreases kept = restore_creases(slight, labels);
  EXPECT_EQ(kept.mesh.num_vertices(), slight.num_vertices());
  EXPECT_EQ(kept.moved, 0u);
  CreaseRestorationOptions any;
  any.min_rounding = 0.0;
  const RestoredCreases restored = restore_creases(slight, labels, any);
  EXPECT_GT(restored.mesh.num_vertices(), slight.num_vertices());
  EXPECT_GT(restored.moved, 0u);
}

TEST(CreaseRestoration, AConcaveCreaseIsRestoredAsTheConvexOne) {
  // The rounded cube with its faces turned over is the cube's complement: its creases are concave, and
  // the rounding fills them. They come back as sharp as the convex ones, with as many vertices refined
  // and moved. (Positions may differ where a vertex lies on the bisector of the two planes: which plane
  // it moves onto follows the order the fit found them in, which the turn swaps.)
  const Mesh rounded = rounded_cube();
  Mesh turned = rounded;
  for (Triangle& t : turned.triangles) std::swap(t[1], t[2]);
  const std::vector<VertexLabel> labels = edge_labels(rounded);
  const RestoredCreases convex = restore_creases(rounded, labels);
  const RestoredCreases concave = restore_creases(turned, labels);
  ASSERT_EQ(concave.mesh.num_vertices(), convex.mesh.num_vertices());
  EXPECT_EQ(concave.moved, convex.moved);
  EXPECT_LT(worst_near_edges(concave.mesh), 0.05);
}

TEST(CreaseRestoration, FalseLabelsOnAFlatFaceAddNoVertices) {
  // The cube's edges labelled, and a patch in the middle of a face too: the patch's balls are one
  // plane, so the refined mesh has as many vertices as with the edges' labels alone.
  // The patch's vertices are shifted within the face, so that their umbrellas do not vanish (an
  // umbrella of zero length would not be bisected anyway).
  Mesh rounded = rounded_cube();
  const std::vector<VertexLabel> edges = edge_labels(rounded);
  std::vector<VertexLabel> with_patch = edges;
  std::size_t patch = 0;
  for (Index i = 0; i < rounded.num_vertices(); ++i) {
    const Eigen::Vector3d p = rounded.positions.col(i);
    if (p.z() > kHalf - 1e-9 && std::abs(p.x()) < 3.0 && std::abs(p.y()) < 3.0) {
      with_patch[static_cast<std::size_t>(i)] = VertexLabel::Edge;
      rounded.positions.col(i) +=
          0.1 * Eigen::Vector3d(std::sin(1.3 * static_cast<double>(i)), std::cos(0.7 * static_cast<double>(i)), 0.0);
      ++patch;
    }
  }
  ASSERT_GT(patch, 10u);
  const Index refined = restore_creases(rounded, edges).mesh.num_vertices();
  ASSERT_GT(refined, rounded.num_vertices());
  EXPECT_EQ(restore_creases(rounded, with_patch).mesh.num_vertices(), refined);
}

TEST(CreaseRestoration, SameResultOnOneThreadAndSeveral) {
  const Mesh rounded = rounded_cube();
  const std::vector<VertexLabel> labels = edge_labels(rounded);
  RestoredCreases one, three;
  {
    const detail::ScopedWorkerCount threads(1);
    one = restore_creases(rounded, labels);
  }
  {
    const detail::ScopedWorkerCount threads(3);
    three = restore_creases(rounded, labels);
  }
  EXPECT_TRUE(one.mesh.positions == three.mesh.positions);
  EXPECT_EQ(one.moved, three.moved);
}

TEST(CreaseRestoration, BadInputIsRefused) {
  const Mesh cube = make_cube(2, 1.0);
  const std::vector<VertexLabel> labels(static_cast<std::size_t>(cube.num_vertices()), VertexLabel::Edge);
  EXPECT_THROW((void)restore_creases(cube, std::vector<VertexLabel>(3, VertexLabel::Edge)), InvalidInputError);
  CreaseRestorationOptions levels;
  levels.levels = 4;
  EXPECT_THROW((void)restore_creases(cube, labels, levels), InvalidInputError);
  CreaseRestorationOptions radius;
  radius.radius = 0.0;
  EXPECT_THROW((void)restore_creases(cube, labels, radius), InvalidInputError);
  CreaseRestorationOptions angle;
  angle.min_angle_degrees = 180.0;
  EXPECT_THROW((void)restore_creases(cube, labels, angle), InvalidInputError);
  CreaseRestorationOptions mode;
  mode.mode_angle_degrees = 50.0;
  EXPECT_THROW((void)restore_creases(cube, labels, mode), InvalidInputError);
  CreaseRestorationOptions third;
  third.max_third_share = 1.5;
  EXPECT_THROW((void)restore_creases(cube, labels, third), InvalidInputError);
  CreaseRestorationOptions rounding;
  rounding.min_rounding = -0.1;
  EXPECT_THROW((void)restore_creases(cube, labels, rounding), InvalidInputError);
  CreaseRestorationOptions line;
  line.line_ratio = 1.5;
  EXPECT_THROW((void)restore_creases(cube, labels, line), InvalidInputError);
}

}  // namespace
}  // namespace contourmesh
