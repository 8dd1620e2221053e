// SPDX-License-Identifier: BSD-3-Clause
// Label maps and 3D Slicer segmentations: volumes whose voxels hold integer labels (NIfTI, NRRD,
// MetaImage label maps; Slicer's .seg.nrrd, 3-D or 4-D with layers), and their surfaces, one closed
// mesh per label (docs/reconstruction.md, "Label maps").
#pragma once

#include "contourmesh/reconstruct/reconstruction.h"
#include "contourmesh/reconstruct/volume.h"

#include <contourmesh/smooth/progress.h>

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace contourmesh {

/// One label of a label map: the voxels of one layer that hold `value`.
struct Label {
  int value = 0;      ///< voxel value, > 0 (0 is background)
  int layer = 0;      ///< layer of a 4-D .seg.nrrd (its first axis); 0 otherwise
  std::string name;   ///< segment name (Slicer's Segment<k>_Name); empty when the file names none
  std::string id;     ///< segment id (Segment<k>_ID); empty when the file has none
  std::size_t voxels = 0;  ///< voxels carrying the label (0 for a declared segment that is empty)
  /// The name when there is one, else the value: "femur", "2".
  [[nodiscard]] std::string display_name() const;
};

/// A label map as read: one image per layer (float voxels holding exact integers, LPS physical space as
/// read by ITK) and its labels.
struct LabelMap {
  std::vector<CtImage::Pointer> layers;  ///< at least one; all on the same grid
  /// A .seg.nrrd: every segment the file declares, in its order (Segment0, Segment1, ...). Otherwise:
  /// every value > 0 present, in increasing order, without names.
  std::vector<Label> labels;
  bool has_segment_metadata = false;  ///< labels come from Slicer's Segment<k>_* keys
};

/// The most distinct labels a label map may hold. A volume with more (a CT scan read as a label map) is
/// refused.
inline constexpr std::size_t kMaxLabels = 4096;

/// Reads a label map from a .nii/.nii.gz, .nrrd/.nhdr or .mha/.mhd file, or a 3D Slicer segmentation
/// (.seg.nrrd): its Segment<k>_Name, _ID, _LabelValue and _Layer keys name the labels, and a 4-D file
/// (first axis of kind "list": one layer per element, as Slicer writes overlapping segments) gives one
/// layer per element. Throws InvalidInputError naming the file for what read_volume refuses, a voxel
/// value that is negative or not an integer (naming it: a CT volume is not a label map), more than
/// kMaxLabels distinct values, or segment metadata that points at a layer the file does not have;
/// LimitError as read_volume.
[[nodiscard]] LabelMap read_label_map(const std::filesystem::path& path);

/// A label map from an image already in memory (one layer, no names). Throws InvalidInputError as
/// read_label_map for values that are not labels.
[[nodiscard]] LabelMap label_map_from_image(CtImage::Pointer image);

/// The labels named by `spec`: "all" (every label with voxels), or a comma-separated list of values
/// ("2", "1,3") or names ("femur,tibia"; matched exactly, then ignoring case). Throws InvalidInputError
/// listing the labels present when a requested one is not in the map, or for an empty spec.
[[nodiscard]] std::vector<Label> select_labels(const LabelMap& map, std::string_view spec);

/// The value of label voxels in label_mask (background is 0). Large against the one-unit margin by which
/// segmentation lifts a region's pixels above its threshold, so that the contour at half of it runs
/// exactly half-way between a label voxel and a background voxel.
inline constexpr float kLabelMaskInside = 100.0f;

/// The voxels of `label` as a binary volume (kLabelMaskInside inside, 0 outside) cropped to the label's
/// bounding box plus one voxel of background on every side (beyond the map's extent where the label
/// touches it, so that every label gives a closed surface); physical positions are those of the map.
/// Throws InvalidInputError when the label has no voxels.
[[nodiscard]] CtImage::Pointer label_mask(const LabelMap& map, const Label& label);

/// Surface of one label: label_mask, then the threshold path of reconstruct() at kLabelMaskInside / 2
/// (the contour runs half-way between a label voxel and a background voxel, so the mesh encloses about
/// the label's voxel volume), with `options` otherwise (their threshold, threshold method and image
/// smoothing are replaced). Errors name the label ("label 'femur' (2): ...").
[[nodiscard]] Reconstruction reconstruct_label(const LabelMap& map, const Label& label,
                                               ReconstructionOptions options = {},
                                               const ProgressCallback& progress = {});

/// A file-name-safe form of the label's display name: letters, digits, '-', '_' and '.' kept, every
/// other run of characters replaced by one '_' ("Left femur" -> "Left_femur", value 2 -> "2").
[[nodiscard]] std::string label_file_tag(const Label& label);

}  // namespace contourmesh
