// SPDX-License-Identifier: BSD-3-Clause
// Private: the per-slice contour noise of render_phantom, the paper's noise model (a segmentation error
// perturbs single contours). Each voxel slice gets its own displacement field f(x, y) in mm, positive
// outward, of the contour along its normal within the slice: a few random plane waves of centimetres
// plus a few Gaussian bumps of a few mm placed on the slice's true boundary, scaled to a given RMS over
// that boundary. The renderer applies it (phantom_render.cpp); the model and its numbers are in
// docs/reconstruction.md ("Contour noise").
#pragma once

#include "detail/sdf_primitives.h"

#include <contourmesh/smooth/metrics.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

namespace contourmesh::detail {

/// One slice's displacement field.
struct ContourNoiseField {
  struct Wave {
    Vec2 k;            ///< wave vector, rad/mm
    double phase;      ///< rad
    double amplitude;  ///< mm
  };
  /// amplitude * (g(r) - g(5 sigma)) within 5 sigma of the centre and 0 beyond, with g(r) =
  /// exp(-r^2 / (2 sigma^2)): a Gaussian made continuous at its cut-off (the offset is 4e-6 of the peak).
  struct Bump {
    Vec2 centre;            ///< mm
    double sigma;           ///< mm
    double inv_two_sigma2;  ///< 1 / (2 sigma^2), 1/mm^2
    double reach2;          ///< (5 sigma)^2, mm^2
    double amplitude;       ///< signed peak, mm
  };
  std::vector<Wave> waves;
  std::vector<Bump> bumps;
  double bound = 0.0;      ///< >= max |f| over the whole plane, mm
  double lipschitz = 0.0;  ///< >= max |grad f| over the whole plane

  /// f(x, y) in mm; 0 for an empty field.
  [[nodiscard]] double operator()(double x, double y) const;
};

/// A quadrature sample of a planar curve: a point and the length of curve it stands for.
struct CurveSample {
  Vec2 point;
  double length;
};

/// The boundary of the section {(x, y) : sdf(x, y, z) < 0} inside `area`, by marching squares on a
/// quadtree whose leaves are `cell` mm wide (|sdf| bounds the distance to the surface, so cells far from
/// it are skipped). Each boundary segment gives one sample at its midpoint.
[[nodiscard]] std::vector<CurveSample> section_boundary(const ScalarField& sdf, const Eigen::AlignedBox2d& area,
                                                        double z, double cell);

/// The parameters of the model.
struct ContourNoiseModel {
  int waves = 4;                     ///< plane waves per slice
  double min_wavelength = 20.0;      ///< mm
  double max_wavelength = 60.0;      ///< mm
  double bump_spacing = 50.0;        ///< one bump per this much boundary length (at least one), mm
  int max_bumps = 24;                ///< per slice
  double min_bump_sigma = 1.5;       ///< mm
  double max_bump_sigma = 4.0;       ///< mm
  double wave_share = 0.75;          ///< share of the mean square carried by the waves before the final scaling
  double max_rescale = 3.0;          ///< a draw that needs more amplification to reach the RMS is redrawn
  int attempts = 8;                  ///< draws per slice at most (the best one is kept)
};

/// The field of one slice whose true boundary is `boundary`: RMS over the boundary (length-weighted)
/// exactly `rms`. Deterministic in (seed, slice). Empty when `boundary` is or rms is 0.
[[nodiscard]] ContourNoiseField make_contour_noise_field(const std::vector<CurveSample>& boundary, double rms,
                                                         std::uint64_t seed, std::int64_t slice,
                                                         const ContourNoiseModel& model = {});

/// The fields of the slices centred at `slice_z` (mm), each `thickness` mm thick, of the solid
/// {sdf < 0} inside `bounds`. A slice's boundary is sampled on its centre plane; when that plane misses
/// the solid, on the nearest plane of the slab that does not (a solid ending inside the slab). Slices
/// run in parallel; the result does not depend on the thread count.
[[nodiscard]] std::vector<ContourNoiseField> contour_noise_fields(const ScalarField& sdf,
                                                                  const Eigen::AlignedBox3d& bounds,
                                                                  const std::vector<double>& slice_z,
                                                                  double thickness, double rms, std::uint64_t seed);

}  // namespace contourmesh::detail
