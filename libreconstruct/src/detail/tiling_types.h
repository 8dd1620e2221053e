// SPDX-License-Identifier: BSD-3-Clause
// Private: the types the tiling phases share. A level is a set of contours on one plane w (a slice, or
// an intermediate plane made by interpolation); a slab mesh collects what one slab's tiling adds.
#pragma once

#include "contourmesh/internal/polygon2d.h"
#include "contourmesh/reconstruct/tiling.h"

#include <contourmesh/smooth/limits.h>
#include <contourmesh/smooth/mesh.h>

#include <Eigen/Geometry>

#include <cstddef>
#include <vector>

namespace contourmesh::detail {

/// A vertex as a slab sees it: >= 0 is a vertex of the stack's own contours (its final index);
/// a vertex the slab adds itself (intermediate contours, copies, cap interiors) is local vertex k,
/// written -2 - k until the slabs are assembled.
using VertexRef = Index;
[[nodiscard]] inline VertexRef local_ref(std::size_t k) { return -2 - static_cast<Index>(k); }
[[nodiscard]] inline bool is_local(VertexRef v) { return v <= -2; }
[[nodiscard]] inline std::size_t local_index(VertexRef v) { return static_cast<std::size_t>(-2 - v); }

/// One contour of a level with the mesh vertex of each point.
struct LevelContour {
  Polygon points;                ///< outer counter-clockwise, hole clockwise
  std::vector<VertexRef> ids;    ///< one per point
  bool is_hole = false;
  int parent = -1;               ///< for a hole: index of its outer contour in the same level
  double area = 0.0;             ///< enclosed area, > 0
  Eigen::AlignedBox2d box;       ///< bounding box of the points

  /// Mean distance between consecutive points.
  [[nodiscard]] double spacing() const;
};

/// The contours of one plane.
struct Level {
  double w = 0.0;
  std::vector<LevelContour> contours;
};

/// Fills area and box from the points.
void finish_contour(LevelContour& c);

/// Where each of 0 .. size - 1 stands in `which` (which[k] = i gives k for i), -1 for those not listed:
/// how restrict_level and restrict_correspondence renumber contours.
[[nodiscard]] std::vector<int> positions_in(const std::vector<int>& which, std::size_t size);

/// The level made of the listed contours of `level` (in that order), parents renumbered. A hole whose
/// parent is not listed keeps parent -1.
[[nodiscard]] Level restrict_level(const Level& level, const std::vector<int>& which);

/// What one slab adds to the mesh: local vertices (in the stack's slice frame, u, v and w) and faces over
/// VertexRefs, with their roles, and the slab's share of the statistics. A scratch mesh made by
/// scratch() continues its parent's local numbering, so that a candidate tiling can be built, measured,
/// and then absorbed or dropped.
struct SlabMesh {
  /// Positions (u, v, w) of the stack's own contour vertices, by index.
  const std::vector<Eigen::Vector3d>* stack_vertices = nullptr;
  std::vector<Eigen::Vector3d> vertices;  ///< this mesh's local vertices, (u, v, w)
  std::vector<Triangle> triangles;
  std::vector<FaceRole> roles;
  TilingStats stats;
  /// Local vertices this mesh and its ancestors may add before LimitError, and the mesh's vertex cap
  /// the error names.
  Index vertex_budget = kDefaultMaxVertices;
  Index vertex_limit = kDefaultMaxVertices;
  /// How faces are judged (measure_defects, band_quality): at (u, v) + shear * w instead of (u, v). The
  /// drift alignment tiles a slab with its upper slice moved to the lower one's centroid and shears the
  /// mesh back after; judged so, the faces are measured as they will be (zero: as tiled). Copied to
  /// scratch meshes.
  Eigen::Vector2d shear = Eigen::Vector2d::Zero();

  VertexRef add_vertex(const Eigen::Vector2d& uv, double w);
  void add_triangle(VertexRef a, VertexRef b, VertexRef c, FaceRole role) {
    triangles.push_back({a, b, c});
    roles.push_back(role);
  }
  /// Position (u, v, w) of any vertex this mesh may refer to.
  [[nodiscard]] Eigen::Vector3d position(VertexRef v) const;
  /// position(v) as faces are judged (see `shear`).
  [[nodiscard]] Eigen::Vector3d judged_position(VertexRef v) const {
    Eigen::Vector3d p = position(v);
    p.head<2>() += shear * p.z();
    return p;
  }
  /// An empty mesh whose local vertices follow this one's. Nothing may be added to this mesh while the
  /// scratch mesh lives.
  [[nodiscard]] SlabMesh scratch() const;
  /// Appends a scratch mesh made by scratch() (and nothing added to this mesh since).
  void absorb(SlabMesh&& child);

 private:
  std::size_t first_local_ = 0;
  const SlabMesh* parent_ = nullptr;
};

/// Whether the triangle's smallest angle is under 10 degrees (cheaper than minimum_angle_degrees: no
/// trigonometry).
[[nodiscard]] bool is_sliver(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// How much of a piece of tiling is of poor shape: faces nearly parallel to the slices (their normal
/// within 10 degrees of the slice axis; caps left out: they are flat by construction) and slivers (a
/// minimum angle under 10 degrees); a face that is both counts once.
struct TilingDefects {
  double area = 0.0;
  double flat_area = 0.0;
  double sliver_area = 0.0;
  double poor_area = 0.0;  ///< flat or sliver
  double bridge_area = 0.0;  ///< faces of role Bridge
  double longest_edge = 0.0;
  /// What candidate tilings are compared by (less is better): flat and sliver area, a face that is both
  /// counting twice.
  [[nodiscard]] double score() const { return flat_area + sliver_area; }
};
/// Judged at the mesh's judged positions (SlabMesh::shear).
[[nodiscard]] TilingDefects measure_defects(const SlabMesh& mesh);
/// Adds the faces `first_face` .. end of `mesh` to `defects`, in order: after faces are only appended,
/// measuring the new ones into the running total gives exactly measure_defects(mesh).
void measure_more_defects(const SlabMesh& mesh, std::size_t first_face, TilingDefects& defects);

}  // namespace contourmesh::detail
