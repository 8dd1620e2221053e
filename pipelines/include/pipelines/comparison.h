// The evaluation harness of SPEC 5 (issue 6): on one CT volume, reconstruct the contour mesh once and
// run every smoothing method on it (none, Laplacian, Taubin, mean curvature flow, MIN-DIST flow, the
// paper's method, VTK's vtkWindowedSincPolyDataFilter with 3D Slicer's settings and
// vtkSmoothPolyDataFilter with feature-edge smoothing), plus the voxel route a 3D Slicer user takes
// (threshold -> vtkDiscreteFlyingEdges3D -> vtkWindowedSincPolyDataFilter), and measure each result
// against the truth: distance, normal error, volume, time per stage, feature labels. Writing the
// tables, plots, renders and report is in comparison_report.h.
#pragma once

#include <reconstruct/phantom.h>
#include <reconstruct/reconstruction.h>
#include <reconstruct/volume.h>
#include <smooth/feature_detection.h>
#include <smooth/feature_smoothing.h>
#include <smooth/mesh.h>
#include <smooth/metrics.h>
#include <smooth/progress.h>
#include <smooth/smoothing.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace contourmesh {

/// What the results are measured against.
enum class TruthKind {
  None,              ///< no reference: volume, timing and labels only
  Phantom,           ///< an analytic phantom: distance, normals, feature / smooth regions, detection scores
  ReferenceSurface,  ///< a reference mesh (e.g. a segmentation checked by hand): distance only
};

/// "none", "phantom", "reference-surface".
[[nodiscard]] std::string_view to_string(TruthKind kind);

/// The reference of a comparison. Build it with phantom_truth or reference_surface_truth.
struct ComparisonTruth {
  TruthKind kind = TruthKind::None;
  std::string description;         ///< e.g. "analytic surface of the femur phantom"
  std::optional<Phantom> phantom;  ///< TruthKind::Phantom
  /// Distance to the reference surface (signed for a phantom, unsigned for a reference mesh); empty
  /// for TruthKind::None.
  ScalarField distance;
};

/// The analytic phantom as truth.
[[nodiscard]] ComparisonTruth phantom_truth(const Phantom& phantom);

/// A reference mesh as truth: the distance of a point is its distance to the nearest triangle
/// (vtkStaticCellLocator). Throws InvalidInputError for a mesh without triangles.
[[nodiscard]] ComparisonTruth reference_surface_truth(const Mesh& reference, std::string description);

/// How the methods are run and measured. The defaults are the paper's and 3D Slicer's settings.
struct ComparisonOptions {
  /// Segmentation and tiling of the contour route. Its threshold is also the voxel route's, and the
  /// voxel route removes islands and fills holes of fewer than min_component_voxels voxels, as the
  /// contour route drops such specks and small holes (3D Slicer's Islands effect and a hole fill).
  ReconstructionOptions reconstruction;
  /// The paper's method (its progress member is ignored).
  FeatureSmoothingOptions paper;
  /// Iterations of Laplacian, Taubin, MCF and MIN-DIST (paper: 20); steps are each method's default.
  int baseline_iterations = 20;
  /// vtkWindowedSincPolyDataFilter as in 3D Slicer's closed-surface conversion: 20 iterations,
  /// passband 0.01 (smoothing factor 0.5), normalized coordinates, no boundary or feature-edge
  /// smoothing, non-manifold smoothing on.
  int sinc_iterations = 20;
  double sinc_passband = 0.01;
  /// vtkSmoothPolyDataFilter with feature-edge smoothing: the baselines' 20 iterations and the
  /// relaxation factor of the paper's Laplacian (0.3), VTK's default feature (45) and edge (15) angles.
  int laplace_iterations = 20;
  double laplace_relaxation = 0.3;
  double laplace_feature_angle = 45.0;
  double laplace_edge_angle = 15.0;
  /// Phantom: vertices within this distance (mm) of a sharp edge or corner form the feature region.
  double feature_radius = 2.0;
  /// Phantom: vertices within this distance (mm) of a sharp edge or corner are the true feature
  /// vertices against which the paper's edge / corner labels are scored (precision, recall).
  double detection_radius = 0.8;
  /// Each method is timed this many times and the fastest run is reported (>= 1).
  int timing_repeats = 1;
  /// Record the volume shrinking rate after every iteration (extra runs, not timed).
  bool volume_curves = true;
  /// Stages "segment" and "tile", then one stage per method (its name), then "metrics"; the fraction
  /// is of that stage. Return false to cancel (CancelledError).
  ProgressCallback progress;
};

