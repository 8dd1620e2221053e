// SPDX-License-Identifier: BSD-3-Clause
// Segmentation of a CT volume into ordered contours per slice (docs/reconstruction.md): optional
// denoising, threshold in HU (or Otsu), connected components, per-slice hole handling, sub-pixel
// contours by marching squares, orientation, and resampling to a target in-plane spacing.
#pragma once

#include "contourmesh/reconstruct/contours.h"
#include "contourmesh/reconstruct/volume.h"

#include <contourmesh/smooth/limits.h>
#include <contourmesh/smooth/progress.h>

#include <cstddef>

namespace contourmesh {

enum class ThresholdMethod {
  Fixed,  ///< voxels >= `threshold` are foreground
  Otsu,   ///< Otsu's threshold of the (smoothed) volume's histogram; for data that is not in HU
};

enum class ImageSmoothing {
  None,
  Median,                  ///< 3 x 3 median in each slice plane
  CurvatureAnisotropic,    ///< 5 steps of curvature anisotropic diffusion (edge preserving), 3-D
};

enum class ComponentSelection {
  KeepAll,      ///< every region of at least `min_region_area` in its slice
  KeepLargest,  ///< only the largest 6-connected 3-D component (drops the table, loose fragments)
};

/// How the pixels of a slice are decided where the boundary crosses their columns near the slice's own
/// centre: a surface lying in or a few degrees off a slice plane, such as an end face on a slice centre
/// (docs/reconstruction.md, "Surfaces that lie in a slice").
enum class FlatCrossings {
  PerPixel,  ///< each pixel by its own value: half-bone pixels fall either way with the noise
  Patches,   ///< each patch of such pixels as a whole, or along a plane fitted over it
};

struct SegmentationOptions {
  ThresholdMethod threshold_method = ThresholdMethod::Fixed;
  /// Foreground threshold in the image's units (HU for CT). 300 HU keeps cortical and most
  /// trabecular bone and rejects soft tissue and contrast-free vessels.
  double threshold = 300.0;
  ImageSmoothing smoothing = ImageSmoothing::None;
  ComponentSelection components = ComponentSelection::KeepAll;
  /// Per slice, foreground regions smaller than this (mm^2) are dropped and holes smaller than this
  /// are filled. >= 0.
  double min_region_area = 2.0;
  /// Fill every hole of every region (per slice), not only the small ones.
  bool fill_holes = false;
  /// Pixels whose column the boundary crosses within a fifth of the slice spacing of the slice's
  /// centre, in flat patches of at least 128: decided per patch by default.
  FlatCrossings flat_crossings = FlatCrossings::Patches;
  /// Target distance between contour points (the paper's "horizontal sampling rate"), mm.
  /// 0 = the smaller in-plane pixel spacing, but at most kMaxDefaultSampling: on coarse scans (3 mm
  /// pixels) contours at pixel spacing give small bones five to ten vertices, and those collapse
  /// under 40 smoothing iterations (a third of the volume lost on the TotalSegmentator sample;
  /// 3 % at 1 mm). A contour that would cross itself at this sampling (a
  /// narrow neck of a small region) is sampled more finely, so every contour is a simple polygon.
  double sampling = 0.0;
  static constexpr double kMaxDefaultSampling = 1.0;  ///< mm
  /// Contours shorter than this (mm) are dropped, with their holes. >= 0.
  double min_contour_length = 3.0;
  /// Vertex cap and memory budget for the contour points: before each contour is resampled, the points
  /// it would add to the stack are checked (a tiny `sampling` is refused with a LimitError at once,
  /// instead of growing until the memory runs out).
  ResourceLimits limits;
};

struct SegmentationResult {
  ContourStack stack;        ///< one entry per image slice (possibly with no contours), ids = slice index
  double threshold = 0.0;    ///< the threshold used (the Otsu value when chosen)
  std::size_t dropped_regions = 0;  ///< regions dropped as too small or too short
  std::size_t voxels = 0;             ///< voxels of the volume
  std::size_t foreground_voxels = 0;  ///< voxels at or above the threshold (before component selection)
  /// The image the contours were traced on when `smoothing` made a new one; null otherwise (the input).
  CtImage::Pointer smoothed_image;
};

/// Segments every slice (index axis 2) of `image` and extracts its contours in the slice frame
/// (origin, axes and w from the image's origin, direction and spacing). Outer contours are
/// counter-clockwise, holes clockwise with `parent` set. Slices are segmented in parallel on the
/// threads a ThreadLimit (threads.h) allows, every core by default; the result does not depend on
/// their number. Throws InvalidInputError for an empty image or options out of range; LimitError when
/// the resampled contour points would exceed `limits`; CancelledError when `progress` (stage
/// "segment", called from the calling thread) returns false.
[[nodiscard]] SegmentationResult segment_contours(const CtImage& image, const SegmentationOptions& options = {},
                                                  const ProgressCallback& progress = {});

}  // namespace contourmesh
