// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/smooth.h"

#include "detail/stopwatch.h"
#include "contourmesh/smooth/adjacency.h"
#include "contourmesh/smooth/divergence.h"
#include "contourmesh/smooth/errors.h"

#include <chrono>
#include <string>
#include <utility>

namespace contourmesh {

namespace {

using Clock = std::chrono::steady_clock;

SmoothResult run_baseline(const Mesh& mesh, SmoothingMethod method, const SmoothOptions& options) {
  SmoothingOptions o = options.baseline;
  o.method = method;
  o.iterations = iterations_of(method, options);
  o.progress = options.progress;
  o.on_iteration = divergence_guard(mesh.positions, "smoothing", std::move(o.on_iteration));
  SmoothResult r;
  const auto t = Clock::now();
  r.mesh = mesh;
  r.mesh.positions = smooth(mesh, o);  // builds the adjacency: part of the method's cost
  r.seconds.smooth = detail::seconds_since(t);
  r.iterations = o.iterations;
  return r;
}

SmoothResult run_feature_preserving(const Mesh& mesh, const SmoothOptions& options) {
  FeatureSmoothingOptions o = options.paper;
  o.iterations = iterations_of(SmoothingMethod::FeaturePreserving, options);
  o.progress = options.progress;
  o.detection.progress = {};
  o.limits = options.limits;
  // Against the input's bounds: the adaptive mesh's added vertices lie among the input's.
  o.on_iteration = divergence_guard(mesh.positions, "smoothing", std::move(o.on_iteration));
  FeatureSmoothingResult f = feature_preserving_smooth(mesh, o);
  SmoothResult r;
  r.mesh = std::move(f.mesh);
  r.labels = f.detection.labels;
  r.detection = std::move(f.detection);
  r.seconds = f.seconds;
  r.iterations = o.iterations;
  r.subdivided_vertices = f.subdivided_vertices;
  r.adaptive_vertices = f.adaptive_vertices;
  return r;
}

SmoothResult run_cross_slice(const Mesh& mesh, const SmoothOptions& options) {
  CrossSliceOptions o = options.cross_slice;
  o.progress = options.progress;
  CrossSliceResult c = cross_slice_smooth(mesh, o);
  SmoothResult r;
  r.mesh = std::move(c.mesh);
  r.labels = std::move(c.labels);
  r.creases = std::move(c.features);
  r.seconds.detect = c.seconds_detect;
  r.seconds.smooth = c.seconds_smooth;
  r.profiles = c.profiles;
  r.noise_across = c.noise_across;
  r.noise_along = c.noise_along;
  r.noise_across_source = c.noise_across_source;
  return r;
}

}  // namespace

int default_iterations(SmoothingMethod method) { return iterations_of(method, SmoothOptions{}); }

int iterations_of(SmoothingMethod method, const SmoothOptions& options) {
  switch (method) {
    case SmoothingMethod::None:
    case SmoothingMethod::CrossSlice: return 0;
    case SmoothingMethod::FeaturePreserving: return options.iterations.value_or(options.paper.iterations);
    case SmoothingMethod::Laplacian:
    case SmoothingMethod::Taubin:
    case SmoothingMethod::MeanCurvatureFlow:
    case SmoothingMethod::MinDistFlow: return options.iterations.value_or(options.baseline.iterations);
  }
  return 0;
}

bool produces_labels(SmoothingMethod method) {
  return method == SmoothingMethod::FeaturePreserving || method == SmoothingMethod::CrossSlice;
}

DetectionOptions* detection_options_of(SmoothingMethod method, SmoothOptions& options) {
  return method == SmoothingMethod::FeaturePreserving ? &options.paper.detection : nullptr;
}

SmoothResult smooth(const Mesh& mesh, SmoothingMethod method, const SmoothOptions& options) {
  if (options.iterations && *options.iterations < 0) {
    throw InvalidInputError("iterations must be >= 0, got " + std::to_string(*options.iterations));
  }
  check_allocation("smoothing input", static_cast<double>(mesh.num_vertices()), 0.0, options.limits);
  const auto start = Clock::now();
  SmoothResult r;
  switch (method) {
    case SmoothingMethod::FeaturePreserving: r = run_feature_preserving(mesh, options); break;
    case SmoothingMethod::CrossSlice: r = run_cross_slice(mesh, options); break;
    case SmoothingMethod::None:
    case SmoothingMethod::Laplacian:
    case SmoothingMethod::Taubin:
    case SmoothingMethod::MeanCurvatureFlow:
    case SmoothingMethod::MinDistFlow: r = run_baseline(mesh, method, options); break;
  }
  // The guard saw every iteration; this also covers the methods without iterations and the paper's
  // resolution step.
  check_not_diverged(r.mesh.positions, DivergenceBounds::of(mesh.positions), "smoothing");
  r.method = method;
  r.seconds.total = detail::seconds_since(start);
  return r;
}

FeatureLabels label_features(const Mesh& mesh, SmoothingMethod method, const SmoothOptions& options) {
  if (!produces_labels(method)) {
    throw InvalidInputError(std::string(to_string(method)) + " does not label features (paper and cross-slice do)");
  }
  FeatureLabels f;
  const auto start = Clock::now();
  if (method == SmoothingMethod::FeaturePreserving) {
    check_allocation("detection input", static_cast<double>(mesh.num_vertices()), 0.0, options.limits);
    DetectionOptions d = options.paper.detection;
    d.progress = options.progress;
    f.detection = detect_features(mesh, build_adjacency(mesh), d);
    f.labels = f.detection->labels;
  } else {
    SmoothResult r = smooth(mesh, method, options);
    f.labels = std::move(r.labels);
    f.creases = std::move(r.creases);
  }
  f.seconds = detail::seconds_since(start);
  return f;
}

std::string_view to_string(Preset preset) {
  switch (preset) {
    case Preset::Default: return "default";
    case Preset::Xu2006: return "xu2006";
  }
  return "default";
}

Preset parse_preset(std::string_view name) {
  if (name == "default") return Preset::Default;
  if (name == "xu2006") return Preset::Xu2006;
  throw InvalidInputError("unknown preset '" + std::string(name) + "' (expected default or xu2006)");
}

MethodConfig preset(Preset p) {
  MethodConfig c;
  switch (p) {
    case Preset::Default:
      c.method = SmoothingMethod::CrossSlice;
      break;
    case Preset::Xu2006: {
      c.method = SmoothingMethod::FeaturePreserving;
      FeatureSmoothingOptions& o = c.options.paper;
      o.max_levels = 3;
      o.diffusion = SmoothingMethod::Taubin;
      o.iterations = 40;
      o.lambda = 0.6307;
      o.mu = -0.6732;
      o.output = OutputResolution::Original;
      DetectionOptions& d = o.detection;
      d.mode = DetectionMode::ContourContinuity;
      d.gamma.reset();
      d.gamma_factor = 2.0;
      d.measure = UmbrellaMeasure::Length;
      d.delta.reset();
      d.delta_factor = 0.5;
      d.in_slice = InSliceFeatures::Noise;
      d.corner_spread = 1.0;  // above 1/3: the corner-spread extension is off
      d.window = 7;
      d.prefilter_iterations = 0;
      d.curvature.umbilic_tolerance = 0.05;
      d.curvature.min_reciprocal_condition = 1e-6;
      break;
    }
  }
  return c;
}

}  // namespace contourmesh
