// SPDX-License-Identifier: BSD-3-Clause
// Which contours of adjacent levels belong together, and how a group changes.
#include "detail/correspondence.h"

#include <gtest/gtest.h>

#include "reconstruct/detail/level_helpers.h"

namespace contourmesh::detail {
namespace {

using test::arc_points;
using test::circle_points;

TEST(Correspondence, OverlappingOuterContoursLinkAndFarOnesDoNot) {
  test::TestStack stack;
  Level lower{0.0, {stack.contour(circle_points(0, 0, 10, 60), 0.0), stack.contour(circle_points(40, 0, 5, 30), 0.0)}};
  Level upper{2.0, {stack.contour(circle_points(3, 0, 10, 60), 2.0), stack.contour(circle_points(-40, 0, 5, 30), 2.0)}};
  const Correspondence c = correspond(lower, upper, 0.05, 0.01);
  EXPECT_EQ(c.up[0], std::vector<int>{0});
  EXPECT_TRUE(c.up[1].empty());
  EXPECT_EQ(c.down[0], std::vector<int>{0});
  EXPECT_TRUE(c.down[1].empty());
  const auto groups = contour_groups(lower, upper, c);
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(classify_group(groups[0], lower, upper, c), GroupChange::OneToOne);
  EXPECT_EQ(classify_group(groups[1], lower, upper, c), GroupChange::EndsAbove);
  EXPECT_EQ(classify_group(groups[2], lower, upper, c), GroupChange::EndsBelow);
}

TEST(Correspondence, AnOverlapBelowTheFractionOfTheSmallerIsNoLink) {
  test::TestStack stack;
  // Two unit squares overlapping by 0.1 x 1.
  const Polygon a = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, b = {{0.9, 0}, {1.9, 0}, {1.9, 1}, {0.9, 1}};
  const Level lower{0.0, {stack.contour(a, 0.0)}}, upper{1.0, {stack.contour(b, 1.0)}};
  EXPECT_TRUE(correspond(lower, upper, 0.05, 0.01).up[0].size() == 1);
  EXPECT_TRUE(correspond(lower, upper, 0.2, 0.01).up[0].empty());
}

TEST(Correspondence, HolesLinkOnlyWhenTheirOuterContoursDo) {
  test::TestStack stack;
  Level lower{
      0.0,
      {stack.contour(circle_points(0, 0, 10, 60), 0.0), stack.contour(circle_points(0, 0, 4, 30, true), 0.0, true, 0)}};
  Level upper{
      2.0,
      {stack.contour(circle_points(0, 0, 10, 60), 2.0), stack.contour(circle_points(0, 0, 4, 30, true), 2.0, true, 0)}};
  std::vector<std::pair<int, int>> pairs;
  const Correspondence c = correspond(lower, upper, 0.05, 0.01);
  EXPECT_EQ(c.up[1], std::vector<int>{1});
  const auto groups = contour_groups(lower, upper, c);
  ASSERT_EQ(groups.size(), 1u);  // the hole goes with its outer contour
  EXPECT_EQ(classify_group(groups[0], lower, upper, c, &pairs), GroupChange::OneToOne);
  EXPECT_EQ(pairs, (std::vector<std::pair<int, int>>{{0, 0}, {1, 1}}));
  // Without the outer link (far outer contour above), the holes do not link either.
  Level far{2.0,
            {stack.contour(circle_points(100, 0, 10, 60), 2.0),
             stack.contour(circle_points(100, 0, 4, 30, true), 2.0, true, 0)}};
  EXPECT_TRUE(correspond(lower, far, 0.05, 0.01).up[1].empty());
}

TEST(Correspondence, AHoleOpensWhereTheOtherLevelHasNoWallAndEndsWhereItIsCovered) {
  test::TestStack stack;
  // A tube's ring below two arcs of its wall (the hole's region is background above: it opens) ...
  Level ring{
      0.0,
      {stack.contour(circle_points(0, 0, 12, 80), 0.0), stack.contour(circle_points(0, 0, 8, 60, true), 0.0, true, 0)}};
  Level arcs{
      2.0,
      {stack.contour(arc_points(0.3, 2.84, 8, 12, 30), 2.0), stack.contour(arc_points(3.44, 5.98, 8, 12, 30), 2.0)}};
  const Correspondence open = correspond(ring, arcs, 0.05, 0.01);
  EXPECT_TRUE(open.up[1].empty());
  EXPECT_TRUE(open.opens_up[1]);
  const auto groups = contour_groups(ring, arcs, open);
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(classify_group(groups[0], ring, arcs, open), GroupChange::Topology);
  // ... and below a full disc (the material covers it: the cavity ends).
  Level disc{2.0, {stack.contour(circle_points(0, 0, 12, 80), 2.0)}};
  const Correspondence covered = correspond(ring, disc, 0.05, 0.01);
  EXPECT_FALSE(covered.opens_up[1]);
  EXPECT_EQ(classify_group(contour_groups(ring, disc, covered)[0], ring, disc, covered), GroupChange::Topology);
}

TEST(Correspondence, AGroupsRestrictedLinksAreThoseOfItsRestrictedLevels) {
  // Two pieces: a far disc, and a tube whose hole opens under two arcs of its wall. The tube's group,
  // taken out of the links of both, is what correspond finds for its contours alone.
  test::TestStack stack;
  Level lower{0.0,
              {stack.contour(circle_points(60, 0, 5, 30), 0.0), stack.contour(circle_points(0, 0, 12, 80), 0.0),
               stack.contour(circle_points(0, 0, 8, 60, true), 0.0, true, 1)}};
  Level upper{2.0,
              {stack.contour(arc_points(0.3, 2.84, 8, 12, 30), 2.0), stack.contour(circle_points(61, 0, 5, 30), 2.0),
               stack.contour(arc_points(3.44, 5.98, 8, 12, 30), 2.0)}};
  const Correspondence all = correspond(lower, upper, 0.05, 0.01);
  const auto groups = contour_groups(lower, upper, all);
  ASSERT_EQ(groups.size(), 2u);
  for (const ContourGroup& group : groups) {
    const Correspondence restricted = restrict_correspondence(all, group);
    const Correspondence direct =
        correspond(restrict_level(lower, group.lower), restrict_level(upper, group.upper), 0.05, 0.01);
    EXPECT_EQ(restricted.up, direct.up);
    EXPECT_EQ(restricted.down, direct.down);
    EXPECT_EQ(restricted.opens_up, direct.opens_up);
    EXPECT_EQ(restricted.opens_down, direct.opens_down);
    EXPECT_EQ(restricted.over_hole_up, direct.over_hole_up);
    EXPECT_EQ(restricted.over_hole_down, direct.over_hole_down);
  }
  // The tube's group renumbers its contours: its hole (lower 2) becomes 1, and it opens.
  const ContourGroup& tube = groups[0].lower.front() == 1 ? groups[0] : groups[1];
  const Correspondence t = restrict_correspondence(all, tube);
  ASSERT_EQ(t.up.size(), 2u);
  EXPECT_EQ(t.up[0], (std::vector<int>{0, 1}));
  EXPECT_TRUE(t.opens_up[1]);
}

// A pocket in a wide wall whose region lies, on the other level, inside the wall's large cavity (a diploe
// cavity over the cranial cavity where the skull's roof is nearly flat): it opens, but over a hole.
TEST(Correspondence, APocketOverTheOtherLevelsCavityOpensOverAHole) {
  test::TestStack stack;
  // Below: a disc of radius 30 with a cavity of radius 20; above: the same disc with a smaller cavity
  // (radius 10) and a pocket (radius 2 at x = 15) over the cavity below (under 1 % of it: no link).
  Level below{0.0,
              {stack.contour(circle_points(0, 0, 30, 120), 0.0),
               stack.contour(circle_points(0, 0, 20, 100, true), 0.0, true, 0)}};
  Level above{
      2.0,
      {stack.contour(circle_points(0, 0, 30, 120), 2.0), stack.contour(circle_points(0, 0, 10, 60, true), 2.0, true, 0),
       stack.contour(circle_points(15, 0, 2, 12, true), 2.0, true, 0)}};
  const Correspondence c = correspond(below, above, 0.05, 0.01);
  EXPECT_TRUE(c.down[2].empty());
  EXPECT_TRUE(c.opens_down[2]);
  EXPECT_TRUE(c.over_hole_down[2]);
  EXPECT_FALSE(c.over_hole_down[1]);
  // Over the outside instead (the wall below ends at radius 14): it opens, not over a hole.
  Level narrow{
      0.0,
      {stack.contour(circle_points(0, 0, 14, 80), 0.0), stack.contour(circle_points(0, 0, 8, 60, true), 0.0, true, 0)}};
  Level wide{
      2.0,
      {stack.contour(circle_points(0, 0, 30, 120), 2.0), stack.contour(circle_points(0, 0, 8, 60, true), 2.0, true, 0),
       stack.contour(circle_points(20, 0, 2, 12, true), 2.0, true, 0)}};
  const Correspondence d = correspond(narrow, wide, 0.05, 0.01);
  EXPECT_TRUE(d.opens_down[2]);
  EXPECT_FALSE(d.over_hole_down[2]);
}

TEST(Correspondence, ASpeckInsideALargeContourDoesNotContinueIt) {
  // A 1 mm^2 speck wholly inside a 300 mm^2 disc: all of the speck overlaps, but under 1 % of the disc.
  test::TestStack stack;
  const Level lower{0.0, {stack.contour(circle_points(0, 0, 10, 60), 0.0)}};
  const Level upper{1.0, {stack.contour(circle_points(3, 0, 0.6, 8), 1.0)}};
  EXPECT_TRUE(correspond(lower, upper, 0.05, 0.01).up[0].empty());
  EXPECT_EQ(correspond(lower, upper, 0.05, 0.0).up[0].size(), 1u);
}

TEST(Correspondence, OneContourOverTwoIsATopologyChange) {
  test::TestStack stack;
  Level lower{0.0, {stack.contour(circle_points(0, 0, 10, 60), 0.0)}};
  Level upper{2.0, {stack.contour(circle_points(-6, 0, 5, 30), 2.0), stack.contour(circle_points(6, 0, 5, 30), 2.0)}};
  const Correspondence c = correspond(lower, upper, 0.05, 0.01);
  const auto groups = contour_groups(lower, upper, c);
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups[0].upper, (std::vector<int>{0, 1}));
  EXPECT_EQ(classify_group(groups[0], lower, upper, c), GroupChange::Topology);
}

}  // namespace
}  // namespace contourmesh::detail
