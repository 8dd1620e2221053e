// SPDX-License-Identifier: BSD-3-Clause
// Private: contours found or drawn on one slice only, which the tiler leaves out (no partner on either
// adjacent slice): slabs for outer contours, hollow slabs for holes (docs/reconstruction.md, "Contours on
// one slice"). Shared by the image route (reconstruct) and the contour route (reconstruct_from_contours).
#pragma once

#include "contourmesh/reconstruct/contours.h"
#include "contourmesh/reconstruct/tiling.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace contourmesh::detail {

/// The contours of a stack that no vertex of a mesh carries: those the tiler left out.
struct UnmeshedContours {
  std::vector<std::pair<std::size_t, std::size_t>> list;  ///< (slice, contour), in slice then contour order
  std::vector<std::vector<std::uint8_t>> flags;           ///< per slice and contour: 1 when left out
  /// Whether contour c of slice s was left out (false for indices outside the stack, such as parent -1).
  [[nodiscard]] bool contains(std::size_t s, int c) const {
    return s < flags.size() && c >= 0 && static_cast<std::size_t>(c) < flags[s].size() &&
           flags[s][static_cast<std::size_t>(c)] != 0;
  }
};
[[nodiscard]] UnmeshedContours unmeshed_contours(const Mesh& mesh, const ContourStack& stack);

/// Half the gaps below and above slice `s` (an end slice reaches as far beyond as its one gap), mm.
[[nodiscard]] std::pair<double, double> half_gaps(const ContourStack& stack, std::size_t s);

/// A slab [w - below, w + above] around outer contour `c` of slice `s` and its holes: the contours
/// tiled between two copies capped in their planes (caps of role FaceRole::Cap). The contour's vertices
/// keep their ids (s, c) and their holes'; every other vertex has none.
[[nodiscard]] TilingResult single_slice_slab(const ContourStack& stack, std::size_t s, std::size_t c, double below,
                                             double above, const TilingOptions& tiling);

/// A closed hollow slab around hole `c` of slice `s`, oriented as a cavity (normals into the hole), as
/// thick as the full one [w - below, w + above] or thinner (1/2, 1/4, 1/10) where the full one would meet
/// `surface` around it (the material narrowing towards the next slice): the hole must lie strictly
/// inside the cross-sections of `surface` near both faces and half-way to them. nullopt when none fits.
/// `thinned` tells whether it is thinner than the full one. Only the faces of `surface` listed in
/// `near_faces` (those that may reach the slab: SlabFaces) are cut.
[[nodiscard]] std::optional<TilingResult> fitting_cavity(const Mesh& surface, const std::vector<Index>& near_faces,
                                                         const ContourStack& stack, std::size_t s, std::size_t c,
                                                         const TilingOptions& tiling, bool& thinned);

/// The faces of `mesh` whose extent along the stack's axis meets [w_s - below, w_s + above] of slice s,
/// for every slice (one pass over the faces).
[[nodiscard]] std::vector<std::vector<Index>> faces_near_slices(const Mesh& mesh, const ContourStack& stack);

/// The share (0 to 1) of the region of contour `c` of slice `s` (an outer contour) that the regions of the
/// adjacent slices cover (outer contours minus their holes), on whichever side covers more. A contour on
/// one slice that overlaps a region next to it is part of a piece that continues there (the tiler did not
/// join them: their overlap is under its thresholds); a slab of it would float beside that piece.
[[nodiscard]] double covered_by_adjacent_slices(const ContourStack& stack, std::size_t s, std::size_t c);

/// Appends `part` (vertices, ids and faces) to `mesh`, and its face roles to `roles` when given.
void append_part(Mesh& mesh, const TilingResult& part, std::vector<FaceRole>* roles = nullptr);

}  // namespace contourmesh::detail
