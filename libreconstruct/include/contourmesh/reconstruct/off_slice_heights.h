// SPDX-License-Identifier: BSD-3-Clause
// Heights of the vertices that the tiler puts between the slices (end caps and their rims, the
// intermediate contours of branchings and refined bands), taken from the image instead of a fixed rule.
//
// A contour mesh knows the surface exactly only on the slices. Between them the tiler has to guess: an
// end cap lies half a spacing beyond the last contour, an intermediate contour at its interpolated
// level. Those guesses hold most of the error of an unsmoothed contour mesh (an end face that falls on
// a slice centre is a whole half spacing off, a dome is flattened, a face a few degrees off the slices
// is a staircase). The image knows better: the intensities of the two slices around such a vertex say
// where along the slice axis the boundary crosses between them. Method: docs/reconstruction.md,
// "Off-slice heights".
#pragma once

#include "contourmesh/reconstruct/tiling.h"
#include "contourmesh/reconstruct/volume.h"

#include <contourmesh/smooth/mesh.h>

#include <cstddef>
#include <vector>

namespace contourmesh {

/// Where the vertices between the slices end up.
enum class OffSlicePlacement {
  /// Where the tiler put them (end caps half a spacing beyond the last contour, intermediate contours
  /// at their interpolated level): the radiotherapy convention, and all a contour stack without an
  /// image allows.
  Tiled,
  /// Moved along the slice axis to where the image crosses the threshold between the two slices around
  /// them (fit_off_slice_heights). Default of the image route.
  ImageCrossing,
};

/// How far inwards of its own column each vertex reads the image.
enum class InwardRead {
  /// Vertices of end caps (faces of role FaceRole::Cap, when the face roles are given) read the whole
  /// step of `inward_pixels`; every other vertex a step scaled by sqrt(1 - |n_w|) for its unit normal
  /// n (the whole step on a wall along the slice axis, none on a face parallel to the slices). At a
  /// cap's rim, and on a steep wall, the boundary column is blurred in the plane and the step reads a
  /// column that crosses; on a face tilted off the slices the column a step inwards crosses at another
  /// height than the vertex's own, a bias of about the step times the face's slope, which laid the
  /// intermediate contours of the pelvis phantom's branchings out as flat rows
  /// (docs/reconstruction.md, "Off-slice heights"). Without face roles every vertex reads the whole
  /// step. Default.
  ScaledOffCaps,
  /// Every vertex reads the whole step (the rule until 2026-11-25).
  Whole,
};

struct OffSliceOptions {
  OffSlicePlacement placement = OffSlicePlacement::ImageCrossing;
  /// Weight of the membrane term that keeps neighbouring heights alike, relative to the image's data
  /// term, > 0. Larger: smoother caps, less detail; the value suits 20-60 HU of noise at 1000 HU of
  /// contrast.
  double smoothness = 0.2;
  /// Jacobi iterations of the fit, >= 1.
  int iterations = 20;
  /// A vertex stays at least this fraction of the slice spacing away from either slice, in [0, 0.5):
  /// it never lands on a slice, where it would make faces of zero area with the contour there.
  double min_fraction = 0.1;
  /// An end cap's vertex (faces of role FaceRole::Cap, when the face roles are given) may come this
  /// near the slice beyond it, the one the cap faces (no contour of its own lies there), in [0, 0.5);
  /// at most `min_fraction` counts: an end face read between 0.9 and 0.98 of the way there is laid
  /// where it is read.
  double cap_far_fraction = 0.02;
  /// The image is read this many pixels inwards along the vertex's in-plane normal (scaled by the
  /// normal's in-plane part), >= 0: at a cap's rim the boundary column itself is blurred in the plane.
  /// Off the caps the step is scaled by default (`inward_read`).
  double inward_pixels = 1.0;
  InwardRead inward_read = InwardRead::ScaledOffCaps;
};

struct OffSliceReport {
  std::size_t candidates = 0;  ///< vertices without ids strictly between two slices
  std::size_t fitted = 0;      ///< of them, vertices where the image crosses the threshold (data terms)
  std::size_t damped = 0;      ///< vertices whose move was reduced so that no face turns over
};

struct OffSliceResult {
  Mesh mesh;  ///< the input with the vertices between the slices moved along the slice axis
  OffSliceReport report;
};

/// Moves the vertices of `mesh` that carry no slice id (mesh.slice_ids[i] < 0) and lie strictly between
/// two slices of `image` along its slice axis (index axis 2 in the image's direction frame), to the
/// height where the image crosses `threshold`, regularised by a membrane over the mesh's edges in which
/// vertices with ids hold still. Per vertex at (u, v) between slices k and k + 1, with values a and b
/// there (bilinear in the plane) and the values beyond, i = k - 1 inside and o = k + 2 outside (or the
/// reverse), the values are normalised by the column's own levels to the shares of the two voxels that
/// lie inside, a' = (a - o) / (i - o) and b' likewise in [0, 1], so that partial volume in the plane
/// cancels. A voxel value is the mean over its slice profile; profiles that tile the axis (a box as wide
/// as the spacing, blurred or not) make a' + b' grow linearly with the boundary's height, so t = a' + b'
/// - 1/2 when slice k is the inside one (3/2 - a' - b' otherwise). Without the levels beyond (the first
/// and last slices) the threshold is interpolated linearly, t = (a - c) / (a - b) for threshold c.
/// The data weight is |n_w| of the vertex normal (the crossing along the axis is well posed only where
/// the surface faces it). Moves stay within the slab, `min_fraction` away from its slices, and are
/// halved on the vertices of any face that would turn by more than about 80 degrees. Vertices with ids
/// and the connectivity are unchanged. `threshold` is the one the contours were traced at; `image` is
/// the one they were traced on. Throws InvalidInputError when the mesh has no ids or the options are
/// out of range.
/// `face_roles` (one per face, as tile_contours gives them, or empty) tell the end caps' vertices apart
/// for InwardRead::ScaledOffCaps; InvalidInputError when given with another count than the faces.
[[nodiscard]] OffSliceResult fit_off_slice_heights(Mesh mesh, const CtImage& image, double threshold,
                                                   const OffSliceOptions& options = {},
                                                   const std::vector<FaceRole>& face_roles = {});

}  // namespace contourmesh
