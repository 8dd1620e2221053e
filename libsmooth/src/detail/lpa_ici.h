// SPDX-License-Identifier: BSD-3-Clause
// One-dimensional local polynomial approximation with adaptive windows chosen by the intersection of
// confidence intervals (LPA-ICI; Goldenshluger & Nemirovski 1997, Katkovnik 1999), with directional
// windows fused by their inverse variances (Katkovnik, Egiazarian & Astola 2002). Used by the
// cross-slice smoother on profiles across slices and along contours.
//
// A profile is a set of samples (x_k, y_k) around x = 0 (the vertex being estimated, itself a sample
// at x = 0), with x in units of the sample spacing. For each window kind, windows grow one unit at a
// time; each gives an estimate of y(0) with standard deviation sigma * sqrt(v) (v from the least-squares
// fit), and the window stops growing when its confidence interval [y - gamma s, y + gamma s] no longer
// meets all the smaller ones. Near a kink the windows reaching across it are stopped early, the others
// grow: edges are kept.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstddef>

namespace contourmesh::detail {

/// Samples of one profile, sorted by x; at most kMaxProfile.
inline constexpr int kMaxProfile = 64;
struct Profile {
  std::array<double, kMaxProfile> x{}, y{};
  int size = 0;
  void clear() { size = 0; }
  bool push(double xv, double yv) {
    if (size >= kMaxProfile) return false;
    x[static_cast<std::size_t>(size)] = xv;
    y[static_cast<std::size_t>(size)] = yv;
    ++size;
    return true;
  }
  /// Sorts by x (insertion sort: profiles are short and nearly sorted).
  void sort();
};

struct LpaIciOptions {
  double sigma = 0.0;  ///< noise standard deviation of y
  double gamma = 2.0;  ///< confidence-interval width, in standard deviations
  int max_half_width = 8;  ///< largest window half-width, in x units
  /// Add a line (degree 1) over the two-sided windows, which replaces the parabola when it agrees
  /// with it within gamma of the parabola's deviation (straight profiles: a third of its variance).
  bool symmetric_mean = true;
};

/// The chosen windows of one estimate, for diagnostics and feature detection.
struct LpaIciResult {
  double value = 0.0;     ///< fused estimate of y(0)
  double variance = 1.0;  ///< its variance in units of sigma^2 (1: the sample itself)
  int below = 0;          ///< half-width chosen by the window reaching to negative x (0: none usable)
  int above = 0;          ///< ... to positive x
  int symmetric = 0;      ///< ... by the symmetric window
  bool valid = false;     ///< false when no window could be fitted (then value = y(0))
};

/// Estimates y(0) from `profile`, which must hold a sample at x = 0 (returns it unchanged otherwise).
/// One-sided windows fit parabolas (their estimate at the window's end is biased by third-order terms
/// only), two-sided windows a parabola and, optionally, a line.
[[nodiscard]] LpaIciResult lpa_ici(const Profile& profile, const LpaIciOptions& options);

}  // namespace contourmesh::detail
