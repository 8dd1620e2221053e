#include "compare/comparison.h"

#include <smooth/closest_point.h>
#include <smooth/errors.h>

#include <memory>
#include <string>
#include <utility>

namespace contourmesh {

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
    for (std::size_t k = 0; k < phantom.feature_points.size(); ++k) points.col(static_cast<Index>(k)) = phantom.feature_points[k];
    // Built once; the lambda shares it with every copy of the truth.
    const auto locator = std::make_shared<const PointLocator>(points);
    surface->feature_distance = [locator](const Eigen::Vector3d& p) { return locator->distance(p); };
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
