// SPDX-License-Identifier: BSD-3-Clause
// Drawn contours to ordered stacks: slice axis, slices, nesting, orientation, repairs and refusals.
#include <contourmesh/reconstruct/contour_resampling.h>
#include <contourmesh/reconstruct/planar_contours.h>
#include <contourmesh/smooth/errors.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace contourmesh {
namespace {

std::vector<Eigen::Vector3d> square3(double x0, double y0, double size, double z, bool clockwise = false) {
  std::vector<Eigen::Vector3d> p{{x0, y0, z}, {x0 + size, y0, z}, {x0 + size, y0 + size, z}, {x0, y0 + size, z}};
  if (clockwise) std::reverse(p.begin(), p.end());
  return p;
}

std::vector<Eigen::Vector3d> circle3(double cx, double cy, double r, double z, int n = 40) {
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * std::numbers::pi * i / n;
    p.emplace_back(cx + r * std::cos(t), cy + r * std::sin(t), z);
  }
  return p;
}

PlanarContour contour(std::vector<Eigen::Vector3d> points, std::string name = "") {
  return {std::move(points), std::move(name), std::nullopt};
}

std::string error_of(const std::vector<PlanarContour>& contours, const PlanarStackOptions& o = {}) {
  try {
    (void)build_contour_stack(contours, "ROI 7 'Test'", o);
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "";
}

TEST(PlanarContours, AxialContoursKeepPatientCoordinates) {
  const PlanarStack s = build_contour_stack({contour(square3(1, 2, 5, 3.0)), contour(square3(1, 2, 5, 0.0))}, "t");
  EXPECT_EQ(s.stack.axis_w, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(s.stack.axis_u, Eigen::Vector3d::UnitX());
  EXPECT_EQ(s.stack.axis_v, Eigen::Vector3d::UnitY());
  ASSERT_EQ(s.stack.slices.size(), 2u);
  EXPECT_DOUBLE_EQ(s.stack.slices[0].w, 0.0);  // ordered along the axis, whatever the input order
  EXPECT_DOUBLE_EQ(s.stack.slices[1].w, 3.0);
  const Eigen::Vector3d p = s.stack.to_physical(s.stack.slices[1].contours[0].points[0], s.stack.slices[1].w);
  EXPECT_NEAR(p.z(), 3.0, 1e-12);
  EXPECT_EQ(s.report.source[0][0], 1u);
  EXPECT_EQ(s.report.source[1][0], 0u);
}

TEST(PlanarContours, SagittalContoursGetTheXAxis) {
  std::vector<PlanarContour> cs;
  for (const double x : {-2.0, 0.0, 2.0}) {
    cs.push_back(contour({{x, 0, 0}, {x, 4, 0}, {x, 4, 4}, {x, 0, 4}}));
  }
  const PlanarStack s = build_contour_stack(cs, "t");
  EXPECT_EQ(s.stack.axis_w, Eigen::Vector3d::UnitX());
  EXPECT_DOUBLE_EQ(s.stack.axis_u.cross(s.stack.axis_v).dot(s.stack.axis_w), 1.0);
  EXPECT_EQ(s.stack.slices.size(), 3u);
}

TEST(PlanarContours, ObliqueContoursGetAnOrthonormalFrame) {
  const Eigen::Vector3d n = Eigen::Vector3d(1, 2, 3).normalized();
  const Eigen::Vector3d a = n.unitOrthogonal(), b = n.cross(a);
  std::vector<PlanarContour> cs;
  for (const double w : {0.0, 2.5}) {
    std::vector<Eigen::Vector3d> p;
    for (int i = 0; i < 12; ++i) {
      const double t = 2.0 * std::numbers::pi * i / 12;
      p.push_back(w * n + 5.0 * std::cos(t) * a + 5.0 * std::sin(t) * b);
    }
    cs.push_back(contour(p));
  }
  const PlanarStack s = build_contour_stack(cs, "t");
  EXPECT_NEAR(std::abs(s.stack.axis_w.dot(n)), 1.0, 1e-12);
  EXPECT_NEAR(s.stack.axis_u.dot(s.stack.axis_v), 0.0, 1e-12);
  EXPECT_NEAR(s.stack.slices[1].w - s.stack.slices[0].w, 2.5, 1e-9);
}

TEST(PlanarContours, ClockwiseAndCounterClockwiseGiveTheSameStack) {
  const PlanarStack ccw = build_contour_stack({contour(square3(0, 0, 4, 0)), contour(square3(0, 0, 4, 1))}, "t");
  const PlanarStack cw =
      build_contour_stack({contour(square3(0, 0, 4, 0, true)), contour(square3(0, 0, 4, 1, true))}, "t");
  EXPECT_EQ(ccw.report.reversed, 0u);
  EXPECT_EQ(cw.report.reversed, 2u);
  for (const PlanarStack* s : {&ccw, &cw}) {
    for (const auto& sl : s->stack.slices) EXPECT_GT(signed_area(sl.contours[0].points), 0.0);
  }
}

TEST(PlanarContours, NestingMakesHolesAndIslands) {
  // A ring (outer + hole) with an island inside the hole, and a separate part.
  const PlanarStack s = build_contour_stack({contour(circle3(0, 0, 3, 0)), contour(circle3(0, 0, 10, 0)),
                                             contour(circle3(0, 0, 6, 0), "hole"), contour(circle3(30, 0, 4, 0))},
                                            "t");
  const auto& cs = s.stack.slices.at(0).contours;
  ASSERT_EQ(cs.size(), 4u);
  EXPECT_FALSE(cs[0].is_hole);  // island: inside two contours
  EXPECT_FALSE(cs[1].is_hole);
  EXPECT_TRUE(cs[2].is_hole);
  EXPECT_EQ(cs[2].parent, 1);   // the smallest contour around it
  EXPECT_FALSE(cs[3].is_hole);
  EXPECT_LT(signed_area(cs[2].points), 0.0);  // holes clockwise
  EXPECT_GT(signed_area(cs[0].points), 0.0);
  EXPECT_EQ(s.report.hole_contours, 1u);
}

TEST(PlanarContours, RepeatedPointsAreDroppedWithAWarning) {
  auto p = square3(0, 0, 4, 0);
  p.insert(p.begin() + 2, p[1]);
  p.insert(p.begin() + 2, p[1]);
  p.push_back(p.front());  // a closing point: usual, not counted
  const PlanarStack s = build_contour_stack({contour(p, "contour 3"), contour(square3(0, 0, 4, 2))}, "ROI 7 'Test'");
  EXPECT_EQ(s.stack.slices[0].contours[0].points.size(), 4u);
  EXPECT_EQ(s.report.repeated_points, 2u);
  ASSERT_EQ(s.report.warnings.size(), 1u);
  EXPECT_NE(s.report.warnings[0].find("contour 3"), std::string::npos) << s.report.warnings[0];
  EXPECT_NE(s.report.warnings[0].find("ROI 7 'Test'"), std::string::npos);
}

TEST(PlanarContours, AClosingPointAloneIsNoWarning) {
  auto p = square3(0, 0, 4, 0);
  p.push_back(p.front());
  const PlanarStack s = build_contour_stack({contour(p), contour(square3(0, 0, 4, 2))}, "t");
  EXPECT_TRUE(s.report.warnings.empty());
  EXPECT_EQ(s.stack.slices[0].contours[0].points.size(), 4u);
}

TEST(PlanarContours, DegenerateContoursAreSkippedWithAWarning) {
  const PlanarStack s = build_contour_stack({contour({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, "contour 2"),
                                             contour(square3(0, 0, 4, 0)), contour(square3(0, 0, 4, 2))},
                                            "t");
  EXPECT_EQ(s.report.dropped_contours, 1u);
  EXPECT_EQ(s.stack.num_contours(), 2u);
  ASSERT_FALSE(s.report.warnings.empty());
  EXPECT_NE(s.report.warnings[0].find("contour 2"), std::string::npos);
}

TEST(PlanarContours, NonPlanarContourIsAnErrorNamingIt) {
  auto p = square3(0, 0, 10, 0);
  p[2].z() = 1.0;
  const std::string e = error_of({contour(p, "contour 5"), contour(square3(0, 0, 10, 3))});
  EXPECT_NE(e.find("ROI 7 'Test'"), std::string::npos) << e;
  EXPECT_NE(e.find("contour 5"), std::string::npos) << e;
  EXPECT_NE(e.find("not planar"), std::string::npos) << e;
}

TEST(PlanarContours, TiltedContourIsAnErrorNamingIt) {
  std::vector<Eigen::Vector3d> tilted{{0, 0, 0}, {10, 0, 0}, {10, 10, 3}, {0, 10, 3}};
  const std::string e = error_of({contour(square3(0, 0, 10, 0)), contour(square3(0, 0, 10, 3)),
                                  contour(square3(0, 0, 10, 6)), contour(tilted, "contour 4")});
  EXPECT_NE(e.find("contour 4"), std::string::npos) << e;
  EXPECT_NE(e.find("tilted"), std::string::npos) << e;
}

TEST(PlanarContours, SelfIntersectionIsAnErrorNamingTheContour) {
  std::vector<Eigen::Vector3d> bow{{0, 0, 0}, {4, 4, 0}, {4, 0, 0}, {0, 4, 0}};
  const std::string e = error_of({contour(bow, "contour 9"), contour(square3(0, 0, 4, 2))});
  EXPECT_NE(e.find("contour 9"), std::string::npos) << e;
  EXPECT_NE(e.find("intersects itself"), std::string::npos) << e;
}

TEST(PlanarContours, ContoursOfASliceThatMeetAreAnError) {
  const std::string e = error_of({contour(square3(0, 0, 4, 0), "contour 1"), contour(square3(2, 2, 4, 0), "contour 2"),
                                  contour(square3(0, 0, 4, 2))});
  EXPECT_NE(e.find("contour 1"), std::string::npos) << e;
  EXPECT_NE(e.find("contour 2"), std::string::npos) << e;
  EXPECT_NE(e.find("meet"), std::string::npos) << e;
}

TEST(PlanarContours, GapsAreWarningsNotErrors) {
  std::vector<PlanarContour> cs;
  for (const double z : {0.0, 3.0, 6.0, 9.0, 18.0, 21.0}) cs.push_back(contour(square3(0, 0, 4, z)));
  const PlanarStack s = build_contour_stack(cs, "ROI 7 'Test'");
  EXPECT_EQ(s.stack.slices.size(), 6u);
  EXPECT_DOUBLE_EQ(s.report.typical_spacing, 3.0);
  EXPECT_DOUBLE_EQ(s.report.largest_gap, 9.0);
  ASSERT_EQ(s.report.warnings.size(), 1u);
  EXPECT_NE(s.report.warnings[0].find("9.00 mm apart"), std::string::npos) << s.report.warnings[0];
  // 1.5 x the spacing exactly is not a gap.
  cs.back() = contour(square3(0, 0, 4, 13.5));
  cs[4] = contour(square3(0, 0, 4, 9.0 + 4.5));
  cs.pop_back();
  EXPECT_TRUE(build_contour_stack(cs, "t").report.warnings.empty());
}

TEST(PlanarContours, SliceIdsGroupContoursWhatEverTheirPositions) {
  std::vector<PlanarContour> cs{contour(square3(0, 0, 4, 0.0)), contour(square3(10, 0, 4, 0.04)),
                                contour(square3(0, 0, 4, 2.0))};
  cs[0].slice_id = 5;
  cs[1].slice_id = 5;
  cs[2].slice_id = 6;
  const PlanarStack s = build_contour_stack(cs, "t");
  ASSERT_EQ(s.stack.slices.size(), 2u);
  EXPECT_EQ(s.stack.slices[0].contours.size(), 2u);
  // Two ids in one plane are refused.
  std::vector<PlanarContour> same{contour(square3(0, 0, 4, 1.0)), contour(square3(20, 0, 4, 1.0))};
  same[0].slice_id = 5;
  same[1].slice_id = 7;
  EXPECT_NE(error_of(same).find("same plane"), std::string::npos) << error_of(same);
}

TEST(PlanarContours, NoContoursIsAnError) { EXPECT_NE(error_of({}).find("no contours"), std::string::npos); }

TEST(PlanarContours, NonFiniteCoordinatesAreAnError) {
  auto p = square3(0, 0, 4, 0);
  p[1].x() = std::nan("");
  EXPECT_NE(error_of({contour(p, "contour 2")}).find("not finite"), std::string::npos);
}

TEST(PlanarContours, SlicewiseVolumeFollowsTheRadiotherapyConvention) {
  // 10 x 10 squares at z = 0, 2, 6: slabs 2, 3, 4 mm thick (the ends reach half a spacing beyond).
  std::vector<PlanarContour> cs;
  for (const double z : {0.0, 2.0, 6.0}) cs.push_back(contour(square3(0, 0, 10, z)));
  const PlanarStack s = build_contour_stack(cs, "t");
  const std::vector<double> t = slice_thicknesses(s.stack);
  EXPECT_DOUBLE_EQ(t[0], 2.0);
  EXPECT_DOUBLE_EQ(t[1], 3.0);
  EXPECT_DOUBLE_EQ(t[2], 4.0);
  EXPECT_DOUBLE_EQ(slicewise_volume(s.stack), 100.0 * 9.0);
  // A hole subtracts.
  cs.push_back(contour(square3(2, 2, 2, 2.0, true)));
  EXPECT_DOUBLE_EQ(slicewise_volume(build_contour_stack(cs, "t").stack), 100.0 * 9.0 - 4.0 * 3.0);
}

TEST(PlanarContours, NormalizeRecomputesHolesAndOrientation) {
  ContourStack st;
  Contour outer;
  outer.points = {{0, 0}, {0, 10}, {10, 10}, {10, 0}};  // clockwise
  Contour inner;
  inner.points = {{2, 2}, {4, 2}, {4, 4}, {2, 4}};  // counter-clockwise, not flagged
  st.slices = {{0.0, {outer, inner}}, {1.0, {outer}}};
  const PlanarStackReport r = normalize_contour_stack(st, "file.json");
  EXPECT_TRUE(st.slices[0].contours[1].is_hole);
  EXPECT_EQ(st.slices[0].contours[1].parent, 0);
  EXPECT_GT(signed_area(st.slices[0].contours[0].points), 0.0);
  EXPECT_LT(signed_area(st.slices[0].contours[1].points), 0.0);
  EXPECT_EQ(r.hole_contours, 1u);
  // Slices out of order are refused.
  std::swap(st.slices[0], st.slices[1]);
  EXPECT_THROW((void)normalize_contour_stack(st, "file.json"), InvalidInputError);
}

TEST(ResampleDrawn, KeepsCornersAndBoundsTheSpacing) {
  const std::vector<Eigen::Vector2d> square{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  const auto r = resample_drawn(square, 1.0, 0.05);
  EXPECT_EQ(r.size(), 40u);
  for (const auto& corner : square) {
    EXPECT_TRUE(std::any_of(r.begin(), r.end(), [&](const Eigen::Vector2d& p) { return (p - corner).norm() < 1e-12; }));
  }
  for (std::size_t i = 0; i < r.size(); ++i) EXPECT_LE((r[(i + 1) % r.size()] - r[i]).norm(), 1.0 + 1e-9);
}

TEST(ResampleDrawn, MergesDensePointsWithinTheTolerance) {
  // A circle drawn with 2000 points: about 63 mm long, so about 63 points at 1 mm, all within 0.05 mm.
  std::vector<Eigen::Vector2d> circle;
  for (int i = 0; i < 2000; ++i) {
    const double t = 2.0 * std::numbers::pi * i / 2000;
    circle.emplace_back(10.0 * std::cos(t), 10.0 * std::sin(t));
  }
  const auto r = resample_drawn(circle, 1.0, 0.05);
  EXPECT_GT(r.size(), 55u);
  EXPECT_LT(r.size(), 80u);
  for (const auto& p : r) EXPECT_NEAR(p.norm(), 10.0, 1e-9);  // points stay on the drawn polygon
  // Chords depart from the circle by at most the tolerance.
  for (std::size_t i = 0; i < r.size(); ++i)
    EXPECT_GE((0.5 * (r[i] + r[(i + 1) % r.size()])).norm(), 10.0 - 0.05 - 1e-3);
}

TEST(ResampleDrawn, SmallerThanTheSpacingKeepsTheDrawnShape) {
  const std::vector<Eigen::Vector2d> tiny{{0, 0}, {0.2, 0}, {0.2, 0.2}, {0, 0.2}};
  EXPECT_EQ(resample_drawn(tiny, 1.0, 0.05).size(), 4u);
}

TEST(ResampleDrawnStack, EvensOutEdgesForTheRefinedCaps) {
  // Dense drawing (0.25 mm, slightly wavy so that nothing simplifies) on three sides, one long side:
  // the longest edge ends within 1.4 x the mean.
  ContourStack st;
  Contour c;
  for (int i = 0; i < 40; ++i) c.points.emplace_back(10.0 * i / 40.0, 0.01 * (i % 2));
  for (int i = 0; i < 40; ++i) c.points.emplace_back(10.0 + 0.01 * (i % 2), 10.0 * i / 40.0);
  c.points.emplace_back(10.0, 10.0);
  for (int i = 40; i > 0; --i) c.points.emplace_back(0.01 * (i % 2), 10.0 * i / 40.0);
  st.slices = {{0.0, {c}}};
  (void)normalize_contour_stack(st, "t");
  (void)resample_drawn_stack(st, 4.0, 0.0);
  const auto& p = st.slices[0].contours[0].points;
  double longest = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) longest = std::max(longest, (p[(i + 1) % p.size()] - p[i]).norm());
  EXPECT_LE(longest, 1.4 * perimeter(p) / static_cast<double>(p.size()) + 1e-9);
}

}  // namespace
}  // namespace contourmesh
