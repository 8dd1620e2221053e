// SPDX-License-Identifier: BSD-3-Clause
// The mid-plane composite and the nested fill left for the finest level of a topology change.
#include "detail/branching.h"

#include "detail/caps.h"
#include "detail/outline.h"

#include <contourmesh/smooth/mesh_quality.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "reconstruct/detail/level_helpers.h"
#include "reconstruct/mesh_checks.h"

namespace contourmesh::detail {
namespace {

using test::arc_points;
using test::circle_points;

// The two levels joined by `middle` and capped below and above, as one mesh.
Mesh closed(test::TestStack& stack, const Level& lower, const Level& upper, const SlabMesh& middle) {
  SlabMesh below = stack.slab(), above = stack.slab();
  for (const LevelContour& c : lower.contours) {
    std::vector<const LevelContour*> holes;
    for (const LevelContour& h : lower.contours) {
      if (h.is_hole && &lower.contours[static_cast<std::size_t>(h.parent)] == &c) holes.push_back(&h);
    }
    if (!c.is_hole) cap_end(c, holes, lower.w, 0.0, false, TilingOptions{}, below);
  }
  for (const LevelContour& c : upper.contours) {
    std::vector<const LevelContour*> holes;
    for (const LevelContour& h : upper.contours) {
      if (h.is_hole && &upper.contours[static_cast<std::size_t>(h.parent)] == &c) holes.push_back(&h);
    }
    if (!c.is_hole) cap_end(c, holes, upper.w, 0.0, true, TilingOptions{}, above);
  }
  return stack.assemble({&below, &middle, &above});
}

// The bridge faces of a slab mesh (their centroids' angles about the axis) and its longest edge.
struct Bridges {
  std::vector<double> angles;
  double longest_edge = 0.0;
};
Bridges bridges_of(const SlabMesh& out) {
  Bridges b;
  for (std::size_t f = 0; f < out.triangles.size(); ++f) {
    const Triangle& t = out.triangles[f];
    const Eigen::Vector3d p = out.position(t[0]), q = out.position(t[1]), r = out.position(t[2]);
    b.longest_edge = std::max({b.longest_edge, (q - p).norm(), (r - q).norm(), (p - r).norm()});
    if (out.roles[f] != FaceRole::Bridge) continue;
    const Eigen::Vector3d m = (p + q + r) / 3.0;
    b.angles.push_back(std::atan2(m.y(), m.x()));
  }
  return b;
}

TEST(Branching, TheOutlineIndexAnswersAsPointInPolygon) {
  // Outline files each outer contour's edges in horizontal strips; its answer must be the even-odd
  // rule's over the whole contour (holes filled), for points anywhere, on vertex heights included.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    Level level;
    for (int k = 0; k < 3; ++k) {
      LevelContour c;
      const double cx = 30.0 * k, r = 8.0 + 4.0 * u(rng), depth = 0.6 * u(rng), lobes = std::floor(1 + 7 * u(rng));
      const int n = 3 + static_cast<int>(300 * u(rng));
      for (int i = 0; i < n; ++i) {
        const double t = 2.0 * std::numbers::pi * i / n, rr = r * (1.0 + depth * std::sin(lobes * t));
        c.points.emplace_back(cx + rr * std::cos(t), rr * std::sin(t));
      }
      c.is_hole = k == 2;  // a hole's region is not tested (filled by its outer)
      finish_contour(c);
      level.contours.push_back(std::move(c));
    }
    const Outline outline(level);
    auto expected = [&](const Eigen::Vector2d& p) {
      for (const LevelContour& c : level.contours) {
        if (!c.is_hole && c.box.contains(p) && point_in_polygon(c.points, p)) return true;
      }
      return false;
    };
    for (int i = 0; i < 2000; ++i) {
      Eigen::Vector2d p(-15.0 + 60.0 * u(rng), -15.0 + 30.0 * u(rng));
      if (i % 4 == 0) {  // on the height of a vertex
        const Polygon& c = level.contours[static_cast<std::size_t>(i % 2)].points;
        p.y() = c[static_cast<std::size_t>(u(rng) * static_cast<double>(c.size())) % c.size()].y();
      }
      ASSERT_EQ(outline.contains(p), expected(p)) << "trial " << trial << " point " << p.transpose();
    }
  }
}

TEST(Branching, OneToTwoIsBridgedOnTheMidPlane) {
  test::TestStack stack;
  const Level lower{0.0, {stack.contour(circle_points(0, 0, 10, 64), 0.0)}};
  // Two discs that poke out of the lower one: not nested, so a composite.
  const Level upper{2.0,
                    {stack.contour(circle_points(-8, 0, 5, 32), 2.0), stack.contour(circle_points(8, 0, 5, 32), 2.0)}};
  SlabMesh out = stack.slab();
  tile_composite(lower, upper, TilingOptions{}, out);
  EXPECT_EQ(out.stats.composites, 1u);
  int bridges = 0;
  for (std::size_t f = 0; f < out.triangles.size(); ++f) {
    if (out.roles[f] != FaceRole::Bridge) continue;
    ++bridges;
    for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(out.position(out.triangles[f][k]).z(), 1.0);  // on the mid-plane
  }
  EXPECT_EQ(bridges, 2);
  const test::Topology t = test::topology_of(closed(stack, lower, upper, out));
  EXPECT_TRUE(t.closed && t.manifold) << t.problems;
  EXPECT_EQ(t.euler, 2);
}

TEST(Branching, ADeferredCompositeFinishedLaterIsTheSameMeshFaceForFace) {
  // A composite band and, after it, the cap of a contour with no partner: the band's faces must go back
  // where they were, before the cap's. (With band refinement the band is a crossing band here, whose
  // vertices and faces are appended when it is solved: the same surface, numbered differently.)
  TilingOptions options;
  options.band_refinement = BandRefinement::None;
  test::TestStack stack;
  const Level lower{0.0,
                    {stack.contour(circle_points(0, 0, 10, 64), 0.0), stack.contour(circle_points(40, 0, 3, 24), 0.0)}};
  const Level upper{2.0,
                    {stack.contour(circle_points(-8, 0, 5, 32), 2.0), stack.contour(circle_points(8, 0, 5, 32), 2.0)}};
  SlabMesh direct = stack.slab();
  tile_composite(lower, upper, options, direct);
  SlabMesh lazy = stack.slab();
  std::vector<DeferredBand> pending;
  tile_composite(lower, upper, options, lazy, &pending);
  ASSERT_EQ(pending.size(), 1u);
  EXPECT_LT(pending[0].position, lazy.triangles.size()) << "faces follow the band";
  EXPECT_EQ(lazy.triangles.size() + 64 + 64, direct.triangles.size());  // the band: one face per point
  const TilingDefects partial = measure_defects(lazy);
  finish_composite(pending, options, lazy);
  const TilingDefects full = measure_defects(lazy);
  EXPECT_EQ(partial.bridge_area, full.bridge_area);
  EXPECT_LE(partial.score(), full.score());
  ASSERT_EQ(lazy.triangles.size(), direct.triangles.size());
  EXPECT_TRUE(lazy.triangles == direct.triangles);
  EXPECT_TRUE(lazy.roles == direct.roles);
  EXPECT_EQ(lazy.vertices, direct.vertices);
}

TEST(Branching, ContoursInsideOneAreJoinedByAWellShapedFill) {
  // Three small discs inside a large one (the noisy end of a flat-topped bone): the composite's band
  // would fan slivers across the flat region between them; the nested fill triangulates it.
  test::TestStack stack;
  const Level lower{0.0, {stack.contour(circle_points(0, 0, 15, 120), 0.0)}};
  const Level upper{0.5,
                    {stack.contour(circle_points(-6, 0, 2, 16), 0.5), stack.contour(circle_points(6, 0, 2, 16), 0.5),
                     stack.contour(circle_points(0, 7, 2, 16), 0.5)}};
  SlabMesh out = stack.slab();
  tile_composite(lower, upper, TilingOptions{}, out);
  double fill = 0.0;
  for (std::size_t f = 0; f < out.triangles.size(); ++f) {
    const Triangle& t = out.triangles[f];
    const Eigen::Vector3d a = out.position(t[0]), b = out.position(t[1]), c = out.position(t[2]);
    if (out.roles[f] == FaceRole::Bridge) {
      fill += 0.5 * (b - a).cross(c - a).norm();
      EXPECT_GT(minimum_angle_degrees(a, b, c), 12.0);
      EXPECT_GT((b - a).cross(c - a).z(), 0.0) << "faces up: material below";
    }
  }
  EXPECT_NEAR(fill, std::numbers::pi * (225.0 - 3 * 4.0), 0.02 * std::numbers::pi * 225.0);
  const test::Topology t = test::topology_of(closed(stack, lower, upper, out));
  EXPECT_TRUE(t.closed && t.manifold) << t.problems;
  EXPECT_EQ(t.components, 1);
}

TEST(Branching, TwoPiecesAreBridgedWhereTheOtherLevelJoinsThem) {
  // Two halves of a ring wall above, apart by 0.6-0.8 mm at angle 0 and by 1.8-2.4 mm at angle pi; below,
  // one C-shaped wall open at angle 0 only. The bridge must cross the wider gap, where the wall below
  // joins the halves: at the nearest pair (angle 0) the composite would be a C open at pi, and the band
  // between it and the C below would cross the slab along the wall.
  test::TestStack stack;
  const double pi = std::numbers::pi;
  const Level lower{0.0, {stack.contour(arc_points(0.02, 2 * pi - 0.02, 15, 20, 120), 0.0)}};
  const Level upper{1.0,
                    {stack.contour(arc_points(0.02, pi - 0.06, 15, 20, 60), 1.0),
                     stack.contour(arc_points(pi + 0.06, 2 * pi - 0.02, 15, 20, 60), 1.0)}};
  SlabMesh out = stack.slab();
  tile_composite(lower, upper, TilingOptions{}, out);
  const Bridges b = bridges_of(out);
  EXPECT_EQ(b.angles.size(), 2u);
  for (double a : b.angles) EXPECT_GT(std::abs(a), pi - 0.1) << "bridged at angle " << a;
  EXPECT_LT(b.longest_edge, 8.0) << "the band crosses the slab along the wall";  // the walls' ends are 5 mm
  const test::Topology t = test::topology_of(closed(stack, lower, upper, out));
  EXPECT_TRUE(t.closed && t.manifold) << t.problems;
}

TEST(Branching, AnOpeningHoleIsBridgedWhereTheContourAboveRunsIntoIt) {
  // A wall 1 mm thick at angle 0 and 8 mm at angle pi (an off-centre hole), open above at angle pi/2
  // where it is about 4.4 mm thick: farther from the nearest pair (1 mm) than the opening rule reaches
  // (twice it plus the two spacings, about 4.1 mm). The contour above runs from the outer wall into the
  // hole there, and the bridge must follow it: at the nearest pair the composite would run round the
  // hole in another order than the contour above, and the band between them would cross the slab.
  test::TestStack stack;
  const double pi = std::numbers::pi;
  const Eigen::Vector2d centre(3.5, 0.0);
  const double ro = 20.0, rh = 15.5, gap = 0.08;  // the opening spans pi/2 -+ gap (rad) on the outer wall
  const Level lower{0.0,
                    {stack.contour(circle_points(0, 0, ro, 120), 0.0),
                     stack.contour(circle_points(centre.x(), centre.y(), rh, 90, true), 0.0, true, 0)}};
  // Above: the outer wall from pi/2 + gap round to pi/2 - gap, then the hole's wall back, clockwise.
  Polygon above;
  for (int k = 0; k <= 110; ++k) {
    const double a = pi / 2 + gap + (2 * pi - 2 * gap) * k / 110;
    above.emplace_back(ro * std::cos(a), ro * std::sin(a));
  }
  // The hole's wall between the rays from its centre through the opening's two ends, clockwise.
  const double h0 = std::atan2(ro * std::sin(pi / 2 - gap) - centre.y(), ro * std::cos(pi / 2 - gap) - centre.x());
  const double h1 = std::atan2(ro * std::sin(pi / 2 + gap) - centre.y(), ro * std::cos(pi / 2 + gap) - centre.x());
  for (int k = 0; k <= 85; ++k) {
    const double a = h0 - (2 * pi - (h1 - h0)) * k / 85;
    above.emplace_back(centre.x() + rh * std::cos(a), centre.y() + rh * std::sin(a));
  }
  const Level upper{1.0, {stack.contour(above, 1.0)}};
  SlabMesh out = stack.slab();
  tile_composite(lower, upper, TilingOptions{}, out);
  const Bridges b = bridges_of(out);
  EXPECT_EQ(b.angles.size(), 2u);
  for (double a : b.angles) EXPECT_NEAR(a, pi / 2, 0.2) << "bridged away from the opening";
  EXPECT_LT(b.longest_edge, 8.0) << "the band crosses the slab";
  const test::Topology t = test::topology_of(closed(stack, lower, upper, out));
  EXPECT_TRUE(t.closed && t.manifold) << t.problems;
}

// A pocket in a wide wall over the other level's cavity (a diploe cavity over the cranial cavity under a
// flat roof) is a cavity of its own, closed a quarter of the slab beyond its plane: no bridge, nothing
// reaches across the wall to the outside, and the surface is closed.
TEST(Branching, APocketOverTheOtherLevelsCavityIsClosedNearItsPlane) {
  test::TestStack stack;
  const Level lower{0.0,
                    {stack.contour(circle_points(0, 0, 30, 120), 0.0),
                     stack.contour(circle_points(0, 0, 20, 100, true), 0.0, true, 0)}};
  const Level upper{
      2.0,
      {stack.contour(circle_points(0, 0, 30, 120), 2.0), stack.contour(circle_points(0, 0, 12, 70, true), 2.0, true, 0),
       stack.contour(circle_points(17, 0, 2, 12, true), 2.0, true, 0)}};
  SlabMesh out = stack.slab();
  tile_composite(lower, upper, TilingOptions{}, out);
  EXPECT_TRUE(bridges_of(out).angles.empty());
  // Every vertex of the pocket's closure lies within its disc and between z = 1.5 and 2.
  std::size_t pocket = 0;
  for (std::size_t f = 0; f < out.triangles.size(); ++f) {
    if (out.roles[f] != FaceRole::Cap) continue;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = out.position(out.triangles[f][k]);
      EXPECT_LT(std::hypot(p.x() - 17.0, p.y()), 2.0 + 1e-9);
      EXPECT_GE(p.z(), 1.5 - 1e-9);
      ++pocket;
    }
  }
  EXPECT_GT(pocket, 0u);
  // Every face at the pocket's contour stays at the pocket (joined to the outer wall, 11 mm away, a face
  // would cross the wall).
  for (const Triangle& t : out.triangles) {
    bool at_pocket = false;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = out.position(t[k]);
      at_pocket = at_pocket || (p.z() == 2.0 && std::abs(std::hypot(p.x() - 17.0, p.y()) - 2.0) < 0.1);
    }
    if (!at_pocket) continue;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = out.position(t[k]);
      EXPECT_LT(std::hypot(p.x() - 17.0, p.y()), 2.0 + 1e-6);
    }
  }
  const test::Topology t = test::topology_of(closed(stack, lower, upper, out));
  EXPECT_TRUE(t.closed && t.manifold) << t.problems;
}

