// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/contour_structure.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/feature_detection.h>
#include <contourmesh/smooth/shapes.h>
#include <contourmesh/smooth/validation.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace contourmesh {
namespace {

// A prism over a circle of radius 20 mm with a sharp ridge (6 mm high) at angle 0, sampled like CT:
// 0.7 mm along the contours, 2 mm between slices. Contour point 0 of every slice is the ridge tip.
ContourStackSpec ridge_spec() {
  ContourStackSpec spec;
  spec.curve = ridge_circle_curve(20.0, 6.0, 0.35);
  spec.slices = 24;
  spec.points_per_contour = 180;
  spec.slice_spacing = 2.0;
  return spec;
}

int count_label(const FeatureDetection& d, VertexLabel l) {
  return static_cast<int>(std::count(d.labels.begin(), d.labels.end(), l));
}

TEST(FeatureDetection, RidgeAcrossSlicesIsEdgeAndSingleContourSpikesAreNoise) {
  const ContourStackSpec spec = ridge_spec();
  Mesh m = make_contour_stack(spec);
  add_noise(m, {0.1, 3, NoiseDirection::InPlane});
  const int P = spec.points_per_contour;
  // Spikes: one vertex pushed 1 mm outwards on a single contour, far from the ridge and the ends.
  std::vector<Index> spikes;
  for (int k = 3; k <= 20; k += 3) {
    for (int at : {50, 90, 130}) {
      const Index v = k * P + at + (k % 2) * 5;
      const Eigen::Vector2d r = m.positions.col(v).head<2>().normalized();
      m.positions.col(v).head<2>() += 1.0 * r;
      spikes.push_back(v);
    }
  }
  const MeshAdjacency adj = build_adjacency(m);
  const FeatureDetection d = detect_features(m, adj);
  int ridge_edges = 0, ridge_total = 0;
  for (int k = 2; k < spec.slices - 2; ++k) {
    ++ridge_total;
    ridge_edges += d.labels[k * P] == VertexLabel::Edge;
  }
  int spike_noise = 0;
  for (Index v : spikes) spike_noise += d.labels[v] == VertexLabel::Noise;
  EXPECT_GE(ridge_edges, 0.9 * ridge_total) << ridge_edges << " of " << ridge_total;
  EXPECT_GE(spike_noise, 0.9 * spikes.size()) << spike_noise << " of " << spikes.size();
  EXPECT_GT(d.gamma, 0.0);
  EXPECT_EQ(static_cast<std::size_t>(count_label(d, VertexLabel::Edge)), d.edges);
  // The numbers behind a ridge label: three curvatures of the same sign and similar size.
  const Index tip = 10 * P;
  EXPECT_GT(d.k0[tip], 0.0);
  EXPECT_NEAR(d.k_below[tip] / d.k0[tip], 1.0, 0.5);
  EXPECT_NEAR(d.k_above[tip] / d.k0[tip], 1.0, 0.5);
}

// A ridge that winds around the prism (each slice turned by 7 degrees, so the ridge crosses the slices
// at about 40 degrees) meets the adjacent contours 2.5 mm from v_i's neighbours there: the curve
// fits must be centred where those contours cross S, not on the neighbours.
TEST(FeatureDetection, RidgeObliqueToTheSlicesIsEdge) {
  const ContourStackSpec spec = ridge_spec();
  Mesh m = make_contour_stack(spec);
  const double turn_per_mm = 0.125 / spec.slice_spacing;  // radians per mm along z
  for (Index i = 0; i < m.num_vertices(); ++i) {
    const double a = turn_per_mm * m.positions(2, i);
    const Eigen::Vector2d p = m.positions.col(i).head<2>();
    m.positions.col(i).head<2>() = Eigen::Rotation2Dd(a) * p;
  }
  const MeshAdjacency adj = build_adjacency(m);
  const FeatureDetection d = detect_features(m, adj);
  const int P = spec.points_per_contour;
  int ridge_edges = 0, ridge_total = 0;
  for (int k = 2; k < spec.slices - 2; ++k) {
    ++ridge_total;
    ridge_edges += d.labels[k * P] == VertexLabel::Edge;
  }
  EXPECT_GE(ridge_edges, 0.9 * ridge_total) << ridge_edges << " of " << ridge_total;
}

// The rims of the end caps are sharp feature lines within slice planes: the paper's rule calls them
// noise (its blind spot) unless an umbilic neighbour's vote makes them corners; the along-the-line
// extension finds them as edges, and still calls spikes noise.
TEST(FeatureDetection, InSliceExtensionFindsCapRimsAndKeepsSpikesNoise) {
  const ContourStackSpec spec = ridge_spec();
  Mesh m = make_contour_stack(spec);
  const int P = spec.points_per_contour;
  std::vector<Index> spikes;
  for (int k = 4; k <= 19; k += 5) {
    const Index v = k * P + 90;
    m.positions.col(v).head<2>() += 1.0 * m.positions.col(v).head<2>().normalized();
    spikes.push_back(v);
  }
  const MeshAdjacency adj = build_adjacency(m);
  const Index rim_begin = static_cast<Index>(spec.slices) * P;  // the end-cap copies follow the slices
  // Rim vertices next to the ear-clipped caps' long chords often fit as umbilic; they then join the
  // feature by the Psi vote (corner), which subdivides them just the same.
  auto rim_features = [&](const FeatureDetection& d) {
    int features = 0;
    for (Index v = rim_begin; v < m.num_vertices(); ++v) {
      features += d.labels[v] == VertexLabel::Edge || d.labels[v] == VertexLabel::Corner;
    }
    return features;
  };
  const FeatureDetection paper = detect_features(m, adj);
  const int rim = static_cast<int>(m.num_vertices() - rim_begin);
  DetectionOptions o;
  o.in_slice = InSliceFeatures::AlongFeatureLine;
  const FeatureDetection extended = detect_features(m, adj, o);
  EXPECT_GE(rim_features(extended), 0.8 * rim) << rim_features(extended) << " of " << rim;
  EXPECT_GT(rim_features(extended), rim_features(paper) + rim / 10);
  for (Index v : spikes) EXPECT_EQ(extended.labels[v], VertexLabel::Noise) << "spike " << v;
}

// A box stacked like thin-slice CT contours: square contours (side 20 mm, 0.5 mm between points, one on
// each corner) every 0.5 mm, the end contours closed by flat caps in their slice planes (a 0.5 mm grid
// of triangles, interior vertices off the contours). Its eight corners are where the caps' rims meet
// the vertical edges. (With 2 mm slices the side triangles outweigh the cap's in the area-weighted
// normal of SPEC 3.2, the rims' quadric fits then turn their principal directions, and the extension
// below does not find the rims: see docs/smoothing.md.)
Mesh box_stack(int slices) {
  constexpr int m = 40;  // segments per side
  constexpr double a = 10.0, h = 2.0 * a / m, spacing = 0.5;
  const int P = 4 * m;
  auto contour_point = [&](int p) -> Eigen::Vector2d {
    const int side = p / m, q = p % m;
    switch (side) {
      case 0: return {-a + h * q, -a};
      case 1: return {a, -a + h * q};
      case 2: return {a - h * q, a};
      default: return {-a, a - h * q};
    }
  };
  std::vector<Eigen::Vector3d> points;
  Mesh mesh;
  for (int k = 0; k < slices; ++k) {
    for (int p = 0; p < P; ++p) {
      points.push_back({contour_point(p).x(), contour_point(p).y(), k * spacing});
      mesh.slice_ids.push_back(k);
      mesh.contour_ids.push_back(0);
    }
  }
  for (int k = 0; k + 1 < slices; ++k) {
    for (int p = 0; p < P; ++p) {
      const Index a0 = k * P + p, a1 = k * P + (p + 1) % P, b0 = a0 + P, b1 = a1 + P;
      mesh.triangles.push_back({a0, a1, b1});
      mesh.triangles.push_back({a0, b1, b0});
    }
  }
  // Caps: grid (i, j) of the square; its border is the end contour.
  for (const int k : {0, slices - 1}) {
    std::vector<Index> grid((m + 1) * (m + 1));
    for (int j = 0; j <= m; ++j) {
      for (int i = 0; i <= m; ++i) {
        int p = -1;
        if (j == 0 && i < m) p = i;
        else if (i == m && j < m) p = m + j;
        else if (j == m && i > 0) p = 2 * m + (m - i);
        else if (i == 0 && j > 0) p = 3 * m + (m - j);
        if (p >= 0) {
          grid[j * (m + 1) + i] = k * P + p;
        } else {
          grid[j * (m + 1) + i] = static_cast<Index>(points.size());
          points.push_back({-a + h * i, -a + h * j, k * spacing});
          mesh.slice_ids.push_back(kNoId);
          mesh.contour_ids.push_back(kNoId);
        }
      }
    }
    for (int j = 0; j < m; ++j) {
      for (int i = 0; i < m; ++i) {
        const Index v00 = grid[j * (m + 1) + i], v10 = grid[j * (m + 1) + i + 1];
        const Index v01 = grid[(j + 1) * (m + 1) + i], v11 = grid[(j + 1) * (m + 1) + i + 1];
        if (k == 0) {  // facing -z
          mesh.triangles.push_back({v00, v11, v10});
          mesh.triangles.push_back({v00, v01, v11});
        } else {
          mesh.triangles.push_back({v00, v10, v11});
          mesh.triangles.push_back({v00, v11, v01});
        }
      }
    }
  }
  mesh.positions.resize(3, static_cast<Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) mesh.positions.col(static_cast<Index>(i)) = points[i];
  return mesh;
}

// Three faces meet at a box corner, so the quadric fit's principal directions mean nothing there and
// the vertex goes to the Psi vote (`corner_spread`): a corner when its feature neighbours outweigh its
// noise neighbours. The vertical edges cross the slices: edge. The caps' rims run within slice planes,
// the paper's blind spot: the along-the-line extension finds most of them, and a corner between two
// found rims and its vertical edge is labelled corner. (Which rim vertices the extension finds next to a
// corner depends on how the triangles are cut there: with the paper's rule alone, 4 of the 8 corners.)
TEST(FeatureDetection, BoxCornersGoToTheVoteAndAreCornersBetweenFeatures) {
  const int slices = 20, P = 160;  // 9.5 mm tall
  const Mesh m = box_stack(slices);
  ASSERT_TRUE(find_mesh_problems(m).empty());
  const MeshAdjacency adj = build_adjacency(m);
  std::vector<Index> corners, vertical_edges;
  for (int c = 0; c < 4; ++c) {
    corners.push_back(c * P / 4);
    corners.push_back((slices - 1) * P + c * P / 4);
    for (int k = 1; k + 1 < slices; ++k) vertical_edges.push_back(k * P + c * P / 4);
  }
  // On this noise-free mesh the sides' umbrellas are zero and 2 mean |U| is set by the caps' rims, above
  // the vertical edges' |U| (0.24 mm): examine every vertex whose umbrella exceeds 0.1 mm.
  DetectionOptions options;
  options.gamma = 0.1;
  options.in_slice = InSliceFeatures::AlongFeatureLine;
  const FeatureDetection d = detect_features(m, adj, options);
  int edges = 0;
  for (Index v : vertical_edges) edges += d.labels[v] == VertexLabel::Edge;
  EXPECT_GE(edges, 0.9 * vertical_edges.size()) << edges << " of " << vertical_edges.size();
  int rims = 0, rim_total = 0;
  for (int k : {0, slices - 1}) {
    for (int p = 0; p < P; ++p) {
      if (p % (P / 4) == 0) continue;
      ++rim_total;
      rims += d.labels[k * P + p] == VertexLabel::Edge;
    }
  }
  EXPECT_GE(rims, 0.8 * rim_total) << rims << " of " << rim_total;
  int labelled_corner = 0;
  for (Index v : corners) {
    EXPECT_NEAR(d.normal_spread[v], 1.0 / 3.0, 1e-9) << v;
    ASSERT_TRUE(std::isfinite(d.psi[v])) << "corner " << v << " did not go to the vote";
    int feature_neighbours = 0, noise_neighbours = 0;
    for (Index j : adj.ring(v)) {
      feature_neighbours += d.labels[j] == VertexLabel::Edge || d.labels[j] == VertexLabel::Corner;
      noise_neighbours += d.labels[j] == VertexLabel::Noise;
    }
    if (feature_neighbours == 3 && noise_neighbours == 0) {
      EXPECT_EQ(d.labels[v], VertexLabel::Corner) << v;
    }
    labelled_corner += d.labels[v] == VertexLabel::Corner;
  }
  EXPECT_EQ(labelled_corner, 8);
  // Corners are found only at the corners.
  EXPECT_EQ(d.corners, static_cast<std::size_t>(labelled_corner));

  // Turned off, the corners are judged by their meaningless principal directions: none is a corner.
  DetectionOptions off = options;
  off.corner_spread = 0.5;
  const FeatureDetection no_rule = detect_features(m, adj, off);
  for (Index v : corners) EXPECT_NE(no_rule.labels[v], VertexLabel::Corner) << "corner " << v;
  EXPECT_EQ(no_rule.corners, 0u);
}

TEST(FeatureDetection, RequiresContourIds) {
  const Mesh s = make_icosphere(2);
  EXPECT_THROW((void)detect_features(s, build_adjacency(s)), InvalidInputError);
}

}  // namespace
}  // namespace contourmesh

