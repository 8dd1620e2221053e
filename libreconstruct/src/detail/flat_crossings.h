// SPDX-License-Identifier: BSD-3-Clause
// Private: the side of the pixels whose column the boundary crosses near the slice's own centre
// (segmentation; docs/reconstruction.md, "Surfaces that lie in a slice").
#pragma once

#include <cstddef>
#include <vector>

namespace contourmesh::detail {

/// A pixel of one slice (index in the slice, x fastest) and the value it is given.
struct PixelValue {
  std::size_t pixel = 0;
  float value = 0.0f;
};

struct FlatCrossingOptions {
  /// A pixel is undecided when the boundary crosses its column within this share of the slice spacing
  /// of the slice's centre: with a the neighbour slice's value on the inside and b the outside one's,
  /// |(c - t) / (a - b)| <= band (c the pixel's value, t the threshold).
  double band = 0.2;
  /// Patches of undecided pixels smaller than this keep the pixels' own sides.
  std::size_t min_pixels = 64;
  /// A patch is flat when the spread of its values (median absolute deviation) is at most this times
  /// their noise's (from second differences of adjacent pixels): its median then decides all of it. Other patches (a
  /// dome's rim, a face a few degrees off the slices, where the crossing's height varies across the
  /// patch) keep their pixels' own sides.
  double flatness = 1.3;
};

/// For slice z of a volume (nx x ny x nz values, x fastest; 0 < z < nz - 1) segmented at `threshold`:
/// the pixels of every patch (4-connected) of undecided pixels whose boundary crosses the same way (the
/// inside below, or above), whose side the patch decides as a whole instead of each pixel's noise. The
/// patch's values, as the share of the way from the outside neighbour to the inside one, minus the
/// threshold's, are fitted by a plane in the pixel coordinates: where the plane's slope is significant
/// (a surface a few degrees off the slices), a pixel is inside when the plane is at or above zero there;
/// otherwise (a surface in the slice, such as an end face on a slice centre), all are inside when the
/// patch's mean is. A pixel whose own value is on the other side gets `above` or `below` (just above or
/// under the threshold); the others keep theirs and are not listed. Empty when nothing changes.
[[nodiscard]] std::vector<PixelValue> flat_crossing_values(const float* volume, int nx, int ny, int nz, int z,
                                                           float threshold, float above, float below,
                                                           const FlatCrossingOptions& options = {});

}  // namespace contourmesh::detail
