// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/curvature.h"

#include "contourmesh/smooth/errors.h"
#include "contourmesh/smooth/normals.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace contourmesh {

namespace {

struct Fit {
  bool ok = false;
  double a0 = 0, a1 = 0, a2 = 0;
};

// Weighted least squares of h = a0 u^2 + a1 u v + a2 v^2 over the given neighbours.
template <typename Neighbours>
Fit fit_quadric(const Eigen::Matrix3Xd& p, Index i, const Eigen::Vector3d& n, const Eigen::Vector3d& eu,
                const Eigen::Vector3d& ev, const Neighbours& nbrs, double min_rcond) {
  Fit fit;
  double dmax = 0.0;
  for (Index j : nbrs) dmax = std::max(dmax, (p.col(j) - p.col(i)).norm());
  if (nbrs.size() < 3 || !(dmax > 0.0)) return fit;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (Index j : nbrs) {
    const Eigen::Vector3d d = p.col(j) - p.col(i);
    const double u = d.dot(eu), v = d.dot(ev), h = d.dot(n);
    const double rho = std::pow(10.0, -d.norm() / dmax);
    const Eigen::Vector3d row(u * u, u * v, v * v);
    A += rho * row * row.transpose();
    b += rho * h * row;
  }
  // Reciprocal condition number from the symmetric eigenvalues. A is a sum of weighted outer products,
  // positive semi-definite: with eigenvalues l1 <= l2 <= l3, det = l1 l2 l3 <= l1 l3^2 and l3 <= trace,
  // so l1 / l3 >= det / trace^3. When that bound clears the threshold by a wide margin (1000x, and 1e-9
  // in any case: far above the rounding of det and of the computed eigenvalues) the eigenvalues pass
  // the test as well, so the iterative eigen-solve, a third of the fit's cost, is skipped; near the
  // threshold it decides as before.
  const double trace = A.trace();
  if (!(trace > 0.0 && A.determinant() > std::max(1e3 * min_rcond, 1e-9) * trace * trace * trace)) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(A, Eigen::EigenvaluesOnly);
    const double lmax = eig.eigenvalues().maxCoeff();
    const double lmin = eig.eigenvalues().minCoeff();
    if (!(lmax > 0.0) || lmin / lmax < min_rcond) return fit;
  }
  const Eigen::Vector3d a = A.ldlt().solve(b);
  if (!a.allFinite()) return fit;
  fit.ok = true;
  fit.a0 = a[0];
  fit.a1 = a[1];
  fit.a2 = a[2];
  return fit;
}

}  // namespace

PrincipalCurvatures principal_curvatures(const Eigen::Matrix3Xd& p, const std::vector<Triangle>& triangles,
                                         const MeshAdjacency& adj, const CurvatureOptions& options) {
  const Index n = adj.num_vertices();
  if (p.cols() != n) throw InvalidInputError("principal_curvatures: positions do not match the adjacency");
  if (!(options.umbilic_tolerance >= 0.0)) throw InvalidInputError("umbilic_tolerance must be >= 0");
  if (!(options.min_reciprocal_condition >= 0.0 && options.min_reciprocal_condition < 1.0)) {
    throw InvalidInputError("min_reciprocal_condition must be in [0, 1)");
  }
  PrincipalCurvatures out;
  out.normals = vertex_normals(p, triangles);
  out.kappa_min = Eigen::VectorXd::Zero(n);
  out.kappa_max = Eigen::VectorXd::Zero(n);
  out.direction_min = Eigen::Matrix3Xd::Zero(3, n);
  out.direction_max = Eigen::Matrix3Xd::Zero(3, n);
  out.umbilic.assign(static_cast<std::size_t>(n), 0);
  out.used_two_ring.assign(static_cast<std::size_t>(n), 0);
  std::vector<std::uint8_t> fitted(static_cast<std::size_t>(n), 0);
  std::vector<Index> two_ring;
  std::vector<Index> mark(static_cast<std::size_t>(n), -1);

  for (Index i = 0; i < n; ++i) {
    const Eigen::Vector3d nrm = out.normals.col(i);
    if (nrm.squaredNorm() == 0.0) continue;
    // Tangent frame: any unit vector orthogonal to n, and n x it.
    const Eigen::Vector3d helper = std::abs(nrm.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d eu = (helper - helper.dot(nrm) * nrm).normalized();
    const Eigen::Vector3d ev = nrm.cross(eu);
    Fit fit = fit_quadric(p, i, nrm, eu, ev, adj.ring(i), options.min_reciprocal_condition);
    if (!fit.ok) {
      two_ring.clear();
      mark[i] = i;
      for (Index j : adj.ring(i)) {
        if (mark[j] != i) {
          mark[j] = i;
          two_ring.push_back(j);
        }
        for (Index k : adj.ring(j)) {
          if (mark[k] != i) {
            mark[k] = i;
            two_ring.push_back(k);
          }
        }
      }
      fit = fit_quadric(p, i, nrm, eu, ev, two_ring, options.min_reciprocal_condition);
      out.used_two_ring[i] = 1;
      if (!fit.ok) continue;
    }
    // Hessian eigenpairs (paper eqs. 10-13); h is measured along the outward normal, so a convex
    // surface has negative a's: negate to report convex curvature as positive.
    const double mean = fit.a0 + fit.a2;
    const double root = std::sqrt((fit.a0 - fit.a2) * (fit.a0 - fit.a2) + fit.a1 * fit.a1);
    const double h_small = mean - root;  // smaller eigenvalue of the Hessian of h
    const double h_large = mean + root;
    out.kappa_min[i] = -h_large;
    out.kappa_max[i] = -h_small;
    // Eigenvector of [[2 a0, a1], [a1, 2 a2]] for eigenvalue h_small: (a1, h_small - 2 a0) or
    // (h_small - 2 a2, a1), whichever is better conditioned.
    Eigen::Vector2d e_small(fit.a1, h_small - 2.0 * fit.a0);
    const Eigen::Vector2d alt(h_small - 2.0 * fit.a2, fit.a1);
    if (alt.squaredNorm() > e_small.squaredNorm()) e_small = alt;
    if (e_small.squaredNorm() > 0.0) {
      e_small.normalize();
      out.direction_max.col(i) = e_small.x() * eu + e_small.y() * ev;  // kappa_max = -h_small
      out.direction_min.col(i) = nrm.cross(out.direction_max.col(i));
    }
    fitted[i] = 1;
  }

  // Umbilics, relative to the mesh's own curvature scale.
  double scale = 0.0;
  Index count = 0;
  for (Index i = 0; i < n; ++i) {
    if (!fitted[i]) continue;
    scale += 0.5 * (std::abs(out.kappa_min[i]) + std::abs(out.kappa_max[i]));
    ++count;
  }
  scale = count ? scale / count : 0.0;
  const double eps = options.umbilic_tolerance * scale;
  for (Index i = 0; i < n; ++i) {
    if (!fitted[i] || out.kappa_max[i] - out.kappa_min[i] < eps || out.direction_max.col(i).squaredNorm() == 0.0) {
      out.umbilic[i] = 1;
      out.direction_min.col(i).setZero();
      out.direction_max.col(i).setZero();
    }
  }
  return out;
}

}  // namespace contourmesh
