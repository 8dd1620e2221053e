// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/phantom_truth.h"

#include "contourmesh/smooth/closest_point.h"
#include "contourmesh/smooth/errors.h"

#include <cstddef>
#include <functional>
#include <memory>
#include <unordered_map>

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

using KnownDistances = std::unordered_map<Eigen::Vector3d, double, PointHash>;

}  // namespace

SurfaceTruth phantom_surface_truth(const Phantom& phantom, const PhantomTruthOptions& options) {
  if (!(options.sample_spacing > 0.0)) throw InvalidInputError("phantom truth: the sample spacing must be > 0 mm");
  if (!(options.margin >= 0.0)) throw InvalidInputError("phantom truth: the margin must be >= 0 mm");
  SurfaceTruth truth;
  truth.distance = phantom.sdf;
  truth.normal = phantom.normal;
  truth.signed_distance = true;
  Eigen::AlignedBox3d box = phantom.bounds;
  box.min().array() -= options.margin;
  box.max().array() += options.margin;
  truth.samples = sample_implicit_surface(phantom.sdf, phantom.normal, box, options.sample_spacing);
  if (phantom.feature_points.empty()) return truth;

  Eigen::Matrix3Xd points(3, static_cast<Index>(phantom.feature_points.size()));
  for (std::size_t k = 0; k < phantom.feature_points.size(); ++k)
    points.col(static_cast<Index>(k)) = phantom.feature_points[k];
  // Built once and shared by every copy of the truth's function.
  const auto locator = std::make_shared<const PointLocator>(points);
  auto known = std::make_shared<KnownDistances>();
  known->reserve(static_cast<std::size_t>(truth.samples.size()));
  for (Index k = 0; k < truth.samples.size(); ++k) {
    const Eigen::Vector3d p = truth.samples.points.col(k);
    known->emplace(p, locator->distance(p));
  }
  truth.feature_distance = [locator, known = std::shared_ptr<const KnownDistances>(std::move(known))](
                               const Eigen::Vector3d& p) {
    const auto it = known->find(p);
    return it != known->end() ? it->second : locator->distance(p);
  };
  return truth;
}

}  // namespace contourmesh
