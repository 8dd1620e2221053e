// SPDX-License-Identifier: BSD-3-Clause
// Shape metrics for the evaluation protocol (the comparison of methods, docs/results.md): volume, area, volume
// shrinking rate, distance to an analytic surface and normal error against an analytic normal field.
#pragma once

#include "contourmesh/smooth/mesh.h"
#include "contourmesh/smooth/smoothing.h"

#include <Eigen/Core>

#include <functional>
#include <span>
#include <vector>

namespace contourmesh {

/// Volume enclosed by a closed, consistently oriented mesh, by the divergence theorem:
/// V = (1/6) * sum_f v0 . (v1 x v2). Positive for outward (counter-clockwise) orientation, in cubic
/// input units. On an open mesh the number depends on the origin and means nothing.
[[nodiscard]] double enclosed_volume(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles);
[[nodiscard]] double enclosed_volume(const Mesh& mesh);

/// Sum of triangle areas, in squared input units.
[[nodiscard]] double surface_area(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles);
[[nodiscard]] double surface_area(const Mesh& mesh);

/// The paper's volume shrinking rate (V_original - V_smoothed) / V_original (Figure 13); negative
/// means the mesh swelled. Throws InvalidInputError when V_original is zero or not finite.
[[nodiscard]] double volume_shrinking_rate(double original_volume, double smoothed_volume);

/// Runs the smoother of `options` and returns the volume shrinking rate after 0, 1, ..., iterations
/// iterations (iterations + 1 values, the first 0). Any `on_iteration` observer in `options` still runs.
[[nodiscard]] std::vector<double> volume_shrinking_curve(const Mesh& mesh, const SmoothingOptions& options);

/// A signed distance function (negative inside) and a unit normal field, both in input units.
using ScalarField = std::function<double(const Eigen::Vector3d&)>;
using VectorField = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;

/// Statistics of |sdf(v)| over a set of vertices, in input units. `count` = 0 gives zeros.
struct DistanceStats {
  double mean = 0.0;
  double rms = 0.0;
  double max = 0.0;
  std::size_t count = 0;
};

/// Distance of every vertex to the surface sdf = 0.
[[nodiscard]] DistanceStats distance_to_surface(const Eigen::Matrix3Xd& positions, const ScalarField& sdf);
/// Distance of the listed vertices only (e.g. a feature region); throws InvalidInputError on an index
/// outside the positions.
[[nodiscard]] DistanceStats distance_to_surface(const Eigen::Matrix3Xd& positions, const ScalarField& sdf,
                                                std::span<const Index> vertices);

/// Angle between each face normal and the analytic normal at the face centroid, in degrees.
struct AngleStats {
  double mean_degrees = 0.0;
  double max_degrees = 0.0;
  std::size_t count = 0;
};

/// Over all faces; zero-area faces are skipped.
[[nodiscard]] AngleStats normal_angular_error(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                                              const VectorField& normal);
/// Over the listed faces only.
[[nodiscard]] AngleStats normal_angular_error(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                                              const VectorField& normal, std::span<const Index> faces);

}  // namespace contourmesh
