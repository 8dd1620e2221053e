// SPDX-License-Identifier: BSD-3-Clause
// The slice axis of a mesh when it has one, for steps that use it where they can and work without it
// elsewhere. Private to libsmooth.
#pragma once

#include "contourmesh/smooth/contour_structure.h"
#include "contourmesh/smooth/errors.h"
#include "contourmesh/smooth/mesh.h"

#include <Eigen/Core>

#include <optional>

namespace contourmesh::detail {

/// The normal of the slice planes (estimate_slice_axis); nothing for a mesh without contour ids or
/// whose slices do not span planes.
inline std::optional<Eigen::Vector3d> slice_axis_if_any(const Mesh& mesh) {
  if (!mesh.has_contour_ids()) return std::nullopt;
  try {
    return estimate_slice_axis(mesh);
  } catch (const InvalidInputError&) {
    return std::nullopt;
  }
}

}  // namespace contourmesh::detail
