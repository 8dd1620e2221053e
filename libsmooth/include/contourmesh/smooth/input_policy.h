// SPDX-License-Identifier: BSD-3-Clause
// The one input policy for meshes handed to ContourMesh from outside (a file, a VTK pipeline): what is
// refused, what is repaired with a warning and what is tolerated, and how the contour ids are made
// usable. The contourmesh CLI and vtkContourFeatureSmoothingFilter both call prepare_input_mesh, so
// that they give the same result on the same (dirty) mesh. docs/robustness.md lists every case.
#pragma once

#include "contourmesh/smooth/feature_detection.h"
#include "contourmesh/smooth/mesh.h"
#include "contourmesh/smooth/validation.h"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace contourmesh {

/// Coordinates beyond this magnitude are refused: the algorithms form squares, cubes (volumes) and
/// fourth powers (curvature fits) of coordinates, which must stay finite in double precision. 1e30 is
/// far beyond any physical unit a mesh is drawn in (millimetres, micrometres, metres).
inline constexpr double kMaxAbsCoordinate = 1e30;

/// What to do with triangles that face against their neighbours (two triangles traversing their
/// shared edge in the same direction).
enum class OrientationPolicy {
  /// Flip the minority of each connected piece so that its triangles agree (on a tie, a closed piece
  /// is oriented to enclose a positive volume); one warning. Default.
  Repair,
  /// Refuse the mesh (InvalidInputError naming two disagreeing triangles).
  Refuse,
};

/// How the contour ids (the slice id c(i) and contour id of every vertex) will be used.
enum class ContourIdUse {
  /// Passed through unused (the baseline smoothers): only the id contract is checked.
  PassThrough,
  /// Needed by the paper's feature detection or by cross-slice smoothing: gaps closed, inconsistent ids
  /// corrected from the slice planes, missing or unusable ids recovered along `slice_axis`, else
  /// MissingIds decides.
  Detection,
};

/// What detection does when a mesh has no usable contour ids and `slice_axis` cannot recover them.
enum class MissingIds {
  CurvatureOnly,  ///< fall back to curvature-only detection, with a warning (the paper's method in the CLI)
  /// InvalidInputError (cross-slice smoothing, which cannot do without ids; the VTK filter's
  /// ContourContinuity mode)
  Refuse,
};

/// Where the contour ids of a prepared mesh come from.
enum class IdSource {
  None,          ///< no usable ids: curvature-only detection (or ids unused)
  File,          ///< as given (gaps between slice ids closed)
  FileRepaired,  ///< as given, with the ids inconsistent with the slice planes corrected from them
  SlicePlanes,   ///< recovered by binning the vertices into slice planes
};

/// "none", "file", "file-repaired", "slice-planes".
[[nodiscard]] std::string_view to_string(IdSource source);

struct InputPolicyOptions {
  ContourIdUse ids = ContourIdUse::PassThrough;
  /// The slice axis given by the user. Used to recover ids that are missing or cannot describe slices
  /// (all equal while the vertices span several planes), and tried first when correcting inconsistent
  /// ids. Unset: such ids are refused, or MissingIds decides.
  std::optional<Eigen::Vector3d> slice_axis;
  /// Binning tolerance along `slice_axis` (0: 1e-4 of the extent); see assign_ids_by_slice_planes.
  double slice_tolerance = 0.0;
  MissingIds missing_ids = MissingIds::CurvatureOnly;
  OrientationPolicy orientation = OrientationPolicy::Repair;
  VertexMerging merging = VertexMerging::Coincident;
};

/// A mesh ready for detection and smoothing, and what was done to it.
struct PreparedMesh {
  Mesh mesh;
  /// One line per thing repaired or tolerated, without the source's name (the caller prefixes it).
  std::vector<std::string> warnings;
  IdSource id_source = IdSource::None;
  /// The detection mode the ids allow: ContourContinuity when they are usable, else CurvatureOnly
  /// (only with ContourIdUse::Detection and MissingIds::CurvatureOnly).
  DetectionMode detection_mode = DetectionMode::ContourContinuity;
  MeshRepair repair;         ///< what repair_mesh changed
  Index flipped_triangles = 0;  ///< triangles turned over by the orientation repair (both kinds)
};

/// Prepares a mesh from outside, in this order:
/// 1. Refuses (InvalidInputError whose message names the vertex, triangle or id; the caller adds the
///    source): no vertices or triangles, a non-finite coordinate, a coordinate beyond
///    kMaxAbsCoordinate, id arrays that do not hold one entry per vertex, a triangle index out of
///    range, an id below -1 (kNoId, -1, is the only legal negative id).
/// 2. Repairs (repair_mesh): coincident vertices merged (per `merging`), triangles with a repeated
///    vertex and duplicate triangles dropped; refuses a mesh left without triangles.
/// 3. Orientation: triangles facing against their neighbours are flipped or refused (`orientation`);
///    with Repair, inside-out closed pieces are turned over too (make_orientation_consistent); a
///    non-orientable piece (a Moebius strip) is refused.
/// 4. Tolerates with a warning what smoothing handles: zero-area and non-manifold elements.
/// 5. Contour ids. Every id -1 counts as no ids. With ContourIdUse::Detection: gaps between slice ids
///    are closed; ids that are all equal while the vertices span several planes are recovered along
///    `slice_axis` or refused; ids inconsistent with the slice planes are corrected from the planes
///    (repair_contour_ids), else recovered, else MissingIds decides; a mesh without ids gets them
///    from `slice_axis` (InvalidInputError when its vertices do not lie on planes normal to it), else
///    MissingIds decides.
[[nodiscard]] PreparedMesh prepare_input_mesh(Mesh mesh, const InputPolicyOptions& options = {});

/// What make_orientation_consistent turned over.
struct OrientationRepair {
  Index against_neighbours = 0;    ///< triangles that faced against the rest of their piece
  Index inside_out_pieces = 0;     ///< closed pieces turned over whole
  Index inside_out_triangles = 0;  ///< their triangles
};

/// The orientation step alone. First each piece (triangles connected through edges of exactly two
/// triangles) is made consistent: every edge traversed once each way; the minority of the piece's
/// triangles turns over. Then a closed piece that encloses a negative volume is turned over whole
/// (inside out), unless its bounding box lies within that of a closed piece enclosing a positive volume
/// (a cavity's surface, which faces into the cavity). Throws InvalidInputError for a non-orientable
/// piece. Precondition: indices in range.
OrientationRepair make_orientation_consistent(Mesh& mesh);

/// The first pair of triangles that share an edge and traverse it in the same direction, or
/// std::nullopt when the orientation is consistent. Precondition: indices in range.
[[nodiscard]] std::optional<std::pair<Index, Index>> find_orientation_conflict(const Mesh& mesh);

}  // namespace contourmesh