TEST(Branching, AnOpeningHoleIsBridgedWhereTheWallIsOpenAbove) {
  // A ring below a ring wall with one slit at angle 2 rad: the composite of outer contour and hole is
  // bridged across the wall at the slit, so that the band above follows the wall.
  test::TestStack stack;
  const Level lower{0.0,
                    {stack.contour(circle_points(0, 0, 20, 120), 0.0),
                     stack.contour(circle_points(0, 0, 15, 90, true), 0.0, true, 0)}};
  const Level upper{1.0, {stack.contour(arc_points(2.1, 2.0 + 2 * std::numbers::pi - 0.1, 15, 20, 110), 1.0)}};
  SlabMesh out = stack.slab();
  tile_composite(lower, upper, TilingOptions{}, out);
  int bridges = 0;
  for (std::size_t f = 0; f < out.triangles.size(); ++f) {
    if (out.roles[f] != FaceRole::Bridge) continue;
    ++bridges;
    const Eigen::Vector3d c =
        (out.position(out.triangles[f][0]) + out.position(out.triangles[f][1]) + out.position(out.triangles[f][2])) /
        3.0;
    EXPECT_NEAR(std::atan2(c.y(), c.x()), 2.0, 0.17);  // the slit spans 1.9 to 2.1 rad
  }
  EXPECT_EQ(bridges, 2);
  const test::Topology t = test::topology_of(closed(stack, lower, upper, out));
  EXPECT_TRUE(t.closed && t.manifold) << t.problems;
}

}  // namespace
}  // namespace contourmesh::detail
