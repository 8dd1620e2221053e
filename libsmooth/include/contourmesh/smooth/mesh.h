// SPDX-License-Identifier: BSD-3-Clause
// The triangle mesh type shared by every ContourMesh library: positions, triangles and the per-vertex
// contour ids that the smoothing of Xu et al. 2006 reads (the slice c(i) of each vertex, paper section 3).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <vector>

namespace contourmesh {

/// Vertex and triangle indices. 32 bits: 2^31 vertices is far beyond what one CT study produces.
using Index = std::int32_t;

/// Id used for "no slice / no contour" (for example a vertex added by capping or read from a file
/// without ids).
inline constexpr std::int32_t kNoId = -1;

using Triangle = std::array<Index, 3>;

/// A triangle mesh with optional contour ids.
///
/// - `positions` is 3 x n, one column per vertex, in the units of the input (millimetres for CT).
/// - `triangles` lists vertex indices counter-clockwise seen from outside (outward normals by the
///   right-hand rule).
/// - `slice_ids[i]` is c(i), the 0-based index of the slice (contour level) that vertex i lies on,
///   ordered along the slice axis; `contour_ids[i]` names the contour within that slice. Both are
///   either empty (a mesh without ids) or hold one entry per vertex; kNoId marks a vertex on no slice
///   (cap interiors, branching composites, intermediate contours, subdivision vertices). Any other
///   negative id is invalid, for every reader, writer, the CLI and the VTK filters.
struct Mesh {
  Eigen::Matrix3Xd positions;
  std::vector<Triangle> triangles;
  std::vector<std::int32_t> slice_ids;
  std::vector<std::int32_t> contour_ids;

  [[nodiscard]] Index num_vertices() const { return static_cast<Index>(positions.cols()); }
  [[nodiscard]] Index num_faces() const { return static_cast<Index>(triangles.size()); }
  /// True when both id arrays hold one entry per vertex.
  [[nodiscard]] bool has_contour_ids() const {
    return !slice_ids.empty() && slice_ids.size() == static_cast<std::size_t>(num_vertices()) &&
           contour_ids.size() == slice_ids.size();
  }
};

}  // namespace contourmesh
