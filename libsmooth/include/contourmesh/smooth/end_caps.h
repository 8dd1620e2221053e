// SPDX-License-Identifier: BSD-3-Clause
// How a contour-based mesh closes the ends of an object (docs/reconstruction.md, "Tiling").
#pragma once

namespace contourmesh {

/// Where the ends of an object are closed.
enum class EndCaps {
  /// Half a slice spacing beyond the last contour: the ending contours are extended by a straight band
  /// to a copy (vertex ids kNoId), and the copy is capped. A slice samples a slab one spacing thick, so
  /// this is the unbiased end position (the "slab" convention of radiotherapy structure volumes).
  /// Default.
  HalfSpacing,
  /// In the plane of the last contour: cap triangles use that slice's vertices only. The
  /// object then ends, on average, half a spacing short at each end.
  AtEndSlice,
};

}  // namespace contourmesh
