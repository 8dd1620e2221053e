// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/feature_detection.h"

#include "contourmesh/smooth/contour_structure.h"
#include "contourmesh/smooth/errors.h"
#include "contourmesh/smooth/smoothing.h"
#include "contourmesh/smooth/umbrella.h"

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <map>

namespace contourmesh {

std::string_view to_string(VertexLabel label) {
  switch (label) {
    case VertexLabel::Smooth: return "smooth";
    case VertexLabel::Edge: return "edge";
    case VertexLabel::Corner: return "corner";
    case VertexLabel::Noise: return "noise";
  }
  return "unknown";
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A slice plane: a point on it and an orthonormal basis (e1, e2) of its directions.
struct PlaneFrame {
  Eigen::Vector3d origin;
  Eigen::Vector3d e1, e2;
  [[nodiscard]] Eigen::Vector2d project(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = p - origin;
    return {d.dot(e1), d.dot(e2)};
  }
  [[nodiscard]] Eigen::Vector2d project_direction(const Eigen::Vector3d& v) const { return {v.dot(e1), v.dot(e2)}; }
};

// Y = a + b X + c X^2 in the principal frame (centre, ax, ay) of a window of contour points.
struct CurveFit {
  bool ok = false;
  Eigen::Vector2d centre, ax, ay;
  double a = 0, b = 0, c = 0;
  double xmin = 0, xmax = 0, spacing = 0;
  Eigen::Vector2d outward;  // unit, plane coordinates

  [[nodiscard]] double x_of(const Eigen::Vector2d& q) const { return (q - centre).dot(ax); }
  [[nodiscard]] Eigen::Vector2d point(double X) const { return centre + X * ax + (a + b * X + c * X * X) * ay; }

  // Signed curvature at X: positive where the curve is convex towards `outward`.
  [[nodiscard]] double curvature(double X) const {
    const double slope = b + 2.0 * c * X;
    const double raw = 2.0 * c / std::pow(1.0 + slope * slope, 1.5);  // > 0: centre on the +Y side
    const Eigen::Vector2d normal_frame(-slope, 1.0);                   // +Y side normal, frame coords
    const Eigen::Vector2d normal = normal_frame.x() * ax + normal_frame.y() * ay;
    return normal.dot(outward) > 0.0 ? -raw : raw;
  }
};

CurveFit fit_curve(const std::vector<Eigen::Vector2d>& pts, const Eigen::Vector2d& outward) {
  CurveFit f;
  const auto n = static_cast<int>(pts.size());
  if (n < 5 || outward.squaredNorm() == 0.0) return f;
  f.centre.setZero();
  for (const auto& p : pts) f.centre += p;
  f.centre /= n;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : pts) cov += (p - f.centre) * (p - f.centre).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  f.ax = eig.eigenvectors().col(1).normalized();
  f.ay = Eigen::Vector2d(-f.ax.y(), f.ax.x());
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  f.xmin = std::numeric_limits<double>::infinity();
  f.xmax = -f.xmin;
  for (const auto& p : pts) {
    const double X = (p - f.centre).dot(f.ax), Y = (p - f.centre).dot(f.ay);
    const Eigen::Vector3d row(1.0, X, X * X);
    A += row * row.transpose();
    rhs += Y * row;
    f.xmin = std::min(f.xmin, X);
    f.xmax = std::max(f.xmax, X);
  }
  if (!(f.xmax - f.xmin > 0.0)) return f;
  const Eigen::Vector3d sol = A.ldlt().solve(rhs);
  if (!sol.allFinite()) return f;
  f.a = sol[0];
  f.b = sol[1];
  f.c = sol[2];
  f.spacing = (f.xmax - f.xmin) / (n - 1);
  f.outward = outward.normalized();
  f.ok = true;
  return f;
}

// Intersections of the fitted curve with the line {q : n . q = d} inside the window (plus half a
// spacing); returns the one nearest to `near`, or nothing.
std::optional<double> intersect(const CurveFit& f, const Eigen::Vector2d& n, double d, const Eigen::Vector2d& near) {
  const double l1 = n.dot(f.ax), l2 = n.dot(f.ay), l0 = d - n.dot(f.centre);
  // l1 X + l2 (a + b X + c X^2) = l0
  const double qa = l2 * f.c, qb = l1 + l2 * f.b, qc = l2 * f.a - l0;
  double roots[2];
  int count = 0;
  const double scale = std::abs(qb) + std::abs(qa) * (f.xmax - f.xmin) + 1e-300;
  if (std::abs(qa) * (f.xmax - f.xmin) < 1e-12 * scale) {
    if (qb != 0.0) roots[count++] = -qc / qb;
  } else {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
      const double s = std::sqrt(disc);
      const double q = -0.5 * (qb + (qb >= 0 ? s : -s));
      roots[count++] = q / qa;
      if (q != 0.0) roots[count++] = qc / q;
    }
  }
  std::optional<double> best;
  double best_d = std::numeric_limits<double>::infinity();
  const double margin = 0.5 * f.spacing;
  for (int k = 0; k < count; ++k) {
    const double X = roots[k];
    if (!(X >= f.xmin - margin && X <= f.xmax + margin)) continue;
    const double dist = (f.point(X) - near).squaredNorm();
    if (dist < best_d) {
      best_d = dist;
      best = X;
    }
  }
  return best;
}

