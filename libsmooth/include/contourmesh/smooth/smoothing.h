// SPDX-License-Identifier: BSD-3-Clause
// The baseline smoothers the paper compares with (Xu et al. 2006, section 6; docs/smoothing.md):
// Laplacian (eq. 5), Taubin lambda|mu (eq. 6), explicit mean curvature flow and MIN-DIST flow.
// All update every vertex simultaneously (Jacobi style) from the positions of the previous step.
#pragma once

#include "contourmesh/smooth/adjacency.h"
#include "contourmesh/smooth/mesh.h"
#include "contourmesh/smooth/progress.h"

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace contourmesh {

/// Every smoothing method of the library. The first five are the baselines of this header; the last
/// two have their own headers and options (feature_smoothing.h, cross_slice.h). smooth.h runs any of
/// them through one entry point.
enum class SmoothingMethod {
  None,               ///< positions returned unchanged
  Laplacian,          ///< v += lambda * U(v), paper eq. 5 with the umbrella operator (eq. 7)
  Taubin,             ///< one iteration = a lambda step then a mu step of the umbrella (eq. 6)
  MeanCurvatureFlow,  ///< explicit cotangent Laplace-Beltrami flow (Desbrun et al. 1999)
  MinDistFlow,        ///< vertex-to-plane distance minimisation (Zhang & Fiume 2002), see below
  FeaturePreserving,  ///< the paper's Algorithm 1 (Xu et al. 2006): feature_preserving_smooth
  CrossSlice,         ///< the project's default for contour meshes: cross_slice_smooth
};

/// "none", "laplacian", "taubin", "mcf", "mindist", "paper", "cross-slice".
[[nodiscard]] std::string_view to_string(SmoothingMethod method);
/// Inverse of to_string (also accepts "mean-curvature-flow", "min-dist", "feature-preserving");
/// throws InvalidInputError listing the valid names.
[[nodiscard]] SmoothingMethod parse_smoothing_method(std::string_view name);
/// Every method, in declaration order.
[[nodiscard]] std::span<const SmoothingMethod> all_smoothing_methods();
/// True for the umbrella-type baselines this header runs (Laplacian, Taubin, mean curvature flow,
/// MIN-DIST flow) and None.
[[nodiscard]] bool is_baseline(SmoothingMethod method);

/// What happens to vertices on the boundary of an open mesh.
enum class BoundaryPolicy {
  Fixed,  ///< boundary vertices never move (default)
  Free,   ///< boundary vertices move like any other (their 1-ring is one-sided: expect shrinkage)
};

/// How the mean-curvature-flow step `lambda` is turned into a time step dt (in squared length units).
enum class TimeStep {
  /// dt = lambda * h^2 / 4 with h the mean edge length of the input mesh. On a regular mesh of
  /// equilateral triangles this makes one MCF step move a vertex exactly as far as a Laplacian step
  /// with the same lambda, so the paper's lambda = 0.3 means the same for both (default).
  RelativeToMeanEdge,
  /// dt = lambda, in squared input units (for analytic checks, e.g. r^2(t) = r0^2 - 4t on a sphere).
  Absolute,
};

/// Called after each completed iteration with the current positions (iteration counts from 1).
using IterationObserver = std::function<void(int iteration, const Eigen::Matrix3Xd& positions)>;

/// Options shared by the baseline smoothers. Defaults are the paper's settings (section 6).
struct SmoothingOptions {
  /// A baseline (is_baseline). smooth.h's entry point sets it from its method argument.
  SmoothingMethod method = SmoothingMethod::Taubin;
  /// Number of iterations, >= 0. Paper: 20 for every baseline.
  int iterations = 20;
  /// Step factor in (0, 1]. Unset = the paper's value for the method (see default_lambda):
  /// Laplacian 0.3, Taubin 0.6307, mean curvature flow 0.3, MIN-DIST flow 0.5.
  std::optional<double> lambda;
  /// Taubin's shrink-compensating factor, in [-1, 0) (paper: -0.6732; needs |mu| > lambda).
  double mu = -0.6732;
  /// MIN-DIST flow feature threshold on 1 - cos(angle between face normals), in [0, 2]
  /// (paper: 0.03, i.e. about 14 degrees).
  double beta = 0.03;
  /// Interpretation of lambda for mean curvature flow.
  TimeStep time_step = TimeStep::RelativeToMeanEdge;
  BoundaryPolicy boundary = BoundaryPolicy::Fixed;
  /// Empty, or one flag per vertex: a non-zero flag keeps that vertex where it is. Not owned.
  std::span<const std::uint8_t> locked;
  /// Progress per iteration under the stage name "smooth"; return false to cancel (CancelledError).
  ProgressCallback progress;
  /// Optional: sees the positions after every iteration (used for the volume-shrinking curve).
  IterationObserver on_iteration;
};

/// The paper's lambda of a baseline (0 for None, FeaturePreserving and CrossSlice: their steps are in
/// their own options).
[[nodiscard]] double default_lambda(SmoothingMethod method);

/// Checks the options against a mesh of `num_vertices` vertices; throws InvalidInputError naming the
/// offending option (iterations < 0, lambda outside (0, 1], mu outside [-1, 0), beta outside [0, 2],
/// a lock mask of the wrong size).
void check_smoothing_options(const SmoothingOptions& options, Index num_vertices);

/// Laplacian smoothing, paper eq. 5 discretised with the umbrella operator (eq. 7):
/// v_i <- v_i + lambda * U(v_i). Shrinks closed surfaces at every step.
[[nodiscard]] Eigen::Matrix3Xd laplacian_smooth(const Mesh& mesh, const MeshAdjacency& adjacency,
                                                const SmoothingOptions& options);

/// Taubin lambda|mu smoothing (Taubin 1995; paper eq. 6): each iteration applies
/// v <- v + lambda * U(v) and then v <- v + mu * U(v), a low-pass filter that largely avoids shrinkage.
[[nodiscard]] Eigen::Matrix3Xd taubin_smooth(const Mesh& mesh, const MeshAdjacency& adjacency,
                                             const SmoothingOptions& options);

/// Explicit mean curvature flow (Desbrun, Meyer, Schroeder, Barr, SIGGRAPH 1999):
/// dv_i/dt = -kappa_i n_i = (1 / (2 A_i)) * sum_j (cot alpha_ij + cot beta_ij) (v_j - v_i),
/// the cotangent Laplace-Beltrami operator normalised by the vertex area A_i (one third of the area of
/// the incident triangles), with kappa = kappa1 + kappa2. Integrated with forward Euler steps
/// v <- v + dt * (dv/dt), dt from lambda per `time_step`. On a sphere of radius r this gives
/// d(r^2)/dt = -4. Explicit steps are stable only for small dt (about h^2 / 4): keep lambda <= ~0.5.
[[nodiscard]] Eigen::Matrix3Xd mean_curvature_flow(const Mesh& mesh, const MeshAdjacency& adjacency,
                                                   const SmoothingOptions& options);

/// MIN-DIST flow after Zhang & Fiume, "Mesh smoothing with shape or feature preservation",
/// Advances in Modelling, Animation and Rendering (CGI 2002), as used by Xu et al. 2006 (lambda 0.5,
/// beta 0.03, 20 iterations). Each vertex moves to reduce the sum of squared distances to the planes
/// of its incident triangles, where each plane passes through its triangle's centroid c_f and has a
/// feature-aware averaged normal m_f; bridges (crease lines) and corners are recognised implicitly by
/// the dihedral angle between adjacent triangles, at every iteration:
///   m_f = normalise( sum_{g sharing a vertex with f, 1 - n_f . n_g <= beta} A_g n_g )
///   v_i <- v_i + lambda * sum_{f incident to i} A_f m_f (m_f . (c_f - v_i)) / sum_f A_f
/// Across a crease (1 - cos > beta) normals are not averaged, so the planes of the two sides stay
/// separate: a vertex on a bridge is pulled onto both planes, a corner onto three, and the faces of
/// an exact polyhedron do not move. The full text of the 2002 paper was not available to us: this is
/// our reading of its published description (vertex-to-plane distance minimisation with dihedral-angle
/// feature classes), see docs/smoothing.md.
[[nodiscard]] Eigen::Matrix3Xd min_dist_flow(const Mesh& mesh, const MeshAdjacency& adjacency,
                                             const SmoothingOptions& options);

/// Runs the baseline named by `options.method` and returns the smoothed positions (3 x n). Throws
/// InvalidInputError for FeaturePreserving and CrossSlice: run those through smooth.h.
[[nodiscard]] Eigen::Matrix3Xd smooth(const Mesh& mesh, const MeshAdjacency& adjacency,
                                      const SmoothingOptions& options);
/// Same, building the adjacency first.
[[nodiscard]] Eigen::Matrix3Xd smooth(const Mesh& mesh, const SmoothingOptions& options);

}  // namespace contourmesh
