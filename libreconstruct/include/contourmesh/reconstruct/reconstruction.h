// SPDX-License-Identifier: BSD-3-Clause
// The reconstruction chain (docs/reconstruction.md): CT volume -> segmentation -> contours -> tiling -> mesh.
#pragma once

#include "contourmesh/reconstruct/off_slice_heights.h"
#include "contourmesh/reconstruct/segmentation.h"
#include "contourmesh/reconstruct/tiling.h"
#include "contourmesh/reconstruct/volume.h"

#include <contourmesh/smooth/mesh.h>
#include <contourmesh/smooth/progress.h>

namespace contourmesh {

struct ReconstructionOptions {
  SegmentationOptions segmentation;
  TilingOptions tiling;
  /// Mesh components enclosing less than this many voxel volumes are dropped as specks (fragments of a
  /// few voxels are noise, and smoothing collapses their few-vertex rings into degenerate triangles).
  /// >= 0; 0 keeps everything.
  double min_component_voxels = 4.0;
  /// Heights of the vertices the tiler puts between the slices (caps, intermediate contours): from the
  /// image by default (off_slice_heights.h).
  OffSliceOptions off_slice;
  /// Contours found on one slice only (no partner on either adjacent slice), which the tiler leaves out:
  /// slabs half-way to the adjacent slices, hollow for holes, by default; specks among them then go
  /// with `min_component_voxels`, and holes whose hollow slab would enclose less are filled.
  SingleSliceContours single_slice = SingleSliceContours::Slab;
};

struct ReconstructionReport {
  std::size_t slices = 0;          ///< slices of the volume
  std::size_t slices_with_contours = 0;
  std::size_t contours = 0;        ///< outer and hole contours extracted
  std::size_t hole_contours = 0;
  double threshold = 0.0;          ///< the threshold used (HU or raw units)
  std::size_t dropped_regions = 0;
  std::size_t dropped_components = 0;  ///< mesh components below min_component_voxels
  /// Contours on one slice only (ReconstructionOptions::single_slice): outer contours made slabs (specks
  /// among them are counted again in dropped_components), holes made hollow slabs (thinned: of them,
  /// thinner than half-way to the adjacent slices), and holes filled (their hollow slab would enclose less
  /// than min_component_voxels, would not fit in the surface around, or single_slice is Drop). Left out:
  /// outer contours not meshed (single_slice is Drop, end caps are not HalfSpacing, or a region of an
  /// adjacent slice covers more than 1 % of the contour's region: a tongue of a piece there, which the
  /// tiler did not join it to) and the holes inside them. A slab's holes are part of it and not counted.
  std::size_t single_slice_slabs = 0;
  std::size_t single_slice_cavities = 0;
  std::size_t single_slice_thinned = 0;
  std::size_t single_slice_filled = 0;
  std::size_t single_slice_left_out = 0;
  TilingStats tiling;
  double seconds_segment = 0.0;
  double seconds_tile = 0.0;
  OffSliceReport off_slice;     ///< vertices between the slices placed from the image
  double seconds_off_slice = 0.0;
};

struct Reconstruction {
  Mesh mesh;  ///< tiled mesh with slice and contour ids (see tile_contours)
  std::vector<FaceRole> face_roles;  ///< one per face of `mesh` (see tile_contours)
  ContourStack contours;
  ReconstructionReport report;
};

/// Segments and tiles a volume. Throws InvalidInputError when no contour is found (for example an
/// all-air volume or a threshold above every voxel), when every voxel is foreground (an all-bone
/// volume, whose only surface would be the volume's box) or when fewer than two slices hold contours,
/// naming the threshold used; LimitError when the tiled mesh would exceed `options.tiling.limits`;
/// CancelledError when `progress` returns false.
[[nodiscard]] Reconstruction reconstruct(const CtImage& image, const ReconstructionOptions& options = {},
                                         const ProgressCallback& progress = {});

}  // namespace contourmesh
