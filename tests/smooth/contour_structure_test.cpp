// SPDX-License-Identifier: BSD-3-Clause
// Consistency of contour ids with the mesh (SPEC 2), and their repair.
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/contour_structure.h>
#include <contourmesh/smooth/shapes.h>

#include <gtest/gtest.h>

#include <functional>
#include <string>

namespace contourmesh {
namespace {

Mesh stack() {
  ContourStackSpec spec;
  spec.curve = ridge_circle_curve(10.0, 2.0, 0.4);
  spec.slices = 6;
  spec.points_per_contour = 30;
  return make_contour_stack(spec);  // slices 0..5, two cap copies with kNoId
}

Index first_of_slice(const Mesh& m, std::int32_t s) {
  Index v = 0;
  while (m.slice_ids[v] != s) ++v;
  return v;
}

TEST(ContourIds, AConsistentStackHasNoProblem) {
  const Mesh m = stack();
  EXPECT_EQ(find_contour_id_problem(m, build_adjacency(m)), "");
  Mesh plain = m;
  plain.slice_ids.clear();
  plain.contour_ids.clear();
  EXPECT_EQ(find_contour_id_problem(plain, build_adjacency(plain)), "") << "no ids: nothing to check";
}

TEST(ContourIds, CompactingClosesInteriorGapsOnly) {
  Mesh m = stack();
  for (auto& s : m.slice_ids) s += s >= 0 ? 3 : 0;  // starts at 3: no gap
  Mesh shifted = m;
  EXPECT_EQ(compact_slice_ids(shifted), 0u);
  EXPECT_EQ(shifted.slice_ids, m.slice_ids);
  for (auto& s : m.slice_ids) s += s >= 5 ? 2 : 0;  // 3, 4, 7, 8, 9, 10: a jump by 3
  const MeshAdjacency adj = build_adjacency(m);
  EXPECT_NE(find_contour_id_problem(m, adj).find("skips 2 slices"), std::string::npos);
  EXPECT_EQ(compact_slice_ids(m), 2u);
  EXPECT_EQ(m.slice_ids, shifted.slice_ids);
  EXPECT_EQ(find_contour_id_problem(m, adj), "");
}

TEST(ContourIds, EveryKindOfInconsistencyIsNamed) {
  const Mesh m = stack();
  const MeshAdjacency adj = build_adjacency(m);
  const Index v = first_of_slice(m, 2);
  auto problem = [&](const std::function<void(Mesh&)>& damage) {
    Mesh d = m;
    damage(d);
    return find_contour_id_problem(d, adj);
  };
  EXPECT_NE(problem([&](Mesh& d) { d.slice_ids[v] = -4; }).find("vertex " + std::to_string(v) + " has slice id -4"),
            std::string::npos);
  EXPECT_NE(problem([&](Mesh& d) { d.contour_ids[v] = kNoId; }).find("has slice id 2 but contour id -1"),
            std::string::npos);
  EXPECT_NE(problem([&](Mesh& d) { d.slice_ids[v] = 3; }).find("(slice 3) skips 1 slice"), std::string::npos);
  // Ids that agree with the edges but not with the geometry: a vertex of slice 2 on the plane of 3.
  const std::string moved = problem([&](Mesh& d) { d.positions(2, v) += 1.6; });  // slices 2 mm apart
  EXPECT_NE(moved.find("vertex " + std::to_string(v) + " has slice id 2 but lies 1.5"), std::string::npos) << moved;
  EXPECT_NE(moved.find("nearer to slice 3"), std::string::npos) << moved;
}

TEST(ContourIds, RepairRestoresTheIdsFromTheSlicePlanes) {
  const Mesh m = stack();
  const MeshAdjacency adj = build_adjacency(m);
  const Index v = first_of_slice(m, 3);
  for (const std::int32_t wrong : {2, 5, -9, 77}) {
    Mesh d = m;
    d.slice_ids[v] = wrong;
    compact_slice_ids(d);
    ASSERT_NE(find_contour_id_problem(d, adj), "") << wrong;
    ASSERT_TRUE(repair_contour_ids(d, adj, Eigen::Vector3d::UnitZ())) << wrong;
    EXPECT_EQ(d.slice_ids, m.slice_ids) << wrong << ": cap copies keep kNoId, the others their slice";
    EXPECT_EQ(d.contour_ids, m.contour_ids) << wrong;
  }
  Mesh d = m;
  d.slice_ids[v] = 5;
  EXPECT_FALSE(repair_contour_ids(d, adj, Eigen::Vector3d::UnitX()))
      << "along x the vertices lie on planes too (every contour has the same samples), but not the file's";
  EXPECT_EQ(d.slice_ids[v], 5) << "untouched on failure";
}

}  // namespace
}  // namespace contourmesh