// Walks along a contour from `start` towards the zero of `signed_distance` (the plane S), at most
// kMaxWalk vertices; returns the vertex nearest to the crossing, or `start` if the contour moves away.
template <typename F>
Index walk_to_plane(const ContourNeighbours& contour, Index start, F&& signed_distance) {
  constexpr int kMaxWalk = 32;
  Index cur = start, prev = -1;
  double dc = signed_distance(cur);
  for (int step = 0; step < kMaxWalk; ++step) {
    Index next = -1;
    double dn = 0.0;
    for (Index nb : contour.of[cur]) {
      if (nb < 0 || nb == prev) continue;
      const double dv = signed_distance(nb);
      if (dv * dc <= 0.0) return std::abs(dv) < std::abs(dc) ? nb : cur;  // crossed S
      if (std::abs(dv) < std::abs(dc) && (next < 0 || std::abs(dv) < std::abs(dn))) {
        next = nb;
        dn = dv;
      }
    }
    if (next < 0) break;
    prev = cur;
    cur = next;
    dc = dn;
  }
  return cur;
}

// At a non-umbilic vertex: t, the principal direction with the smaller |kappa| (the way a feature line
// runs), the other principal direction (across the feature; the normal of the plane S), and the
// curvature across the feature.
struct FeatureDirections {
  Eigen::Vector3d along, across;
  double curvature_across;
};

FeatureDirections feature_directions(const PrincipalCurvatures& c, Index i) {
  if (std::abs(c.kappa_min[i]) <= std::abs(c.kappa_max[i])) {
    return {c.direction_min.col(i), c.direction_max.col(i), c.kappa_max[i]};
  }
  return {c.direction_max.col(i), c.direction_min.col(i), c.kappa_min[i]};
}

// The smallest eigenvalue of sum_f theta_f n_f n_f^T over the faces around vertex i (theta_f: the
// face's angle at i, n_f: its unit normal), divided by the trace: how far the normals spread in a third
// direction. Angle weights make it independent of how the faces are cut into triangles.
double normal_spread(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                     const MeshAdjacency& adj, Index i) {
  Eigen::Matrix3d tensor = Eigen::Matrix3d::Zero();
  for (Index f : adj.incident_faces(i)) {
    const Triangle& t = triangles[static_cast<std::size_t>(f)];
    const int k = t[0] == i ? 0 : t[1] == i ? 1 : 2;
    const Eigen::Vector3d e1 = positions.col(t[(k + 1) % 3]) - positions.col(i);
    const Eigen::Vector3d e2 = positions.col(t[(k + 2) % 3]) - positions.col(i);
    const Eigen::Vector3d cross = e1.cross(e2);
    const double area2 = cross.norm();
    if (!(area2 > 0.0)) continue;
    const double angle = std::atan2(area2, e1.dot(e2));
    const Eigen::Vector3d normal = cross / area2;
    tensor += angle * normal * normal.transpose();
  }
  const double trace = tensor.trace();
  if (!(trace > 0.0)) return 0.0;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(tensor, Eigen::EigenvaluesOnly);
  return std::max(0.0, eig.eigenvalues()(0)) / trace;
}

