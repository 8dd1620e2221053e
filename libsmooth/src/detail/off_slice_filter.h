// SPDX-License-Identifier: BSD-3-Clause
// The last stage of cross-slice smoothing (docs/smoothing.md, "Vertices between the slices"): bilateral
// filtering of the normals of the faces that touch a vertex without contour ids, then a vertex update
// that fits those vertices to the filtered normals (Zheng, Fu, Au, Tai: "Bilateral normal filtering for
// mesh denoising", IEEE TVCG 2011, equations 4 and 6). Contour vertices do not move.
#pragma once

#include "detail/contour_profiles.h"
#include "contourmesh/smooth/cross_slice.h"

#include <Eigen/Core>

#include <atomic>

namespace contourmesh::detail {

/// When true, the normal filter recomputes every face in every iteration instead of only those whose
/// inputs changed; the output must not change, bit for bit (tests). Set it through ScopedFullRecompute.
inline std::atomic<bool>& full_recompute_override() {
  static std::atomic<bool> full{false};
  return full;
}
inline bool full_recompute() { return full_recompute_override(); }

/// Makes the normal filter recompute everything while it lives (tests of the change-skipping).
class ScopedFullRecompute {
 public:
  ScopedFullRecompute() : previous_(full_recompute_override().exchange(true)) {}
  ~ScopedFullRecompute() { full_recompute_override() = previous_; }
  ScopedFullRecompute(const ScopedFullRecompute&) = delete;
  ScopedFullRecompute& operator=(const ScopedFullRecompute&) = delete;

 private:
  bool previous_;
};

/// Moves the vertices of `positions` that are not contour vertices of `frame` (caps, intermediate
/// contours) so that the faces around them follow their bilaterally filtered normals; each stays in its
/// slab between two slice planes, at least a twentieth of a spacing from either, and within
/// `options.max_move` slice spacings of where it started. Returns the number of vertices moved.
std::size_t filter_off_slice_normals(const ContourFrame& frame, const std::vector<Triangle>& triangles,
                                     const OffSliceFilterOptions& options, Eigen::Matrix3Xd& positions);

}  // namespace contourmesh::detail