/// Distance (mm) and face-normal error (degrees) of one region of a mesh.
struct RegionMetrics {
  DistanceStats distance;
  AngleStats normals;
};

/// Wall-clock seconds of one stage of one method.
struct StageTime {
  std::string stage;
  double seconds = 0.0;
};

/// The paper's labels on the contour mesh, scored against the phantom's feature vertices.
struct LabelSummary {
  std::size_t candidates = 0, edges = 0, corners = 0, noise = 0;
  std::size_t subdivided_vertices = 0;
  Index adaptive_vertices = 0;
  /// Phantom only: true feature vertices (within detection_radius of a feature), vertices labelled
  /// edge or corner, and those that are both; precision and recall are NaN when undefined.
  std::optional<std::size_t> true_features, detected, true_positives;
  double precision = 0.0, recall = 0.0;
};

/// The result of one method.
struct MethodResult {
  std::string name;      ///< "none", "laplacian", "taubin", "mcf", "mindist", "paper", "vtk-windowed-sinc",
                         ///< "vtk-smooth-feature-edges", "voxel-flying-edges", "voxel-windowed-sinc"
  std::string route;     ///< "contour" (the reconstructed mesh) or "voxel" (flying edges on the thresholded volume)
  std::string settings;  ///< the parameters, in words
  int iterations = 0;    ///< iterations of the smoother (0: unsmoothed)
  Mesh mesh;             ///< the smoothed mesh
  double volume_input = 0.0;                   ///< volume of the mesh the method started from, mm^3
  double volume_output = 0.0;                  ///< volume of its result
  double volume_change_percent = 0.0;          ///< 100 (output - input) / input
  std::optional<double> volume_error_percent;  ///< 100 (output - truth) / truth (phantom only)
  /// Distance to the truth over all vertices (unset without a truth); feature and smooth regions and
  /// the normal errors only for a phantom.
  std::optional<RegionMetrics> all, feature, smooth;
  /// Per stage: "detect", "subdivide", "smooth" (the paper), "smooth" (baselines, VTK filters),
  /// "threshold" (with the island and hole clean-up), "surface", "smooth" (voxel route); and "total".
  std::vector<StageTime> seconds;
  std::optional<LabelSummary> labels;  ///< the paper's method only
  /// Volume shrinking rate (V0 - Vk) / V0 after k = 0, 1, ..., iterations iterations; empty for a
  /// method without intermediate results: none, and vtkWindowedSincPolyDataFilter, whose iteration
  /// count is the degree of one polynomial filter (with 1 or 2 iterations it collapses the mesh), so
  /// only its final rate means something.
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
  /// The paper's labels on the contour mesh, and (phantom only) one flag per contour-mesh vertex for
  /// the true feature vertices (within detection_radius) and the feature region (within feature_radius).
  std::vector<VertexLabel> labels;
  std::vector<std::uint8_t> true_features, feature_region;
  std::vector<MethodResult> methods;

  /// The method called `name`, or nullptr.
  [[nodiscard]] const MethodResult* find(std::string_view name) const;
};

/// Reconstructs `image`, runs every method and measures the results. `source` names the volume in
/// messages and reports. Throws InvalidInputError (naming `source`) when the volume yields no mesh or
/// options are out of range, LimitError beyond the vertex limits, CancelledError on request.
[[nodiscard]] Comparison run_comparison(const CtImage& image, const std::string& source, const ComparisonTruth& truth,
                                        const ComparisonOptions& options = {});

}  // namespace contourmesh
