// SPDX-License-Identifier: BSD-3-Clause
// Cross-slice smoothing: the project's default smoothing of contour meshes (docs/smoothing.md,
// "Cross-slice smoothing"). It follows the paper's observation (Xu et al. 2006, section 3) that
// segmentation errors perturb single contours while true shape continues from contour to contour:
// every contour vertex is corrected from the profile the surface traces across the neighbouring
// slices, and then from the profile along its own contour, never from its umbrella.
//
// 1. Across the slices: the plane through a contour vertex perpendicular to its contour cuts the
//    corresponding contours of up to `reach` slices above and below; their offsets along the vertex's
//    in-slice normal, against their height, form the profile. A local polynomial fit of the profile,
//    with windows grown by the intersection of confidence intervals (LPA-ICI) from the measured noise
//    level, gives the vertex's corrected offset: windows that would reach across a kink (a ridge within
//    a slice plane, the end of a feature) stop before it, those on the smooth side grow. The local
//    fit is a parabola, or (ProfileModel::Circle) an algebraic circle. First, a hinge test over the
//    whole profile finds a significant slope break (a junction between parts), and only the side of it
//    holding the vertex is fitted (ProfileKinks); there a line may replace each one-sided fit (KinkSides).
// 2. Along the contour: the same on the profile of the contour's own vertices (in-slice jitter), where
//    windows stop at corners (ridges crossing the slices).
// 3. Contour vertices move along their in-slice normals only, so they stay in their slice planes;
//    vertices off the slices (caps, branchings) follow the harmonic extension of those displacements.
// 3b. Then the faces around the vertices off the slices follow their bilaterally filtered normals
//    (OffSliceFilterOptions); contour vertices stay.
// 4. Labels: the creases of the result (detect_creases), edge or corner, in a band along them.
// With noise-free contours the estimated noise is zero and nothing moves.
#pragma once

#include "contourmesh/smooth/crease_detection.h"
#include "contourmesh/smooth/crease_restoration.h"
#include "contourmesh/smooth/feature_detection.h"
#include "contourmesh/smooth/mesh.h"
#include "contourmesh/smooth/progress.h"

#include <optional>
#include <string_view>
#include <vector>

