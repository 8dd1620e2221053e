// SPDX-License-Identifier: BSD-3-Clause
// Numerical corner cases of issue 7: degenerate 1-rings (collinear neighbours, valence 3), a sphere
// (umbilic everywhere), flat regions (zero curvature), and meshes scaled by 1e-6 and 1e6. Curvatures,
// umbrellas, labels and smoothed positions must stay finite, and the labels must not depend on the
// mesh's scale. fuzz_features (tests/fuzz) explores the same ground at random.
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/curvature.h>
#include <contourmesh/smooth/feature_detection.h>
#include <contourmesh/smooth/feature_smoothing.h>
#include <contourmesh/smooth/shapes.h>
#include <contourmesh/smooth/umbrella.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "test_meshes.h"

namespace contourmesh {
namespace {

int count_label(const FeatureDetection& d, VertexLabel l) {
  return static_cast<int>(std::count(d.labels.begin(), d.labels.end(), l));
}

// Every number the detection and the paper's smoothing return is finite; returns the detection.
FeatureDetection expect_finite_everywhere(const Mesh& m, const DetectionOptions& detection) {
  const MeshAdjacency adj = build_adjacency(m);
  const PrincipalCurvatures c = principal_curvatures(m.positions, m.triangles, adj);
  EXPECT_TRUE(c.kappa_min.allFinite() && c.kappa_max.allFinite());
  EXPECT_TRUE(c.direction_min.allFinite() && c.direction_max.allFinite() && c.normals.allFinite());
  EXPECT_TRUE(umbrella(m.positions, adj).allFinite());
  const FeatureDetection d = detect_features(m, adj, detection);
  EXPECT_EQ(d.labels.size(), static_cast<std::size_t>(m.num_vertices()));
  EXPECT_TRUE(d.umbrella.allFinite());
  EXPECT_TRUE(std::isfinite(d.gamma) && std::isfinite(d.mean_umbrella));
  for (Index i = 0; i < m.num_vertices(); ++i) {
    if (d.labels[i] == VertexLabel::Corner || d.labels[i] == VertexLabel::Noise) {
      // psi is computed for umbilic candidates only; it is finite where computed.
      EXPECT_FALSE(std::isinf(d.psi[i])) << i;
    }
  }
  FeatureSmoothingOptions o;
  o.detection = detection;
  const FeatureSmoothingResult r = feature_preserving_smooth(m, o);
  EXPECT_TRUE(r.mesh.positions.allFinite());
  EXPECT_EQ(r.detection.labels, d.labels);
  return d;
}

DetectionOptions curvature_only() {
  DetectionOptions o;
  o.mode = DetectionMode::CurvatureOnly;
  return o;
}

TEST(NumericalCornerCases, CollinearOneRingsGiveFiniteResults) {
  // An icosphere with the 1-ring of vertex 0 flattened onto a line through it (every neighbour
  // collinear with it and each other: its triangles have zero area), and a vertex of another ring
  // moved onto the midpoint of an edge (one zero-area triangle, a straight angle).
  Mesh m = make_icosphere(2, 5.0);
  const MeshAdjacency adj = build_adjacency(m);
  const Eigen::Vector3d centre = m.positions.col(0);
  const Eigen::Vector3d line = centre.unitOrthogonal();
  const auto ring = adj.ring(0);
  for (std::size_t k = 0; k < ring.size(); ++k) {
    m.positions.col(ring[k]) = centre + (static_cast<double>(k) - 2.0) * 0.5 * line;
  }
  const Triangle& t = m.triangles[100];
  m.positions.col(t[0]) = 0.5 * (m.positions.col(t[1]) + m.positions.col(t[2]));
  expect_finite_everywhere(m, curvature_only());
}

TEST(NumericalCornerCases, ValenceThreeVerticesGiveFiniteResults) {
  // Every vertex of a tetrahedron and the 8 corners of a coarse cube have valence 3.
  expect_finite_everywhere(test::tetrahedron(), curvature_only());
  const FeatureDetection cube = expect_finite_everywhere(make_cube(1, 2.0), curvature_only());
  EXPECT_EQ(count_label(cube, VertexLabel::Edge), 0) << "a cube's corners are not edges";
  // A contour stack over a triangle: valence-3 rings on the caps' rims, with contour ids.
  ContourStackSpec spec;
  spec.curve = [](double t) {
    const double a = 2.0 * std::numbers::pi * t;
    return Eigen::Vector2d(4.0 * std::cos(a), 4.0 * std::sin(a));
  };
  spec.slices = 4;
  spec.points_per_contour = 3;
  expect_finite_everywhere(make_contour_stack(spec), DetectionOptions{});
}

TEST(NumericalCornerCases, SphereIsUmbilicEverywhereAndKeepsItsShape) {
  const double r = 10.0;
  const Mesh s = make_icosphere(3, r);
  const PrincipalCurvatures c = principal_curvatures(s.positions, s.triangles, build_adjacency(s));
  EXPECT_EQ(std::count(c.umbilic.begin(), c.umbilic.end(), 1), s.num_vertices());
  const FeatureDetection d = expect_finite_everywhere(s, curvature_only());
  EXPECT_EQ(count_label(d, VertexLabel::Edge), 0) << "an umbilic vertex is never an edge";
  // With a threshold below every umbrella, every vertex is an umbilic candidate and votes.
  DetectionOptions all = curvature_only();
  all.gamma = 1e-9;
  const FeatureDetection every = expect_finite_everywhere(s, all);
  EXPECT_EQ(every.candidates, static_cast<std::size_t>(s.num_vertices()));
  EXPECT_EQ(count_label(every, VertexLabel::Edge), 0);
  for (Index i = 0; i < s.num_vertices(); ++i) EXPECT_TRUE(std::isfinite(every.psi[i])) << i;
  FeatureSmoothingOptions o;
  o.detection = all;
  // Taubin's lambda|mu pair may scale a sphere a little; it stays round.
  const Eigen::VectorXd radii = feature_preserving_smooth(s, o).mesh.positions.colwise().norm().transpose();
  EXPECT_LT(radii.maxCoeff() - radii.minCoeff(), 0.01 * radii.mean());
  EXPECT_NEAR(radii.mean(), r, 0.05 * r);
}

TEST(NumericalCornerCases, FlatRegionsHaveZeroCurvatureAndAreNotFeatures) {
  const double half = 10.0;
  const Mesh cube = make_cube(8, half);
  const PrincipalCurvatures c = principal_curvatures(cube.positions, cube.triangles, build_adjacency(cube));
  const FeatureDetection d = expect_finite_everywhere(cube, curvature_only());
  int interior = 0;
  for (Index i = 0; i < cube.num_vertices(); ++i) {
    const Eigen::Vector3d a = cube.positions.col(i).cwiseAbs();
    if ((a.array() > half - 1e-9).count() != 1 || (a.array() > 0.7 * half).count() != 1) continue;  // face interior
    ++interior;
    EXPECT_NEAR(c.kappa_min[i] * half, 0.0, 1e-9) << i;
    EXPECT_NEAR(c.kappa_max[i] * half, 0.0, 1e-9) << i;
    EXPECT_EQ(d.labels[i], VertexLabel::Smooth) << i;
  }
  EXPECT_GT(interior, 6 * 9);
  // A prism over a square: flat sides with contour ids, the square's corners are ridges.
  ContourStackSpec spec;
  spec.curve = [](double t) {
    const double u = 4.0 * t;
    const int side = std::min(3, static_cast<int>(u));
    const double f = u - side;
    const Eigen::Vector2d corners[] = {{5, -5}, {5, 5}, {-5, 5}, {-5, -5}};
    return Eigen::Vector2d((1.0 - f) * corners[side] + f * corners[(side + 1) % 4]);
  };
  spec.slices = 12;
  spec.points_per_contour = 64;
  const Mesh prism = make_contour_stack(spec);
  const FeatureDetection p = expect_finite_everywhere(prism, DetectionOptions{});
  for (int k = 2; k < spec.slices - 2; ++k) {
    for (int at : {8, 24, 40, 56}) EXPECT_EQ(p.labels[k * spec.points_per_contour + at], VertexLabel::Smooth);
  }
}

// The labels depend on shape, not size: gamma is relative to the mean umbrella, delta to |k0|, the
// umbilic tolerance to the mean curvature, and the fits' weights to the ring's own size.
TEST(NumericalCornerCases, ScalingByOneMillionthOrOneMillionKeepsTheLabels) {
  ContourStackSpec spec;
  spec.curve = ridge_circle_curve(20.0, 6.0, 0.35);
  spec.slices = 16;
  spec.points_per_contour = 120;
  Mesh stack = make_contour_stack(spec);
  add_noise(stack, {0.1, 5, NoiseDirection::InPlane});
  Mesh cube = make_cube(10, 10.0);
  add_noise(cube, {0.05, 2, NoiseDirection::Normal});
  struct Case {
    const Mesh* mesh;
    DetectionOptions options;
  };
  for (const Case& c : {Case{&stack, DetectionOptions{}}, Case{&cube, curvature_only()}}) {
    const MeshAdjacency adj = build_adjacency(*c.mesh);
    const FeatureDetection reference = detect_features(*c.mesh, adj, c.options);
    ASSERT_GT(reference.edges, 0u);
    FeatureSmoothingOptions o;
    o.detection = c.options;
    const FeatureSmoothingResult smoothed = feature_preserving_smooth(*c.mesh, o);
    for (double scale : {1e-6, 1e6}) {
      Mesh scaled = *c.mesh;
      scaled.positions *= scale;
      const FeatureDetection d = detect_features(scaled, adj, c.options);
      EXPECT_EQ(d.labels, reference.labels) << "scale " << scale;
      EXPECT_NEAR(d.gamma / scale, reference.gamma, 1e-9 * reference.gamma);
      const FeatureSmoothingResult r = feature_preserving_smooth(scaled, o);
      ASSERT_TRUE(r.mesh.positions.allFinite());
      EXPECT_LT((r.mesh.positions / scale - smoothed.mesh.positions).cwiseAbs().maxCoeff(), 1e-9 * 20.0)
          << "scale " << scale;
    }
  }
}

}  // namespace
}  // namespace contourmesh
