// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/adaptive_subdivision.h>
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/metrics.h>
#include <contourmesh/smooth/shapes.h>
#include <contourmesh/smooth/topology.h>
#include <contourmesh/smooth/umbrella.h>

#include <gtest/gtest.h>

namespace contourmesh {
namespace {

TEST(AdaptiveSubdivision, HalvesTheUmbrellaPerLevelAndStaysClosedManifold) {
  Mesh m = make_icosphere(2);
  add_noise(m, {0.02, 4, NoiseDirection::Normal});
  std::vector<std::uint8_t> selected(static_cast<std::size_t>(m.num_vertices()), 0);
  selected[5] = selected[6] = selected[40] = 1;  // 5 and 6 are neighbours: shared edges too
  const double u0 = umbrella_norms(m.positions, build_adjacency(m))[5];
  for (int levels = 1; levels <= 3; ++levels) {
    SubdivisionOptions o;
    o.max_levels = levels;
    o.gamma = 0.0;  // always subdivide: test the halving itself
    const AdaptiveMesh a = subdivide_adaptively(m, selected, o);
    const TopologySummary t = summarize_topology(a.mesh);
    EXPECT_TRUE(t.closed);
    EXPECT_TRUE(t.manifold) << t.first_problems;
    EXPECT_EQ(t.euler_characteristic, 2);
    EXPECT_EQ(a.original_vertices, m.num_vertices());
    EXPECT_EQ(a.mesh.positions.leftCols(m.num_vertices()), m.positions) << "original vertices never move";
    EXPECT_NEAR(enclosed_volume(a.mesh), enclosed_volume(m), 1e-12) << "geometry unchanged";
    EXPECT_EQ(a.per_level.size(), static_cast<std::size_t>(levels));
    const double u = umbrella_norms(a.mesh.positions, build_adjacency(a.mesh))[5];
    EXPECT_NEAR(u / u0, std::pow(0.5, levels), 1e-9) << levels << " levels";
  }
}

TEST(AdaptiveSubdivision, StopsBelowGammaAndTouchesOnlyTheOneRing) {
  const Mesh m = make_icosphere(2);
  const MeshAdjacency adj = build_adjacency(m);
  std::vector<std::uint8_t> selected(static_cast<std::size_t>(m.num_vertices()), 0);
  selected[12] = 1;
  const double u = umbrella_norms(m.positions, adj)[12];
  SubdivisionOptions o;
  o.max_levels = 5;
  o.gamma = 0.3 * u;  // 1/2 and 1/4 of u are above... 1/4 is below 0.3: two levels
  const AdaptiveMesh a = subdivide_adaptively(m, selected, o);
  EXPECT_EQ(a.per_level.size(), 2u);
  ASSERT_EQ(a.subdivided.size(), 1u);
  EXPECT_EQ(a.subdivided[0], 12);
  // Faces not incident to vertex 12 are unchanged.
  const auto faces12 = adj.incident_faces(12);
  std::size_t kept = 0;
  for (Index f = 0; f < m.num_faces(); ++f) {
    if (std::find(faces12.begin(), faces12.end(), f) != faces12.end()) continue;
    kept += std::find(a.mesh.triangles.begin(), a.mesh.triangles.end(), m.triangles[f]) != a.mesh.triangles.end();
  }
  EXPECT_EQ(kept, m.triangles.size() - faces12.size());
}

TEST(AdaptiveSubdivision, MidpointsOnAContourKeepItsIds) {
  ContourStackSpec spec;
  spec.curve = ridge_circle_curve(10, 3, 0.4);
  spec.slices = 5;
  spec.points_per_contour = 40;
  const Mesh m = make_contour_stack(spec);
  std::vector<std::uint8_t> selected(static_cast<std::size_t>(m.num_vertices()), 0);
  selected[2 * 40] = 1;  // the ridge tip of slice 2
  SubdivisionOptions o;
  o.max_levels = 1;
  const AdaptiveMesh a = subdivide_adaptively(m, selected, o);
  int on_contour = 0, between = 0;
  for (Index i = m.num_vertices(); i < a.mesh.num_vertices(); ++i) {
    if (a.mesh.slice_ids[i] == 2) ++on_contour;
    else if (a.mesh.slice_ids[i] == kNoId) ++between;
  }
  EXPECT_EQ(on_contour, 2);  // the midpoints of the two contour edges
  EXPECT_GE(between, 2);
}

TEST(AdaptiveSubdivision, RejectsABadMask) {
  const Mesh m = make_icosphere(1);
  std::vector<std::uint8_t> short_mask(3, 1);
  EXPECT_THROW((void)subdivide_adaptively(m, short_mask, {}), InvalidInputError);
}

TEST(AdaptiveSubdivision, RefusesALevelBeyondTheLimitsBeforeAllocatingIt) {
  const Mesh m = make_icosphere(2);  // 162 vertices of valence 5 or 6
  std::vector<std::uint8_t> selected(static_cast<std::size_t>(m.num_vertices()), 1);
  SubdivisionOptions o;
  o.max_levels = 2;
  o.limits.max_vertices = m.num_vertices() + 100;
  try {
    (void)subdivide_adaptively(m, selected, o);
    FAIL() << "every vertex selected: level 1 can reach far more than 100 new vertices";
  } catch (const LimitError& e) {
    EXPECT_NE(std::string(e.what()).find("adaptive subdivision level 1: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("exceed the limit of 262 vertices"), std::string::npos) << e.what();
  }
  o.limits.max_vertices = kDefaultMaxVertices;
  o.limits.max_memory_bytes = 10'000;  // 10 kB: not even level 1
  EXPECT_THROW((void)subdivide_adaptively(m, selected, o), LimitError);
  o.limits.max_memory_bytes = 0;  // the machine's available memory
  EXPECT_NO_THROW((void)subdivide_adaptively(m, selected, o));
}

}  // namespace
}  // namespace contourmesh
