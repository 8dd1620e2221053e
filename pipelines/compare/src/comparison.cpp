// SPDX-License-Identifier: BSD-3-Clause
#include "compare/comparison.h"

#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/metrics.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace contourmesh {

double MethodResult::stage_seconds(std::string_view stage) const {
  for (const StageTime& s : seconds) {
    if (s.stage == stage) return s.seconds;
  }
  return 0.0;
}

const MethodResult* Comparison::find(std::string_view id) const {
  for (const MethodResult& m : methods) {
    if (m.spec.id == id) return &m;
  }
  return nullptr;
}

const MethodResult* Comparison::find(const MethodKey& key) const {
  for (const MethodResult& m : methods) {
    if (!m.spec.variant && m.spec.key == key) return &m;
  }
  return nullptr;
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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

void check_options(const ComparisonOptions& o) {
  const auto fail = [](const std::string& what) { throw InvalidInputError("comparison: " + what); };
  if (!(o.metrics.feature_radius > 0.0 && std::isfinite(o.metrics.feature_radius))) {
    fail("the feature radius must be > 0 mm");
  }
  if (!(o.metrics.density > 0.0 && std::isfinite(o.metrics.density))) fail("the sample density must be > 0 per mm^2");
  if (!(o.detection_radius > 0.0 && std::isfinite(o.detection_radius))) fail("the detection radius must be > 0 mm");
  if (o.timing_repeats < 1) fail("timing repeats must be >= 1");
}

// A method's labels scored against the true feature vertices (phantom) or just counted.
LabelSummary score(const MethodOutput& out, const Comparison& c) {
  LabelSummary l;
  const FeatureLabels& f = *out.labels;
  for (VertexLabel v : f.labels) {
    l.edges += v == VertexLabel::Edge;
    l.corners += v == VertexLabel::Corner;
    l.noise += v == VertexLabel::Noise;
  }
  if (f.detection) l.candidates = f.detection->candidates;
  l.subdivided_vertices = out.subdivided_vertices;
  l.adaptive_vertices = out.adaptive_vertices;
  l.precision = l.recall = l.recall_examinable = kNaN;
  if (c.true_features.empty()) return l;
  std::size_t truths = 0, examinable_truths = 0, detected = 0, both = 0, examinable_both = 0;
  for (std::size_t i = 0; i < f.labels.size() && i < c.true_features.size(); ++i) {
    const bool is_detected = f.labels[i] == VertexLabel::Edge || f.labels[i] == VertexLabel::Corner;
    const bool is_true = c.true_features[i] != 0, examinable = c.examinable[i] != 0;
    truths += is_true;
    examinable_truths += is_true && examinable;
    detected += is_detected;
    both += is_detected && is_true;
    examinable_both += is_detected && is_true && examinable;
  }
  l.true_features = truths;
  l.examinable_true_features = examinable_truths;
  l.detected = detected;
  l.true_positives = both;
  l.examinable_true_positives = examinable_both;
  if (detected > 0) l.precision = static_cast<double>(both) / static_cast<double>(detected);
  if (truths > 0) l.recall = static_cast<double>(both) / static_cast<double>(truths);
  if (examinable_truths > 0) {
    l.recall_examinable = static_cast<double>(examinable_both) / static_cast<double>(examinable_truths);
  }
  return l;
}

}  // namespace

Comparison run_comparison(const CtImage& image, const std::string& source, const ComparisonTruth& truth,
                          const ComparisonOptions& options) {
  check_options(options);
  const std::vector<MethodSpec> table = method_table(options.methods);
  const Progress progress(options.progress);
  Comparison c;
  c.source = source;
  c.truth = truth.kind;
  c.truth_description = truth.description;
  c.truth_volume = truth.volume;
  c.feature_radius = options.metrics.feature_radius;
  c.detection_radius = options.detection_radius;

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

  // 2. The true feature vertices of the contour mesh, what labels are scored against.
  if (truth.kind == TruthKind::Phantom && truth.surface && truth.surface->feature_distance) {
    const auto n = static_cast<std::size_t>(mesh.num_vertices());
    c.true_features.assign(n, 0);
    c.examinable.assign(n, 0);
    for (Index i = 0; i < mesh.num_vertices(); ++i) {
      c.true_features[i] = truth.surface->feature_distance(mesh.positions.col(i)) < options.detection_radius;
      c.examinable[i] = mesh.has_contour_ids() && mesh.slice_ids[i] >= 0;
    }
  }

  // 3. Every method of the table.
  for (const MethodSpec& spec : table) {
    progress(spec.id, 0.0);
    const MethodContext context{mesh,
                                image,
                                options.reconstruction,
                                options.limits,
                                options.timing_repeats,
                                options.volume_curves,
                                progress.renamed(spec.id)};
    MethodOutput out;
    try {
      out = spec.run(context);
    } catch (const LimitError& e) {
      throw LimitError(source + ": " + spec.id + ": " + e.what());
    } catch (const InvalidInputError& e) {
      throw InvalidInputError(source + ": " + spec.id + ": " + e.what());
    }
    MethodResult r;
    r.spec = spec;
    r.iterations = out.iterations;
    r.volume_input = out.volume_input;
    for (const auto& [stage, seconds] : out.seconds) r.seconds.push_back({stage, seconds});
    if (out.labels) {
      r.labels = score(out, c);
      r.vertex_labels = out.labels->labels;
    }
    r.volume_curve = std::move(out.volume_curve);
    r.mesh = std::move(out.mesh);
    c.methods.push_back(std::move(r));
  }

  // 4. Metrics, over the surface.
  for (std::size_t k = 0; k < c.methods.size(); ++k) {
    progress("metrics", static_cast<double>(k) / static_cast<double>(c.methods.size()));
    MethodResult& r = c.methods[k];
    r.volume_output = enclosed_volume(r.mesh);
    r.volume_change_percent = 100.0 * (r.volume_output - r.volume_input) / r.volume_input;
    if (c.truth_volume > 0.0) r.volume_error_percent = 100.0 * (r.volume_output - c.truth_volume) / c.truth_volume;
    if (truth.surface) r.accuracy = surface_accuracy(r.mesh, *truth.surface, options.metrics);
  }
  progress("metrics", 1.0);
  return c;
}

}  // namespace contourmesh
