// SPDX-License-Identifier: BSD-3-Clause
#include "volume_options.h"

#include "cli_common.h"
#include "progress_display.h"

#include <CLI/CLI.hpp>
#include <contourmesh/smooth/errors.h>

#include <iostream>

namespace contourmesh::cli {

void add_volume_options(CLI::App* command, VolumeArgs& args) {
  command->add_flag("--allow-uneven-slices", args.allow_uneven_slices,
                    "DICOM: resample unevenly spaced slices (a missing slice) onto an even grid by linear "
                    "interpolation, with a warning, instead of refusing the series");
  command->add_flag("--non-finite-as-air", args.non_finite_as_air,
                    "Read NaN and infinite voxels as air (the volume's lowest value), with a warning, instead of "
                    "refusing the volume");
  command
      ->add_option("--off-slice", args.off_slice,
                   "Heights of the vertices between the slices (end caps, intermediate contours): image (where the "
                   "intensity between the two slices crosses the threshold) | tiled (end caps half a spacing beyond "
                   "the last contour)")
      ->capture_default_str();
  command
      ->add_option("--flat-crossings", args.flat_crossings,
                   "Pixels whose column the boundary crosses near the slice's centre (an end face on a slice): "
                   "patches (a flat patch of them is decided as a whole) | per-pixel (each by its own value)")
      ->capture_default_str();
}

OffSlicePlacement off_slice_placement(const VolumeArgs& args) {
  if (args.off_slice == "image") return OffSlicePlacement::ImageCrossing;
  if (args.off_slice == "tiled") return OffSlicePlacement::Tiled;
  throw InvalidInputError("--off-slice must be image or tiled, got '" + args.off_slice + "'");
}

FlatCrossings flat_crossings(const VolumeArgs& args) {
  if (args.flat_crossings == "patches") return FlatCrossings::Patches;
  if (args.flat_crossings == "per-pixel") return FlatCrossings::PerPixel;
  throw InvalidInputError("--flat-crossings must be patches or per-pixel, got '" + args.flat_crossings + "'");
}

VolumeReadOptions volume_read_options(const VolumeArgs& args, const std::string& command) {
  VolumeReadOptions o;
  o.uneven_slices = args.allow_uneven_slices ? UnevenSlices::Resample : UnevenSlices::Refuse;
  o.non_finite = args.non_finite_as_air ? NonFiniteVoxels::AsAir : NonFiniteVoxels::Refuse;
  o.library_messages = verbose() ? LibraryMessages::PassThrough : LibraryMessages::Capture;
  o.on_warning = [command](const std::string& line) {
    std::cerr << "contourmesh " << command << ": warning: " << cli_wording(line) << "\n";
  };
  return o;
}

}  // namespace contourmesh::cli
