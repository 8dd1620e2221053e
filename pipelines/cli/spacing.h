// SPDX-License-Identifier: BSD-3-Clause
// The --spacing option's text ("sx,sy,sz" in mm), parsed for the contourmesh subcommands and the
// documentation tools (pipelines/tools) alike.
#pragma once

#include <Eigen/Core>

#include <string>

namespace contourmesh::cli {

/// Parses "sx,sy,sz": three comma-separated finite numbers > 0 (voxel spacing in mm); throws
/// InvalidInputError quoting the text otherwise.
[[nodiscard]] Eigen::Vector3d parse_spacing(const std::string& text);

}  // namespace contourmesh::cli
