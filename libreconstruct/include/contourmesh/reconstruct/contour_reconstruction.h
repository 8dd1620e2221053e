// SPDX-License-Identifier: BSD-3-Clause
// The contour route: a stack of drawn contours (radiotherapy structures, contour files, VTK polylines)
// -> resampling -> tiling -> a closed mesh with contour ids. The counterpart of reconstruct() for input
// that is already contours. See docs/contours.md.
#pragma once

#include "contourmesh/reconstruct/contours.h"
#include "contourmesh/reconstruct/tiling.h"

#include <contourmesh/smooth/mesh.h>
#include <contourmesh/smooth/progress.h>

#include <cstddef>
#include <string>
#include <vector>

namespace contourmesh {

/// How the tiler sees slices whose one contour drifts sideways from slice to slice.
enum class DriftAlignment {
  /// Between two adjacent slices that each hold exactly one contour, and whose contours overlap (by
  /// twice the tiler's minimum overlap) and overlap at least as much once their centroids meet (a drift,
  /// not an outline growing on one side), the upper slice is shifted so that the centroids coincide
  /// while tiling; the mesh is shifted back after (an exact, piecewise affine shear along the slice
  /// axis), and the tiler judges the slab's faces as they will be once shifted back, refining leaning
  /// bands through intermediate contours. The minimum-area tiling otherwise pinches an oblique structure
  /// into an hourglass between slices. Never changes which contours are connected. Default
  /// (docs/contours.md, "Drift alignment").
  Centroids,
  /// Tile the contours where they are.
  None,
};

struct ContourReconstructionOptions {
  TilingOptions tiling;
  /// Largest distance between contour points, mm (resample_drawn_stack); 0 tiles the points as drawn.
  /// >= 0.
  double sampling = 1.0;
  /// Largest distance a resampled contour may depart from the drawn one, mm, >= 0.
  double sampling_tolerance = 0.05;
  DriftAlignment alignment = DriftAlignment::Centroids;
  SingleSliceContours single_slice = SingleSliceContours::Slab;
  /// Thickness (mm) of the slab made when every contour lies in one slice; 0 refuses such a stack.
  /// >= 0.
  double slab_thickness = 0.0;
};

struct ContourReconstructionReport {
  std::size_t slices = 0;          ///< slices with contours
  std::size_t contours = 0;
  std::size_t hole_contours = 0;
  std::size_t points_drawn = 0;    ///< contour points before resampling
  std::size_t points_tiled = 0;    ///< after
  std::size_t slabs = 0;           ///< single-slice contours made into slabs
  std::size_t aligned_gaps = 0;    ///< slice gaps tiled with centroid alignment
  double slicewise_volume = 0.0;   ///< slicewise_volume() of the stack, mm^3
  TilingStats tiling;
  double seconds_tile = 0.0;
  std::vector<std::string> warnings;
};

struct ContourReconstruction {
  Mesh mesh;               ///< closed, outward-oriented, with slice and contour ids (see tile_contours)
  ContourStack contours;   ///< the stack as tiled (resampled); ids of the mesh index it
  ContourReconstructionReport report;
};

/// Tiles a normalised contour stack (from build_contour_stack or normalize_contour_stack; slices may be
/// empty). Slice ids of the mesh are indices into `stack.slices` (and `result.contours.slices`),
/// contour ids the indices within a slice. Throws InvalidInputError, prefixed by `what`, when there is
/// no contour, when every contour lies in one slice and `slab_thickness` is 0, when nothing can be
/// tiled, or for options out of range (and whatever tile_contours throws); LimitError past
/// `options.tiling.limits`; CancelledError when `progress` returns false.
[[nodiscard]] ContourReconstruction reconstruct_from_contours(const ContourStack& stack, const std::string& what,
                                                              const ContourReconstructionOptions& options = {},
                                                              const ProgressCallback& progress = {});

}  // namespace contourmesh
