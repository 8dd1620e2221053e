// SPDX-License-Identifier: BSD-3-Clause
// Options of the commands that read a CT volume (reconstruct, run, compare): what to do with unevenly
// spaced DICOM slices and with NaN or infinite voxels.
#pragma once

#include <contourmesh/reconstruct/off_slice_heights.h>
#include <contourmesh/reconstruct/segmentation.h>
#include <contourmesh/reconstruct/volume.h>

#include <string>

namespace CLI {
class App;
}

namespace contourmesh::cli {

struct VolumeArgs {
  bool allow_uneven_slices = false;
  bool non_finite_as_air = false;
  std::string off_slice = "image";
  std::string flat_crossings = "patches";
};

/// Registers --allow-uneven-slices, --non-finite-as-air, --off-slice and --flat-crossings.
void add_volume_options(CLI::App* command, VolumeArgs& args);

/// The placement --off-slice names (image | tiled); InvalidInputError for anything else.
[[nodiscard]] OffSlicePlacement off_slice_placement(const VolumeArgs& args);

/// The rule --flat-crossings names (patches | per-pixel); InvalidInputError for anything else.
[[nodiscard]] FlatCrossings flat_crossings(const VolumeArgs& args);

/// The read options for `args`; warnings are printed as "contourmesh COMMAND: warning: ..." lines, and
/// the libraries' own messages pass through with --verbose.
[[nodiscard]] VolumeReadOptions volume_read_options(const VolumeArgs& args, const std::string& command);

}  // namespace contourmesh::cli
