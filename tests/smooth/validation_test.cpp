#include <smooth/errors.h>
#include <smooth/shapes.h>
#include <smooth/validation.h>

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

}  // namespace
}  // namespace contourmesh
