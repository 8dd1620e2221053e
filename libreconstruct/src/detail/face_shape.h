// SPDX-License-Identifier: BSD-3-Clause
// Private: the face-shape measure and the angle thresholds shared by the passes that mend slivers (the
// slab pass after tiling, slab_remeshing.h; the flips after the off-slice heights, moved_face_flips.h;
// the collapses, sliver_collapse.h) and by the tiler's measure of its candidates (measure_defects).
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace contourmesh::detail {

/// A face whose smallest angle is under 10 degrees is a sliver: sharpness above this.
inline const double kSliverCosine = std::cos(10.0 * std::numbers::pi / 180.0);
/// A face whose normal is within 30 degrees of the slice axis lies nearly in the slice planes.
inline const double kLevelCosine = std::cos(30.0 * std::numbers::pi / 180.0);
/// A face whose normal is within 10 degrees of the slice axis is part of a shelf.
inline const double kShelfCosine = std::cos(10.0 * std::numbers::pi / 180.0);

/// Cosine of the smallest angle of triangle (a, b, c), the angle opposite its shortest edge: in [0.5, 1],
/// a measure of shape that falls as the smallest angle grows, without trigonometry. 1 for a degenerate
/// triangle.
[[nodiscard]] inline double sharpness(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  double e[3] = {(b - c).squaredNorm(), (c - a).squaredNorm(), (a - b).squaredNorm()};
  std::sort(e, e + 3);
  const double denominator = 2.0 * std::sqrt(e[1] * e[2]);
  if (!(denominator > 0.0)) return 1.0;
  return std::clamp((e[1] + e[2] - e[0]) / denominator, -1.0, 1.0);
}

}  // namespace contourmesh::detail
