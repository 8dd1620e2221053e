// SPDX-License-Identifier: BSD-3-Clause
// Meshes with a known analytic surface, for tests and benchmarks: icosphere, cube, and
// contour stacks (prisms over a closed planar curve, tiled slice by slice, with contour ids) with
// their signed distance functions; plus reproducible noise.
#pragma once

#include "contourmesh/smooth/end_caps.h"
#include "contourmesh/smooth/mesh.h"
#include "contourmesh/smooth/metrics.h"

#include <Eigen/Core>

#include <cstdint>
#include <functional>

namespace contourmesh {

/// Icosahedron subdivided `subdivisions` times (1-to-4) and projected onto the sphere of `radius`
/// around `center`: 10 * 4^s + 2 vertices, outward-oriented, no contour ids.
[[nodiscard]] Mesh make_icosphere(int subdivisions, double radius = 1.0,
                                  const Eigen::Vector3d& center = Eigen::Vector3d::Zero());

/// Axis-aligned cube [-half, half]^3 with each face an n x n grid of quads split into triangles:
/// 6 n^2 + 2 vertices, outward-oriented, no contour ids. n >= 1.
[[nodiscard]] Mesh make_cube(int divisions, double half_size = 1.0);

/// A closed planar curve t in [0, 1) -> (x, y), counter-clockwise, simple (not self-intersecting).
using PlanarCurve = std::function<Eigen::Vector2d(double t)>;

/// A right prism over a planar curve, sampled like a stack of CT contours.
struct ContourStackSpec {
  PlanarCurve curve;
  int slices = 20;               ///< number of contours (slice planes), >= 2
  int points_per_contour = 64;   ///< samples per contour, uniform in t, >= 3
  double z0 = 0.0;               ///< z of slice 0, input units (mm)
  double slice_spacing = 2.0;    ///< distance between slice planes, > 0
  EndCaps end_caps = EndCaps::HalfSpacing;  ///< as the reconstruction's tiler does by default
};

/// Tiles contour k to contour k+1 vertex by vertex (each quad split into two triangles) and closes
/// both ends with ear-clipped caps, half a spacing beyond the end slices (on copies of the end
/// contours, ids kNoId, appended after the slice vertices) or in the end slices (caps then use only
/// the end contours' vertices, as in end_caps.h). Vertex ids: slice k for every vertex of contour k, contour
/// index 0. Outward-oriented and closed.
/// Throws InvalidInputError for parameters out of range.
[[nodiscard]] Mesh make_contour_stack(const ContourStackSpec& spec);

/// Exact signed distance (negative inside) to the prism the stack samples: between the first and last
/// slice planes, extended by half a spacing at both ends for EndCaps::HalfSpacing; the curve is
/// sampled at `curve_samples` points (error about R (2 pi / samples)^2 / 8).
[[nodiscard]] ScalarField contour_stack_sdf(const ContourStackSpec& spec, int curve_samples = 2048);

/// A circle of `radius` with one sharp triangular ridge of `height` centred at angle 0 and spanning
/// +/- `half_width` radians: r(theta) = radius + height * max(0, 1 - |theta| / half_width).
/// Its prism is a "cylinder with a ridge": a sharp ridge running across the slices.
[[nodiscard]] PlanarCurve ridge_circle_curve(double radius, double height, double half_width);

enum class NoiseDirection {
  Isotropic,  ///< independent Gaussian in x, y, z
  InPlane,    ///< x and y only: contours stay on their slice planes, like segmentation noise
  Normal,     ///< along the area-weighted vertex normal
};

struct NoiseOptions {
  double sigma = 0.1;  ///< standard deviation, input units (mm), >= 0
  std::uint64_t seed = 1;
  NoiseDirection direction = NoiseDirection::InPlane;
};

/// Adds reproducible Gaussian noise to every vertex position (same seed, same noise on a platform).
void add_noise(Mesh& mesh, const NoiseOptions& options);

}  // namespace contourmesh
