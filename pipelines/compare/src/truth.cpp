// SPDX-License-Identifier: BSD-3-Clause
#include "compare/comparison.h"

#include <contourmesh/smooth/closest_point.h>
#include <contourmesh/smooth/errors.h>

#include <memory>
#include <string>
#include <unordered_map>
#include <utility>

namespace contourmesh {

namespace {

// Hash of a point's exact coordinates.
struct PointHash {
  std::size_t operator()(const Eigen::Vector3d& p) const {
    std::size_t h = 0;
    for (int a = 0; a < 3; ++a) h = h * 1000003u ^ std::hash<double>{}(p[a]);
    return h;
  }
};

}  // namespace

std::string_view to_string(TruthKind kind) {
  switch (kind) {
    case TruthKind::None: return "none";
    case TruthKind::Phantom: return "phantom";
    case TruthKind::ReferenceSurface: return "reference-surface";
  }
  return "none";
}

ComparisonTruth phantom_truth(const Phantom& phantom, double spacing, double margin) {
  if (!(margin >= 0.0)) throw InvalidInputError("phantom truth: the margin must be >= 0 mm");
  auto surface = std::make_shared<SurfaceTruth>();
  surface->distance = phantom.sdf;
  surface->normal = phantom.normal;
  surface->signed_distance = true;
  Eigen::AlignedBox3d box = phantom.bounds;
  box.min().array() -= margin;
  box.max().array() += margin;
  surface->samples = sample_implicit_surface(phantom.sdf, phantom.normal, box, spacing);
  if (!phantom.feature_points.empty()) {
    Eigen::Matrix3Xd points(3, static_cast<Index>(phantom.feature_points.size()));
    for (std::size_t k = 0; k < phantom.feature_points.size(); ++k)
      points.col(static_cast<Index>(k)) = phantom.feature_points[k];
    // Built once; the lambda shares it with every copy of the truth. Every measured mesh asks for the
    // feature distance of every truth sample again: those are looked up (exact coordinates), not searched.
    const auto locator = std::make_shared<const PointLocator>(points);
    auto known = std::make_shared<std::unordered_map<Eigen::Vector3d, double, PointHash>>();
    known->reserve(static_cast<std::size_t>(surface->samples.size()));
    for (Index k = 0; k < surface->samples.size(); ++k) {
      const Eigen::Vector3d p = surface->samples.points.col(k);
      known->emplace(p, locator->distance(p));
    }
    surface->feature_distance = [locator, known = std::shared_ptr<const decltype(known)::element_type>(known)](
                                    const Eigen::Vector3d& p) {
      const auto it = known->find(p);
      return it != known->end() ? it->second : locator->distance(p);
    };
  }
  ComparisonTruth t;
  t.kind = TruthKind::Phantom;
  t.description = "analytic surface of the " + std::string(to_string(phantom.shape)) + " phantom";
  t.volume = phantom.volume;
  t.surface = std::move(surface);
  return t;
}

ComparisonTruth reference_surface_truth(const Mesh& reference, std::string description, double density) {
  if (reference.num_faces() == 0) throw InvalidInputError(description + ": the reference surface has no triangles");
  auto surface = std::make_shared<SurfaceTruth>();
  const auto locator = std::make_shared<const TriangleLocator>(reference.positions, reference.triangles);
  surface->distance = [locator](const Eigen::Vector3d& p) { return locator->closest(p).distance; };
  surface->signed_distance = false;
  surface->samples = sample_mesh_surface(reference.positions, reference.triangles, density);
  ComparisonTruth t;
  t.kind = TruthKind::ReferenceSurface;
  t.description = std::move(description);
  t.surface = std::move(surface);
  return t;
}

}  // namespace contourmesh
