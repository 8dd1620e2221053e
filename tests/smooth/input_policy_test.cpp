// SPDX-License-Identifier: BSD-3-Clause
// The one input policy (prepare_input_mesh): what is refused, repaired or tolerated, and how contour
// ids are made usable; and the divergence guard that stops a smoother whose result means nothing.
#include <contourmesh/smooth/divergence.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/input_policy.h>
#include <contourmesh/smooth/metrics.h>
#include <contourmesh/smooth/shapes.h>
#include <contourmesh/smooth/smoothing.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "test_meshes.h"

namespace contourmesh {
namespace {

Mesh ridge_stack() {
  ContourStackSpec spec;
  spec.curve = ridge_circle_curve(10.0, 2.0, 0.4);
  spec.slices = 8;
  spec.points_per_contour = 40;
  return make_contour_stack(spec);
}

std::string error_of(const Mesh& mesh, const InputPolicyOptions& options = {}) {
  try {
    (void)prepare_input_mesh(mesh, options);
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "";
}

bool has_warning(const PreparedMesh& p, const std::string& fragment) {
  for (const std::string& w : p.warnings) {
    if (w.find(fragment) != std::string::npos) return true;
  }
  return false;
}

InputPolicyOptions for_detection() {
  InputPolicyOptions o;
  o.ids = ContourIdUse::Detection;
  return o;
}

TEST(InputPolicy, ACleanMeshPassesUnchangedWithoutWarnings) {
  const Mesh m = ridge_stack();
  const PreparedMesh p = prepare_input_mesh(m, for_detection());
  EXPECT_TRUE(p.warnings.empty()) << p.warnings.front();
  EXPECT_EQ(p.id_source, IdSource::File);
  EXPECT_EQ(p.mesh.triangles, m.triangles);
  EXPECT_EQ(p.mesh.slice_ids, m.slice_ids);
}

TEST(InputPolicy, NonFiniteAndOverflowingCoordinatesAreRefusedNamingTheVertex) {
  Mesh m = test::tetrahedron();
  m.positions(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(error_of(m).find("vertex 2 has a non-finite coordinate"), std::string::npos) << error_of(m);
  m.positions(1, 2) = 1e200;  // its cube overflows: volumes and areas would be inf, then NaN
  EXPECT_NE(error_of(m).find("vertex 2 has a coordinate beyond +-1e30"), std::string::npos) << error_of(m);
  m.positions(1, 2) = -1e30;
  EXPECT_EQ(error_of(m), "");
}

TEST(InputPolicy, IdsBelowMinusOneAreRefusedNamingTheVertex) {
  Mesh m = ridge_stack();
  m.slice_ids[17] = -7;
  for (ContourIdUse use : {ContourIdUse::PassThrough, ContourIdUse::Detection}) {
    InputPolicyOptions o;
    o.ids = use;
    EXPECT_NE(error_of(m, o).find("vertex 17 has slice id -7"), std::string::npos) << error_of(m, o);
  }
  m.slice_ids[17] = kNoId;  // -1 is legal (a vertex on no slice)
  EXPECT_EQ(error_of(m, for_detection()), "");
}

TEST(InputPolicy, HalfTheTrianglesFlippedAreTurnedBackWithAWarning) {
  const Mesh clean = ridge_stack();
  const double volume = enclosed_volume(clean);
  for (int parity : {0, 1}) {
    Mesh m = clean;
    for (std::size_t f = parity; f < m.triangles.size(); f += 2) std::swap(m.triangles[f][1], m.triangles[f][2]);
    ASSERT_LT(std::abs(enclosed_volume(m)), 0.2 * volume) << "the damage shows in the volume";
    const PreparedMesh p = prepare_input_mesh(m);
    EXPECT_EQ(p.mesh.triangles, clean.triangles) << "parity " << parity;
    EXPECT_NEAR(enclosed_volume(p.mesh), volume, 1e-9 * volume);
    EXPECT_TRUE(has_warning(p, "faced against their neighbours") || has_warning(p, "inside out")) << parity;
  }
}

TEST(InputPolicy, AnInsideOutClosedMeshIsTurnedOverButACavityIsNot) {
  Mesh inside_out = make_icosphere(2);
  for (Triangle& t : inside_out.triangles) std::swap(t[1], t[2]);
  const PreparedMesh p = prepare_input_mesh(inside_out);
  EXPECT_GT(enclosed_volume(p.mesh), 0.0);
  EXPECT_TRUE(has_warning(p, "inside out"));
  // A hollow ball: the inner sphere faces into the cavity and must stay so.
  Mesh hollow = make_icosphere(2, 2.0);
  const Mesh inner = make_icosphere(2, 1.0);
  const Index n = hollow.num_vertices();
  hollow.positions.conservativeResize(3, n + inner.num_vertices());
  hollow.positions.rightCols(inner.num_vertices()) = inner.positions;
  for (Triangle t : inner.triangles) hollow.triangles.push_back({t[0] + n, t[2] + n, t[1] + n});
  const double volume = enclosed_volume(hollow);
  const PreparedMesh q = prepare_input_mesh(hollow);
  EXPECT_NEAR(enclosed_volume(q.mesh), volume, 1e-12);
  EXPECT_TRUE(q.warnings.empty());
}

TEST(InputPolicy, RefusalOfInconsistentOrientationNamesTwoTriangles) {
  Mesh m = test::tetrahedron();
  std::swap(m.triangles[3][1], m.triangles[3][2]);
  InputPolicyOptions o;
  o.orientation = OrientationPolicy::Refuse;
  EXPECT_NE(error_of(m, o).find("inconsistent orientation: triangles"), std::string::npos) << error_of(m, o);
  EXPECT_EQ(find_orientation_conflict(test::tetrahedron()), std::nullopt);
}

TEST(InputPolicy, AMoebiusStripIsRefused) {
  // A strip of 6 quads whose ends are joined with a half twist.
  Mesh m;
  const int n = 6;
  m.positions.resize(3, 2 * n);
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * M_PI * k / n, twist = a / 2.0;
    const Eigen::Vector3d c(std::cos(a), std::sin(a), 0.0);
    const Eigen::Vector3d d = 0.3 * (std::cos(twist) * c + std::sin(twist) * Eigen::Vector3d::UnitZ());
    m.positions.col(2 * k) = c + d;
    m.positions.col(2 * k + 1) = c - d;
  }
  for (int k = 0; k < n; ++k) {
    const Index a = 2 * k, b = 2 * k + 1;
    const Index c = k + 1 < n ? 2 * (k + 1) : 1, d = k + 1 < n ? 2 * (k + 1) + 1 : 0;  // the twist swaps sides
    m.triangles.push_back({a, b, c});
    m.triangles.push_back({b, d, c});
  }
  EXPECT_NE(error_of(m).find("not orientable"), std::string::npos) << error_of(m);
}

TEST(InputPolicy, EveryIdMinusOneCountsAsNoIds) {
  Mesh m = ridge_stack();
  std::fill(m.slice_ids.begin(), m.slice_ids.end(), kNoId);
  std::fill(m.contour_ids.begin(), m.contour_ids.end(), kNoId);
  const PreparedMesh p = prepare_input_mesh(m, for_detection());
  EXPECT_EQ(p.detection_mode, DetectionMode::CurvatureOnly);
  EXPECT_TRUE(has_warning(p, "every slice id is -1"));
  InputPolicyOptions axis = for_detection();
  axis.slice_axis = Eigen::Vector3d::UnitZ();
  const PreparedMesh q = prepare_input_mesh(m, axis);
  EXPECT_EQ(q.id_source, IdSource::SlicePlanes);
  EXPECT_EQ(q.detection_mode, DetectionMode::ContourContinuity);
}

TEST(InputPolicy, IdsAllEqualAcrossManyPlanesAreRefusedOrRecoveredAlongTheGivenAxis) {
  const Mesh clean = ridge_stack();
  Mesh m = clean;
  std::fill(m.slice_ids.begin(), m.slice_ids.end(), 0);
  std::fill(m.contour_ids.begin(), m.contour_ids.end(), 0);
  EXPECT_NE(error_of(m, for_detection()).find("every vertex has slice id 0, but the vertices do not lie in one plane"),
            std::string::npos)
      << error_of(m, for_detection());
  InputPolicyOptions axis = for_detection();
  axis.slice_axis = Eigen::Vector3d::UnitZ();
  const PreparedMesh p = prepare_input_mesh(m, axis);
  EXPECT_EQ(p.id_source, IdSource::SlicePlanes);
  EXPECT_TRUE(has_warning(p, "recovered the ids from the slice planes along z"));
  // The recovered slice ids order the planes as the clean ones do (caps included).
  std::set<std::int32_t> slices(p.mesh.slice_ids.begin(), p.mesh.slice_ids.end());
  EXPECT_GE(slices.size(), 8u);
  // Unused ids pass through for the baselines.
  EXPECT_EQ(error_of(m), "");
}

TEST(InputPolicy, MissingIdsFallBackOrAreRefusedAsAsked) {
  Mesh m = ridge_stack();
  m.slice_ids.clear();
  m.contour_ids.clear();
  PreparedMesh p = prepare_input_mesh(m, for_detection());
  EXPECT_EQ(p.detection_mode, DetectionMode::CurvatureOnly);
  EXPECT_TRUE(has_warning(p, "has no contour ids"));
  InputPolicyOptions refuse = for_detection();
  refuse.missing_ids = MissingIds::Refuse;
  EXPECT_NE(error_of(m, refuse).find("has no contour ids"), std::string::npos);
  InputPolicyOptions x = for_detection();
  x.slice_axis = Eigen::Vector3d::UnitX();
  add_noise(m, {0.1, 5, NoiseDirection::InPlane});  // off any plane normal to x
  EXPECT_NE(error_of(m, x).find("do not lie on planes normal to the slice axis x"), std::string::npos)
      << error_of(m, x);
}

TEST(InputPolicy, GappedIdsAreCompactedWithAWarning) {
  Mesh m = ridge_stack();
  for (auto& s : m.slice_ids) s += s >= 4 ? 1 : 0;
  const PreparedMesh p = prepare_input_mesh(m, for_detection());
  EXPECT_EQ(p.mesh.slice_ids, ridge_stack().slice_ids);
  EXPECT_TRUE(has_warning(p, "skip 1 unused value"));
}

TEST(DivergenceGuard, ATaubinRunForAMillionIterationsStopsWithAnError) {
  const Mesh m = ridge_stack();
  SmoothingOptions o;
  o.method = SmoothingMethod::Taubin;
  o.iterations = 1'000'000;
  o.on_iteration = divergence_guard(m.positions, "smoothing");
  try {
    (void)smooth(m, o);
    FAIL() << "a million Taubin iterations amplify the high frequencies until they overflow";
  } catch (const DivergenceError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("smoothing diverged at iteration"), std::string::npos) << what;
  }
}

TEST(DivergenceGuard, ConvergingRunsPass) {
  const Mesh m = ridge_stack();
  SmoothingOptions o;
  o.iterations = 200;
  o.on_iteration = divergence_guard(m.positions, "smoothing");
  EXPECT_NO_THROW((void)smooth(m, o));
  Eigen::Matrix3Xd p = m.positions;
  p(0, 3) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(check_not_diverged(p, DivergenceBounds::of(m.positions), "x"), DivergenceError);
}

}  // namespace
}  // namespace contourmesh
