// SPDX-License-Identifier: BSD-3-Clause
// The evaluation harness (docs/results.md, docs/smoothing.md "How accuracy is measured"): on one CT
// volume, reconstruct the contour mesh once and run every method of the method table on it (libsmooth's
// methods, VTK's filters on the same mesh, 3D Slicer's voxel route on the same volume), then measure each
// result against the truth over the surface: two-sided RMS and Hausdorff distance, overall and split
// into the feature region and the smooth rest, area-weighted normal error, volume, time per stage, and
// the feature labels against the phantom's true features. Part of the contourmesh_compare target (not
// installed); series over noise regimes and seeds are in series.h, the files in report.h.
#pragma once

#include "compare/method_table.h"

#include <contourmesh/reconstruct/phantom.h>
#include <contourmesh/reconstruct/reconstruction.h>
#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/feature_detection.h>
#include <contourmesh/smooth/limits.h>
#include <contourmesh/smooth/mesh.h>
#include <contourmesh/smooth/progress.h>
#include <contourmesh/smooth/surface_metrics.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace contourmesh {

/// What the results are measured against.
enum class TruthKind {
  None,              ///< no reference: volume, timing and labels only
  Phantom,           ///< an analytic phantom: distances, normals, feature / smooth regions, detection scores
  ReferenceSurface,  ///< a reference mesh (e.g. a segmentation checked by hand): distances only
};

/// "none", "phantom", "reference-surface".
[[nodiscard]] std::string_view to_string(TruthKind kind);

/// The reference of a comparison. Build it once (phantom_truth, reference_surface_truth) and reuse it
/// for every volume of that object: its surface samples and feature locator are the expensive part.
struct ComparisonTruth {
  TruthKind kind = TruthKind::None;
  std::string description;  ///< e.g. "analytic surface of the femur phantom"
  double volume = 0.0;      ///< phantom only: the solid's exact volume, mm^3
  /// What surface_accuracy measures against (distance, normals, surface samples, distance to the
  /// nearest true feature); null for TruthKind::None.
  std::shared_ptr<const SurfaceTruth> surface;
};

/// The analytic phantom as truth: its signed distance and normal, samples of its surface on a grid of
/// `spacing` mm inside its bounds grown by `margin` mm (sample_implicit_surface), and the distance to
/// its sharp features through a PointLocator over phantom.feature_points.
[[nodiscard]] ComparisonTruth phantom_truth(const Phantom& phantom, double spacing = 0.4, double margin = 2.0);

/// A reference mesh as truth: unsigned distance to its nearest triangle (TriangleLocator) and uniform
/// samples of its surface at `density` per mm^2 (sample_mesh_surface). Throws InvalidInputError for a
/// mesh without triangles.
[[nodiscard]] ComparisonTruth reference_surface_truth(const Mesh& reference, std::string description,
                                                      double density = 4.0);

/// How the methods are run and measured.
struct ComparisonOptions {
  /// Segmentation and tiling of the contour route. Its threshold is also the voxel route's, and the
  /// voxel route removes islands and fills holes of fewer than min_component_voxels voxels, as the
  /// contour route drops such specks and small holes (3D Slicer's Islands effect and a hole fill).
  ReconstructionOptions reconstruction;
  /// Which methods run, their settings and the shared iteration count (method_table.h).
  MethodTableOptions methods;
  /// Samples per mm^2 on each result, the seed of their placement, and the feature radius (mm) that
  /// splits the surface into the feature region and the smooth rest.
  SurfaceMetricsOptions metrics;
  /// Phantom: contour-mesh vertices within this distance (mm) of a true sharp edge or corner are the
  /// true feature vertices that labels are scored against (precision, recall).
  double detection_radius = 1.5;
  /// Vertex cap and memory budget of every mesh a method builds.
  ResourceLimits limits;
  /// Each method is timed this many times and the fastest run is reported (>= 1).
  int timing_repeats = 1;
  /// Record the volume shrinking rate after every iteration (extra runs, not timed).
  bool volume_curves = true;
  /// Stages "segment" and "tile", then one stage per method (its id), then "metrics"; the fraction is
  /// of that stage. Return false to cancel (CancelledError).
  ProgressCallback progress;
};

