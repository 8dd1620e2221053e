// Options of the commands that read a CT volume (reconstruct, run, compare): what to do with unevenly
// spaced DICOM slices and with NaN or infinite voxels.
#pragma once

#include <reconstruct/volume.h>

#include <string>

namespace CLI {
class App;
}

namespace contourmesh::cli {

struct VolumeArgs {
  bool allow_uneven_slices = false;
  bool non_finite_as_air = false;
};

/// Registers --allow-uneven-slices and --non-finite-as-air.
void add_volume_options(CLI::App* command, VolumeArgs& args);

/// The read options for `args`; warnings are printed as "contourmesh COMMAND: warning: ..." lines, and
/// the libraries' own messages pass through with --verbose.
[[nodiscard]] VolumeReadOptions volume_read_options(const VolumeArgs& args, const std::string& command);

}  // namespace contourmesh::cli
