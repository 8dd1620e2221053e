// SPDX-License-Identifier: BSD-3-Clause
#include "compare/comparison.h"

#include <contourmesh/reconstruct/phantom_truth.h>
#include <contourmesh/smooth/closest_point.h>
#include <contourmesh/smooth/errors.h>

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
  PhantomTruthOptions options;
  options.sample_spacing = spacing;
  options.margin = margin;
  auto surface = std::make_shared<SurfaceTruth>(phantom_surface_truth(phantom, options));
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