/// Wall-clock seconds of one stage of one method.
struct StageTime {
  std::string stage;
  double seconds = 0.0;
};

/// A method's feature labels on the contour mesh, scored against the phantom's true features.
struct LabelSummary {
  std::size_t edges = 0, corners = 0, noise = 0;
  std::optional<std::size_t> candidates;  ///< the paper's detection: vertices examined (|U| > gamma)
  std::size_t subdivided_vertices = 0;    ///< the paper's method
  Index adaptive_vertices = 0;            ///< the paper's method
  /// Phantom only. True feature vertices: contour-mesh vertices within the detection radius of a true
  /// feature. "Examinable" ones lie on a contour (a slice id >= 0): vertices off the slice planes (end-cap
  /// and branching copies) have no adjacent contours, so no contour-continuity rule can examine them.
  std::optional<std::size_t> true_features, examinable_true_features, detected, true_positives,
      examinable_true_positives;
  /// true_positives / detected; true_positives / true_features; examinable_true_positives /
  /// examinable_true_features. NaN when undefined.
  double precision = 0.0, recall = 0.0, recall_examinable = 0.0;
};

/// The result of one method.
struct MethodResult {
  MethodSpec spec;       ///< id, title, colour, route, key, settings in words
  int iterations = 0;    ///< iterations of the smoother (0: unsmoothed or no iteration count)
  Mesh mesh;             ///< the result
  double volume_input = 0.0;                   ///< volume of the mesh the method started from, mm^3
  double volume_output = 0.0;                  ///< volume of its result
  double volume_change_percent = 0.0;          ///< 100 (output - input) / input
  std::optional<double> volume_error_percent;  ///< 100 (output - truth) / truth (phantom only)
  /// Accuracy over the surface (with a truth): two-sided RMS / Hausdorff, feature and smooth regions,
  /// normal error (phantom), mean signed distance, vertex RMS.
  std::optional<SurfaceAccuracy> accuracy;
  /// Per stage ("detect", "subdivide", "smooth"; "threshold", "surface", "smooth" for the voxel route)
  /// and "total".
  std::vector<StageTime> seconds;
  std::optional<LabelSummary> labels;  ///< methods that label features
  std::vector<VertexLabel> vertex_labels;  ///< their labels per contour-mesh vertex (for the renders)
  /// Volume shrinking rate (V0 - Vk) / V0 after k = 0, 1, ..., iterations iterations; empty for a
  /// method without intermediate results: none, cross-slice smoothing, the voxel route, and
  /// vtkWindowedSincPolyDataFilter, whose iteration count is the degree of one polynomial filter.
  std::vector<double> volume_curve;

  /// The seconds of `stage`, 0 when absent.
  [[nodiscard]] double stage_seconds(std::string_view stage) const;
};

/// Everything measured on one volume.
struct Comparison {
  std::string source;  ///< the volume: a file name or "phantom 'femur' (...)"
  TruthKind truth = TruthKind::None;
  std::string truth_description;
  double truth_volume = 0.0;  ///< phantom only, mm^3
  double feature_radius = 0.0, detection_radius = 0.0;
  ReconstructionReport reconstruction;
  Mesh contour_mesh;  ///< the reconstructed mesh every contour-route method starts from
  /// Phantom only, one flag per contour-mesh vertex: a true feature vertex (within the detection radius),
  /// and on a contour (examinable by a contour-continuity rule).
  std::vector<std::uint8_t> true_features, examinable;
  std::vector<MethodResult> methods;  ///< in method-table order

  /// The method with this id, or nullptr.
  [[nodiscard]] const MethodResult* find(std::string_view id) const;
  /// The standard (not a variant) method of this key, or nullptr.
  [[nodiscard]] const MethodResult* find(const MethodKey& key) const;
};

/// Reconstructs `image`, runs every method of the table and measures the results. `source` names the
/// volume in messages and reports. Throws InvalidInputError (naming `source`) when the volume yields no
/// mesh or options are out of range, LimitError beyond the vertex limits, CancelledError on request.
[[nodiscard]] Comparison run_comparison(const CtImage& image, const std::string& source, const ComparisonTruth& truth,
                                        const ComparisonOptions& options = {});

}  // namespace contourmesh
