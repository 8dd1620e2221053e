// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/crease_restoration.h"

#include "detail/parallel.h"
#include "detail/slice_axis.h"
#include "detail/vertex_ball.h"
#include "contourmesh/smooth/adaptive_subdivision.h"
#include "contourmesh/smooth/adjacency.h"
#include "contourmesh/smooth/contour_structure.h"
#include "contourmesh/smooth/errors.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <utility>

namespace contourmesh {

namespace {

void check(const Mesh& mesh, const std::vector<VertexLabel>& labels, const CreaseRestorationOptions& o) {
  const auto fail = [](const std::string& what) { throw InvalidInputError("crease restoration: " + what); };
  if (labels.size() != static_cast<std::size_t>(mesh.num_vertices())) fail("one label per vertex is needed");
  if (!(o.levels >= 0 && o.levels <= 3)) fail("levels must be in [0, 3]");
  const auto positive = [&](double v, const char* name) {
    if (!(v > 0.0 && std::isfinite(v))) fail(std::string(name) + " must be a finite number > 0");
  };
  positive(o.radius, "radius");
  positive(o.slab, "slab");
  positive(o.max_residual, "max residual");
  positive(o.max_line_distance, "max line distance");
  positive(o.max_move, "max move");
  if (!(o.mode_angle_degrees > 0.0 && o.mode_angle_degrees <= 45.0)) fail("mode angle must be in (0, 45] degrees");
  if (!(o.min_angle_degrees > 0.0 && o.min_angle_degrees < 180.0)) fail("min angle must be in (0, 180) degrees");
  if (!(o.max_third_share >= 0.0 && o.max_third_share <= 1.0)) fail("max third share must be in [0, 1]");
  if (!(o.min_rounding >= 0.0 && std::isfinite(o.min_rounding))) fail("min rounding must be a finite number >= 0");
  if (!(o.line_ratio >= 0.0 && o.line_ratio <= 1.0)) fail("line ratio must be in [0, 1]");
}

// The most vertices a ball gathers (detail::gather_ball's safeguard).
constexpr std::size_t kMaxRestorationBall = 1024;

// The two planes of a ball, as unit normals m and offsets o (m . x = o on the plane).
// `convex`: each side's vertices lie behind the other side's plane (the solid is behind both planes);
// otherwise both lie in front of it (concave: the solid is behind either).
struct Planes {
  Eigen::Vector3d m[2];
  double o[2] = {0.0, 0.0};
  bool convex = true;
};

// Steps 2 and 3 of the header; nothing where the ball is not two planes as the options ask.
std::optional<Planes> fit_planes(const Mesh& mesh, const Eigen::Matrix3Xd& area_normal, const std::vector<double>& area,
                                 const std::vector<Index>& ball, const Eigen::Vector3d& centre,
                                 const CreaseRestorationOptions& options) {
  Eigen::Matrix3d tensor = Eigen::Matrix3d::Zero();
  for (Index j : ball) {
    const double len = area[static_cast<std::size_t>(j)];
    if (len > 0.0) tensor += area_normal.col(j) * area_normal.col(j).transpose() / len;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(tensor);
  const Eigen::Vector3d split = eigen.eigenvectors().col(1);
  Planes p;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (Index j : ball) {
    const double len = area[static_cast<std::size_t>(j)];
    if (!(len > 0.0)) continue;
    const double s = area_normal.col(j).dot(split) / len;
    if (s > hi) hi = s, p.m[0] = area_normal.col(j) / len;
    if (s < lo) lo = s, p.m[1] = area_normal.col(j) / len;
  }
  if (!(hi > lo)) return std::nullopt;
  const auto side = [&](Index j) { return area_normal.col(j).dot(p.m[0]) >= area_normal.col(j).dot(p.m[1]) ? 0 : 1; };
  const double mode_cos = std::cos(options.mode_angle_degrees * std::numbers::pi / 180.0);
  const auto near_mode = [&](Index j, int k) {
    const double len = area[static_cast<std::size_t>(j)];
    return len > 0.0 && area_normal.col(j).dot(p.m[k]) >= mode_cos * len;
  };
  for (int round = 0; round < 9; ++round) {  // five rounds of 2-means, then four of the mode
    Eigen::Vector3d sum[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    for (Index j : ball) {
      const int k = side(j);
      if (round < 5 || near_mode(j, k)) sum[k] += area_normal.col(j);
    }
    const double len0 = sum[0].norm(), len1 = sum[1].norm();
    if (!(len0 > 0.0 && len1 > 0.0)) return std::nullopt;
    p.m[0] = sum[0] / len0;
    p.m[1] = sum[1] / len1;
  }
  if (p.m[0].dot(p.m[1]) > std::cos(options.min_angle_degrees * std::numbers::pi / 180.0)) return std::nullopt;
  const Eigen::Vector3d along = p.m[0].cross(p.m[1]).normalized();
  // A third plane (a corner): normals far out of the plane of the two sides' normals.
  double out_of_plane = 0.0, total = 0.0;
  for (Index j : ball) {
    const double len = area[static_cast<std::size_t>(j)];
    total += len;
    if (std::abs(area_normal.col(j).dot(along)) > 0.5 * len) out_of_plane += len;
  }
  if (out_of_plane > options.max_third_share * total) return std::nullopt;
  double sum[2] = {0.0, 0.0}, sum2[2] = {0.0, 0.0}, weight[2] = {0.0, 0.0};
  Eigen::Vector3d centroid[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  double count[2] = {0.0, 0.0};
  for (Index j : ball) {
    const int k = side(j);
    centroid[k] += mesh.positions.col(j);
    count[k] += 1.0;
    if (!near_mode(j, k) || std::abs((mesh.positions.col(j) - centre).dot(along)) > options.slab) continue;
    const double w = area[static_cast<std::size_t>(j)], d = p.m[k].dot(mesh.positions.col(j));
    sum[k] += w * d;
    sum2[k] += w * d * d;
    weight[k] += w;
  }
  for (int k = 0; k < 2; ++k) {
    if (!(weight[k] > 0.0)) return std::nullopt;
    p.o[k] = sum[k] / weight[k];
    if (std::sqrt(std::max(0.0, sum2[k] / weight[k] - p.o[k] * p.o[k])) > options.max_residual) return std::nullopt;
  }
  // Which side of the other plane each side's centroid lies on.
  const double behind0 = p.m[0].dot(centroid[1] / count[1]) - p.o[0];
  const double behind1 = p.m[1].dot(centroid[0] / count[0]) - p.o[1];
  if (behind0 < 0.0 && behind1 < 0.0) {
    p.convex = true;
  } else if (behind0 > 0.0 && behind1 > 0.0) {
    p.convex = false;
  } else {
    return std::nullopt;
  }
  return p;
}

// How far x lies inside both planes of a convex crease (outside both of a concave one): the depth of
// the rounding at x; 0 where x lies on or beyond either plane.
double rounded_by(const Planes& p, const Eigen::Vector3d& x) {
  const double sign = p.convex ? 1.0 : -1.0;
  return std::max(0.0, -std::max(sign * (p.m[0].dot(x) - p.o[0]), sign * (p.m[1].dot(x) - p.o[1])));
}

// Step 4 of the header: the move of the vertex at x onto the crease of `p`; nothing where it stays.
// `axis`: the slice axis for a contour vertex (it moves within its slice plane), else null.
std::optional<Eigen::Vector3d> move_onto(const Planes& p, const Eigen::Vector3d& x, const Eigen::Vector3d* axis,
                                         const CreaseRestorationOptions& options) {
  const double d[2] = {p.m[0].dot(x) - p.o[0], p.m[1].dot(x) - p.o[1]};
  const double g = p.m[0].dot(p.m[1]), det = 1.0 - g * g;
  // The nearest point of the planes' line is x + a m0 + b m1 with m_k . x = o_k.
  const double a = (-d[0] + g * d[1]) / det, b = (-d[1] + g * d[0]) / det;
  const Eigen::Vector3d to_line = a * p.m[0] + b * p.m[1];
  if (to_line.norm() > options.max_line_distance) return std::nullopt;
  // In the convex frame (a concave crease mirrored) the surface is max(e0, e1) = 0.
  const double sign = p.convex ? 1.0 : -1.0;
  const double e[2] = {sign * d[0], sign * d[1]};
  const int nearer = e[0] > e[1] ? 0 : 1;  // inside both: the nearer plane; outside both: the farther
  int k = nearer;
  Eigen::Vector3d move;
  if (e[0] <= 0.0 && e[1] <= 0.0 && std::max(e[0], e[1]) <= options.line_ratio * std::min(e[0], e[1])) {
    move = to_line;  // inside both, about as deep below each: near the bisector, onto the line
  } else if (e[0] <= 0.0 && e[1] <= 0.0) {
    move = -d[k] * p.m[k];
  } else if (e[0] > 0.0 && e[1] > 0.0) {
    move = to_line;
  } else {
    k = e[0] > 0.0 ? 0 : 1;
    move = -d[k] * p.m[k];
  }
  if (axis != nullptr) {
    // Within the slice plane, along plane k's in-plane normal, by as much as brings x onto plane k
    // (or, towards the line, as far along its normal as the 3-D move goes).
    Eigen::Vector3d u = p.m[k] - p.m[k].dot(*axis) * *axis;
    const double len = u.norm();
    if (len < 0.5) return std::nullopt;  // a plane within 30 degrees of the slices: no in-plane fix
    u /= len;
    move = p.m[k].dot(move) / p.m[k].dot(u) * u;
  }
  if (!(move.norm() <= options.max_move)) return std::nullopt;
  return move;
}

// Per vertex, the sum of its faces' area vectors (twice their area times their unit normal) and its
// length, read many times per ball.
struct AreaNormals {
  Eigen::Matrix3Xd sum;
  std::vector<double> length;
};

AreaNormals area_normals(const Mesh& m) {
  const Index n = m.num_vertices();
  AreaNormals a{Eigen::Matrix3Xd::Zero(3, n), std::vector<double>(static_cast<std::size_t>(n))};
  for (const Triangle& t : m.triangles) {
    const Eigen::Vector3d c =
        (m.positions.col(t[1]) - m.positions.col(t[0])).cross(m.positions.col(t[2]) - m.positions.col(t[0]));
    for (Index v : t) a.sum.col(v) += c;
  }
  for (Index v = 0; v < n; ++v) a.length[static_cast<std::size_t>(v)] = a.sum.col(v).norm();
  return a;
}

// Step 2 for every vertex with `examine` set: its ball's two planes, where it fits them (in parallel;
// each vertex writes only its own entries).
std::vector<std::optional<Planes>> fit_balls(const Mesh& m, const MeshAdjacency& adjacency,
                                             const std::vector<std::uint8_t>& examine,
                                             const CreaseRestorationOptions& options) {
  const Index n = m.num_vertices();
  const AreaNormals normals = area_normals(m);
  std::vector<std::optional<Planes>> planes(static_cast<std::size_t>(n));
  detail::BallScratchPool pool(n);
  detail::parallel_chunks(static_cast<std::size_t>(n), 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
    std::unique_ptr<detail::BallScratch> ball;  // taken at the chunk's first vertex to examine
    for (std::size_t k = begin; k < end; ++k) {
      if (!examine[k]) continue;
      const auto i = static_cast<Index>(k);
      if (!ball) ball = pool.take();
      detail::gather_ball(m, adjacency, i, options.radius, kMaxRestorationBall, *ball);
      planes[k] = fit_planes(m, normals.sum, normals.length, ball->ball, m.positions.col(i), options);
    }
    if (ball) pool.give_back(std::move(ball));
  });
  return planes;
}

// Per input vertex: its ball fits two planes (`planes`) and the mesh is rounded there: the vertex or one
// of its ring lies inside both planes (a convex crease; outside both for a concave one) by more than
// min_rounding.
std::vector<std::uint8_t> rounded_creases(const Mesh& mesh, const MeshAdjacency& adjacency,
                                          const std::vector<std::optional<Planes>>& planes,
                                          const CreaseRestorationOptions& options) {
  std::vector<std::uint8_t> fitted(planes.size(), 0);
  for (std::size_t i = 0; i < fitted.size(); ++i) {
    if (!planes[i]) continue;
    double rounding = rounded_by(*planes[i], mesh.positions.col(static_cast<Index>(i)));
    for (Index u : adjacency.ring(static_cast<Index>(i))) {
      rounding = std::max(rounding, rounded_by(*planes[i], mesh.positions.col(u)));
    }
    fitted[i] = rounding > options.min_rounding ? 1 : 0;
  }
  return fitted;
}

}  // namespace

RestoredCreases restore_creases(const Mesh& mesh, const std::vector<VertexLabel>& labels,
                                const CreaseRestorationOptions& options) {
  check(mesh, labels, options);
  RestoredCreases result;
  result.original_vertices = mesh.num_vertices();
  // Step 2 on the input's edge vertices first: only those whose ball already fits two planes, with the
  // mesh rounded inside them, are refined (step 1) and examined again; elsewhere (gentle or noisy folds,
  // corners, creases already sharp) the mesh stays as it is.
  std::vector<std::uint8_t> selected(labels.size(), 0);
  for (std::size_t i = 0; i < labels.size(); ++i) selected[i] = labels[i] == VertexLabel::Edge ? 1 : 0;
  if (std::find(selected.begin(), selected.end(), 1) == selected.end()) {
    result.mesh = mesh;
    return result;
  }
  const MeshAdjacency input_adjacency = build_adjacency(mesh);
  const std::vector<std::optional<Planes>> planes = fit_balls(mesh, input_adjacency, selected, options);
  const std::vector<std::uint8_t> fitted = rounded_creases(mesh, input_adjacency, planes, options);
  if (std::find(fitted.begin(), fitted.end(), 1) == fitted.end()) {
    result.mesh = mesh;
    return result;
  }
  if (options.levels > 0) {
    SubdivisionOptions subdivision;
    subdivision.max_levels = options.levels;
    subdivision.gamma = 0.0;  // every level bisects every spoke of a selected vertex
    result.mesh = subdivide_adaptively(mesh, fitted, subdivision).mesh;
  } else {
    result.mesh = mesh;
  }
  Mesh& m = result.mesh;
  const Index n = m.num_vertices();
  // Contour vertices stay in their slice planes; without ids, or ids that span no planes, every vertex
  // moves freely.
  const std::optional<Eigen::Vector3d> axis = detail::slice_axis_if_any(m);
  // Steps 2-4 again on the refined mesh, for the fitted input vertices and the new ones (without
  // refinement, the planes found); every move from the positions before any (Jacobi).
  std::vector<std::optional<Planes>> refined;
  if (options.levels > 0) {
    std::vector<std::uint8_t> examine(static_cast<std::size_t>(n), 1);
    std::copy(fitted.begin(), fitted.end(), examine.begin());
    refined = fit_balls(m, build_adjacency(m), examine, options);
  } else {
    refined = planes;
    for (std::size_t i = 0; i < refined.size(); ++i) {
      if (!fitted[i]) refined[i].reset();
    }
  }
  Eigen::Matrix3Xd moves = Eigen::Matrix3Xd::Zero(3, n);
  std::vector<std::uint8_t> moved(static_cast<std::size_t>(n), 0);
  detail::parallel_chunks(static_cast<std::size_t>(n), 8192, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      if (!refined[k]) continue;
      const bool on_contour = axis && m.slice_ids[k] >= 0;
      const auto i = static_cast<Index>(k);
      const std::optional<Eigen::Vector3d> move =
          move_onto(*refined[k], m.positions.col(i), on_contour ? &*axis : nullptr, options);
      if (!move) continue;
      moves.col(i) = *move;
      moved[k] = 1;
    }
  });
  for (Index i = 0; i < n; ++i) {
    if (!moved[static_cast<std::size_t>(i)]) continue;
    m.positions.col(i) += moves.col(i);
    ++result.moved;
  }
  return result;
}

}  // namespace contourmesh
