// SPDX-License-Identifier: BSD-3-Clause
// Synthetic CT phantoms with analytic ground truth (docs/reconstruction.md, "Phantoms"): bone-like solids given by
// signed distance functions, rendered into CT-like volumes in Hounsfield units with partial-volume effect, blur and
// noise. The evaluation compares reconstructed and smoothed meshes against the analytic surface.
#pragma once

#include "contourmesh/reconstruct/volume.h"

#include <contourmesh/smooth/metrics.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <string_view>
#include <vector>

namespace contourmesh {

/// The built-in phantoms. The first seven are bone-like; the next three isolate the failure classes of
/// contour stacks; the last is an extra, harder case outside `--phantom all` (extra_phantom_shapes). The
/// slice-alignment claims hold for the default PhantomVolumeOptions (0.7 x 0.7 x 2 mm, 6 mm margin);
/// docs/reconstruction.md ("Phantoms") gives each shape's dimensions.
enum class PhantomShape {
  RidgeBox,    ///< "ridge-box": a block with a roof ridge running along the slice axis, sharp edges and corners
  Femur,       ///< "femur": shaft with a sharp posterior ridge, neck and head, two condyles
  Pelvis,      ///< "pelvis": a tilted ring with a sharp crest (genus 1; slices hold rings and split arcs)
  Skull,       ///< "skull": a dome-shaped shell open at the bottom with two orbit holes (genus 2)
  Branch,      ///< "branch": a trunk that splits into two limbs along the slice axis
  TwoObjects,  ///< "two-objects": two separate bones side by side in the same slices
  Cavity,      ///< "cavity": a solid with an internal cavity, so slices hold hole contours
  /// "tilted-box": a 70 x 50 x 20 mm slab whose large faces are 4 degrees off the slice planes, bevelled
  /// at one end by a face 15 degrees off them; every edge oblique to the slices
  TiltedBox,
  /// "in-slice-ridge": a prism lying across the slice axis whose two roof ridges run within slice
  /// planes: ridge A (z = 10) on a slice centre, ridge B (z = 15, the top) half-way between slices
  InSliceRidge,
  /// "end-face-on-slice": a cylinder whose flat end faces (z = -15 and 13) lie exactly on slice centres,
  /// beside a box whose end faces (z = +-20) lie half-way between slices
  EndFaceOnSlice,
  /// "skull-diploe": the skull with 120 closed spherical cavities (radius 1.5 mm) in its wall, as the diploe
  /// between a real skull's two tables: every slab holds holes that start or end while the wall's ring
  /// hardly changes (the condition of real head scans)
  SkullDiploe,
};

/// The CLI name ("ridge-box", "femur", ...).
[[nodiscard]] std::string_view to_string(PhantomShape shape);
/// Inverse of to_string; throws InvalidInputError listing the valid names.
[[nodiscard]] PhantomShape parse_phantom_shape(std::string_view name);
/// The ten shapes that `contourmesh compare --phantom all` runs (and the issues' bars count), in
/// declaration order.
[[nodiscard]] std::vector<PhantomShape> all_phantom_shapes();
/// The shapes outside `all`, reachable by name: harder cases that measure what the ten do not (today the
/// skull with a diploe, docs/reconstruction.md, "Phantoms").
[[nodiscard]] std::vector<PhantomShape> extra_phantom_shapes();

/// The analytic truth of a phantom. Lengths in millimetres, centred near the origin, slice axis z.
struct Phantom {
  PhantomShape shape = PhantomShape::RidgeBox;
  /// Signed distance, negative inside bone. Exact for the primitives; where primitives are combined
  /// (min / max) it is a lower bound of the true distance away from the zero set and exact on it.
  ScalarField sdf;
  /// Outward unit normal field (the normalised gradient of sdf), defined everywhere.
  VectorField normal;
  /// Axis-aligned bounding box of the solid (sdf <= 0), in mm.
  Eigen::AlignedBox3d bounds;
  /// Volume of the solid in mm^3: analytic where the shape allows, otherwise integrated numerically
  /// to a relative accuracy better than 1e-3.
  double volume = 0.0;
  /// Number of connected surface components (a cavity counts as its own surface) and the Euler
  /// characteristic of the whole boundary surface (2 per sphere-like surface, 0 per torus, ...).
  int surface_components = 1;
  int euler_characteristic = 2;
  /// Points densely sampled (spacing <= 0.5 mm) along the sharp edges and at the corners of the solid:
  /// the "feature lines" that define feature regions in the evaluation (docs/results.md).
  std::vector<Eigen::Vector3d> feature_points;
};

/// Builds the analytic description of a shape.
[[nodiscard]] Phantom make_phantom(PhantomShape shape);

/// Distance from `p` to the nearest feature point, in mm (infinity when the phantom has none).
[[nodiscard]] double distance_to_features(const Phantom& phantom, const Eigen::Vector3d& p);

/// How a phantom becomes a CT-like volume.
struct PhantomVolumeOptions {
  Eigen::Vector3d spacing{0.7, 0.7, 2.0};  ///< voxel size in mm (x, y, slice); clinical CT is anisotropic
  double margin = 6.0;                     ///< mm of soft tissue around the bounding box
  double bone_hu = 1000.0;                 ///< value inside bone
  double tissue_hu = 40.0;                 ///< value outside (soft tissue)
  double blur = 0.0;                       ///< Gaussian blur sigma in mm (partial-volume / scanner PSF), >= 0
  double noise = 0.0;                      ///< Gaussian noise sigma in HU, >= 0
  /// Contour noise, the RMS in mm of a per-slice displacement of the boundary along its normal, in
  /// [0, kMaxContourNoise]: a segmentation error that perturbs single contours (Xu et al. 2006, section 3),
  /// as a hand-drawn contour has. Each voxel slice k gets its own field f_k(x, y), independent from
  /// slice to slice: four plane waves (wavelengths 20-60 mm, random directions and phases) plus one
  /// Gaussian bump (sigma 1.5-4 mm, random sign) per 50 mm of the slice's boundary, centred on it. Before
  /// the final scaling the waves carry 3/4 of the mean square and the bumps 1/4; f_k is then scaled so
  /// that its RMS over the true boundary of the phantom's section by the slice's centre plane is exactly
  /// `contour_noise`. Every supersample p of a voxel of slice k is inside when
  /// sdf(p) < f_k(p.x, p.y) |grad_xy sdf(p)|: to first order the section's contour moves by f_k along its
  /// normal within the slice plane, as a drawn or segmented contour errs. A wall parallel to the slice
  /// axis moves by f_k; a face parallel to the slices does not move (an end slice gets no holes). The
  /// Phantom itself (the truth) is not changed. Details: docs/reconstruction.md, "Contour noise".
  /// 0 (the default) renders the unperturbed solid, bit for bit.
  double contour_noise = 0.0;
  std::uint64_t seed = 1;  ///< seed of both noises (independent streams): same seed, same volume
};

/// The largest contour noise RMS that render_phantom accepts, in mm.
inline constexpr double kMaxContourNoise = 10.0;

/// Renders the phantom: each voxel gets tissue + (bone - tissue) * (fraction of the voxel inside the
/// solid, by supersampling; the solid displaced by the contour noise of the voxel's slice), then blur,
/// then noise. Throws InvalidInputError for options out of range
/// or a volume over 2^31 voxels.
[[nodiscard]] CtImage::Pointer render_phantom(const Phantom& phantom, const PhantomVolumeOptions& options = {});

}  // namespace contourmesh
