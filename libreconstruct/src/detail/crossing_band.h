// SPDX-License-Identifier: BSD-3-Clause
// Private: the band between two composite contours whose outlines cross in the plane, as the lifted
// fill of the regions where exactly one of them has material (docs/reconstruction.md, "Tiling",
// many-to-many branchings).
#pragma once

#include "detail/tiling_types.h"

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

namespace contourmesh::detail {

/// A band between two rings made by crossing_band, not yet part of its parent mesh.
struct CrossingBand {
  SlabMesh mesh;  ///< scratch mesh of the parent: the crossing vertices, the lifted interior vertices, the faces
  /// Ring edges split at crossing vertices (the edge as the ring runs, and the crossings from its first
  /// end to its second).
  std::vector<std::pair<std::pair<VertexRef, VertexRef>, std::vector<VertexRef>>> split_edges;
  /// Found by find_split_faces: the faces of the parent that hold those edges, each with the faces that
  /// replace it (same role), in the face's orientation.
  std::vector<std::pair<std::size_t, std::vector<Triangle>>> splits;
  TilingDefects defects;  ///< of `mesh`'s faces
};

/// The surface between ring `lower` on plane wl and ring `upper` on plane wu > wl (both
/// counter-clockwise, or both clockwise: holes) where their outlines cross. Each crossing of two edges
/// becomes one vertex (no ids) at the crossing point, half-way between the planes. It is inserted into
/// the edges of a ring that may be split (`split_lower`, `split_upper`: a composite, whose every edge has
/// exactly one face of `parent` on its other side, its copy band or a bridge; that face is split with
/// it); a ring that may not be split keeps its edge, and a fan of faces stands between the edge and the
/// crossings on it. The rings' arcs between crossings then bound the faces of the
/// plane arrangement where exactly one ring encloses material; each face is triangulated as a refined
/// cap would be, and its interior vertices are lifted between the planes by their relative distance to
/// the face's lower and upper arcs. Faces look up where the lower ring alone has material, down where the
/// upper one alone has. A least-area band between two such rings must cover the regions between their
/// crossings by fans that fold over themselves (every other face facing down); this fill covers each
/// once. Returns nothing when the rings do not cross, touch, cross themselves, when a face of the
/// arrangement is not simple, or when the arrangement has fewer such faces than crossings (the region
/// inside both rings in pieces, or a pocket inside neither that they enclose): that surface would have
/// more handles than the annulus of a band.
[[nodiscard]] std::optional<CrossingBand> crossing_band(const LevelContour& lower, double wl,
                                                        const LevelContour& upper, double wu, bool split_lower,
                                                        bool split_upper, const SlabMesh& parent);

/// Finds the face of `parent` on the other side of each split ring edge (the costly part, left until the
/// band is chosen); false when an edge has no such face, or several, or a face holds two split edges.
[[nodiscard]] bool find_split_faces(CrossingBand& band, const SlabMesh& parent);

/// Appends `band`'s vertices and faces to `parent` (after find_split_faces; nothing may have been added
/// to it since crossing_band) and splits the parent's faces at the crossing vertices.
void absorb_crossing_band(CrossingBand&& band, SlabMesh& parent);

}  // namespace contourmesh::detail
