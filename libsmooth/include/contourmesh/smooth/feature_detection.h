// SPDX-License-Identifier: BSD-3-Clause
// Feature detection by contour continuity: the paper's Algorithm 2 (Xu et al. 2006, section 3.2). A vertex
// whose umbrella is large is an edge when the in-slice curvatures of its own contour and of the two adjacent
// contours agree where the feature line crosses them, noise when they do not; umbilic vertices vote with their
// neighbours (eq. 8) for corner or noise.
#pragma once

#include "contourmesh/smooth/adjacency.h"
#include "contourmesh/smooth/curvature.h"
#include "contourmesh/smooth/mesh.h"
#include "contourmesh/smooth/progress.h"

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace contourmesh {

enum class VertexLabel : std::uint8_t {
  Smooth = 0,  ///< umbrella measure <= gamma: not examined, never subdivided
  Edge = 1,    ///< on a feature line continuous across adjacent contours
  Corner = 2,  ///< umbilic, with feature neighbours outweighing noise neighbours (Psi > 0)
  Noise = 3,   ///< large umbrella without continuity across contours
};

/// "smooth", "edge", "corner", "noise".
[[nodiscard]] std::string_view to_string(VertexLabel label);

/// Which size of the umbrella U(v) decides whether a vertex is examined (the threshold gamma of Algorithm 2 on the
/// umbrella of paper eq. 7).
enum class UmbrellaMeasure {
  Length,           ///< |U|, the paper's choice (default)
  NormalComponent,  ///< |U . n|: ignores tangential irregularity of the tiling
};

/// How features are told from noise.
enum class DetectionMode {
  /// The paper's Algorithm 2: curvature continuity across adjacent contours (needs contour ids).
  ContourContinuity,
  /// Fallback for meshes without contour ids: a candidate is an edge when its curvature is strongly
  /// anisotropic (the larger |kappa| at least `anisotropy` times the smaller), a corner by the Psi vote
  /// when umbilic, noise otherwise. Cannot tell a ridge from a scratch: use ids when you have them.
  CurvatureOnly,
};

/// What happens to a candidate whose feature line runs within a slice plane (S parallel to the
/// slices), or that lies off the slices (end-cap rims, branching copies): the paper's blind spot
/// (paper Algorithm 2).
enum class InSliceFeatures {
  /// The paper's rule (default): no continuity across contours can be shown, so the vertex is noise.
  Noise,
  /// Extension: continuity along the feature line itself. The vertex is an edge when the curvature
  /// across the feature (the principal curvature with the larger |kappa|) of its two neighbours
  /// nearest to the feature direction, one on each side, agrees with its own in sign and within delta.
  /// Applied to the blind spot, and also to a candidate whose feature direction lies within its slice
  /// plane (|t . slice axis| <= 0.1) where S is not parallel to the slices, such as a cap's rim meeting
  /// a side at 45 degrees; when it fails there, the paper's test decides. A neighbour where three faces
  /// meet (`corner_spread`) ends the line and counts as agreeing.
  /// Finds cap rims and ridges parallel to the slices, but cannot tell them from a whole contour
  /// segmented too large or too small (that also looks continuous along the contour).
  AlongFeatureLine,
};

struct DetectionOptions {
  DetectionMode mode = DetectionMode::ContourContinuity;
  /// CurvatureOnly: minimum ratio |kappa_large| / |kappa_small| of an edge, > 1.
  double anisotropy = 3.0;
  /// Threshold on the umbrella measure, in length units. Unset: gamma_factor * its mean over the
  /// vertices that lie on contours (paper: 2 mean |U|; copies off the slices are left out).
  std::optional<double> gamma;
  double gamma_factor = 2.0;
  UmbrellaMeasure measure = UmbrellaMeasure::Length;
  /// Curvatures agree when |k0 - k| < delta. Unset: delta_factor * |k0| (scale-free).
  std::optional<double> delta;
  double delta_factor = 0.5;
  InSliceFeatures in_slice = InSliceFeatures::Noise;
  /// Corners where faces meet (an extension; the paper examines corners only at umbilic vertices).
  /// At a vertex where three or more faces meet, such as a box corner, the quadric fit of curvature.h (paper eq. 9)
  /// gives two curvatures that differ, and principal directions that mean nothing. A candidate whose face normals
  /// spread in three directions therefore goes to the Psi vote (eq. 8), as an umbilic one does. The measure is the
  /// smallest eigenvalue of the angle-weighted normal tensor sum_f theta_f n_f n_f^T, divided by its trace: 1/3 at a
  /// cube corner, 0 along a sharp edge, about (h kappa)^2 / 8 on a smooth patch with edges h long. The threshold is
  /// scale-free, in [0, 1/3]; a value above 1/3 turns the rule off.
  double corner_spread = 0.1;
  /// Consecutive contour vertices in each curve fit (odd, >= 5; default 7).
  int window = 7;
  /// Taubin lambda|mu iterations applied to a copy used for detection only (paper section 5), >= 0.
  int prefilter_iterations = 0;
  CurvatureOptions curvature;
  /// Stage "detect", called a few times; return false to cancel (CancelledError).
  ProgressCallback progress;
};

/// The labels and the numbers behind them. Per-vertex values are NaN where not computed.
struct FeatureDetection {
  std::vector<VertexLabel> labels;
  Eigen::VectorXd umbrella;  ///< the umbrella measure of every vertex (on the detection positions)
  double gamma = 0.0;
  double mean_umbrella = 0.0;
  PrincipalCurvatures curvature;
  Eigen::VectorXd k_below;  ///< signed curvature of contour c(i)-1 where the feature line crosses it
  Eigen::VectorXd k0;       ///< signed curvature of contour c(i) at v_i
  Eigen::VectorXd k_above;  ///< signed curvature of contour c(i)+1
  Eigen::VectorXd psi;      ///< corner vote of umbilic candidates (eq. 8)
  Eigen::VectorXd normal_spread;  ///< the corner_spread measure of every candidate
  std::size_t candidates = 0, edges = 0, corners = 0, noise = 0;
};

/// Runs Algorithm 2 on a mesh with contour ids (DetectionMode::ContourContinuity; InvalidInputError
/// without them) or the curvature-only fallback; throws InvalidInputError for options out of range.
///
/// Contour curvatures: the `window` consecutive vertices of a contour are projected into their slice
/// plane and fitted, by least squares, with a parabola Y = a + b X + c X^2 in the frame of their
/// principal axes (a conic with its axis across the contour: robust with 5-9 points, unlike a general
/// conic). k0 is that curve's curvature at v_i on its own contour. For the contours c(i) -/+ 1 the
/// window is centred on the neighbour of v_i in that slice, the curve is intersected with the line
/// where the plane S (through v_i, containing the feature direction t = the principal direction with
/// the smaller |kappa| and the normal; its normal is the other principal direction) cuts that slice,
/// and k is the curvature at the intersection nearest to v_i. Curvatures are signed: positive where the
/// contour is convex towards the outside (the side the mesh normals point to).
/// Edge test: k0 k > 0 and |k0 - k| < delta for each adjacent contour that exists (one at the first
/// and last slice, none for a vertex off the slices: noise). No intersection inside the window
/// (S misses the contour there) is noise; so is S parallel to the slices (a feature line within a
/// slice plane: the paper's blind spot).
/// Umbilic candidates, and those whose face normals spread in three directions (`corner_spread`), are
/// classified after all others, in index order, by Psi_i = sum_j w_j tau_j with w_j = exp(-d_ij / d_max)
/// and tau_j = +1 for edge/corner, -1 for noise, 0 otherwise (eq. 8).
[[nodiscard]] FeatureDetection detect_features(const Mesh& mesh, const MeshAdjacency& adjacency,
                                               const DetectionOptions& options = {});

}  // namespace contourmesh
