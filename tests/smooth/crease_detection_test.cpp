// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/crease_detection.h"
#include "contourmesh/smooth/errors.h"
#include "contourmesh/smooth/shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace contourmesh {
namespace {

// Distance from p to the nearest edge of the cube [-h, h]^3 (p on its surface).
double distance_to_cube_edges(const Eigen::Vector3d& p, double h) {
  const Eigen::Vector3d a = p.cwiseAbs();
  // On a face the nearest edge is the nearer of the face's two in-face coordinates' limits.
  std::array<double, 3> gaps{h - a.x(), h - a.y(), h - a.z()};
  std::sort(gaps.begin(), gaps.end());
  return gaps[1];  // gaps[0] is ~0 (the face the point lies on)
}

TEST(CreaseDetection, CubeEdgesAreFoundInABandAndFacesAreSmooth) {
  const double h = 10.0;
  const Mesh cube = make_cube(20, h);  // 1 mm grid
  const CreaseDetection d = detect_creases(cube, build_adjacency(cube));
  for (Index i = 0; i < cube.num_vertices(); ++i) {
    const double to_edge = distance_to_cube_edges(cube.positions.col(i), h);
    const VertexLabel l = d.labels[static_cast<std::size_t>(i)];
    if (to_edge < 0.5) {
      EXPECT_TRUE(l == VertexLabel::Edge || l == VertexLabel::Corner) << "vertex " << i << " at " << to_edge;
    }
    if (to_edge > 2.5) {
      EXPECT_EQ(l, VertexLabel::Smooth) << "vertex " << i << " at " << to_edge;
    }
  }
}

TEST(CreaseDetection, CubeCornersAreCorners) {
  const double h = 10.0;
  const Mesh cube = make_cube(20, h);
  const CreaseDetection d = detect_creases(cube, build_adjacency(cube));
  for (Index i = 0; i < cube.num_vertices(); ++i) {
    if ((cube.positions.col(i).cwiseAbs() - Eigen::Vector3d::Constant(h)).norm() < 1e-9) {
      EXPECT_EQ(d.labels[static_cast<std::size_t>(i)], VertexLabel::Corner);
    }
  }
  EXPECT_GT(d.corners, 0u);
}

// The ball is examined only where a vertex can become a core vertex: on the cube's edges (the ridge
// maxima), not at the candidates beside them, which the suppression across the crease rules out first.
TEST(CreaseDetection, OnlyRidgeMaximaAndCornersAreExaminedOverTheBall) {
  const double h = 10.0;
  const Mesh cube = make_cube(20, h);  // 1 mm grid
  const CreaseOptions options;
  const CreaseDetection d = detect_creases(cube, build_adjacency(cube), options);
  std::size_t beside = 0, on_edges = 0;
  for (Index i = 0; i < cube.num_vertices(); ++i) {
    const double to_edge = distance_to_cube_edges(cube.positions.col(i), h);
    if (to_edge < 1e-9) {
      ++on_edges;
      EXPECT_GE(d.confirm_strength[i], options.confirm_threshold) << "vertex " << i;
    } else if (d.edge_strength[i] >= options.edge_threshold && d.corner_strength[i] < options.corner_threshold) {
      ++beside;  // a crease candidate one grid step from an edge, weaker than the edge across it
      EXPECT_EQ(d.confirm_strength[i], 0.0) << "vertex " << i << " at " << to_edge;
      EXPECT_NE(d.labels[static_cast<std::size_t>(i)], VertexLabel::Noise) << "vertex " << i;
    }
  }
  EXPECT_GT(on_edges, 100u);
  EXPECT_GT(beside, 100u);
}

TEST(CreaseDetection, SmoothSphereHasNoFeature) {
  const Mesh sphere = make_icosphere(4, 10.0);
  const CreaseDetection d = detect_creases(sphere, build_adjacency(sphere));
  EXPECT_EQ(d.edges + d.corners + d.noise, 0u);
}

TEST(CreaseDetection, AShortDentIsNoiseNotAFeature) {
  // One vertex of a fine sphere pushed in: a crease around it, but no line.
  Mesh sphere = make_icosphere(5, 10.0);
  sphere.positions.col(0) *= 0.93;
  const CreaseDetection d = detect_creases(sphere, build_adjacency(sphere));
  EXPECT_EQ(d.edges + d.corners, 0u);
  EXPECT_GT(d.noise, 0u);
}

// A right prism over a regular polygon with `corners` corners (circumradius 15 mm), sampled like CT
// contours: 2 mm slices, about 0.7 mm between contour points, a contour point on every corner.
struct PolygonPrism {
  Mesh mesh;
  std::vector<Eigen::Vector2d> corners;
  double z_low = 0.0, z_high = 0.0;  // the end slices

