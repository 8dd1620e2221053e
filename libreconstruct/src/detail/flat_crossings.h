// SPDX-License-Identifier: BSD-3-Clause
// Private: the side of the pixels whose column the boundary crosses near the slice's own centre
// (segmentation; docs/reconstruction.md, "Surfaces that lie in a slice").
#pragma once

#include "detail/slice_components.h"

#include <cstddef>
#include <cstdint>
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
  /// Patches of undecided pixels smaller than this keep the pixels' own sides: on fewer the ratio of
  /// the two spreads below varies too much (at 60 HU, patches of 70 pixels on the skull phantom's dome
  /// passed as flat).
  std::size_t min_pixels = 128;
  /// A patch is flat when the spread of its values (median absolute deviation) is at most this times
  /// their noise's (from second differences of adjacent pixels): its median then decides all of it. Other patches (a
  /// dome's rim, a face a few degrees off the slices, where the crossing's height varies across the
  /// patch) keep their pixels' own sides.
  double flatness = 1.3;
  /// A flat patch is inside when its median share (c - b) / (a - b) is above this, whatever the
  /// threshold: the face then lies that far beyond the slice's centre (0.04 of a spacing). Inside, the
  /// off-slice heights lay its cap at least a tenth of a spacing beyond the slice; outside, between the
  /// slice before and this one, at most 0.02 of a spacing short of it (OffSliceOptions::min_fraction
  /// and cap_far_fraction): from 0.04 on, inside is the nearer of the two.
  double inside_share = 0.54;
};

/// The buffers of flat_crossing_values, kept from call to call (one per thread): the undecided pixels of
/// one way of crossing, their patches and what each patch's test reads, and which pixels got a value.
struct FlatCrossingScratch {
  std::vector<std::uint8_t> mask;  // 1: undecided
  std::vector<float> offset;       // (c - t) / (a - b): the share above the threshold's
  std::vector<PixelRun> runs;
  UnionFind<int> labels;
  std::vector<std::vector<float>> values, differences, shares;  // per patch
  std::vector<std::uint8_t> changed;                            // per pixel: given a value already
};

/// For slice z of a volume (nx x ny x nz values, x fastest; 0 < z < nz - 1) segmented at `threshold`:
/// new values for the pixels of every flat patch of undecided pixels (4-connected; those with the inside
/// below and those with it above apart), which the patch decides as a whole instead of each pixel's
/// noise. A patch of at least `min_pixels` is flat when the median absolute deviation of its values
/// (c - t) / (a - b) is at most `flatness` times their noise's, from second differences of adjacent
/// pixels: a surface in the slice, such as an end face on a slice centre. On a dome's rim or a face a
/// few degrees off the slices, where the crossing's height runs across the band, the pixels keep their
/// own values. A flat patch is inside when its median share (c - b) / (a - b) is above `inside_share`:
/// its pixels and their neighbours are then divided by that share, as if the voxels were wholly inside
/// (at least `above` in the patch); otherwise its pixels are at most `below`. Pixels whose value does
/// not change are not listed. Empty when nothing changes.
[[nodiscard]] std::vector<PixelValue> flat_crossing_values(const float* volume, int nx, int ny, int nz, int z,
                                                           float threshold, float above, float below,
                                                           const FlatCrossingOptions& options,
                                                           FlatCrossingScratch& scratch);

/// The same with buffers of its own.
[[nodiscard]] std::vector<PixelValue> flat_crossing_values(const float* volume, int nx, int ny, int nz, int z,
                                                           float threshold, float above, float below,
                                                           const FlatCrossingOptions& options = {});

}  // namespace contourmesh::detail
