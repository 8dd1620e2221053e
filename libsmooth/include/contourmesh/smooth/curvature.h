// SPDX-License-Identifier: BSD-3-Clause
// Principal curvatures and directions by weighted quadric fitting (Milroy et al. 1997), as used by
// Xu et al. 2006, section 3.1 (paper eqs. 9-13).
#pragma once

#include "contourmesh/smooth/adjacency.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace contourmesh {

struct CurvatureOptions {
  /// A vertex is umbilic when |kappa_max - kappa_min| < umbilic_tolerance * K, with K the mean over
  /// the mesh of (|kappa_min| + |kappa_max|) / 2: scale-free, so the same mesh scaled by any factor
  /// gets the same umbilic set. In [0, inf).
  double umbilic_tolerance = 0.05;
  /// A fit is widened to the 2-ring when the 1-ring has fewer than 3 neighbours or its normal
  /// equations have a reciprocal condition number below this. In [0, 1).
  double min_reciprocal_condition = 1e-6;
};

/// Per-vertex curvature estimates. Sign convention: positive where the surface is convex, i.e. bends
/// away from its outward normal (a sphere of radius r has kappa_min = kappa_max = 1/r with outward
/// normals; a concave crease has a negative curvature across it).
struct PrincipalCurvatures {
  Eigen::VectorXd kappa_min;       ///< smaller normal curvature (the paper's kappa1, eq. 12), 1 / length
  Eigen::VectorXd kappa_max;       ///< larger normal curvature (kappa2, eq. 13)
  Eigen::Matrix3Xd direction_min;  ///< unit direction of kappa_min in 3-D (the paper's m1); zero if umbilic
  Eigen::Matrix3Xd direction_max;  ///< unit direction of kappa_max (m2); zero if umbilic
  Eigen::Matrix3Xd normals;        ///< the unit vertex normals used (area-weighted, outward)
  std::vector<std::uint8_t> umbilic;    ///< 1 for umbilic vertices (and isolated ones)
  std::vector<std::uint8_t> used_two_ring;  ///< 1 where the fit was widened to the 2-ring
};

/// Fits h(u, v) = a0 u^2 + a1 u v + a2 v^2 in the local frame (u, v tangent, h along the normal) to
/// the 1-ring of each vertex by least squares with weights rho_j = 10^(-d_ij / d_max) (paper eq. 9),
/// and takes the eigen-decomposition of the Hessian [[2 a0, a1], [a1, 2 a2]]. `positions` is 3 x n
/// with n == adjacency.num_vertices(); triangles give the normals.
[[nodiscard]] PrincipalCurvatures principal_curvatures(const Eigen::Matrix3Xd& positions,
                                                       const std::vector<Triangle>& triangles,
                                                       const MeshAdjacency& adjacency,
                                                       const CurvatureOptions& options = {});

}  // namespace contourmesh
