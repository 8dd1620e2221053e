#include <smooth/adjacency.h>
#include <smooth/contour_structure.h>
#include <smooth/errors.h>
#include <smooth/feature_detection.h>
#include <smooth/shapes.h>

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
