// SPDX-License-Identifier: BSD-3-Clause
// Private: closing contours that end (an object's end, a cavity's roof or floor).
#pragma once

#include "detail/tiling_types.h"

#include <vector>

namespace contourmesh::detail {

/// Closes an outer contour of plane `w` (with its holes) that has no partner going up (`upward`) or
/// down. With `extension` > 0 the contours are first extended by a straight band to copies that far
/// beyond the plane, and the copies are capped. The cap is ear clipping refined into a constrained
/// Delaunay triangulation with interior vertices about one contour spacing apart
/// (CapRefinement::Interior) or left as clipped (CapRefinement::EarClipping). Faces of the cap have
/// `role` (Cap for an end; Bridge where a piece is parted) and face away from the object.
void cap_end(const LevelContour& outer, const std::vector<const LevelContour*>& holes, double w, double extension,
             bool upward, const TilingOptions& options, SlabMesh& out, FaceRole role = FaceRole::Cap);

/// Triangulates the planar region inside `outer` minus `holes` (clockwise), all on plane w, facing up or
/// down, with faces of `role`: a refined constrained Delaunay triangulation (CapRefinement::Interior,
/// interior vertices about one spacing of `outer` apart) or ear clipping.
void fill_planar(const LevelContour& outer, const std::vector<LevelContour>& holes, double w, bool facing_up,
                 FaceRole role, const TilingOptions& options, SlabMesh& out);

/// Closes a hole of plane `w` that ends going up (`upward`) or down inside an outer contour that goes
/// on: a cap facing into the cavity, after the same extension.
void cap_hole_end(const LevelContour& hole, double w, double extension, bool upward, const TilingOptions& options,
                  SlabMesh& out);

}  // namespace contourmesh::detail
