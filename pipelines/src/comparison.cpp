#include "pipelines/comparison.h"

#include "pipelines/vtk_convert.h"
#include "pipelines/vtk_image_convert.h"

#include <smooth/errors.h>

#include <vtkCellArray.h>
#include <vtkDiscreteFlyingEdges3D.h>
#include <vtkImageConnectivityFilter.h>
#include <vtkImageConstantPad.h>
#include <vtkImageData.h>
#include <vtkImageThreshold.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkSmoothPolyDataFilter.h>
#include <vtkStaticCellLocator.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <utility>

namespace contourmesh {

std::string_view to_string(TruthKind kind) {
  switch (kind) {
    case TruthKind::None:
      return "none";
    case TruthKind::Phantom:
      return "phantom";
    case TruthKind::ReferenceSurface:
      return "reference-surface";
  }
  return "none";
}

ComparisonTruth phantom_truth(const Phantom& phantom) {
  ComparisonTruth t;
  t.kind = TruthKind::Phantom;
  t.description = "analytic surface of the " + std::string(to_string(phantom.shape)) + " phantom";
  t.phantom = phantom;
  t.distance = phantom.sdf;
  return t;
}

ComparisonTruth reference_surface_truth(const Mesh& reference, std::string description) {
  if (reference.num_faces() == 0) throw InvalidInputError(description + ": the reference surface has no triangles");
  vtkSmartPointer<vtkPolyData> poly = to_polydata(reference);
  auto locator = vtkSmartPointer<vtkStaticCellLocator>::New();
  locator->SetDataSet(poly);
  locator->BuildLocator();
  ComparisonTruth t;
  t.kind = TruthKind::ReferenceSurface;
  t.description = std::move(description);
  // The polydata must outlive the locator's queries: the lambda keeps both.
  t.distance = [poly, locator](const Eigen::Vector3d& p) {
    double x[3] = {p.x(), p.y(), p.z()};
    double closest[3];
    vtkIdType cell = -1;
    int sub = 0;
    double d2 = 0.0;
    locator->FindClosestPoint(x, closest, cell, sub, d2);
    return std::sqrt(d2);
  };
  return t;
}

double MethodResult::stage_seconds(std::string_view stage) const {
  for (const StageTime& s : seconds) {
    if (s.stage == stage) return s.seconds;
  }
  return 0.0;
}

const MethodResult* Comparison::find(std::string_view name) const {
  for (const MethodResult& m : methods) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Reports a stage to the caller's progress callback; throws CancelledError when it asks to stop.
class Progress {
 public:
  explicit Progress(const ProgressCallback& callback) : callback_(callback) {}
  void operator()(const std::string& stage, double fraction) const {
    if (callback_ && !callback_(stage, fraction)) throw CancelledError(stage);
  }
  // A callback for a library call that reports everything under `stage`.
  [[nodiscard]] ProgressCallback renamed(const std::string& stage) const {
    if (!callback_) return {};
    return [this, stage](std::string_view, double fraction) { return callback_(stage, fraction); };
  }

 private:
  const ProgressCallback& callback_;
};

// Runs `body` `repeats` times (the result of the last run is kept by `body`) and returns the fastest
// time of each stage it reports through `record`.
using StageRecorder = std::function<void(const std::string& stage, double seconds)>;

std::vector<StageTime> timed(int repeats, const std::function<void(const StageRecorder&)>& body) {
  std::vector<StageTime> best;
  for (int r = 0; r < repeats; ++r) {
    std::vector<StageTime> run;
    body([&](const std::string& stage, double seconds) { run.push_back({stage, seconds}); });
    double total = 0.0;
    for (const StageTime& s : run) total += s.seconds;
    run.push_back({"total", total});
    if (best.empty()) {
      best = run;
    } else {
      for (std::size_t i = 0; i < best.size() && i < run.size(); ++i)
        best[i].seconds = std::min(best[i].seconds, run[i].seconds);
    }
  }
  return best;
}

Eigen::Matrix3Xd positions_of(vtkPolyData* poly) {
  const auto n = static_cast<Index>(poly->GetNumberOfPoints());
  Eigen::Matrix3Xd p(3, n);
  for (Index i = 0; i < n; ++i) poly->GetPoint(i, p.col(i).data());
  return p;
}

// vtkWindowedSincPolyDataFilter as 3D Slicer configures it for closed surfaces
// (vtkBinaryLabelmapToClosedSurfaceConversionRule).
vtkSmartPointer<vtkPolyData> windowed_sinc(vtkPolyData* input, int iterations, double passband) {
  vtkNew<vtkWindowedSincPolyDataFilter> filter;
  filter->SetInputData(input);
  filter->SetNumberOfIterations(iterations);
  filter->SetPassBand(passband);
  filter->NormalizeCoordinatesOn();
  filter->BoundarySmoothingOff();
  filter->FeatureEdgeSmoothingOff();
  filter->NonManifoldSmoothingOn();
  filter->Update();
  return filter->GetOutput();
}

vtkSmartPointer<vtkPolyData> smooth_polydata(vtkPolyData* input, int iterations, const ComparisonOptions& o) {
  vtkNew<vtkSmoothPolyDataFilter> filter;
  filter->SetInputData(input);
  filter->SetNumberOfIterations(iterations);
  filter->SetRelaxationFactor(o.laplace_relaxation);
  filter->SetConvergence(0.0);  // run every iteration
  filter->FeatureEdgeSmoothingOn();
  filter->SetFeatureAngle(o.laplace_feature_angle);
  filter->SetEdgeAngle(o.laplace_edge_angle);
  filter->BoundarySmoothingOn();
  filter->Update();
  return filter->GetOutput();
}

// The volume-shrinking curve of a VTK filter run with 1, 2, ..., iterations iterations.
std::vector<double> vtk_curve(const Mesh& mesh, vtkPolyData* input, int iterations,
                              const std::function<vtkSmartPointer<vtkPolyData>(vtkPolyData*, int)>& filter) {
  const double v0 = enclosed_volume(mesh);
  std::vector<double> curve{0.0};
  for (int k = 1; k <= iterations; ++k) {
    const vtkSmartPointer<vtkPolyData> out = filter(input, k);
    curve.push_back(volume_shrinking_rate(v0, enclosed_volume(positions_of(out), mesh.triangles)));
  }
  return curve;
}

std::string format_settings(const std::function<void(std::ostringstream&)>& f) {
  std::ostringstream s;
  f(s);
  return s.str();
}

// Indices of flagged vertices, and of the faces with at least one flagged vertex / with none.
struct Regions {
  std::vector<Index> feature_vertices, smooth_vertices, feature_faces, smooth_faces;
};

Regions split_regions(const Mesh& mesh, const std::vector<std::uint8_t>& in_feature) {
  Regions r;
  for (Index i = 0; i < mesh.num_vertices(); ++i) (in_feature[i] ? r.feature_vertices : r.smooth_vertices).push_back(i);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    const Triangle& t = mesh.triangles[f];
    const bool feature = in_feature[t[0]] || in_feature[t[1]] || in_feature[t[2]];
    (feature ? r.feature_faces : r.smooth_faces).push_back(f);
  }
  return r;
}

// Distance of every vertex to the phantom's nearest feature point (a linear scan per vertex: compute
// it once per mesh).
std::vector<double> feature_distances(const Mesh& mesh, const Phantom& phantom) {
  std::vector<double> d(static_cast<std::size_t>(mesh.num_vertices()));
  for (Index i = 0; i < mesh.num_vertices(); ++i) d[i] = distance_to_features(phantom, mesh.positions.col(i));
  return d;
}

std::vector<std::uint8_t> closer_than(const std::vector<double>& distances, double radius) {
  std::vector<std::uint8_t> flags(distances.size(), 0);
  for (std::size_t i = 0; i < distances.size(); ++i) flags[i] = distances[i] < radius ? 1 : 0;
  return flags;
}

// The statistics of the union of two disjoint sets, from the statistics of each.
DistanceStats merge(const DistanceStats& a, const DistanceStats& b) {
  DistanceStats m;
  m.count = a.count + b.count;
  if (m.count == 0) return m;
  const double na = static_cast<double>(a.count), nb = static_cast<double>(b.count), n = na + nb;
  m.mean = (na * a.mean + nb * b.mean) / n;
  m.rms = std::sqrt((na * a.rms * a.rms + nb * b.rms * b.rms) / n);
  m.max = std::max(a.max, b.max);
  return m;
}

AngleStats merge(const AngleStats& a, const AngleStats& b) {
  AngleStats m;
  m.count = a.count + b.count;
  if (m.count == 0) return m;
  m.mean_degrees = (static_cast<double>(a.count) * a.mean_degrees + static_cast<double>(b.count) * b.mean_degrees) /
                   static_cast<double>(m.count);
  m.max_degrees = std::max(a.max_degrees, b.max_degrees);
  return m;
}

// Distance, normals and volume of a result; `regions` is empty without a phantom.
void measure(MethodResult& r, const ComparisonTruth& truth, const Regions* regions, double truth_volume) {
  r.volume_output = enclosed_volume(r.mesh);
  r.volume_change_percent = 100.0 * (r.volume_output - r.volume_input) / r.volume_input;
  if (truth_volume > 0.0) r.volume_error_percent = 100.0 * (r.volume_output - truth_volume) / truth_volume;
  if (!truth.distance) return;
  RegionMetrics all;
  if (truth.phantom) {
    // The whole mesh is the union of the two regions: measure each once.
    const Phantom& ph = *truth.phantom;
    RegionMetrics feature, smooth;
    feature.distance = distance_to_surface(r.mesh.positions, ph.sdf, regions->feature_vertices);
    smooth.distance = distance_to_surface(r.mesh.positions, ph.sdf, regions->smooth_vertices);
    feature.normals = normal_angular_error(r.mesh.positions, r.mesh.triangles, ph.normal, regions->feature_faces);
    smooth.normals = normal_angular_error(r.mesh.positions, r.mesh.triangles, ph.normal, regions->smooth_faces);
    all.distance = merge(feature.distance, smooth.distance);
    all.normals = merge(feature.normals, smooth.normals);
    r.feature = feature;
    r.smooth = smooth;
  } else {
    all.distance = distance_to_surface(r.mesh.positions, truth.distance);
  }
  r.all = all;
}

// Keeps the 6-connected regions of value 1 with at least `min_voxels` voxels, as 1; the rest becomes 0.
void keep_large_regions(vtkImageConnectivityFilter* filter, vtkIdType min_voxels) {
  filter->SetScalarRange(1.0, 1.0);
  filter->SetExtractionModeToAllRegions();
  filter->SetSizeRange(min_voxels, std::numeric_limits<vtkIdType>::max());
  filter->SetLabelModeToConstantValue();
  filter->SetLabelConstantValue(1);
  filter->SetLabelScalarTypeToUnsignedChar();
  filter->GenerateRegionExtentsOff();
}

// 0 -> 1 and 1 -> 0 on a binary unsigned char image.
void invert(vtkImageThreshold* filter) {
  filter->ThresholdByLower(0.5);
  filter->SetInValue(1);
  filter->SetOutValue(0);
  filter->ReplaceInOn();
  filter->ReplaceOutOn();
  filter->SetOutputScalarTypeToUnsignedChar();
}

// The flying-edges surface of the thresholded volume, in physical coordinates, outward oriented.
struct VoxelSurface {
  Mesh raw, smoothed;
  std::vector<StageTime> seconds;  // threshold, surface, smooth, total
};

VoxelSurface voxel_route(const CtImage& image, const ComparisonOptions& o, const Progress& progress) {
  VoxelSurface v;
  // Work in index space scaled by the spacing (origin 0, identity direction) and map the points to
  // physical space afterwards, whatever the image's direction matrix.
  vtkSmartPointer<vtkImageData> vtk_image = to_image_data(&image);
  double first[3];
  vtk_image->GetOrigin(first);
  Eigen::Matrix3d direction;
  const auto& d = image.GetDirection();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) direction(r, c) = d(r, c);
  }
  vtk_image->SetOrigin(0.0, 0.0, 0.0);
  vtk_image->SetDirectionMatrix(1, 0, 0, 0, 1, 0, 0, 0, 1);
  int extent[6];
  vtk_image->GetExtent(extent);

  // The contour route drops mesh components enclosing less than min_component_voxels voxels.
  const auto min_speck_voxels = static_cast<vtkIdType>(std::ceil(o.reconstruction.min_component_voxels));
  vtkSmartPointer<vtkPolyData> raw_poly, smooth_poly;
  v.seconds = timed(o.timing_repeats, [&](const StageRecorder& record) {
    auto t = Clock::now();
    vtkNew<vtkImageThreshold> threshold;
    threshold->SetInputData(vtk_image);
    threshold->ThresholdByUpper(o.reconstruction.segmentation.threshold);
    threshold->SetInValue(1);
    threshold->SetOutValue(0);
    threshold->ReplaceInOn();
    threshold->ReplaceOutOn();
    threshold->SetOutputScalarTypeToUnsignedChar();
    vtkAlgorithm* binary = threshold;
    // Islands and holes below the contour route's speck size are removed and filled (3D Slicer's
    // Islands effect and a hole fill), as the contour route drops such regions and holes per slice and
    // such components after tiling; otherwise noise voxels decide the voxel route's metrics.
    vtkNew<vtkImageConnectivityFilter> islands;
    vtkNew<vtkImageThreshold> background;
    vtkNew<vtkImageConnectivityFilter> large_background;
    vtkNew<vtkImageThreshold> filled;
    if (min_speck_voxels > 0) {
      islands->SetInputConnection(threshold->GetOutputPort());
      keep_large_regions(islands, min_speck_voxels);
      background->SetInputConnection(islands->GetOutputPort());
      invert(background);
      large_background->SetInputConnection(background->GetOutputPort());
      keep_large_regions(large_background, min_speck_voxels);
      filled->SetInputConnection(large_background->GetOutputPort());
      invert(filled);
      binary = filled;
    }
    // One voxel of background around the volume, so that bone touching the border gives a closed
    // surface (Slicer pads the labelmap the same way).
    vtkNew<vtkImageConstantPad> pad;
    pad->SetInputConnection(binary->GetOutputPort());
    pad->SetOutputWholeExtent(extent[0] - 1, extent[1] + 1, extent[2] - 1, extent[3] + 1, extent[4] - 1, extent[5] + 1);
    pad->SetConstant(0);
    pad->Update();
    record("threshold", seconds_since(t));
    progress("voxel-flying-edges", 0.3);

    t = Clock::now();
    vtkNew<vtkDiscreteFlyingEdges3D> surface;
    surface->SetInputConnection(pad->GetOutputPort());
    surface->SetValue(0, 1.0);
    surface->ComputeNormalsOff();
    surface->ComputeGradientsOff();
    surface->ComputeScalarsOff();
    surface->Update();
    raw_poly = surface->GetOutput();
    record("surface", seconds_since(t));
    progress("voxel-windowed-sinc", 0.3);

    t = Clock::now();
    smooth_poly = windowed_sinc(raw_poly, o.sinc_iterations, o.sinc_passband);
    record("smooth", seconds_since(t));
  });
  if (raw_poly->GetNumberOfPolys() == 0) {
    throw InvalidInputError("the voxel route found no surface at threshold " +
                            std::to_string(o.reconstruction.segmentation.threshold));
  }

  const Eigen::Vector3d origin(first[0], first[1], first[2]);
  const auto to_physical = [&](vtkPolyData* poly) {
    Mesh m = from_polydata(poly);
    m.positions = (direction * m.positions).colwise() + origin;
    return m;
  };
  v.raw = to_physical(raw_poly);
  v.smoothed = to_physical(smooth_poly);
  // Marching-cubes triangles may wind inwards; the volume's sign tells, and the metrics want outward.
  if (enclosed_volume(v.raw) < 0.0) {
    for (Triangle& t : v.raw.triangles) std::swap(t[1], t[2]);
    v.smoothed.triangles = v.raw.triangles;
  }
  return v;
}