// The extension for feature lines within a slice plane: the curvature across the feature at the
// neighbours of i nearest to +t and -t agrees with i's in sign and within delta. A line may end in a
// corner (a neighbour whose face normals spread in three directions): that side then agrees.
bool continuous_along_line(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                           const MeshAdjacency& adj, const PrincipalCurvatures& c, Index i,
                           const DetectionOptions& options) {
  const FeatureDirections f = feature_directions(c, i);
  const Eigen::Vector3d& t = f.along;
  const double ki = f.curvature_across;
  if (!(t.squaredNorm() > 0.5) || !std::isfinite(ki) || ki == 0.0) return false;
  const double delta = options.delta.value_or(options.delta_factor * std::abs(ki));
  for (const double side : {-1.0, 1.0}) {
    Index best = -1;
    double best_cos = 0.8;  // within about 37 degrees of the feature direction
    for (Index j : adj.ring(i)) {
      const Eigen::Vector3d e = positions.col(j) - positions.col(i);
      const double len = e.norm();
      if (!(len > 0.0)) continue;
      const double cosine = side * e.dot(t) / len;
      if (cosine > best_cos) {
        best_cos = cosine;
        best = j;
      }
    }
    if (best < 0) return false;
    if (normal_spread(positions, triangles, adj, best) > options.corner_spread) continue;
    if (c.umbilic[best]) return false;
    const double kj = feature_directions(c, best).curvature_across;
    if (!(ki * kj > 0.0 && std::abs(ki - kj) < delta)) return false;
  }
  return true;
}

// Umbilic candidates vote with their neighbours, in index order (eq. 8); then the label counts.
void vote_corners(const Eigen::Matrix3Xd& positions, const MeshAdjacency& adj,
                  const std::vector<Index>& umbilic_candidates, FeatureDetection& out) {
  for (Index i : umbilic_candidates) {
    double dmax = 0.0;
    for (Index j : adj.ring(i)) dmax = std::max(dmax, (positions.col(j) - positions.col(i)).norm());
    double psi = 0.0;
    for (Index j : adj.ring(i)) {
      const VertexLabel l = out.labels[j];
      const double tau = (l == VertexLabel::Edge || l == VertexLabel::Corner) ? 1.0
                         : l == VertexLabel::Noise                            ? -1.0
                                                                              : 0.0;
      if (tau == 0.0) continue;
      // Unclassified umbilic neighbours (still Smooth-labelled but candidates) count as 0.
      psi += std::exp(-(positions.col(j) - positions.col(i)).norm() / dmax) * tau;
    }
    out.psi[i] = psi;
    out.labels[i] = psi > 0.0 ? VertexLabel::Corner : VertexLabel::Noise;
  }
  for (VertexLabel l : out.labels) {
    out.edges += l == VertexLabel::Edge;
    out.corners += l == VertexLabel::Corner;
    out.noise += l == VertexLabel::Noise;
  }
}

}  // namespace