  explicit PolygonPrism(int n, int slices = 16) {
    for (int k = 0; k < n; ++k) {
      const double a = 2.0 * M_PI * k / n;
      corners.emplace_back(15.0 * std::cos(a), 15.0 * std::sin(a));
    }
    const std::vector<Eigen::Vector2d> c = corners;
    ContourStackSpec spec;
    spec.curve = [c](double t) {
      const double u = t * static_cast<double>(c.size());
      const auto k = static_cast<std::size_t>(std::floor(u)) % c.size();
      const double f = u - std::floor(u);
      return Eigen::Vector2d((1.0 - f) * c[k] + f * c[(k + 1) % c.size()]);
    };
    const double side = (corners[1] - corners[0]).norm();
    spec.points_per_contour = n * static_cast<int>(std::round(side / 0.7));
    spec.slices = slices;
    mesh = make_contour_stack(spec);
    z_high = 2.0 * (slices - 1);
  }
  // Distance from a vertex to the nearest edge line running across the slices.
  [[nodiscard]] double to_edge(Index i) const {
    double d = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector2d& c : corners) d = std::min(d, (mesh.positions.col(i).head<2>() - c).norm());
    return d;
  }
  // On the prism's wall, at least `margin` from both end slices.
  [[nodiscard]] bool on_wall(Index i, double margin) const {
    const double z = mesh.positions(2, i);
    return mesh.slice_ids[i] >= 0 && z >= z_low + margin && z <= z_high - margin;
  }
};

bool labelled(const CreaseDetection& d, Index i) {
  const VertexLabel l = d.labels[static_cast<std::size_t>(i)];
  return l == VertexLabel::Edge || l == VertexLabel::Corner;
}

TEST(CreaseDetection, RightAngledPrismEdgesAreFound) {
  const PolygonPrism prism(4);
  const CreaseDetection d = detect_creases(prism.mesh, build_adjacency(prism.mesh));
  int near = 0, found = 0;
  for (Index i = 0; i < prism.mesh.num_vertices(); ++i) {
    if (!prism.on_wall(i, 3.0) || prism.to_edge(i) > 1.0) continue;
    ++near;
    found += labelled(d, i);
  }
  ASSERT_GT(near, 50);
  EXPECT_EQ(found, near);
}

// A square prism (circumradius 15 mm) turning by `turn` radians per 2 mm slice about its axis, sampled as
// a contour stack whose 120 points per contour (about 0.7 mm apart) keep their angles from slice to
// slice, so that the stack is tiled point to point: each edge crosses adjacent contours at points
// 15 x turn mm apart along them, which share no mesh edge when that is two point spacings or more.
struct TwistedSquare {
  Mesh mesh;
  double turn = 0.0;
  double top = 0.0;  // z of the last slice
  static constexpr double kCircumradius = 15.0;

