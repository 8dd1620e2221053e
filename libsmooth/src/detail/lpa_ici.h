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

/// Running sums of a window of samples for least-squares polynomials of degree <= 2 in x: S_p = sum x^p
/// (p <= 4), T_a = sum x^a y (a <= 2); the normal matrix of a parabola is [[S0 S1 S2] [S1 S2 S3]
/// [S2 S3 S4]]. Shared by the windows of lpa_ici and the null model of the kink test.
struct Moments {
  double s[5] = {0, 0, 0, 0, 0};
  double t[3] = {0, 0, 0};
  int distinct = 0;  ///< samples added (profiles hold distinct x)
  void add(double x, double y) {
    const double x2 = x * x;
    s[0] += 1.0;
    s[1] += x;
    s[2] += x2;
    s[3] += x2 * x;
    s[4] += x2 * x2;
    t[0] += y;
    t[1] += x * y;
    t[2] += x2 * y;
    ++distinct;
  }
  /// Field by field, written out: the copy-and-loop form was a tenth of lpa_ici's instructions (GCC 12
  /// kept the struct in memory), and the same sums this way leave every result bit for bit as it was.
  Moments operator+(const Moments& o) const {
    Moments m;
    m.s[0] = s[0] + o.s[0];
    m.s[1] = s[1] + o.s[1];
    m.s[2] = s[2] + o.s[2];
    m.s[3] = s[3] + o.s[3];
    m.s[4] = s[4] + o.s[4];
    m.t[0] = t[0] + o.t[0];
    m.t[1] = t[1] + o.t[1];
    m.t[2] = t[2] + o.t[2];
    m.distinct = distinct + o.distinct;
    return m;
  }
};

struct LpaIciOptions {
  double sigma = 0.0;  ///< noise standard deviation of y
  double gamma = 2.0;  ///< confidence-interval width, in standard deviations
  int max_half_width = 8;  ///< largest window half-width, in x units
  /// Add a line (degree 1) over the two-sided windows, which replaces the parabola when it agrees
  /// with it within gamma of the parabola's deviation (straight profiles: a third of its variance).
  bool symmetric_mean = true;
  /// Fit circles instead of parabolas (see fit_circle below): y = c0 + c1 x + c2 (x^2 + (y / x_unit)^2),
  /// exact on any arc, a line where c2 = 0. A window where the circle is ill-posed falls back to the
  /// parabola. Needs x and y in one frame scaled by x_unit (a rigid frame: the tangent frame across slices).
  bool circle = false;
  /// The length of one x unit in y's unit (mm per slice spacing); used by the circle model only, > 0.
  double x_unit = 1.0;
  /// Look for a slope break first (find_kink in profile_kinks.h, over the samples within max_half_width):
  /// where one is significant, only the side of it holding x = 0 (with the hinge's own sample) is fitted,
  /// and where it is at x = 0 only the one-sided windows are; repeated on what is left, up to three times.
  bool kinks = false;
  /// The kink test's false-alarm probability on a kink-free profile, in (0, 1).
  double kink_false_rate = 0.01;
  /// Fit the two-sided windows (parabola, line, mean); false: the one-sided windows only.
  bool two_sided = true;
  /// Where a kink bounds the profile (kinks above): grow a line on each one-sided window too, which
  /// replaces that side's parabola where it agrees with it within gamma of the parabola's deviation and is
  /// more precise (as the line replaces the two-sided parabola), or where the side is too short for a
  /// parabola. A profile without a significant kink is fitted as without this option.
  bool kink_side_lines = false;
  /// Grow the one-sided lines on every profile, kink or not (lpa_ici turns them on where kink_side_lines
  /// holds and a kink was found).
  bool one_sided_lines = false;
};

/// The chosen windows of one estimate, for diagnostics and feature detection.
struct LpaIciResult {
  double value = 0.0;     ///< fused estimate of y(0)
  double variance = 1.0;  ///< its variance in units of sigma^2 (1: the sample itself)
  int below = 0;          ///< half-width chosen by the window reaching to negative x (0: none usable)
  int above = 0;          ///< ... to positive x
  int symmetric = 0;      ///< ... by the symmetric window
  int kinks = 0;          ///< slope breaks found (options.kinks): each bounded the profile
  bool valid = false;     ///< false when no window could be fitted (then value = y(0))
};

/// The circle through a window's samples (algebraic least squares, linear in three parameters), at x = 0.
/// With x and y in units of x_unit (yn = y / x_unit, w = x^2 + yn^2), every circle not tangent to the y
/// direction is yn = c0 + c1 x + c2 w exactly (c2 = 0: a line), so the normal equations of (1, x, w) give
/// (c0, c1, c2), and the circle meets x = 0 at the root of c2 yn^2 - yn + c0 = 0 nearer to c0: yn0 = 2 c0 /
/// (1 + sqrt(1 - 4 c0 c2)). Its variance in units of sigma^2 is the linearised J M^-1 J^T, J = (1, 0, yn0^2)
/// / (1 - 2 c2 yn0), with M the normal matrix: the noise of y inside w is left out (it scales a sample's
/// noise by 1 - yn / R, R the radius). Returns false, for the caller to fall back to the parabola, when the
/// window has fewer than four samples or a near-singular normal matrix, the circle does not hold the window
/// as a graph (a sample beyond its centre's abscissa +- its radius), 2 |c2| max |yn| > 1 (a sample beyond the
/// near half of the circle, where a sample's residual, which moves by 1 - 2 c2 yn per unit of its noise,
/// would stop following it), or 1 - 4 c0 c2 < 1/4 (the root would be more than 4/3 of c0: a circle barely
/// reaching x = 0). The sums are over the window: n, x, x^2, w, x w, w^2 and y, x y, w y (y in its own unit).
/// lpa_ici floors the variance at the parabola's on the same window (equal to first order in c2 yn), since
/// the linearisation leaves the noise in w out.
struct CircleSums {
  double s1 = 0, sx = 0, sxx = 0, sw = 0, sxw = 0, sww = 0;
  double ty = 0, txy = 0, twy = 0;
  double min_x = 1e300, max_x = -1e300, max_abs_yn = 0;
  int count = 0;
  void add(double x, double y, double x_unit);
  CircleSums operator+(const CircleSums& o) const;
};
[[nodiscard]] bool fit_circle(const CircleSums& sums, double x_unit, double& value, double& variance);

/// Estimates y(0) from `profile`, which must hold a sample at x = 0 (returns it unchanged otherwise).
/// One-sided windows fit parabolas (their estimate at the window's end is biased by third-order terms
/// only), two-sided windows a parabola and, optionally, a line; with `circle`, circles replace the
/// parabolas of both (exact on arcs), each window falling back to the parabola where its circle is
/// ill-posed. With `kinks`, the profile is first bounded at its significant slope breaks; with
/// `kink_side_lines` as well, the one-sided windows of a profile so bounded may take a line instead.
[[nodiscard]] LpaIciResult lpa_ici(const Profile& profile, const LpaIciOptions& options);

}  // namespace contourmesh::detail
