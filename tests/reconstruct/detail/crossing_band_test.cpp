// SPDX-License-Identifier: BSD-3-Clause
// The band between the two composites of a many-to-many branching whose outlines cross.
#include "detail/crossing_band.h"

#include "detail/band_tiling.h"
#include "detail/branching.h"
#include "detail/caps.h"

#include <contourmesh/smooth/mesh_quality.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "reconstruct/detail/level_helpers.h"
#include "reconstruct/mesh_checks.h"

namespace contourmesh::detail {
namespace {

using test::circle_points;

// Two discs below (centres x = -6 and 6) and two above (x = -2 and 10), radius 5, all on the x axis:
// each upper disc overlaps a lower one and the middle ones overlap across, so the group is
// many-to-many. The lower composite's bridge runs inside the upper left disc, the upper one's inside
// the lower right disc: the composites' outlines cross six times and enclose no pocket.
struct Chain {
  test::TestStack stack;
  Level lower, upper;
  Chain() {
    lower = {0.0,
             {stack.contour(circle_points(-6, 0, 5, 40), 0.0), stack.contour(circle_points(6, 0, 5, 40), 0.0)}};
    upper = {1.2,
             {stack.contour(circle_points(-2, 0, 5, 40), 1.2), stack.contour(circle_points(10, 0, 5, 40), 1.2)}};
  }
  [[nodiscard]] static bool in_lower(const Eigen::Vector2d& p) {
    return (p - Eigen::Vector2d(-6, 0)).norm() < 5.0 || (p - Eigen::Vector2d(6, 0)).norm() < 5.0;
  }
  [[nodiscard]] static bool in_upper(const Eigen::Vector2d& p) {
    return (p - Eigen::Vector2d(-2, 0)).norm() < 5.0 || (p - Eigen::Vector2d(10, 0)).norm() < 5.0;
  }
};

// Faces between the two composites (at w 0.4 and 0.8) that face against the material: up where only
// the upper level has material, or down where only the lower one has (a pleat's every other face).
// Faces near the bridges (|y| < 1) and near the discs' rims are left out.
int faces_against_material(const SlabMesh& out) {
  int against = 0;
  for (const Triangle& t : out.triangles) {
    const Eigen::Vector3d a = out.position(t[0]), b = out.position(t[1]), c = out.position(t[2]);
    const double lo = std::min({a.z(), b.z(), c.z()}), hi = std::max({a.z(), b.z(), c.z()});
    if (lo < 0.4 - 1e-9 || hi > 0.8 + 1e-9 || hi - lo < 1e-9) continue;  // copy bands, bridges
    const Eigen::Vector2d m = ((a + b + c) / 3.0).head<2>();
    if (std::abs(m.y()) < 1.0) continue;
    const bool l = Chain::in_lower(m), u = Chain::in_upper(m);
    const double nz = (b - a).cross(c - a).z();
    if ((l && !u && nz < 0.0) || (u && !l && nz > 0.0)) ++against;
  }
  return against;
}

TEST(CrossingBand, AManyToManyChainIsClosedWithoutHandlesOrFacesAgainstTheMaterial) {
  Chain chain;
  SlabMesh out = chain.stack.slab();
  tile_composite(chain.lower, chain.upper, TilingOptions{}, out);
  EXPECT_EQ(out.stats.composites, 2u);
  EXPECT_EQ(faces_against_material(out), 0);
  // Closed by caps below and above: one object without handles.
  SlabMesh below = chain.stack.slab(), above = chain.stack.slab();
  for (const LevelContour& c : chain.lower.contours) cap_end(c, {}, 0.0, 0.0, false, TilingOptions{}, below);
  for (const LevelContour& c : chain.upper.contours) cap_end(c, {}, 1.2, 0.0, true, TilingOptions{}, above);
  const test::Topology t = test::topology_of(chain.stack.assemble({&below, &out, &above}));
  EXPECT_TRUE(t.closed && t.manifold) << t.problems;
  EXPECT_EQ(t.euler, 2);
}

TEST(CrossingBand, TwoOffsetDiscsMeetInTwoLunesEachCoveredOnce) {
  // Copies of a disc below (w 0.4) and of a disc 3 mm to its right above (w 0.8), each joined to its
  // contour by a straight band, as a composite's copies are: their outlines cross twice.
  test::TestStack stack;
  const LevelContour below = stack.contour(circle_points(0, 0, 5, 48), 0.0);
  const LevelContour above = stack.contour(circle_points(3, 0, 5, 48), 1.2);
  SlabMesh out = stack.slab();
  const LevelContour a = copy_contour(below, 0.4, out);
  emit_copy_band(below.ids, a.ids, out);
  const LevelContour b = copy_contour(above, 0.8, out);
  emit_copy_band(b.ids, above.ids, out);
  std::optional<CrossingBand> band = crossing_band(a, 0.4, b, 0.8, true, true, out);
  ASSERT_TRUE(band.has_value());
  ASSERT_TRUE(find_split_faces(*band, out));
  EXPECT_EQ(band->splits.size(), 4u) << "two crossings, each on an edge of both rings";
  // Every face looks up where only the lower disc has material, down where only the upper one has,
  // and their shadows cover the two lunes once: area 2 (r^2 acos(d / 2r) - d/4 sqrt(4r^2 - d^2)) short
  // of the two discs.
  double up = 0.0, down = 0.0;
  for (const Triangle& t : band->mesh.triangles) {
    const Eigen::Vector3d p = band->mesh.position(t[0]), q = band->mesh.position(t[1]), r = band->mesh.position(t[2]);
    const double nz = 0.5 * (q - p).cross(r - p).z();
    const Eigen::Vector2d m = ((p + q + r) / 3.0).head<2>();
    const bool in_a = m.norm() < 5.0, in_b = (m - Eigen::Vector2d(3, 0)).norm() < 5.0;
    if (in_a && !in_b) {
      EXPECT_GT(nz, 0.0);
    }
    if (in_b && !in_a) {
      EXPECT_LT(nz, 0.0);
    }
    (nz > 0.0 ? up : down) += std::abs(nz);
  }
  const double r = 5.0, d = 3.0;
  const double lens = 2.0 * (r * r * std::acos(d / (2.0 * r)) - d / 4.0 * std::sqrt(4.0 * r * r - d * d));
  const double lune = std::numbers::pi * r * r - lens;  // inscribed polygons: a little less
  EXPECT_NEAR(up, lune, 0.03 * lune);
  EXPECT_NEAR(down, lune, 0.03 * lune);
  absorb_crossing_band(std::move(*band), out);
  SlabMesh caps = stack.slab();
  cap_end(below, {}, 0.0, 0.0, false, TilingOptions{}, caps);
  cap_end(above, {}, 1.2, 0.0, true, TilingOptions{}, caps);
  const test::Topology t = test::topology_of(stack.assemble({&out, &caps}));
  EXPECT_TRUE(t.closed && t.manifold) << t.problems;
  EXPECT_EQ(t.euler, 2);
}

TEST(CrossingBand, ASliceContourKeepsItsEdgesAndGetsFansUnderThem) {
  // The copy of a disc below (w 0.6, a composite's ring) and a slice contour 3 mm to its right (w 1.2)
  // that may not be split: its edges stay, and fans join them to the crossings half-way down.
  test::TestStack stack;
  const LevelContour below = stack.contour(circle_points(0, 0, 5, 48), 0.0);
  const LevelContour above = stack.contour(circle_points(3, 0, 5, 48), 1.2);
  SlabMesh out = stack.slab();
  const LevelContour a = copy_contour(below, 0.6, out);
  emit_copy_band(below.ids, a.ids, out);
  std::optional<CrossingBand> band = crossing_band(a, 0.6, above, 1.2, true, false, out);
  ASSERT_TRUE(band.has_value());
  ASSERT_TRUE(find_split_faces(*band, out));
  EXPECT_EQ(band->splits.size(), 2u) << "the copy's two crossed edges";
  absorb_crossing_band(std::move(*band), out);
  for (const Triangle& t : out.triangles) {
    for (std::size_t k = 0; k + 1 < above.ids.size(); ++k) {
      // No face joins two contour points that are not neighbours: the contour's edges are as they were.
      const bool has_k = std::find(t.begin(), t.end(), above.ids[k]) != t.end();
      for (std::size_t j = k + 2; j < above.ids.size() && has_k; ++j) {
        if (k == 0 && j + 1 == above.ids.size()) continue;
        EXPECT_EQ(std::find(t.begin(), t.end(), above.ids[j]), t.end());
      }
    }
  }
  SlabMesh caps = stack.slab();
  cap_end(below, {}, 0.0, 0.0, false, TilingOptions{}, caps);
  cap_end(above, {}, 1.2, 0.0, true, TilingOptions{}, caps);
  const test::Topology t = test::topology_of(stack.assemble({&out, &caps}));
  EXPECT_TRUE(t.closed && t.manifold) << t.problems;
  EXPECT_EQ(t.euler, 2);
}

TEST(CrossingBand, RingsThatDoNotCrossAreLeftToTheBand) {
  test::TestStack stack;
  const LevelContour lower = stack.contour(circle_points(0, 0, 10, 40), 0.4);
  const LevelContour upper = stack.contour(circle_points(0, 0, 4, 20), 0.8);
  EXPECT_FALSE(crossing_band(lower, 0.4, upper, 0.8, true, true, stack.slab()).has_value());
}

}  // namespace
}  // namespace contourmesh::detail
