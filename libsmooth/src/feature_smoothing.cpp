// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/feature_smoothing.h"

#include "detail/stopwatch.h"
#include "contourmesh/smooth/adjacency.h"
#include "contourmesh/smooth/errors.h"

#include <chrono>

namespace contourmesh {

namespace {

}  // namespace

FeatureSmoothingResult feature_preserving_smooth(const Mesh& mesh, const FeatureSmoothingOptions& options) {
  if (options.diffusion != SmoothingMethod::Taubin && options.diffusion != SmoothingMethod::Laplacian) {
    throw InvalidInputError("the paper's method diffuses with taubin or laplacian, not " +
                            std::string(to_string(options.diffusion)));
  }
  if (!options.locked.empty() && options.locked.size() != static_cast<std::size_t>(mesh.num_vertices())) {
    throw InvalidInputError("lock mask has " + std::to_string(options.locked.size()) + " entries for " +
                            std::to_string(mesh.num_vertices()) + " vertices");
  }
  const auto start = std::chrono::steady_clock::now();
  FeatureSmoothingResult result;

  // 1. Detect features on the original mesh.
  auto t = std::chrono::steady_clock::now();
  const MeshAdjacency adjacency = build_adjacency(mesh);
  DetectionOptions detection = options.detection;
  if (!detection.progress) detection.progress = options.progress;
  result.detection = detect_features(mesh, adjacency, detection);
  result.seconds.detect = detail::seconds_since(t);

  // 2. Subdivide around edge and corner vertices.
  t = std::chrono::steady_clock::now();
  std::vector<std::uint8_t> selected(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    const VertexLabel l = result.detection.labels[i];
    selected[i] = l == VertexLabel::Edge || l == VertexLabel::Corner;
  }
  SubdivisionOptions sub;
  sub.max_levels = options.max_levels;
  sub.gamma = result.detection.gamma;
  sub.measure = options.detection.measure;
  sub.limits = options.limits;
  AdaptiveMesh adaptive = subdivide_adaptively(mesh, selected, sub);
  result.subdivided_vertices = adaptive.subdivided.size();
  result.adaptive_vertices = adaptive.mesh.num_vertices();
  result.per_level = adaptive.per_level;
  result.seconds.subdivide = detail::seconds_since(t);
  if (options.progress && !options.progress("subdivide", 1.0)) throw CancelledError("subdivision");

  // 3. Isotropic smoothing of the adaptive mesh; new vertices are never locked.
  t = std::chrono::steady_clock::now();
  std::vector<std::uint8_t> locked;
  if (!options.locked.empty()) {
    locked.assign(options.locked.begin(), options.locked.end());
    locked.resize(static_cast<std::size_t>(adaptive.mesh.num_vertices()), 0);
  }
  SmoothingOptions smoothing;
  smoothing.method = options.diffusion;
  smoothing.iterations = options.iterations;
  smoothing.lambda = options.lambda;
  smoothing.mu = options.mu;
  smoothing.boundary = options.boundary;
  smoothing.locked = locked;
  smoothing.progress = options.progress;
  smoothing.on_iteration = options.on_iteration;
  const MeshAdjacency adaptive_adjacency = build_adjacency(adaptive.mesh);
  Eigen::Matrix3Xd smoothed = smooth(adaptive.mesh, adaptive_adjacency, smoothing);
  result.seconds.smooth = detail::seconds_since(t);

  // 4. Resume the resolution (or keep the adaptive mesh).
  if (options.output == OutputResolution::Adaptive) {
    result.mesh = std::move(adaptive.mesh);
    result.mesh.positions = std::move(smoothed);
  } else {
    result.mesh = mesh;
    result.mesh.positions = smoothed.leftCols(mesh.num_vertices());
  }
  result.seconds.total = detail::seconds_since(start);
  return result;
}

}  // namespace contourmesh
