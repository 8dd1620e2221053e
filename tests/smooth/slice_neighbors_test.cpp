// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/shapes.h>
#include <contourmesh/smooth/slice_neighbors.h>

#include <gtest/gtest.h>

namespace contourmesh {
namespace {

Mesh stack(int slices, int points) {
  ContourStackSpec spec;
  spec.curve = ridge_circle_curve(10.0, 2.0, 0.4);
  spec.slices = slices;
  spec.points_per_contour = points;
  return make_contour_stack(spec);
}

TEST(SliceNeighbors, SplitsEveryRingIntoSameBelowAbove) {
  const Mesh m = stack(6, 40);
  const MeshAdjacency adj = build_adjacency(m);
  const SliceRings rings = split_rings_by_slice(m, adj);
  for (Index i = 0; i < m.num_vertices(); ++i) {
    const int s = m.slice_ids[i];
    if (s == kNoId) {  // the end-cap copies
      EXPECT_EQ(rings.other(i).size(), static_cast<std::size_t>(adj.valence(i)));
      continue;
    }
    for (Index j : rings.same(i)) EXPECT_EQ(m.slice_ids[j], s);
    for (Index j : rings.below(i)) EXPECT_EQ(m.slice_ids[j], s - 1);
    for (Index j : rings.above(i)) EXPECT_EQ(m.slice_ids[j], s + 1);
    const bool end_slice = s == 0 || s == 5;  // neighbours on the end-cap copies are "other"
    if (!end_slice) {
      EXPECT_TRUE(rings.other(i).empty());
    }
    EXPECT_EQ(rings.same(i).size() + rings.below(i).size() + rings.above(i).size() + rings.other(i).size(),
              static_cast<std::size_t>(adj.valence(i)));
    if (s > 0 && s < 5) {
      // Interior slices: exactly the two contour neighbours on the same slice, and both adjacent slices.
      EXPECT_EQ(rings.same(i).size(), 2u);
      EXPECT_GE(rings.below(i).size(), 1u);
      EXPECT_GE(rings.above(i).size(), 1u);
    }
    if (s == 0) {
      EXPECT_TRUE(rings.below(i).empty());
    }
    if (s == 5) {
      EXPECT_TRUE(rings.above(i).empty());
    }
  }
}

TEST(SliceNeighbors, VerticesWithoutIdsGoToOther) {
  Mesh m = stack(3, 12);
  m.slice_ids[0] = kNoId;
  const MeshAdjacency adj = build_adjacency(m);
  const SliceRings rings = split_rings_by_slice(m, adj);
  EXPECT_EQ(rings.other(0).size(), static_cast<std::size_t>(adj.valence(0)));
  for (Index j : adj.ring(0)) {
    bool in_other = false;
    for (Index k : rings.other(j)) in_other |= k == 0;
    EXPECT_TRUE(in_other);
  }
}

TEST(SliceNeighbors, RequiresIds) {
  Mesh m = make_icosphere(1);
  EXPECT_THROW((void)split_rings_by_slice(m, build_adjacency(m)), InvalidInputError);
}

}  // namespace
}  // namespace contourmesh
