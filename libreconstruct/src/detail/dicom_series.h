// SPDX-License-Identifier: BSD-3-Clause
// Private: a DICOM image series checked before it is stacked into a voxel grid. ITK's series reader
// stacks what it is given: a duplicated position made the spacing 0.3 mm (volume -74 %), a file cut in
// half was read as a slice of zeros, a missing slice was spread over a uniform spacing (slices
// misplaced by up to 0.6 mm), and only its raw warning said anything.
#pragma once

#include "contourmesh/reconstruct/volume.h"

#include <filesystem>
#include <string>
#include <vector>

namespace contourmesh::detail {

/// Reads the DICOM image series `series_uid` in `directory` (empty: the directory's only series; several
/// without a choice, or a UID the directory does not hold, are errors listing the UIDs): every file that carries the
/// DICOM magic must decode; the images must agree in size, pixel spacing and orientation, be single-frame, hold all
/// their pixel data, and lie on one line along the slice normal (no sideways drift: a gantry tilt shears the volume),
/// at distinct positions, evenly spaced (or, with UnevenSlices::Resample, interpolated linearly onto an even grid, with
/// a warning appended to `warnings`). The geometry is set from the checked headers: origin at the first slice's Image
/// Position, axes from Image Orientation and the normal, spacing from Pixel Spacing and the slice distance. Throws
/// InvalidInputError starting with `shown` and naming the files concerned; LimitError when the volume exceeds the
/// memory available.
[[nodiscard]] CtImage::Pointer read_dicom_series(const std::filesystem::path& directory, const std::string& shown,
                                                 const std::string& series_uid, UnevenSlices uneven,
                                                 std::vector<std::string>& warnings);

}  // namespace contourmesh::detail
