// SPDX-License-Identifier: BSD-3-Clause
// The methods a comparison runs, as one table: per method its key (libsmooth's SmoothingMethod for the
// contour-route methods, ExternalMethod for VTK's filters and the voxel route), id, title, colour,
// route, settings and how to run it. Ablation variants (a method with some options changed) are rows
// like the others. Part of the contourmesh_compare target.
#pragma once

#include <contourmesh/reconstruct/reconstruction.h>
#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/limits.h>
#include <contourmesh/smooth/mesh.h>
#include <contourmesh/smooth/progress.h>
#include <contourmesh/smooth/smooth.h>

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace contourmesh {

/// The methods of a comparison that are not libsmooth's.
enum class ExternalMethod {
  VtkWindowedSinc,        ///< vtkWindowedSincPolyDataFilter on the contour mesh, 3D Slicer's settings
  VtkSmoothFeatureEdges,  ///< vtkSmoothPolyDataFilter with feature-edge smoothing on the contour mesh
  VoxelFlyingEdges,       ///< 3D Slicer's voxel route unsmoothed: threshold, islands, vtkDiscreteFlyingEdges3D
  VoxelWindowedSinc,      ///< the voxel route then vtkWindowedSincPolyDataFilter: what a Slicer user gets
};

/// "vtk-windowed-sinc", "vtk-smooth-feature-edges", "voxel-flying-edges", "voxel-windowed-sinc".
[[nodiscard]] std::string_view to_string(ExternalMethod method);

/// Which method a row runs.
using MethodKey = std::variant<SmoothingMethod, ExternalMethod>;

/// Where a method starts: the reconstructed contour mesh, or the thresholded volume.
enum class Route { Contour, Voxel };

/// "contour", "voxel".
[[nodiscard]] std::string_view to_string(Route route);

/// What a method's run sees.
struct MethodContext {
  const Mesh& contour_mesh;  ///< every contour-route method starts from it
  const CtImage& image;      ///< the voxel route starts from it
  const ReconstructionOptions& reconstruction;  ///< its threshold and speck size are the voxel route's
  ResourceLimits limits;
  int timing_repeats = 1;      ///< time the method this many times, keep the fastest
  bool volume_curves = false;  ///< also record the volume shrinking rate per iteration (untimed)
  ProgressCallback progress;   ///< reports under the method's id
};

/// What a method's run gives back.
struct MethodOutput {
  Mesh mesh;
  double volume_input = 0.0;  ///< volume of the mesh the method started from, mm^3
  int iterations = 0;
  /// Seconds per stage, fastest of the repeats, then "total".
  std::vector<std::pair<std::string, double>> seconds;
  std::optional<FeatureLabels> labels;  ///< libsmooth methods that label features
  std::size_t subdivided_vertices = 0;  ///< the paper's method
  Index adaptive_vertices = 0;
  std::vector<double> volume_curve;     ///< see MethodResult::volume_curve
};

/// One row of the table.
struct MethodSpec {
  MethodKey key = SmoothingMethod::None;
  std::string id;      ///< unique in a comparison: file names, CSV and JSON ("taubin", "cross-slice", ...)
  std::string title;   ///< in the reports ("Taubin", "cross-slice smoothing (the default)", ...)
  std::string legend;  ///< short title for plot legends
  std::array<double, 3> colour{0.0, 0.0, 0.0};  ///< RGB in [0, 1] for plots
  Route route = Route::Contour;
  std::string settings;  ///< the parameters, in words
  /// libsmooth methods: the options they run with; the preset they come from ("default", "xu2006"), if
  /// any; whether the row is an ablation variant rather than a standard method.
  SmoothOptions options;
  std::string preset;
  bool variant = false;
  std::function<MethodOutput(const MethodContext&)> run;
};

/// An ablation variant: a libsmooth method with some options changed (parse_variant).
struct MethodVariant {
  std::string id;
  SmoothingMethod method = SmoothingMethod::CrossSlice;
  std::string preset;  ///< the preset the options start from, if any
  SmoothOptions options;
  std::string changes;  ///< the key=value list it was made from
};

/// "NAME:key=value,key=value,...": a method (key `method`, default cross-slice; or `preset`, default or
/// xu2006) with the listed options changed. NAME (letters, digits, '-', '_', '.') becomes the row's id.
/// Keys, by method:
/// - cross-slice: reach, along-reach, gamma, precise-noise (mm), noise-across, noise-along (mm),
///   profile-model (parabola | circle), kinks (ignore | bound), kink-rate (probability), kink-sides
///   (lines | curves), stages (across-then-along | across-only), extension-iterations, off-slice-filter
///   (bilateral | none), off-slice-motion (free | axis), off-slice-range (faces | patches), normal-iterations,
///   normal-sigma (degrees), vertex-iterations, vertex-step, max-move (slice spacings), contour-max-move (mm),
///   crease-radius, edge-threshold, corner-threshold, min-extent, band, creases (none | restore),
///   restore-levels;
/// - paper: iterations, lambda, mu, max-levels, diffusion (taubin | laplacian), measure (length | normal),
///   in-slice (noise | along-line), gamma-factor, delta-factor, window, corner-spread, prefilter;
/// - baselines: iterations, lambda, mu, beta.
/// Throws InvalidInputError naming the text and the offending key or value.
[[nodiscard]] MethodVariant parse_variant(std::string_view text);

/// The shared settings of the table.
struct MethodTableOptions {
  /// One iteration count for every iterative method of the contour route: the baselines, VTK's two
  /// filters, cross-slice smoothing when it has a count, and variants that do not set their own. The
  /// xu2006 preset keeps its own 40 (and is labelled so); the voxel route keeps 3D Slicer's 20.
  int iterations = default_iterations(SmoothingMethod::Taubin);
  /// vtkWindowedSincPolyDataFilter's pass band (3D Slicer: 0.01) and the voxel route's iterations.
  double sinc_passband = 0.01;
  int voxel_sinc_iterations = 20;
  /// vtkSmoothPolyDataFilter: the paper's Laplacian step, VTK's default feature and edge angles.
  double laplace_relaxation = 0.3;
  double laplace_feature_angle = 45.0;
  double laplace_edge_angle = 15.0;
  /// Rows added after the standard ones.
  std::vector<MethodVariant> variants;
  /// Ids of the standard methods to run; empty: all of them.
  std::vector<std::string> only;
};

/// The ids of the standard methods, in table order: none, laplacian, taubin, mcf, mindist, paper (the
/// xu2006 preset), cross-slice (the default preset), vtk-windowed-sinc, vtk-smooth-feature-edges,
/// voxel-flying-edges, voxel-windowed-sinc.
[[nodiscard]] std::vector<std::string> standard_method_ids();

/// The table: the standard methods (or those in `only`), then the variants. Throws InvalidInputError for
/// an unknown id in `only`, a variant id used twice or equal to a standard id, or settings out of range.
[[nodiscard]] std::vector<MethodSpec> method_table(const MethodTableOptions& options = {});

}  // namespace contourmesh