  explicit TwistedSquare(double turn_per_slice, int slices = 24) : turn(turn_per_slice), top(2.0 * (slices - 1)) {
    ContourStackSpec spec;
    spec.curve = [](double t) { return Eigen::Vector2d(std::cos(2.0 * M_PI * t), std::sin(2.0 * M_PI * t)); };
    spec.points_per_contour = 120;
    spec.slices = slices;
    mesh = make_contour_stack(spec);
    const double apothem = kCircumradius / std::sqrt(2.0);
    for (Index i = 0; i < mesh.num_vertices(); ++i) {
      const double k = std::clamp(std::round(mesh.positions(2, i) / 2.0), 0.0, slices - 1.0);  // caps: end slices
      const double theta = std::atan2(mesh.positions(1, i), mesh.positions(0, i));
      double c = 0.0;  // cosine to the nearest face normal, at angles k turn + m pi / 2
      for (int m = 0; m < 4; ++m) c = std::max(c, std::cos(theta - k * turn - m * M_PI / 2.0));
      mesh.positions.col(i).head<2>() = apothem / c * Eigen::Vector2d(std::cos(theta), std::sin(theta));
    }
  }
  // Distance from a wall vertex to the nearest edge, in its slice plane.
  [[nodiscard]] double to_edge(Index i) const {
    const double phi = mesh.positions(2, i) / 2.0 * turn + M_PI / 4.0;
    double d = std::numeric_limits<double>::infinity();
    for (int m = 0; m < 4; ++m) {
      const double a = phi + m * M_PI / 2.0;
      const Eigen::Vector2d corner = kCircumradius * Eigen::Vector2d(std::cos(a), std::sin(a));
      d = std::min(d, (mesh.positions.col(i).head<2>() - corner).norm());
    }
    return d;
  }
};

TEST(CreaseDetection, EdgesObliqueToTheSlicesAreLinkedAcrossContours) {
  // 0.12 rad per slice: the edges cross adjacent contours 1.8 mm (2.6 point spacings) apart, about 48
  // degrees to the slice planes. Their core vertices share no edge from contour to contour, so each
  // contour's is a group of its own, shorter than min_extent, unless linked along the crease.
  const TwistedSquare twisted(0.12);
  const MeshAdjacency adjacency = build_adjacency(twisted.mesh);
  CreaseOptions edges_only;
  edges_only.link_radius = 0.0;
  const CreaseDetection unlinked = detect_creases(twisted.mesh, adjacency, edges_only);
  const CreaseDetection linked = detect_creases(twisted.mesh, adjacency);
  int near = 0, found_unlinked = 0, found = 0, far = 0, false_labels = 0;
  for (Index i = 0; i < twisted.mesh.num_vertices(); ++i) {
    const double z = twisted.mesh.positions(2, i);
    if (twisted.mesh.slice_ids[i] < 0 || z < 4.0 || z > twisted.top - 4.0) continue;  // the wall, away from the ends
    const double d = twisted.to_edge(i);
    if (d <= 1.0) {
      ++near;
      found_unlinked += labelled(unlinked, i);
      found += labelled(linked, i);
    } else if (d > 3.0) {
      ++far;
      false_labels += labelled(linked, i);
    }
  }
  ASSERT_GT(near, 100);
  ASSERT_GT(far, 1000);
  EXPECT_LT(found_unlinked, near / 2);
  EXPECT_GE(found, near * 9 / 10);
  EXPECT_EQ(false_labels, 0);
}

TEST(CreaseDetection, NoisySmoothCylinderWallHasNoLabel) {
  // A 64-gon is a circle to 0.005 mm; contour noise of 0.05 mm is what the phantoms' smoothed
  // contours keep.
  PolygonPrism prism(64);
  add_noise(prism.mesh, {0.05, 7, NoiseDirection::InPlane});
  const CreaseDetection d = detect_creases(prism.mesh, build_adjacency(prism.mesh));
  int wall = 0, labels = 0;
  for (Index i = 0; i < prism.mesh.num_vertices(); ++i) {
    if (!prism.on_wall(i, 4.0)) continue;
    ++wall;
    labels += labelled(d, i);
  }
  ASSERT_GT(wall, 1000);
  EXPECT_EQ(labels, 0);
}

TEST(CreaseDetection, NoisySphereHasNoLabel) {
  Mesh sphere = make_icosphere(4, 10.0);  // edges about 0.7 mm
  add_noise(sphere, {0.05, 3, NoiseDirection::Normal});
  const CreaseDetection d = detect_creases(sphere, build_adjacency(sphere));
  EXPECT_EQ(d.edges + d.corners, 0u);
}

