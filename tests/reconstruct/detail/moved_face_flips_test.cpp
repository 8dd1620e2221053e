// SPDX-License-Identifier: BSD-3-Clause
// Flips after the off-slice heights: a sliver between vertices without ids is mended; contour edges,
// chords across a contour, caps, faces of different roles and bent quads are left alone.
#include "detail/moved_face_flips.h"

#include <contourmesh/smooth/mesh_quality.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace contourmesh::detail {
namespace {

// Two faces (A, B, C) and (B, A, D) of a rhombus standing across the slice axis (z), with the long
// diagonal A B: each face has a smallest angle of 5.7 degrees; the other diagonal C D makes two faces
// of 11.4 degrees.
struct Rhombus {
  Mesh mesh;
  std::vector<FaceRole> roles{FaceRole::Band, FaceRole::Band};
  Rhombus() {
    mesh.positions.resize(3, 4);
    mesh.positions.col(0) = Eigen::Vector3d(0.0, 0.0, 0.0);   // A
    mesh.positions.col(1) = Eigen::Vector3d(10.0, 0.0, 0.0);  // B
    mesh.positions.col(2) = Eigen::Vector3d(5.0, 0.0, 0.5);   // C
    mesh.positions.col(3) = Eigen::Vector3d(5.0, 0.0, -0.5);  // D
    mesh.triangles = {{0, 1, 2}, {1, 0, 3}};
    mesh.slice_ids.assign(4, kNoId);
    mesh.contour_ids.assign(4, kNoId);
  }
  std::size_t flip(double max_deviation = 0.5) {
    return flip_moved_slivers(mesh, roles, Eigen::Vector3d::UnitZ(), max_deviation);
  }
  [[nodiscard]] double smallest_angle() const {
    double smallest = 180.0;
    for (const Triangle& t : mesh.triangles) {
      smallest = std::min(smallest, minimum_angle_degrees(mesh.positions.col(t[0]), mesh.positions.col(t[1]),
                                                          mesh.positions.col(t[2])));
    }
    return smallest;
  }
};

TEST(MovedFaceFlips, FlipsSliversBetweenVerticesWithoutIds) {
  Rhombus r;
  ASSERT_LT(r.smallest_angle(), 10.0);
  const Eigen::Matrix3Xd before = r.mesh.positions;
  EXPECT_EQ(r.flip(), 1U);
  EXPECT_GT(r.smallest_angle(), 10.0);
  EXPECT_TRUE(r.mesh.positions.isApprox(before));  // no vertex moves
  // The faces keep the orientation: both normals still point along -y.
  for (const Triangle& t : r.mesh.triangles) {
    const Eigen::Vector3d n = (r.mesh.positions.col(t[1]) - r.mesh.positions.col(t[0]))
                                  .cross(r.mesh.positions.col(t[2]) - r.mesh.positions.col(t[0]));
    EXPECT_LT(n.y(), 0.0);
  }
}

TEST(MovedFaceFlips, KeepsContourEdges) {
  Rhombus r;
  r.mesh.slice_ids[0] = r.mesh.slice_ids[1] = 3;  // A B is an edge of a contour of slice 3
  r.mesh.contour_ids[0] = r.mesh.contour_ids[1] = 0;
  EXPECT_EQ(r.flip(), 0U);
}

TEST(MovedFaceFlips, MakesNoChordAcrossAContour) {
  Rhombus r;
  r.mesh.slice_ids[2] = r.mesh.slice_ids[3] = 3;  // C D would join two vertices of slice 3
  r.mesh.contour_ids[2] = r.mesh.contour_ids[3] = 0;
  EXPECT_EQ(r.flip(), 0U);
}

TEST(MovedFaceFlips, JoinsVerticesOfDifferentSlices) {
  Rhombus r;
  r.mesh.slice_ids[2] = 4;
  r.mesh.slice_ids[3] = 3;
  r.mesh.contour_ids[2] = r.mesh.contour_ids[3] = 0;
  EXPECT_EQ(r.flip(), 1U);
}

TEST(MovedFaceFlips, LeavesCapsAndMixedRoles) {
  Rhombus caps;
  caps.roles = {FaceRole::Cap, FaceRole::Cap};
  EXPECT_EQ(caps.flip(), 0U);
  Rhombus mixed;
  mixed.roles = {FaceRole::Band, FaceRole::Bridge};
  EXPECT_EQ(mixed.flip(), 0U);
}

TEST(MovedFaceFlips, LeavesQuadsBentMoreThanTheDeviation) {
  Rhombus r;
  r.mesh.positions.col(3) = Eigen::Vector3d(5.0, 1.0, -0.5);  // D 1 mm off the plane of A B C
  EXPECT_EQ(r.flip(0.25), 0U);
  EXPECT_EQ(r.flip(2.0), 1U);
}

TEST(MovedFaceFlips, NeedsContourIds) {
  Rhombus r;
  r.mesh.slice_ids.clear();
  r.mesh.contour_ids.clear();
  EXPECT_EQ(r.flip(), 0U);
}

}  // namespace
}  // namespace contourmesh::detail