namespace contourmesh {
namespace {

TEST(ContourIdRecovery, BinningRecoversSlicesAndContours) {
  ContourStackSpec spec = ridge_spec();
  spec.end_caps = EndCaps::AtEndSlice;
  const Mesh original = make_contour_stack(spec);
  Mesh stripped = original;
  stripped.slice_ids.clear();
  stripped.contour_ids.clear();
  const MeshAdjacency adj = build_adjacency(stripped);
  ASSERT_TRUE(assign_ids_by_slice_planes(stripped, adj, Eigen::Vector3d::UnitZ()));
  EXPECT_EQ(stripped.slice_ids, original.slice_ids);
  EXPECT_EQ(stripped.contour_ids, original.contour_ids);
  // A noisy sphere's vertices do not lie on planes.
  Mesh sphere = make_icosphere(3);
  add_noise(sphere, {0.01, 1, NoiseDirection::Isotropic});
  EXPECT_FALSE(assign_ids_by_slice_planes(sphere, build_adjacency(sphere), Eigen::Vector3d::UnitZ()));
  EXPECT_FALSE(sphere.has_contour_ids());
  // With the default half-spacing end caps the two cap planes become slices of their own.
  Mesh with_caps = make_contour_stack(ridge_spec());
  const Index n = with_caps.num_vertices();
  with_caps.slice_ids.clear();
  with_caps.contour_ids.clear();
  ASSERT_TRUE(assign_ids_by_slice_planes(with_caps, build_adjacency(with_caps), Eigen::Vector3d::UnitZ()));
  EXPECT_EQ(*std::max_element(with_caps.slice_ids.begin(), with_caps.slice_ids.end()), ridge_spec().slices + 1);
  EXPECT_EQ(with_caps.num_vertices(), n);
}

TEST(FeatureDetection, CurvatureOnlyFallbackFindsCubeEdgesWithoutIds) {
  Mesh cube = make_cube(12, 10.0);
  add_noise(cube, {0.05, 2, NoiseDirection::Normal});
  DetectionOptions o;
  o.mode = DetectionMode::CurvatureOnly;
  const FeatureDetection d = detect_features(cube, build_adjacency(cube), o);
  int on_edges = 0, edge_labels_on_edges = 0;
  for (Index i = 0; i < cube.num_vertices(); ++i) {
    const Eigen::Vector3d a = cube.positions.col(i).cwiseAbs();
    const int near_faces = (a.array() > 9.5).count();
    if (near_faces == 2) {
      ++on_edges;
      edge_labels_on_edges += d.labels[i] == VertexLabel::Edge;
    }
  }
  EXPECT_GT(edge_labels_on_edges, 0.8 * on_edges) << edge_labels_on_edges << " of " << on_edges;
}

}  // namespace
}  // namespace contourmesh
