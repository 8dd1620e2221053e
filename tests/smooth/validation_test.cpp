// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/shapes.h>
#include <contourmesh/smooth/validation.h>

#include <gtest/gtest.h>

#include <limits>

#include "smooth/test_meshes.h"

namespace contourmesh {
namespace {

bool has(const std::vector<MeshProblem>& problems, MeshProblemKind kind, Index index) {
  for (const auto& p : problems) {
    if (p.kind == kind && p.index == index) return true;
  }
  return false;
}

TEST(Validation, CleanMeshesPass) {
  EXPECT_TRUE(find_mesh_problems(make_icosphere(2)).empty());
  EXPECT_TRUE(find_mesh_problems(make_cube(3)).empty());
  EXPECT_NO_THROW(validate_mesh(test::tetrahedron()));
}

TEST(Validation, NanCoordinateIsAnInputErrorNamingTheVertex) {
  Mesh m = test::tetrahedron();
  m.positions(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(has(find_mesh_problems(m), MeshProblemKind::NonFiniteCoordinate, 2));
  try {
    validate_mesh(m);
    FAIL();
  } catch (const TopologyError&) {
    FAIL() << "NaN is not a topology error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 2"), std::string::npos) << e.what();
  }
}

TEST(Validation, InfinityIsReported) {
  Mesh m = test::tetrahedron();
  m.positions(0, 3) = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(has(find_mesh_problems(m), MeshProblemKind::NonFiniteCoordinate, 3));
}

TEST(Validation, IndexOutOfRangeIsAnInputError) {
  Mesh m = test::tetrahedron();
  m.triangles[1][2] = -4;
  EXPECT_TRUE(has(find_mesh_problems(m), MeshProblemKind::IndexOutOfRange, 1));
  EXPECT_THROW(validate_mesh(m), InvalidInputError);
}

TEST(Validation, NonManifoldEdgeIsATopologyErrorNamingTheEdge) {
  Mesh m = test::tetrahedron();
  // A fifth vertex and a fin triangle on edge (0, 1): three faces share it.
  m.positions.conservativeResize(3, 5);
  m.positions.col(4) << 0.5, -1.0, 0.5;
  m.triangles.push_back({0, 1, 4});
  const auto problems = find_mesh_problems(m);
  bool found = false;
  for (const auto& p : problems) found |= p.kind == MeshProblemKind::NonManifoldEdge && p.index == 0 && p.other == 1;
  EXPECT_TRUE(found);
  try {
    validate_mesh(m);
    FAIL();
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("non-manifold edge between vertices 0 and 1"), std::string::npos) << e.what();
  }
}

TEST(Validation, BowtieVertexIsNonManifold) {
  // Two triangles touching only at vertex 0.
  Mesh m;
  m.positions.resize(3, 5);
  m.positions << 0, 1, 1, -1, -1,  //
      0, 0, 1, 0, -1,              //
      0, 0, 0, 0, 0;
  m.triangles = {{0, 1, 2}, {0, 3, 4}};
  EXPECT_TRUE(has(find_mesh_problems(m), MeshProblemKind::NonManifoldVertex, 0));
  EXPECT_THROW(validate_mesh(m), TopologyError);
}

TEST(Validation, DegenerateAndDuplicateTrianglesAreReportedByIndex) {
  Mesh m = make_icosphere(1);
  m.triangles.push_back(m.triangles[3]);             // duplicate of 3 (same order)
  const Triangle t = m.triangles[5];
  m.triangles.push_back({t[2], t[1], t[0]});          // duplicate of 5 (reversed)
  m.triangles.push_back({t[0], t[0], t[1]});          // repeated vertex
  const auto last = static_cast<Index>(m.triangles.size() - 1);
  const auto problems = find_mesh_problems(m);
  EXPECT_TRUE(has(problems, MeshProblemKind::DegenerateTriangle, last));
  int duplicates = 0;
  for (const auto& p : problems) duplicates += p.kind == MeshProblemKind::DuplicateTriangle;
  EXPECT_EQ(duplicates, 2);
}

TEST(Validation, ZeroAreaTriangleWithDistinctVerticesIsDegenerate) {
  Mesh m;
  m.positions.resize(3, 3);
  m.positions << 0, 1, 2,  //
      0, 0, 0,             //
      0, 0, 0;
  m.triangles = {{0, 1, 2}};
  EXPECT_TRUE(has(find_mesh_problems(m), MeshProblemKind::DegenerateTriangle, 0));
}