void check_options(const ComparisonOptions& o) {
  const auto fail = [](const std::string& what) { throw InvalidInputError("comparison: " + what); };
  if (o.baseline_iterations < 0) fail("baseline iterations must be >= 0");
  if (o.sinc_iterations < 1) fail("windowed-sinc iterations must be >= 1");
  if (!(o.sinc_passband > 0.0 && o.sinc_passband <= 2.0)) fail("windowed-sinc passband must be in (0, 2]");
  if (o.laplace_iterations < 1) fail("vtkSmoothPolyDataFilter iterations must be >= 1");
  if (!(o.laplace_relaxation > 0.0 && o.laplace_relaxation <= 1.0)) fail("relaxation factor must be in (0, 1]");
  if (!(o.feature_radius > 0.0 && std::isfinite(o.feature_radius))) fail("the feature radius must be > 0 mm");
  if (!(o.detection_radius > 0.0 && std::isfinite(o.detection_radius))) fail("the detection radius must be > 0 mm");
  if (o.timing_repeats < 1) fail("timing repeats must be >= 1");
}

}  // namespace

Comparison run_comparison(const CtImage& image, const std::string& source, const ComparisonTruth& truth,
                          const ComparisonOptions& options) {
  check_options(options);
  const Progress progress(options.progress);
  Comparison c;
  c.source = source;
  c.truth = truth.kind;
  c.truth_description = truth.description;
  c.feature_radius = options.feature_radius;
  c.detection_radius = options.detection_radius;
  if (truth.phantom) c.truth_volume = truth.phantom->volume;

  // 1. The contour mesh every contour-route method starts from.
  Reconstruction rec;
  try {
    rec = reconstruct(image, options.reconstruction, options.progress);
  } catch (const LimitError& e) {
    throw LimitError(source + ": " + e.what());
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(source + ": " + e.what());
  }
  c.reconstruction = rec.report;
  c.contour_mesh = std::move(rec.mesh);
  const Mesh& mesh = c.contour_mesh;
  const double v0 = enclosed_volume(mesh);
  if (!(std::abs(v0) > 0.0) || !std::isfinite(v0)) {
    throw InvalidInputError(source + ": the reconstructed mesh encloses no volume");
  }

  std::optional<Regions> regions;
  if (truth.phantom) {
    const std::vector<double> to_features = feature_distances(mesh, *truth.phantom);
    c.feature_region = closer_than(to_features, options.feature_radius);
    c.true_features = closer_than(to_features, options.detection_radius);
    regions = split_regions(mesh, c.feature_region);
  }
  const auto contour_result = [&](std::string name, std::string settings) {
    MethodResult r;
    r.name = std::move(name);
    r.route = "contour";
    r.settings = std::move(settings);
    r.volume_input = v0;
    return r;
  };

  // 2. The library's baselines.
  const std::pair<const char*, SmoothingMethod> baselines[] = {
      {"none", SmoothingMethod::None},           {"laplacian", SmoothingMethod::Laplacian},
      {"taubin", SmoothingMethod::Taubin},       {"mcf", SmoothingMethod::MeanCurvatureFlow},
      {"mindist", SmoothingMethod::MinDistFlow},
  };
  for (const auto& [name, method] : baselines) {
    progress(name, 0.0);
    SmoothingOptions so;
    so.method = method;
    so.iterations = method == SmoothingMethod::None ? 0 : options.baseline_iterations;
    so.progress = progress.renamed(name);
    MethodResult r =
        contour_result(name, method == SmoothingMethod::None ? std::string("the reconstructed contour mesh, unsmoothed")
                                                             : format_settings([&](std::ostringstream& s) {
                                                                 s << so.iterations << " iterations, lambda "
                                                                   << default_lambda(method);
                                                                 if (method == SmoothingMethod::Taubin)
                                                                   s << ", mu " << so.mu;
                                                                 if (method == SmoothingMethod::MinDistFlow)
                                                                   s << ", beta " << so.beta;
                                                               }));
    r.mesh = mesh;
    r.iterations = so.iterations;
    if (method == SmoothingMethod::None) {
      r.seconds = {{"total", 0.0}};
    } else {
      r.seconds = timed(options.timing_repeats, [&](const StageRecorder& record) {
        const auto t = Clock::now();
        r.mesh.positions = smooth(mesh, so);  // the adjacency is part of the cost, as inside VTK's filters
        record("smooth", seconds_since(t));
      });
    }
    if (options.volume_curves && method != SmoothingMethod::None) {
      SmoothingOptions curve = so;
      curve.progress = {};
      r.volume_curve = volume_shrinking_curve(mesh, curve);
    }
    c.methods.push_back(std::move(r));
  }

  // 3. The paper's method.
  {
    progress("paper", 0.0);
    FeatureSmoothingOptions po = options.paper;
    po.progress = progress.renamed("paper");
    po.on_iteration = {};
    MethodResult r = contour_result("paper", format_settings([&](std::ostringstream& s) {
                                      s << "Algorithm 1: detection (gamma " << po.detection.gamma_factor
                                        << " x mean |U|, window " << po.detection.window << "), up to " << po.max_levels
                                        << " subdivision levels, " << to_string(po.diffusion) << " " << po.iterations
                                        << " iterations";
                                    }));
    FeatureSmoothingResult result;
    r.seconds = timed(options.timing_repeats, [&](const StageRecorder& record) {
      result = feature_preserving_smooth(mesh, po);
      record("detect", result.seconds.detect);
      record("subdivide", result.seconds.subdivide);
      record("smooth", result.seconds.smooth);
    });
    r.mesh = result.mesh;
    r.iterations = po.iterations;
    LabelSummary labels;
    const FeatureDetection& d = result.detection;
    labels.candidates = d.candidates;
    labels.edges = d.edges;
    labels.corners = d.corners;
    labels.noise = d.noise;
    labels.subdivided_vertices = result.subdivided_vertices;
    labels.adaptive_vertices = result.adaptive_vertices;
    labels.precision = labels.recall = std::numeric_limits<double>::quiet_NaN();
    if (truth.phantom) {
      std::size_t truths = 0, detected = 0, both = 0;
      for (Index i = 0; i < mesh.num_vertices(); ++i) {
        const bool is_detected = d.labels[i] == VertexLabel::Edge || d.labels[i] == VertexLabel::Corner;
        truths += c.true_features[i];
        detected += is_detected;
        both += is_detected && c.true_features[i];
      }
      labels.true_features = truths;
      labels.detected = detected;
      labels.true_positives = both;
      if (detected > 0) labels.precision = static_cast<double>(both) / static_cast<double>(detected);
      if (truths > 0) labels.recall = static_cast<double>(both) / static_cast<double>(truths);
    }
    r.labels = labels;
    c.labels = d.labels;
    if (options.volume_curves) {
      po.progress = {};
      r.volume_curve = {0.0};
      po.on_iteration = [&](int, const Eigen::Matrix3Xd& positions) {
        const Eigen::Matrix3Xd original = positions.leftCols(mesh.num_vertices());
        r.volume_curve.push_back(volume_shrinking_rate(v0, enclosed_volume(original, mesh.triangles)));
      };
      (void)feature_preserving_smooth(mesh, po);
    }
    c.methods.push_back(std::move(r));
  }

  // 4. VTK's filters on the same contour mesh.
  vtkSmartPointer<vtkPolyData> poly = to_polydata(mesh);
  {
    progress("vtk-windowed-sinc", 0.0);
    MethodResult r = contour_result("vtk-windowed-sinc", format_settings([&](std::ostringstream& s) {
                                      s << "3D Slicer's settings: " << options.sinc_iterations
                                        << " iterations, passband " << options.sinc_passband
                                        << ", normalized coordinates, no boundary or feature-edge smoothing";
                                    }));
    vtkSmartPointer<vtkPolyData> out;
    r.seconds = timed(options.timing_repeats, [&](const StageRecorder& record) {
      const auto t = Clock::now();
      out = windowed_sinc(poly, options.sinc_iterations, options.sinc_passband);
      record("smooth", seconds_since(t));
    });
    r.mesh = mesh;
    r.mesh.positions = positions_of(out);
    r.iterations = options.sinc_iterations;
    c.methods.push_back(std::move(r));
  }
  {
    progress("vtk-smooth-feature-edges", 0.0);
    MethodResult r = contour_result("vtk-smooth-feature-edges", format_settings([&](std::ostringstream& s) {
                                      s << options.laplace_iterations << " iterations, relaxation "
                                        << options.laplace_relaxation << ", feature-edge smoothing on (feature angle "
                                        << options.laplace_feature_angle << ", edge angle "
                                        << options.laplace_edge_angle << ")";
                                    }));
    vtkSmartPointer<vtkPolyData> out;
    r.seconds = timed(options.timing_repeats, [&](const StageRecorder& record) {
      const auto t = Clock::now();
      out = smooth_polydata(poly, options.laplace_iterations, options);
      record("smooth", seconds_since(t));
    });
    r.mesh = mesh;
    r.mesh.positions = positions_of(out);
    r.iterations = options.laplace_iterations;
    if (options.volume_curves) {
      r.volume_curve = vtk_curve(mesh, poly, options.laplace_iterations,
                                 [&](vtkPolyData* in, int k) { return smooth_polydata(in, k, options); });
    }
    c.methods.push_back(std::move(r));
  }

  // 5. The voxel route on the same volume and threshold.
  progress("voxel-flying-edges", 0.0);
  VoxelSurface voxel = voxel_route(image, options, progress);
  const double voxel_v0 = enclosed_volume(voxel.raw);
  const auto islands_text = [&] {
    const double min_voxels = std::ceil(options.reconstruction.min_component_voxels);
    return min_voxels > 0.0 ? ", islands and holes under " + std::to_string(static_cast<long>(min_voxels)) +
                                  " voxels removed and filled"
                            : std::string();
  };
  std::optional<Regions> voxel_regions;
  if (truth.phantom) {
    voxel_regions =
        split_regions(voxel.raw, closer_than(feature_distances(voxel.raw, *truth.phantom), options.feature_radius));
  }
  {
    MethodResult raw;
    raw.name = "voxel-flying-edges";
    raw.route = "voxel";
    raw.settings = format_settings([&](std::ostringstream& s) {
      s << "threshold at " << options.reconstruction.segmentation.threshold << islands_text()
        << ", vtkDiscreteFlyingEdges3D on the padded binary image, unsmoothed";
    });
    raw.mesh = voxel.raw;
    raw.volume_input = voxel_v0;
    raw.seconds = {{"threshold", voxel.seconds[0].seconds},
                   {"surface", voxel.seconds[1].seconds},
                   {"total", voxel.seconds[0].seconds + voxel.seconds[1].seconds}};
    c.methods.push_back(std::move(raw));
    MethodResult smoothed;
    smoothed.name = "voxel-windowed-sinc";
    smoothed.route = "voxel";
    smoothed.settings = format_settings([&](std::ostringstream& s) {
      s << "3D Slicer's voxel route: threshold at " << options.reconstruction.segmentation.threshold << islands_text()
        << ", vtkDiscreteFlyingEdges3D, vtkWindowedSincPolyDataFilter (" << options.sinc_iterations
        << " iterations, passband " << options.sinc_passband << ")";
    });
    smoothed.mesh = voxel.smoothed;
    smoothed.volume_input = voxel_v0;
    smoothed.seconds = voxel.seconds;
    smoothed.iterations = options.sinc_iterations;
    c.methods.push_back(std::move(smoothed));
  }

  // 6. Metrics.
  progress("metrics", 0.0);
  for (std::size_t m = 0; m < c.methods.size(); ++m) {
    MethodResult& r = c.methods[m];
    const Regions* reg =
        r.route == "voxel" ? (voxel_regions ? &*voxel_regions : nullptr) : (regions ? &*regions : nullptr);
    measure(r, truth, reg, c.truth_volume);
    progress("metrics", static_cast<double>(m + 1) / static_cast<double>(c.methods.size()));
  }
  return c;
}

}  // namespace contourmesh
