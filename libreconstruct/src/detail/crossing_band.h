// SPDX-License-Identifier: BSD-3-Clause
// Private: the band between two composite contours whose outlines cross in the plane, as the lifted
// fill of the regions where exactly one of them has material (docs/reconstruction.md, "Tiling",
// many-to-many branchings).
#pragma once

#include "detail/tiling_types.h"

#include <cstddef>
#include <optional>
#include <vector>

namespace contourmesh::detail {

/// A band between two rings made by crossing_band, not yet part of its parent mesh.
struct CrossingBand {
  SlabMesh mesh;  ///< scratch mesh of the parent: the crossing vertices, the lifted interior vertices, the faces
  /// Faces of the parent that hold a ring edge split at crossing vertices: the face's index and the faces
  /// that replace it (same role), in the face's orientation.
  std::vector<std::pair<std::size_t, std::vector<Triangle>>> splits;
  TilingDefects defects;  ///< of `mesh`'s faces
};

/// The surface between ring `lower` on plane wl and ring `upper` on plane wu > wl (both
/// counter-clockwise, made of vertices the parent mesh owns; every ring edge already has exactly one
/// face of `parent` on its other side, as a composite's copy band or bridge has) where their outlines
/// cross. Each crossing of two edges becomes one vertex (no ids) at the crossing point, half-way between
/// the planes, inserted into both rings. The rings' arcs between crossings then bound the faces of the
/// plane arrangement where exactly one ring encloses material; each face is triangulated as a refined
/// cap would be, and its interior vertices are lifted between the planes by their relative distance to
/// the face's lower and upper arcs. Faces look up where the lower ring alone has material, down where the
/// upper one alone has. A least-area band between two such rings must cover the regions between their
/// crossings by fans that fold over themselves (every other face facing down); this fill covers each
/// once. Returns nothing when the rings do not cross, touch, cross themselves, or a face of the
/// arrangement is not simple.
[[nodiscard]] std::optional<CrossingBand> crossing_band(const LevelContour& lower, double wl,
                                                        const LevelContour& upper, double wu,
                                                        const SlabMesh& parent);

/// Appends `band`'s vertices and faces to `parent` (nothing may have been added to it since
/// crossing_band) and splits the parent's faces at the crossing vertices.
void absorb_crossing_band(CrossingBand&& band, SlabMesh& parent);

}  // namespace contourmesh::detail