TEST(Validation, IdArraysOfTheWrongSizeAreReported) {
  Mesh m = test::tetrahedron();
  m.slice_ids = {0, 0, 1};
  m.contour_ids = {0, 0, 0};
  EXPECT_THROW(validate_mesh(m), InvalidInputError);
}

TEST(Repair, DropsTrianglesWithARepeatedVertexAndDuplicatesKeepingTheFirst) {
  Mesh m = make_icosphere(1);
  const Mesh clean = m;
  const Triangle t = m.triangles[5];
  m.triangles.insert(m.triangles.begin() + 2, {t[0], t[0], t[1]});  // repeated vertex, before the rest
  m.triangles.push_back(m.triangles[3]);                              // duplicate
  m.triangles.push_back({t[2], t[1], t[0]});                          // duplicate, reversed
  const MeshRepair r = repair_mesh(m);
  EXPECT_EQ(r.dropped_degenerate, 1);
  EXPECT_EQ(r.dropped_duplicates, 2);
  EXPECT_EQ(r.merged_vertices, 0);
  EXPECT_EQ(m.triangles, clean.triangles) << "the first of each set is kept, in order";
  EXPECT_EQ(m.positions, clean.positions);
  EXPECT_EQ(r.describe(), "dropped 1 triangle with a repeated vertex and 2 duplicate triangles");
  EXPECT_TRUE(find_mesh_problems(m).empty());
  EXPECT_FALSE(repair_mesh(m).changed()) << "idempotent";
}

TEST(Repair, MergesCoincidentVerticesOfASoupIntoTheClosedMesh) {
  const Mesh sphere = make_icosphere(1);
  Mesh soup;
  soup.positions.resize(3, 3 * sphere.num_faces());
  for (Index f = 0; f < sphere.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) soup.positions.col(3 * f + k) = sphere.positions.col(sphere.triangles[f][k]);
    soup.triangles.push_back({3 * f, 3 * f + 1, 3 * f + 2});
  }
  const MeshRepair r = repair_mesh(soup);
  EXPECT_EQ(r.merged_vertices, 3 * sphere.num_faces() - sphere.num_vertices());
  EXPECT_EQ(soup.num_vertices(), sphere.num_vertices());
  EXPECT_TRUE(find_mesh_problems(soup).empty()) << "closed and manifold again";
  for (Index f = 0; f < sphere.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(soup.positions.col(soup.triangles[f][k]), sphere.positions.col(sphere.triangles[f][k]));
    }
  }
  EXPECT_NE(r.describe().find("merged"), std::string::npos);
}

TEST(Repair, KeepsVerticesWithDifferentIdsAndZeroAreaTrianglesWithDistinctVertices) {
  Mesh m;
  m.positions.resize(3, 5);
  m.positions << 0, 1, 2, 0, 0,  //
      0, 0, 0, 1, 1,             //
      0, 0, 0, 0, 0;
  m.triangles = {{0, 1, 2}, {0, 1, 3}, {0, 1, 4}};  // a sliver; 3 and 4 coincide
  m.slice_ids = {0, 0, 0, 1, 2};
  m.contour_ids = {0, 0, 0, 0, 0};
  Mesh with_ids = m;
  EXPECT_FALSE(repair_mesh(with_ids).changed()) << "3 and 4 lie on different slices";
  m.slice_ids.clear();
  m.contour_ids.clear();
  const MeshRepair r = repair_mesh(m);
  EXPECT_EQ(r.merged_vertices, 1);
  EXPECT_EQ(r.dropped_duplicates, 1) << "(0, 1, 3) and (0, 1, 4) became one triangle";
  ASSERT_EQ(m.num_faces(), 2);
  EXPECT_EQ(m.triangles[0], (Triangle{0, 1, 2})) << "the zero-area sliver stays: dropping it would open a hole";
  Mesh nothing_merged = with_ids;
  nothing_merged.slice_ids.clear();
  nothing_merged.contour_ids.clear();
  EXPECT_EQ(repair_mesh(nothing_merged, {VertexMerging::Off}).merged_vertices, 0);
}

TEST(Repair, RejectsIndicesOutOfRange) {
  Mesh m = test::tetrahedron();
  m.triangles[2][1] = 9001;
  try {
    (void)repair_mesh(m);
    FAIL();
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 2 references vertex 9001 but the mesh has 4 vertices"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace contourmesh