namespace contourmesh {

/// Which profiles are smoothed.
enum class CrossSliceStages {
  AcrossThenAlong,  ///< across the slices, then along the contours (default)
  AcrossOnly,       ///< across the slices only (the paper's per-contour noise model)
};

/// The curve a cross-slice profile is fitted with, in each window (docs/smoothing.md, "Under contour
/// noise"). A line or the window's mean replaces it where consistent with it, as for both.
enum class ProfileModel {
  Parabola,  ///< a local parabola (default): biased where a profile bends more than a parabola does
  Circle,    ///< an algebraic circle in the tangent frame: exact on the arcs of spheres, cylinders seen
             ///< across their axis and tori; a window where it is ill-posed (too few or collinear
             ///< samples, a circle smaller than the window) falls back to the parabola
};

/// Whether the profiles across the slices are first cut at their slope breaks (docs/smoothing.md, "Kinks
/// in the profiles"): where two parts of a surface meet (a shaft and a condyle), a profile has a kink that
/// no smooth model fits, and every two-sided window reaching across it is biased.
enum class ProfileKinks {
  Ignore,  ///< the windows are chosen by LPA-ICI alone
  Bound,   ///< (default) a hinge test over the whole profile (a parabola with a slope break at one sample,
           ///< against one parabola, at the measured noise) finds the most significant break; where it
           ///< passes, only the side holding the vertex is fitted (at the vertex: its one-sided windows)
};

/// The model of the one-sided windows of a profile cut at a slope break (ProfileKinks::Bound; docs/smoothing.md,
/// "Lines beside a kink"). A profile without a significant break is fitted the same either way.
enum class KinkSides {
  Curves,  ///< (default) the across model (parabola or circle), as on any profile
  Lines,   ///< a line grows beside each one-sided curve and replaces it where the two agree within
           ///< gamma standard deviations of the curve and the line is more precise, or where the side has
           ///< too few samples for a curve: a third of the parameters, half the variance or less at the
           ///< window's end
};

/// What happens to the vertices between the slices after the contour vertices have moved.
enum class OffSliceFilter {
  None,              ///< they follow the harmonic extension of the contour vertices' moves only
  BilateralNormals,  ///< then the faces around them follow their bilaterally filtered normals (default)
};

/// How a vertex between the slices may move in the normal-filtering stage.
enum class OffSliceMotion {
  Free,       ///< in any direction, within the bounds (default)
  AlongAxis,  ///< along the slice axis only, as off-slice heights placed it
};

/// What the range kernel of the normal filter compares.
enum class OffSliceRange {
  /// The faces' own normals (Zheng et al. 2011). Terraces between the slices (heights of the vertices
  /// between the slices pulled towards the middle of their slab, as reading them from an image does) read
  /// as creases and are kept.
  FaceNormals,
  /// Guidance normals (default): per face, the mean normal of the most consistent patch (the faces sharing
  /// a vertex with a face, area- and distance-weighted; consistency: the length of the weighted mean
  /// normal over the weights) among the patches holding it whose mean normal lies within the kernel's
  /// angle of its own normal, its own patch always a candidate (after Zhang, Deng, Zhang, Bouaziz, Liu,
  /// "Guided mesh normal filtering", Pacific Graphics 2015). Terraces within a patch average out; next to
  /// a crease a face takes a patch of its own side. docs/smoothing.md, "Terraces between the slices".
  PatchGuidance,
};

/// What the normal-filtering stage does about the volume its moves enclose.
enum class OffSliceVolume {
  Free,  ///< nothing: the fitted positions stand
  /// Each region of vertices between the slices (the moving vertices joined through their faces, not
  /// through contour vertices) is then offset along its vertex normals, uniformly and within the bounds,
  /// until the faces around it enclose the volume they enclosed before the stage: fitting to filtered
  /// normals rounds a structure a few millimetres thick inwards at its ends (docs/smoothing.md, "The
  /// volume of the vertices between the slices").
  Preserve,
};

/// The normal-filtering stage for the vertices between the slices (docs/smoothing.md, "Vertices between
/// the slices"): bilateral filtering of the normals of the faces that touch them (Zheng, Fu, Au, Tai,
/// IEEE TVCG 2011, eq. 4: a Gaussian of the distance between face centroids, of the mean such distance,
/// times a Gaussian of the difference of the normals, or of guidance normals: OffSliceRange), then
/// their positions fitted to those normals (eq. 6). Contour vertices never move here; a vertex between
/// the slices stays in its slab.
struct OffSliceFilterOptions {
  OffSliceFilter filter = OffSliceFilter::BilateralNormals;
  OffSliceMotion motion = OffSliceMotion::Free;
  OffSliceRange range = OffSliceRange::PatchGuidance;
  /// Iterations of the normal filter, >= 0.
  int normal_iterations = 20;
  /// Width of the range kernel as an angle between two normals, degrees, in (0, 90]: normals further
  /// apart than this (a crease) barely mix.
  double sigma_angle_degrees = 12.0;
  /// With OffSliceRange::PatchGuidance: the guidance normals are computed in every this many normal-filter
  /// iterations (rim iterations included), >= 1, starting with the first (from the unfiltered normals); in
  /// between, they and the range kernels stay, and an iteration is one weighted sum per face. 1: every
  /// iteration, as Zhang et al. Default 10: against 5, the two-sided RMS lower on 37 and higher on 23 of 60
  /// phantom-regimes (seeds 1-3 and 4-6, mean -0.09 %), the feature RMS and normal error within 0.2 %, and
  /// the smoothing of the head-and-neck scan 9 % faster (docs/smoothing.md, "How often the guidance is
  /// computed").
  int guidance_interval = 10;
  /// Extra iterations of the normal filter, after `normal_iterations`, for the faces at rims only, >= 0
  /// (default 20; 0: none). A rim face has, among the faces sharing a vertex with it, two whose unfiltered
  /// normals are more than `rim_angle_degrees` apart; `rim_rings` rings of filtered faces around them take the
  /// iterations too, the others keep their normals. More iterations everywhere sharpen the rims of flat
  /// faces but shift faces a few degrees off the slice planes; near sharp rims only they do the first
  /// without the second (docs/smoothing.md, "How many normal-filter iterations": 60 at 70 degrees and one
  /// ring lowered the two-sided RMS on 23 of 30 phantom-regimes, raised it on 2 by 0.001 mm at most).
  int rim_iterations = 20;
  /// The angle between two faces' normals that marks a rim, degrees, in (0, 180).
  double rim_angle_degrees = 70.0;
  /// Rings of filtered faces around a rim face that also take the rim iterations, >= 0.
  int rim_rings = 1;
  /// Iterations of the vertex update, >= 0.
  int vertex_iterations = 27;
  /// Step of the vertex update, in (0, 2]: each iteration moves a vertex by this times the mean of its
  /// faces' offsets to their planes (Sun et al. 2007, eq. 6, has 1). A face's centroid holds a third of
  /// each corner, so a step of 1 closes only two thirds of a lone vertex's offset to its face's plane, and
  /// 1.5 all of it; up to 2 the update stays stable (it overshoots by a third at 2). The update has not
  /// converged after its iterations: what counts is about the product of step and iterations, and 27
  /// iterations of 1.5 end within 0.01 % of the RMS of 40 of 1 on the phantoms in a third less time
  /// (docs/smoothing.md, "The vertex update's step").
  double vertex_step = 1.5;
  /// Largest move of a vertex, in slice spacings, >= 0.
  double max_move = 0.25;
  /// Largest move of a contour vertex, in its slice plane, mm, >= 0; 0: contour vertices stay.
  double contour_max_move = 0.0;
  OffSliceVolume volume = OffSliceVolume::Free;
};

struct CrossSliceOptions {
  /// Slices on each side that a cross-slice profile may use, in [1, 30]. Unset: from the noise level
  /// across the slices (see `precise_noise`).
  std::optional<int> reach;
  /// Contour vertices on each side that an along-contour profile may use, in [1, 30].
  int along_reach = 8;
  /// Confidence-interval width of the window selection, in noise standard deviations, > 0. Larger:
  /// wider windows, more smoothing, more bias where profiles bend.
  double gamma = 2.0;
  /// The rule for an unset `reach`, mm, >= 0: where the noise across the slices (estimated or given) is
  /// below this, the contours are precise and a window's bias on a curved profile is most of what is left
  /// to correct, so the reach is 4 slices; otherwise the noisy reach below, to average segmentation error
  /// that differs from slice to slice. The phantoms' estimates: 0.02-0.09 mm under CT noise, 0.36-0.39 mm
  /// under 0.4 mm of contour noise (docs/smoothing.md, "The reach from the noise level").
  double precise_noise = 0.2;
  /// The reach of an unset `reach` on noisy contours (noise across at least `precise_noise`), as a length
  /// along the slice axis, mm, finite and >= 0: max(8, round(noisy_reach_length / slice spacing)) slices, at
  /// most 30. 24 mm gives 12 slices at 2 mm, 24 at 1 mm and 8 at 3 mm or more; 0 gives 8 at any spacing
  /// (the rule before 2026-12-07). Measured in docs/smoothing.md, "The reach on noisy contours".
  double noisy_reach_length = 24.0;
  /// Noise standard deviation of the contour offsets across the slices and along the contours, mm.
  /// Unset: estimated from the mesh (robust fourth differences of the profiles; docs/smoothing.md).
  std::optional<double> noise_across, noise_along;
  /// In [0, 1]: the share of the sampled contour vertices that must have a regular profile over five
  /// slices for an unset `noise_across` to be estimated from those profiles. Below it, as on thick slices
  /// through a short or flat object (5 mm slices leave 16 % on the pelvis phantom, 1 % on the tilted box,
  /// against 47-92 % on every phantom at 2 mm), the few profiles that remain measure the shape, not the
  /// noise (0.44 mm on the pelvis, whose contours are as precise as at 2 mm, 0.05 mm), and the noise
  /// along the contours stands in for it (docs/smoothing.md, "Thick slices").
  double min_profile_share = 0.25;
  /// The curve fitted to the profiles across the slices (the along-contour profiles always use
  /// parabolas: their abscissa is arc length, not a rigid frame).
  ProfileModel across_model = ProfileModel::Parabola;
  /// Slope breaks in the profiles across the slices.
  ProfileKinks across_kinks = ProfileKinks::Bound;
  /// With ProfileKinks::Bound: the probability, in (0, 1), that a kink-free profile with Gaussian noise of
  /// the measured level is cut (a Bonferroni bound over the hinges scanned).
  double kink_false_rate = 0.01;
  /// With ProfileKinks::Bound: the model of the one-sided windows of a profile cut at a slope break.
  KinkSides kink_sides = KinkSides::Curves;
  CrossSliceStages stages = CrossSliceStages::AcrossThenAlong;
  /// Jacobi iterations of the harmonic extension to vertices off the slices, >= 0.
  int extension_iterations = 30;
  /// The vertices between the slices, after the extension.
  OffSliceFilterOptions off_slice;
  /// The feature labels of the result: creases of the smoothed mesh (crease_detection.h); its noise
  /// unset: the estimated noise across the slices.
  CreaseOptions features;
  /// Creases the image's blur rounded, restored after the labels (crease_restoration.h; docs/smoothing.md,
  /// "Creases rounded by the image's blur"). With CreaseRestoration::Subdivide the result may have
  /// more vertices than the input (the input's first, in order); the labels stay one per input vertex.
  CreaseRestoration crease_restoration = CreaseRestoration::None;
  CreaseRestorationOptions restoration;
  /// Stages "smooth" and "detect"; return false to cancel (CancelledError).
  ProgressCallback progress;
};

/// Where the noise level across the slices came from.
enum class NoiseSource {
  Given,           ///< CrossSliceOptions::noise_across
  AcrossProfiles,  ///< estimated from the profiles across the slices
  AlongProfiles,   ///< too few profiles across the slices (min_profile_share): the noise along the contours
};

/// "given", "across" or "along".
[[nodiscard]] std::string_view to_string(NoiseSource source);

struct CrossSliceResult {
  /// Smoothed, same connectivity and ids; with CreaseRestoration::Subdivide the restored, subdivided mesh
  /// (the input's vertices first).
  Mesh mesh;
  std::vector<VertexLabel> labels;  ///< per vertex: Smooth, Edge, Corner, or Noise (a crease too short)
  CreaseDetection features;         ///< how the labels were found
  double noise_across = 0.0;   ///< the noise levels used, mm
  double noise_along = 0.0;
  NoiseSource noise_across_source = NoiseSource::AcrossProfiles;  ///< where noise_across came from
  int reach = 0;               ///< the reach across the slices used
  std::size_t profiles = 0;    ///< contour vertices corrected from a cross-slice profile
  std::size_t off_slice_moved = 0;  ///< vertices between the slices moved by the normal filter
  double seconds_detect = 0.0, seconds_smooth = 0.0, seconds_total = 0.0;
};

/// Smooths a contour mesh. Needs contour ids (InvalidInputError otherwise; recover them with
/// assign_ids_by_slice_planes); throws InvalidInputError for options out of range and CancelledError
/// on request.
[[nodiscard]] CrossSliceResult cross_slice_smooth(const Mesh& mesh, const CrossSliceOptions& options = {});

}  // namespace contourmesh
