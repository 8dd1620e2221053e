// SPDX-License-Identifier: BSD-3-Clause
// Element quality of triangle meshes, for judging a tiling before any smoothing: the share of the area
// in slivers, the area of faces parallel to the slice planes ("shelves"), and the share of vertices that
// carry no contour id. docs/reconstruction.md ("Judging a tiling") says how these numbers are used.
#pragma once

#include "contourmesh/smooth/mesh.h"

#include <Eigen/Core>

#include <cstdint>
#include <span>
#include <vector>

namespace contourmesh {

/// Smallest interior angle of the triangle (a, b, c), in degrees, in [0, 60]. 0 for a triangle with a
/// repeated corner or collinear corners.
[[nodiscard]] double minimum_angle_degrees(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                           const Eigen::Vector3d& c);

/// Share of the surface area, in [0, 1], held by faces whose smallest angle is below
/// `min_angle_degrees` (slivers: their normals, curvatures and umbrella operators are unreliable).
/// 0 for a mesh of zero area. Throws InvalidInputError for an angle outside [0, 60] or a triangle index
/// outside the positions.
[[nodiscard]] double sliver_area_share(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                                       double min_angle_degrees = 10.0);
[[nodiscard]] double sliver_area_share(const Mesh& mesh, double min_angle_degrees = 10.0);

/// Area (squared input units) of the faces whose normal lies within `max_angle_degrees` of the line of
/// `axis` (either direction): for axis = the slice axis, the faces within that angle of the slice
/// planes. Faces f with skip[f] != 0 are left out (for example a tiler's end caps, which are flat by
/// construction); `skip` is empty or holds one entry per face. Zero-area faces count for nothing.
/// Throws InvalidInputError for a zero or non-finite axis, an angle outside [0, 90], a `skip` of the wrong
/// size or a triangle index outside the positions.
[[nodiscard]] double area_facing_axis(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                                      const Eigen::Vector3d& axis, double max_angle_degrees,
                                      std::span<const std::uint8_t> skip = {});

/// Share of the surface area, in [0, 1], held by faces that share an edge with a face whose normal is more
/// than `min_turn_degrees` (in [0, 180]) from theirs: folds, where the surface doubles back on itself (the
/// pleats and teeth of a tiling, a spike). A cube's edges turn by 90 degrees; the default 120 counts only
/// sharper turns. Zero-area faces count for nothing and fold nothing; edges shared by other than two
/// faces are skipped. 0 for a mesh of zero area. Throws InvalidInputError for an angle outside [0, 180] or
/// a triangle index outside the positions. Sorts the edges: O(F log F), unlike the one-pass measures.
[[nodiscard]] double fold_area_share(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                                     double min_turn_degrees = 120.0);

/// Share of the vertices, in [0, 1], that lie on no input contour: slice id kNoId (cap interiors,
/// intermediate contours, subdivision vertices). 1 for a non-empty mesh without ids, 0 for an empty one.
[[nodiscard]] double share_without_ids(const Mesh& mesh);

/// The thresholds of mesh_quality.
struct MeshQualityOptions {
  double sliver_angle_degrees = 10.0;                   ///< faces with a smaller minimum angle are slivers
  double shelf_angle_degrees = 10.0;                    ///< faces whose normal is this close to the axis are shelves
  Eigen::Vector3d slice_axis = Eigen::Vector3d::UnitZ();  ///< normal of the slice planes (any length > 0)
};

/// The element-quality summary of a mesh.
struct MeshQuality {
  double area = 0.0;                 ///< total surface area
  double min_angle_degrees = 60.0;   ///< smallest angle of any face of non-zero area (60 for an empty mesh)
  double sliver_area_share = 0.0;    ///< sliver_area_share with options.sliver_angle_degrees
  double shelf_area = 0.0;           ///< area_facing_axis with the options' axis and angle, `skip` left out
  double shelf_area_share = 0.0;     ///< shelf_area / area (0 for a mesh of zero area)
  double share_without_ids = 0.0;    ///< share_without_ids
};

/// Computes the summary in one pass over the faces. `skip` as in area_facing_axis (it affects the shelf
/// numbers only). Throws InvalidInputError as the single measures do.
[[nodiscard]] MeshQuality mesh_quality(const Mesh& mesh, const MeshQualityOptions& options = {},
                                       std::span<const std::uint8_t> skip = {});

}  // namespace contourmesh
