// SPDX-License-Identifier: BSD-3-Clause
// One slab: bands, caps, refinement, and topology changes through interpolated levels.
#include "detail/slab_tiling.h"

#include <contourmesh/smooth/mesh_quality.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "reconstruct/detail/level_helpers.h"
#include "reconstruct/mesh_checks.h"

namespace contourmesh::detail {
namespace {

using test::arc_points;
using test::circle_points;

// Tiles the levels as a stack: end slabs against empty levels one gap beyond, and each pair.
Mesh tile_levels(test::TestStack& stack, const std::vector<Level>& levels, const TilingOptions& options,
                 std::vector<SlabMesh>* slabs_out = nullptr) {
  std::vector<SlabMesh> slabs;
  slabs.reserve(levels.size() + 1);
  const double gap = levels[1].w - levels[0].w;
  for (std::size_t k = 0; k <= levels.size(); ++k) {
    slabs.push_back(stack.slab());
    Level empty;
    if (k == 0) {
      empty.w = levels[0].w - gap;
      tile_slab(empty, levels[0], options, slabs.back());
    } else if (k == levels.size()) {
      empty.w = levels.back().w + gap;
      tile_slab(levels.back(), empty, options, slabs.back());
    } else {
      tile_slab(levels[k - 1], levels[k], options, slabs.back());
    }
  }
  std::vector<const SlabMesh*> refs;
  for (const SlabMesh& s : slabs) refs.push_back(&s);
  Mesh mesh = stack.assemble(refs);
  if (slabs_out) *slabs_out = std::move(slabs);
  return mesh;
}

TEST(SlabTiling, AShrinkingContourIsRefinedUntilItsBandHasNoSlivers) {
  // A wide disc under a narrow one (a face 10 degrees off the slices): one least-area band is all
  // slivers; the default refines it.
  auto levels = [](test::TestStack& stack) {
    return std::vector<Level>{{0.0, {stack.contour(circle_points(0, 0, 20, 180), 0.0)}},
                              {2.0, {stack.contour(circle_points(0, 0, 9, 80), 2.0)}}};
  };
  TilingOptions plain;
  plain.band_refinement = BandRefinement::None;
  test::TestStack a, b;
  const Mesh raw = tile_levels(a, levels(a), plain);
  const Mesh refined = tile_levels(b, levels(b), TilingOptions{});
  EXPECT_GT(sliver_area_share(raw), 0.1);
  EXPECT_LT(sliver_area_share(refined), 0.02);
  const test::Topology t = test::topology_of(refined);
  EXPECT_TRUE(t.closed && t.manifold) << t.problems;
  EXPECT_EQ(t.euler, 2);
}

TEST(SlabTiling, StatisticsCountTheSlabsGroupsOnce) {
  test::TestStack stack;
  const Level lower{0.0,
                    {stack.contour(circle_points(0, 0, 10, 64), 0.0), stack.contour(circle_points(40, 0, 5, 32), 0.0)}};
  const Level upper{2.0,
                    {stack.contour(circle_points(-6, 0, 5, 32), 2.0), stack.contour(circle_points(6, 0, 5, 32), 2.0),
                     stack.contour(circle_points(40, 0, 5, 32), 2.0)}};
  SlabMesh out = stack.slab();
  tile_slab(lower, upper, TilingOptions{}, out);
  EXPECT_EQ(out.stats.branchings, 1u);
  EXPECT_EQ(out.stats.one_to_one, 1u);
  EXPECT_GT(out.stats.intermediate_contours, 0u);
}

TEST(SlabTiling, SlitsThatMoveAroundAThinWallAreNotJoinedAcrossIt) {
  // A ring wall whose narrow slit turns from slice to slice: each pair is one outer contour to one, but
  // joining them directly spans the wall's inside. No face may be longer than the wall is wide plus a
  // few spacings.
  test::TestStack stack;
  std::vector<Level> levels;
  for (int k = 0; k < 4; ++k) {
    const double a = 0.8 * k;
    levels.push_back(
        {1.5 * k, {stack.contour(arc_points(a + 0.04, a + 2 * std::numbers::pi - 0.04, 18, 21, 120), 1.5 * k)}});
  }
  const Mesh mesh = tile_levels(stack, levels, TilingOptions{});
  const test::Topology t = test::topology_of(mesh);
  EXPECT_TRUE(t.closed && t.manifold) << t.problems;
  double longest = 0.0;
  for (const Triangle& f : mesh.triangles) {
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest, (mesh.positions.col(f[k]) - mesh.positions.col(f[(k + 1) % 3])).norm());
  }
  EXPECT_LT(longest, 12.0);
}

TEST(SlabTiling, IntermediateContoursOfABranchLieBetweenTheSlices) {
  test::TestStack stack;
  const std::vector<Level> levels = {
      {0.0, {stack.contour(circle_points(0, 0, 10, 64), 0.0)}},
      {2.0, {stack.contour(circle_points(-7, 0, 4.5, 32), 2.0), stack.contour(circle_points(7, 0, 4.5, 32), 2.0)}}};
  std::vector<SlabMesh> slabs;
  const Mesh mesh = tile_levels(stack, levels, TilingOptions{}, &slabs);
  const test::Topology t = test::topology_of(mesh);
  EXPECT_TRUE(t.closed && t.manifold) << t.problems;
  EXPECT_EQ(t.euler, 2);
  ASSERT_GT(slabs[1].stats.intermediate_contours, 0u);
  for (const Eigen::Vector3d& v : slabs[1].vertices) {
    EXPECT_GT(v.z(), 0.0);
    EXPECT_LT(v.z(), 2.0);
  }
}

TEST(SlabTiling, DefectsMeasuredAsFacesAreAppendedAreThoseOfTheWholeMesh) {
  // The halves of a branching slab are given up once their flat and sliver area, measured as faces are
  // appended, reaches their rival's: the running measure must be the whole mesh's, bit for bit.
  test::TestStack stack;
  const Level lower{0.0, {stack.contour(circle_points(0, 0, 10, 64), 0.0)}};
  const Level upper{2.0,
                    {stack.contour(circle_points(-7, 0, 4.5, 32), 2.0),
                     stack.contour(circle_points(7, 0, 4.5, 32), 2.0)}};
  SlabMesh slab = stack.slab();
  tile_slab(lower, upper, TilingOptions{}, slab);
  ASSERT_GT(slab.triangles.size(), 10u);
  const TilingDefects whole = measure_defects(slab);
  ASSERT_GT(whole.score(), 0.0);
  for (const std::size_t split : {std::size_t{0}, slab.triangles.size() / 3, slab.triangles.size()}) {
    SlabMesh part = stack.slab();
    part.vertices = slab.vertices;
    part.triangles.assign(slab.triangles.begin(), slab.triangles.begin() + static_cast<std::ptrdiff_t>(split));
    part.roles.assign(slab.roles.begin(), slab.roles.begin() + static_cast<std::ptrdiff_t>(split));
    TilingDefects running;
    measure_more_defects(part, 0, running);
    part.triangles = slab.triangles;
    part.roles = slab.roles;
    measure_more_defects(part, split, running);
    EXPECT_EQ(running.area, whole.area) << split;
    EXPECT_EQ(running.flat_area, whole.flat_area) << split;
    EXPECT_EQ(running.sliver_area, whole.sliver_area) << split;
    EXPECT_EQ(running.poor_area, whole.poor_area) << split;
    EXPECT_EQ(running.bridge_area, whole.bridge_area) << split;
    EXPECT_EQ(running.longest_edge, whole.longest_edge) << split;
  }
}

}  // namespace
}  // namespace contourmesh::detail