FeatureDetection detect_features(const Mesh& mesh, const MeshAdjacency& adj, const DetectionOptions& options) {
  const bool continuity = options.mode == DetectionMode::ContourContinuity;
  if (continuity && !mesh.has_contour_ids()) {
    throw InvalidInputError(
        "feature detection by contour continuity needs contour ids (slice and contour index per vertex); "
        "recover them from the slice planes or use the curvature-only mode");
  }
  if (!(options.anisotropy > 1.0)) throw InvalidInputError("anisotropy must be > 1");
  if (adj.num_vertices() != mesh.num_vertices()) throw InvalidInputError("feature detection: adjacency does not match");
  if (options.window < 5 || options.window % 2 == 0) throw InvalidInputError("detection window must be odd and >= 5");
  if (options.gamma && !(*options.gamma >= 0.0)) throw InvalidInputError("gamma must be >= 0");
  if (!(options.gamma_factor > 0.0)) throw InvalidInputError("gamma factor must be > 0");
  if (options.delta && !(*options.delta > 0.0)) throw InvalidInputError("delta must be > 0");
  if (!(options.delta_factor > 0.0)) throw InvalidInputError("delta factor must be > 0");
  if (options.prefilter_iterations < 0) throw InvalidInputError("prefilter iterations must be >= 0");
  if (!(options.corner_spread >= 0.0)) throw InvalidInputError("corner spread must be >= 0");
  auto report = [&](double f) {
    if (options.progress && !options.progress("detect", f)) throw CancelledError("feature detection");
  };

  const Index n = mesh.num_vertices();
  Eigen::Matrix3Xd positions = mesh.positions;
  if (options.prefilter_iterations > 0) {
    SmoothingOptions pre;
    pre.method = SmoothingMethod::Taubin;
    pre.iterations = options.prefilter_iterations;
    positions = taubin_smooth(mesh, adj, pre);
  }

  FeatureDetection out;
  out.curvature = principal_curvatures(positions, mesh.triangles, adj, options.curvature);
  report(0.3);
  out.umbrella = options.measure == UmbrellaMeasure::Length
                     ? umbrella_norms(positions, adj)
                     : umbrella_normal_norms(positions, adj, out.curvature.normals);
  // The paper's mean |U| is over contour vertices; copies off the slices (end caps, branching) and
  // their long cap triangles would inflate it.
  {
    double sum = 0.0;
    Index count = 0;
    for (Index i = 0; i < n; ++i) {
      if (mesh.has_contour_ids() && mesh.slice_ids[i] == kNoId) continue;
      sum += out.umbrella[i];
      ++count;
    }
    out.mean_umbrella = count ? sum / count : 0.0;
  }
  out.gamma = options.gamma.value_or(options.gamma_factor * out.mean_umbrella);
  out.labels.assign(static_cast<std::size_t>(n), VertexLabel::Smooth);
  out.k_below = Eigen::VectorXd::Constant(n, kNaN);
  out.k0 = Eigen::VectorXd::Constant(n, kNaN);
  out.k_above = Eigen::VectorXd::Constant(n, kNaN);
  out.psi = Eigen::VectorXd::Constant(n, kNaN);
  out.normal_spread = Eigen::VectorXd::Constant(n, kNaN);
  // Umbilic, or a point where faces meet: the principal directions are undefined; the Psi vote decides.
  auto corner_like = [&](Index i) {
    out.normal_spread[i] = normal_spread(positions, mesh.triangles, adj, i);
    return out.curvature.umbilic[i] || out.normal_spread[i] > options.corner_spread;
  };

  std::vector<Index> umbilic_candidates;
  if (!continuity) {
    for (Index i = 0; i < n; ++i) {
      if (!(out.umbrella[i] > out.gamma)) continue;
      ++out.candidates;
      if (corner_like(i)) {
        umbilic_candidates.push_back(i);
        continue;
      }
      const double small = std::min(std::abs(out.curvature.kappa_min[i]), std::abs(out.curvature.kappa_max[i]));
      const double large = std::max(std::abs(out.curvature.kappa_min[i]), std::abs(out.curvature.kappa_max[i]));
      out.labels[i] = large >= options.anisotropy * small ? VertexLabel::Edge : VertexLabel::Noise;
    }
    vote_corners(positions, adj, umbilic_candidates, out);
    report(1.0);
    return out;
  }
  const ContourNeighbours contour = contour_neighbours(mesh, adj);
  const Eigen::Vector3d axis = estimate_slice_axis(mesh);
  const Eigen::Vector3d helper = std::abs(axis.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = (helper - helper.dot(axis) * axis).normalized();
  const Eigen::Vector3d e2 = axis.cross(e1);
  std::map<std::int32_t, PlaneFrame> planes;
  {
    std::map<std::int32_t, std::pair<Eigen::Vector3d, int>> sums;
    std::pair<Eigen::Vector3d, int>* sum = nullptr;  // vertices come slice by slice: look up on change
    std::int32_t last = kNoId;
    for (Index i = 0; i < n; ++i) {
      if (mesh.slice_ids[i] == kNoId) continue;
      if (mesh.slice_ids[i] != last) {
        last = mesh.slice_ids[i];
        sum = &sums[last];
        if (sum->second == 0) sum->first.setZero();
      }
      sum->first += mesh.positions.col(i);
      ++sum->second;
    }
    for (const auto& [slice, s] : sums) planes[slice] = {s.first / s.second, e1, e2};
  }

  // The curve through the window of contour vertices centred on `centre`, in the plane of its slice.
  auto curve_around = [&](Index centre, const PlaneFrame& plane) {
    const std::vector<Index> window = contour.window(centre, options.window);
    std::vector<Eigen::Vector2d> pts;
    Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();
    for (Index v : window) {
      pts.push_back(plane.project(positions.col(v)));
      normal_sum += out.curvature.normals.col(v);
    }
    return fit_curve(pts, plane.project_direction(normal_sum));
  };

  for (Index i = 0; i < n; ++i) {
    if (!(out.umbrella[i] > out.gamma)) continue;
    ++out.candidates;
    const std::int32_t s = mesh.slice_ids[i];
    if (corner_like(i)) {
      umbilic_candidates.push_back(i);
      continue;
    }
    // S contains t and n; its normal `across` is the other principal direction. Every slice plane
    // shares the in-plane axes e1, e2, so n2, the normal of the line S cuts from a slice, is the same
    // in all of them.
    const FeatureDirections directions = feature_directions(out.curvature, i);
    const Eigen::Vector3d& across = directions.across;
    const Eigen::Vector2d n2(across.dot(e1), across.dot(e2));
    // Off the slices, or a feature line within a slice plane: the paper's blind spot. With the
    // extension, a line that runs within a slice plane (t across the slice axis) is also followed along
    // itself where the plane S is not parallel to the slices (a cap's rim meeting a side at an angle).
    const bool blind_spot = s == kNoId || n2.norm() <= 0.1;
    if (options.in_slice == InSliceFeatures::AlongFeatureLine &&
        (blind_spot || std::abs(directions.along.dot(axis)) <= 0.1) &&
        continuous_along_line(positions, mesh.triangles, adj, out.curvature, i, options)) {
      out.labels[i] = VertexLabel::Edge;
      continue;
    }
    if (blind_spot) {
      out.labels[i] = VertexLabel::Noise;
      continue;
    }
    const PlaneFrame& own_plane = planes[s];
    const CurveFit own = curve_around(i, own_plane);
    if (!own.ok) {
      out.labels[i] = VertexLabel::Noise;
      continue;
    }
    const Eigen::Vector2d qi = own_plane.project(positions.col(i));
    const double k0 = own.curvature(own.x_of(qi));
    out.k0[i] = k0;
    const double delta = options.delta.value_or(options.delta_factor * std::abs(k0));
    bool edge = true;
    int sides = 0;
    for (const int side : {-1, +1}) {
      const std::int32_t target = s + side;
      // The neighbour of v_i on the adjacent slice nearest to it anchors that contour's window.
      Index anchor = -1;
      double best = std::numeric_limits<double>::infinity();
      for (Index j : adj.ring(i)) {
        if (mesh.slice_ids[j] != target) continue;
        const double d = (positions.col(j) - positions.col(i)).squaredNorm();
        if (d < best) {
          best = d;
          anchor = j;
        }
      }
      if (anchor < 0) continue;  // no adjacent contour on this side (end slice, or a branching copy)
      const PlaneFrame& plane = planes[target];
      // S = {p : across . (p - v_i) = 0}; within this slice plane (p = origin + X e1 + Y e2) that is
      // the line n2 . (X, Y) = across . (v_i - origin), which includes the offset along the slice axis.
      const double d = across.dot(positions.col(i) - plane.origin);
      // A feature line that runs obliquely to the slices meets the adjacent contour away from v_i's
      // nearest neighbour there: centre the window where that contour crosses S.
      anchor = walk_to_plane(contour, anchor, [&](Index v) { return n2.dot(plane.project(positions.col(v))) - d; });
      const CurveFit curve = curve_around(anchor, plane);
      if (!curve.ok) continue;
      ++sides;
      double k = kNaN;
      if (const auto X = intersect(curve, n2, d, plane.project(positions.col(i)))) k = curve.curvature(*X);
      (side < 0 ? out.k_below : out.k_above)[i] = k;
      if (!(std::isfinite(k) && k0 * k > 0.0 && std::abs(k0 - k) < delta)) edge = false;
    }
    out.labels[i] = edge && sides > 0 ? VertexLabel::Edge : VertexLabel::Noise;
  }
  report(0.8);

  vote_corners(positions, adj, umbilic_candidates, out);
  report(1.0);
  return out;
}

}  // namespace contourmesh
