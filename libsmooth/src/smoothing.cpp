// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/smoothing.h"

#include "contourmesh/smooth/errors.h"

#include <cmath>
#include <string>

namespace contourmesh {

std::string_view to_string(SmoothingMethod method) {
  switch (method) {
    case SmoothingMethod::None: return "none";
    case SmoothingMethod::Laplacian: return "laplacian";
    case SmoothingMethod::Taubin: return "taubin";
    case SmoothingMethod::MeanCurvatureFlow: return "mcf";
    case SmoothingMethod::MinDistFlow: return "mindist";
    case SmoothingMethod::FeaturePreserving: return "paper";
    case SmoothingMethod::CrossSlice: return "cross-slice";
  }
  return "unknown";
}

SmoothingMethod parse_smoothing_method(std::string_view name) {
  if (name == "none") return SmoothingMethod::None;
  if (name == "laplacian") return SmoothingMethod::Laplacian;
  if (name == "taubin") return SmoothingMethod::Taubin;
  if (name == "mcf" || name == "mean-curvature-flow") return SmoothingMethod::MeanCurvatureFlow;
  if (name == "mindist" || name == "min-dist") return SmoothingMethod::MinDistFlow;
  if (name == "paper" || name == "feature-preserving") return SmoothingMethod::FeaturePreserving;
  if (name == "cross-slice") return SmoothingMethod::CrossSlice;
  throw InvalidInputError("unknown smoothing method '" + std::string(name) +
                          "' (expected none, laplacian, taubin, mcf, mindist, paper or cross-slice)");
}

std::span<const SmoothingMethod> all_smoothing_methods() {
  static constexpr SmoothingMethod kAll[] = {
      SmoothingMethod::None,        SmoothingMethod::Laplacian,         SmoothingMethod::Taubin,
      SmoothingMethod::MeanCurvatureFlow, SmoothingMethod::MinDistFlow, SmoothingMethod::FeaturePreserving,
      SmoothingMethod::CrossSlice};
  return kAll;
}

bool is_baseline(SmoothingMethod method) {
  return method != SmoothingMethod::FeaturePreserving && method != SmoothingMethod::CrossSlice;
}

double default_lambda(SmoothingMethod method) {
  switch (method) {
    case SmoothingMethod::None: return 0.0;
    case SmoothingMethod::Laplacian: return 0.3;
    case SmoothingMethod::Taubin: return 0.6307;
    case SmoothingMethod::MeanCurvatureFlow: return 0.3;
    case SmoothingMethod::MinDistFlow: return 0.5;
    case SmoothingMethod::FeaturePreserving:
    case SmoothingMethod::CrossSlice: return 0.0;
  }
  return 0.0;
}

void check_smoothing_options(const SmoothingOptions& o, Index num_vertices) {
  if (o.iterations < 0) throw InvalidInputError("iterations must be >= 0, got " + std::to_string(o.iterations));
  if (o.lambda) {
    const double l = *o.lambda;
    if (!(l > 0.0 && l <= 1.0)) throw InvalidInputError("lambda must be in (0, 1], got " + std::to_string(l));
  }
  if (!(o.mu >= -1.0 && o.mu < 0.0)) throw InvalidInputError("mu must be in [-1, 0), got " + std::to_string(o.mu));
  if (!(o.beta >= 0.0 && o.beta <= 2.0))
    throw InvalidInputError("beta must be in [0, 2], got " + std::to_string(o.beta));
  if (!o.locked.empty() && o.locked.size() != static_cast<std::size_t>(num_vertices)) {
    throw InvalidInputError("lock mask has " + std::to_string(o.locked.size()) + " entries for " +
                            std::to_string(num_vertices) + " vertices");
  }
}

Eigen::Matrix3Xd smooth(const Mesh& mesh, const MeshAdjacency& adjacency, const SmoothingOptions& options) {
  switch (options.method) {
    case SmoothingMethod::None: check_smoothing_options(options, mesh.num_vertices()); return mesh.positions;
    case SmoothingMethod::Laplacian: return laplacian_smooth(mesh, adjacency, options);
    case SmoothingMethod::Taubin: return taubin_smooth(mesh, adjacency, options);
    case SmoothingMethod::MeanCurvatureFlow: return mean_curvature_flow(mesh, adjacency, options);
    case SmoothingMethod::MinDistFlow: return min_dist_flow(mesh, adjacency, options);
    case SmoothingMethod::FeaturePreserving:
    case SmoothingMethod::CrossSlice:
      throw InvalidInputError(std::string(to_string(options.method)) +
                              " is not a baseline smoother: run it through smooth(mesh, method, SmoothOptions)");
  }
  throw InvalidInputError("unknown smoothing method");
}

Eigen::Matrix3Xd smooth(const Mesh& mesh, const SmoothingOptions& options) {
  return smooth(mesh, build_adjacency(mesh), options);
}

}  // namespace contourmesh