TEST(CreaseDetection, AStepOfAFewTenthsOfAMillimetreIsNotACrease) {
  // A fine sphere whose cap above z = 5 is lowered by 0.4 mm: a step all round, as the rim of an end
  // cap on a contour stack has. The ring sees a crease; the ball of confirm_radius does not.
  Mesh sphere = make_icosphere(5, 10.0);
  for (Index i = 0; i < sphere.num_vertices(); ++i) {
    if (sphere.positions(2, i) > 5.0) sphere.positions(2, i) -= 0.4;
  }
  const MeshAdjacency adjacency = build_adjacency(sphere);
  CreaseOptions ring_only;
  ring_only.confirm = CreaseConfirmation::None;
  ASSERT_GT(detect_creases(sphere, adjacency, ring_only).edges, 0u);  // the ring alone labels the step
  const CreaseDetection d = detect_creases(sphere, adjacency);
  EXPECT_EQ(d.edges + d.corners, 0u);
}

TEST(CreaseDetection, GentleCreasesAcrossTheSlicesAreKeptWhereTheWallIsSteep) {
  // A nonagon prism: nine creases of 40 degrees, running across the slices on vertical walls, where
  // the contours sample the surface finely. Isotropically they are below confirm_threshold.
  const PolygonPrism prism(9);
  const MeshAdjacency adjacency = build_adjacency(prism.mesh);
  CreaseOptions isotropic;
  isotropic.sampling = CreaseSampling::Isotropic;
  const CreaseDetection slice_aware = detect_creases(prism.mesh, adjacency);
  const CreaseDetection iso = detect_creases(prism.mesh, adjacency, isotropic);
  int near = 0, found = 0, found_isotropic = 0;
  for (Index i = 0; i < prism.mesh.num_vertices(); ++i) {
    if (!prism.on_wall(i, 3.0) || prism.to_edge(i) > 1.0) continue;
    ++near;
    found += labelled(slice_aware, i);
    found_isotropic += labelled(iso, i);
  }
  ASSERT_GT(near, 100);
  EXPECT_EQ(found, near);
  EXPECT_LT(found_isotropic, near / 4);
}

TEST(CreaseDetection, NoiseRaisesTheConfirmingThreshold) {
  // The nonagon's 40-degree creases (l2 / trace about 0.1 over the ball) against positions said to
  // carry 1 mm of noise: the threshold rises by 2 (1 / 2.5)^2 = 0.32, above them.
  const PolygonPrism prism(9);
  CreaseOptions noisy;
  noisy.noise = 1.0;
  const CreaseDetection d = detect_creases(prism.mesh, build_adjacency(prism.mesh), noisy);
  EXPECT_EQ(d.edges + d.corners, 0u);
}

TEST(CreaseDetection, BadOptionsAreRefused) {
  const Mesh cube = make_cube(2, 1.0);
  CreaseOptions o;
  o.radius = 0.0;
  EXPECT_THROW((void)detect_creases(cube, build_adjacency(cube), o), InvalidInputError);
  CreaseOptions steep;
  steep.steep_confirm_threshold = steep.confirm_threshold + 0.01;
  EXPECT_THROW((void)detect_creases(cube, build_adjacency(cube), steep), InvalidInputError);
  CreaseOptions noise;
  noise.noise = -0.1;
  EXPECT_THROW((void)detect_creases(cube, build_adjacency(cube), noise), InvalidInputError);
  CreaseOptions link;
  link.link_radius = -1.0;
  EXPECT_THROW((void)detect_creases(cube, build_adjacency(cube), link), InvalidInputError);
  CreaseOptions angle;
  angle.link_angle_degrees = 91.0;
  EXPECT_THROW((void)detect_creases(cube, build_adjacency(cube), angle), InvalidInputError);
}

}  // namespace
}  // namespace contourmesh
