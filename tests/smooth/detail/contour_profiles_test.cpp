// SPDX-License-Identifier: BSD-3-Clause
// White-box tests of the cross-slice smoother's profiles (libsmooth/src/detail/contour_profiles.h).
#include "detail/contour_profiles.h"

#include "contourmesh/smooth/normals.h"
#include "contourmesh/smooth/shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace contourmesh::detail {
namespace {

// The along-contour profile as the samples are taken: the centre, then one step along each side in
// turn, stably sorted by x. along_contour_profile writes the two sides out in order instead and falls
// back to this where they do not interleave strictly; both must give the same samples in the same order.
Profile walked_then_sorted(const ContourFrame& f, const Eigen::Matrix3Xd& x, Index i, const Eigen::Vector3d& m,
                           int reach) {
  Profile out;
  out.push(0.0, 0.0);
  const Eigen::Vector3d v = x.col(i), tangent = f.axis.cross(m);
  std::array<std::array<Index, 2>, 2> cursor{};
  std::array<double, 2> arc{0.0, 0.0}, sign{1.0, 1.0};
  for (std::size_t side = 0; side < 2; ++side) {
    cursor[side] = {i, f.contour.of[static_cast<std::size_t>(i)][side]};
    sign[side] = (x.col(cursor[side][1]) - v).dot(tangent) >= 0.0 ? 1.0 : -1.0;
  }
  if (sign[0] == sign[1]) sign[1] = -sign[0];
  for (int k = 1; k <= reach; ++k) {
    for (std::size_t side = 0; side < 2; ++side) {
      auto& [prev, cur] = cursor[side];
      if (cur < 0 || cur == i) continue;
      const auto& other = cursor[1 - side];
      if (cur == other[1] || cur == other[0]) {
        cur = -1;
        continue;
      }
      arc[side] += (x.col(cur) - x.col(prev)).norm();
      if (!out.push(sign[side] * arc[side] / f.point_spacing, (x.col(cur) - v).dot(m))) {
        cur = -1;
        continue;
      }
      const auto& nb = f.contour.of[static_cast<std::size_t>(cur)];
      const Index next = nb[0] == prev ? nb[1] : nb[0];
      prev = cur;
      cur = next;
    }
  }
  out.sort();
  return out;
}

// A cylinder of 24-point contours, with jagged contours (points pushed back and forth along the
// contour, so that arc lengths fold and repeat) and zero-length contour edges (a point moved onto its
// neighbour): profiles that interleave strictly, and ones that do not.
Mesh awkward_cylinder() {
  ContourStackSpec spec;
  spec.curve = [](double t) {
    return Eigen::Vector2d(5.0 * std::cos(2 * std::numbers::pi * t), 5.0 * std::sin(2 * std::numbers::pi * t));
  };
  spec.slices = 6;
  spec.points_per_contour = 24;
  Mesh mesh = make_contour_stack(spec);
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.slice_ids[static_cast<std::size_t>(i)] == 2 && i % 5 == 0) {
      mesh.positions.col(i) = mesh.positions.col(i + 1);  // a zero-length edge
    } else if (mesh.slice_ids[static_cast<std::size_t>(i)] == 3 && i % 3 == 0 &&
               mesh.slice_ids[static_cast<std::size_t>(i - 2)] == 3) {
      mesh.positions.col(i) = 0.5 * (mesh.positions.col(i - 2) + mesh.positions.col(i - 1));  // folds back
    }
  }
  return mesh;
}

TEST(AlongContourProfile, EqualsTheWalkedSamplesSortedStably) {
  const Mesh mesh = awkward_cylinder();
  const ContourFrame frame = make_contour_frame(mesh);
  const Eigen::Matrix3Xd normals = vertex_normals(mesh.positions, mesh.triangles);
  int checked = 0;
  for (const int reach : {1, 2, 8, 30}) {
    for (Index i = 0; i < mesh.num_vertices(); ++i) {
      Eigen::Vector3d m;
      if (!frame.is_contour_vertex(i) || !in_slice_normal(frame, normals.col(i), m)) continue;
      Profile got;
      along_contour_profile(frame, mesh.positions, i, m, reach, got);
      const Profile want = walked_then_sorted(frame, mesh.positions, i, m, reach);
      ASSERT_EQ(got.size, want.size) << "vertex " << i << ", reach " << reach;
      for (int k = 0; k < want.size; ++k) {
        ASSERT_EQ(got.x[static_cast<std::size_t>(k)], want.x[static_cast<std::size_t>(k)]) << "vertex " << i;
        ASSERT_EQ(got.y[static_cast<std::size_t>(k)], want.y[static_cast<std::size_t>(k)]) << "vertex " << i;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 4 * 100);
}

}  // namespace
}  // namespace contourmesh::detail
