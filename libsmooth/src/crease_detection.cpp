// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/crease_detection.h"

#include "contourmesh/internal/huge_pages.h"
#include "detail/parallel.h"
#include "detail/slice_axis.h"
#include "detail/vertex_ball.h"
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
#include <queue>
#include <string>

namespace contourmesh {

namespace {

// The most vertices a ball neighbourhood gathers (a safeguard against degenerate, very dense meshes).
constexpr std::size_t kMaxBall = 512;
// The smallest sin^2 of the angle between a surface and the slices that the slice-aware threshold
// divides by.
constexpr double kMinSine2 = 1e-3;

void check(const Mesh& mesh, const MeshAdjacency& adjacency, const CreaseOptions& o) {
  const auto fail = [](const std::string& what) { throw InvalidInputError("crease detection: " + what); };
  if (adjacency.num_vertices() != mesh.num_vertices()) fail("the adjacency belongs to another mesh");
  if (!(o.radius > 0.0 && std::isfinite(o.radius))) fail("radius must be a finite number > 0");
  if (!(o.edge_threshold > 0.0 && o.edge_threshold <= 0.5)) fail("edge threshold must be in (0, 0.5]");
  if (!(o.corner_threshold > 0.0 && o.corner_threshold <= 1.0 / 3.0)) fail("corner threshold must be in (0, 1/3]");
  if (!(o.min_extent >= 0.0 && std::isfinite(o.min_extent))) fail("min extent must be a finite number >= 0");
  if (!(o.band >= 0.0 && std::isfinite(o.band))) fail("band must be a finite number >= 0");
  if (!(o.link_radius >= 0.0 && std::isfinite(o.link_radius))) fail("link radius must be a finite number >= 0");
  if (!(o.link_angle_degrees >= 0.0 && o.link_angle_degrees <= 90.0)) fail("link angle must be in [0, 90] degrees");
  if (!(o.confirm_radius > 0.0 && std::isfinite(o.confirm_radius))) fail("confirm radius must be a finite number > 0");
  if (!(o.confirm_threshold > 0.0 && o.confirm_threshold <= 0.5)) fail("confirm threshold must be in (0, 0.5]");
  if (!(o.confirm_corner_threshold > 0.0 && o.confirm_corner_threshold <= 1.0 / 3.0)) {
    fail("confirm corner threshold must be in (0, 1/3]");
  }
  if (o.noise && !(*o.noise >= 0.0 && std::isfinite(*o.noise))) fail("noise must be a finite number >= 0");
  if (!(o.noise_factor >= 0.0 && std::isfinite(o.noise_factor))) fail("noise factor must be a finite number >= 0");
  if (!(o.steep_confirm_threshold > 0.0 && o.steep_confirm_threshold <= o.confirm_threshold)) {
    fail("steep confirm threshold must be in (0, confirm threshold]");
  }
}

// Multi-source shortest paths along the edges, up to `limit`; sources at distance 0.
std::vector<double> distances_from(const Mesh& mesh, const MeshAdjacency& adjacency, const std::vector<Index>& sources,
                                   double limit) {
  std::vector<double> d;
  detail::assign_huge(d, static_cast<std::size_t>(mesh.num_vertices()), std::numeric_limits<double>::infinity());
  using Item = std::pair<double, Index>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (Index s : sources) {
    d[static_cast<std::size_t>(s)] = 0.0;
    queue.emplace(0.0, s);
  }
  while (!queue.empty()) {
    const auto [di, i] = queue.top();
    queue.pop();
    if (di > d[static_cast<std::size_t>(i)]) continue;
    for (Index j : adjacency.ring(i)) {
      const double dj = di + (mesh.positions.col(j) - mesh.positions.col(i)).norm();
      if (dj <= limit && dj < d[static_cast<std::size_t>(j)]) {
        d[static_cast<std::size_t>(j)] = dj;
        queue.emplace(dj, j);
      }
    }
  }
  return d;
}

using Tensor6 = Eigen::Matrix<double, 6, 1>;  // xx, yy, zz, xy, xz, yz of a symmetric 3 x 3 tensor

Eigen::Matrix3d as_matrix(const Tensor6& t) {
  Eigen::Matrix3d m;
  m << t[0], t[3], t[4], t[3], t[1], t[5], t[4], t[5], t[2];
  return m;
}

struct BallTensor {
  double edge = 0.0, corner = 0.0;                       // l2 / trace, l3 / trace
  Eigen::Vector3d mean_normal = Eigen::Vector3d::Zero();  // unit, area-weighted (zero if undefined)
};

using detail::BallScratch;
using detail::BallScratchPool;

// The ball of vertex i in crease detection: at most about kMaxBall vertices (detail::gather_ball).
void gather_ball(const Mesh& mesh, const MeshAdjacency& adjacency, Index i, double radius, BallScratch& scratch) {
  detail::gather_ball(mesh, adjacency, i, radius, kMaxBall, scratch);
}

// The normal tensor of the ball of `radius` around vertex i (gather_ball).
BallTensor ball_tensor(const Mesh& mesh, const MeshAdjacency& adjacency, const std::vector<Tensor6>& own,
                       const Eigen::Matrix3Xd& area_normal, Index i, double radius, BallScratch& scratch) {
  gather_ball(mesh, adjacency, i, radius, scratch);
  const std::vector<Index>& ball = scratch.ball;
  Tensor6 t = Tensor6::Zero();
  BallTensor result;
  for (Index j : ball) {
    t += own[static_cast<std::size_t>(j)];
    result.mean_normal += area_normal.col(j);
  }
  const double len = result.mean_normal.norm();
  result.mean_normal = len > 0.0 ? Eigen::Vector3d(result.mean_normal / len) : Eigen::Vector3d::Zero();
  const Eigen::Matrix3d tensor = as_matrix(t);
  const double trace = tensor.trace();
  if (!(trace > 0.0)) return result;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(tensor, Eigen::EigenvaluesOnly);
  result.edge = std::max(0.0, eigen.eigenvalues()[1]) / trace;
  result.corner = std::max(0.0, eigen.eigenvalues()[0]) / trace;
  return result;
}

// Whether candidate i is the strongest across its crease: no ring neighbour lying across the crease
// direction `along` (more across it than along it) has a larger `strength`.
bool across_maximum(const Mesh& mesh, const MeshAdjacency& adjacency, const Eigen::Vector3d& along,
                    const Eigen::VectorXd& strength, Index i) {
  for (Index j : adjacency.ring(i)) {
    const Eigen::Vector3d d = mesh.positions.col(j) - mesh.positions.col(i);
    const double along_part = std::abs(d.dot(along));
    const double across_part = (d - d.dot(along) * along).norm();
    if (across_part > along_part && strength[j] > strength[i]) return false;
  }
  return true;
}

// Links of the crease lines (step 2 of detect_creases): per core vertex on a slice, in CSR, the core
// vertices on an adjacent contour's slice within `radius` of it (through vertices within it: gather_ball,
// in the order it meets them) such that the segment between them passes `along_crease` at both ends. They
// do not depend on the grouping, so they are found in fixed chunks on every core.
template <typename AlongCrease>
void link_partners(const Mesh& mesh, const MeshAdjacency& adjacency, const std::vector<std::uint8_t>& core,
                   double radius, const AlongCrease& along_crease, BallScratchPool& pool, std::vector<Index>& offsets,
                   std::vector<Index>& partners) {
  const auto n = static_cast<std::size_t>(mesh.num_vertices());
  constexpr std::size_t kChunk = 4096;
  detail::assign_huge(offsets, n + 1, Index{0});
  const std::vector<std::vector<Index>> parts =
      detail::map_chunks<std::vector<Index>>(n, kChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
        std::unique_ptr<BallScratch> scratch;  // taken at the chunk's first core vertex
        std::vector<Index> part;
        for (std::size_t v = begin; v < end; ++v) {
          const std::int32_t sv = mesh.slice_ids[v];
          if (!core[v] || sv < 0) continue;
          if (!scratch) scratch = pool.take();
          const auto vi = static_cast<Index>(v);
          gather_ball(mesh, adjacency, vi, radius, *scratch);
          for (Index j : scratch->ball) {
            const std::int32_t sj = mesh.slice_ids[static_cast<std::size_t>(j)];
            if (!core[static_cast<std::size_t>(j)] || sj < 0 || (sv - sj != 1 && sj - sv != 1)) continue;
            const Eigen::Vector3d d = mesh.positions.col(j) - mesh.positions.col(vi);
            const double len = d.norm();
            if (len > 0.0 && along_crease(vi, d / len) && along_crease(j, d / len)) {
              part.push_back(j);
              ++offsets[v + 1];
            }
          }
        }
        if (scratch) pool.give_back(std::move(scratch));
        return part;
      });
  for (std::size_t v = 0; v < n; ++v) offsets[v + 1] += offsets[v];
  partners.clear();
  partners.reserve(static_cast<std::size_t>(offsets.back()));
  for (const std::vector<Index>& part : parts) partners.insert(partners.end(), part.begin(), part.end());
}

}  // namespace

CreaseDetection detect_creases(const Mesh& mesh, const MeshAdjacency& adjacency, const CreaseOptions& options) {
  check(mesh, adjacency, options);
  const Index n = mesh.num_vertices();
  CreaseDetection result;
  detail::assign_huge(result.labels, static_cast<std::size_t>(n), VertexLabel::Smooth);
  result.edge_strength = detail::huge_zero<Eigen::VectorXd>(n, 1);
  result.corner_strength = detail::huge_zero<Eigen::VectorXd>(n, 1);
  // Per vertex, the direction of least normal variation: along a crease.
  Eigen::Matrix3Xd along = detail::huge_zero<Eigen::Matrix3Xd>(3, n);

  // 1. Normal tensors: each vertex's own, a third of sum A_f n_f n_f^T over its faces, then summed over
  //    the vertex and its ring neighbours within the radius (about one or two edge lengths).
  //    A face's unit normal and area come from one cross product, as face_normals and face_areas
  //    compute them (the same values, without the two per-face arrays).
  Eigen::Matrix3Xd area_normal = detail::huge_zero<Eigen::Matrix3Xd>(3, n);  // sum of the faces' area vectors, x2
  std::vector<Tensor6> own;
  detail::assign_huge(own, static_cast<std::size_t>(n), Tensor6(Tensor6::Zero()));
  for (const Triangle& tri : mesh.triangles) {
    const Eigen::Vector3d c = (mesh.positions.col(tri[1]) - mesh.positions.col(tri[0]))
                                  .cross(mesh.positions.col(tri[2]) - mesh.positions.col(tri[0]));
    const double len = c.norm();
    const Eigen::Vector3d nf = len > 0.0 ? Eigen::Vector3d(c / len) : Eigen::Vector3d::Zero();
    const double w = 0.5 * len / 3.0;
    Tensor6 t;
    t << nf.x() * nf.x(), nf.y() * nf.y(), nf.z() * nf.z(), nf.x() * nf.y(), nf.x() * nf.z(), nf.y() * nf.z();
    const Tensor6 wt = w * t;
    for (Index v : tri) {
      own[static_cast<std::size_t>(v)] += wt;
      area_normal.col(v) += c;
    }
  }
  const double r2 = options.radius * options.radius;
  const std::optional<Eigen::Vector3d> slice_axis =
      options.confirm == CreaseConfirmation::Ball && options.sampling == CreaseSampling::SliceAware
          ? detail::slice_axis_if_any(mesh)
          : std::nullopt;
  const double relative_noise = options.noise.value_or(0.0) / options.confirm_radius;
  const double lift = options.noise_factor * relative_noise * relative_noise;
  Eigen::VectorXd threshold = detail::huge_matrix<Eigen::VectorXd>(n, 1);
  threshold.setConstant(options.confirm_threshold + lift);
  result.confirm_strength = detail::huge_zero<Eigen::VectorXd>(n, 1);
  result.confirm_corner_strength = detail::huge_zero<Eigen::VectorXd>(n, 1);
  BallScratchPool scratch_pool(n);
  detail::parallel_chunks(static_cast<std::size_t>(n), 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const Index i = static_cast<Index>(k);
      const Eigen::Vector3d centre = mesh.positions.col(i);
      Tensor6 t = own[k];
      for (Index j : adjacency.ring(i)) {
        if ((mesh.positions.col(j) - centre).squaredNorm() <= r2) t += own[static_cast<std::size_t>(j)];
      }
      const Eigen::Matrix3d tensor = as_matrix(t);
      const double trace = tensor.trace();
      if (!(trace > 0.0)) continue;
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
      eigen.computeDirect(tensor, Eigen::EigenvaluesOnly);
      const Eigen::Vector3d l = eigen.eigenvalues();  // increasing
      result.edge_strength[i] = std::max(0.0, l[1]) / trace;
      result.corner_strength[i] = std::max(0.0, l[0]) / trace;
      if (result.edge_strength[i] < options.edge_threshold && result.corner_strength[i] < options.corner_threshold) {
        continue;
      }
      eigen.computeDirect(tensor);  // the crease direction, for the suppression below
      along.col(i) = eigen.eigenvectors().col(0);
    }
  });

  // Non-maximum suppression on the ring's strengths: a candidate is a ridge maximum when no neighbour
  // lying across its crease, rather than along it, is stronger. Only ridge maxima and the ring's corners
  // can become core vertices, so only they are examined over the ball (on a real scan half of the
  // candidates); the other candidates are not core whatever their ball, and keep no label of their own.
  std::vector<std::uint8_t> ridge_maximum;
  detail::assign_huge(ridge_maximum, static_cast<std::size_t>(n), std::uint8_t{0});
  detail::parallel_chunks(static_cast<std::size_t>(n), 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
    std::unique_ptr<BallScratch> scratch;  // taken at the chunk's first vertex examined over its ball
    for (std::size_t k = begin; k < end; ++k) {
      const Index i = static_cast<Index>(k);
      const bool ring_corner = result.corner_strength[i] >= options.corner_threshold;
      if (result.edge_strength[i] >= options.edge_threshold) {
        ridge_maximum[k] = across_maximum(mesh, adjacency, along.col(i), result.edge_strength, i) ? 1 : 0;
      }
      if (!(ring_corner || ridge_maximum[k]) || options.confirm == CreaseConfirmation::None) continue;
      // The same tensor over the ball of confirm_radius: a crease is a change of the normal that
      // persists at that scale, not a step or fold of a few tenths of a millimetre.
      if (!scratch) scratch = scratch_pool.take();
      const BallTensor b = ball_tensor(mesh, adjacency, own, area_normal, i, options.confirm_radius, *scratch);
      result.confirm_strength[i] = b.edge;
      result.confirm_corner_strength[i] = b.corner;
      if (slice_axis) {
        // Where the surface turns parallel to the slices, the contours lie further apart along it and a
        // smooth surface folds more between them: the threshold grows as 1 / sin^2 of its angle to the
        // slices, up to confirm_threshold.
        const double c = b.mean_normal.dot(*slice_axis);
        const double sine2 = std::max(1.0 - c * c, kMinSine2);
        threshold[i] = std::min(options.confirm_threshold, options.steep_confirm_threshold / sine2) + lift;
      }
    }
    if (scratch) scratch_pool.give_back(std::move(scratch));
  });

  // 2. Core vertices: the confirmed corners (kept whole) and ridge maxima (suppression above). Then grouped
  //    along the edges and the links between slices; groups shorter than min_extent are noise.
  std::vector<std::uint8_t> core;
  detail::assign_huge(core, static_cast<std::size_t>(n), std::uint8_t{0});
  const bool confirm = options.confirm == CreaseConfirmation::Ball;
  // A corner on the ring, and over the ball too when confirming.
  const auto is_corner = [&](Index i) {
    return result.corner_strength[i] >= options.corner_threshold &&
           (!confirm || result.confirm_corner_strength[i] >= options.confirm_corner_threshold);
  };
  // Each vertex reads the strengths and sets its own entries only: fixed chunks on every core.
  detail::parallel_chunks(static_cast<std::size_t>(n), 8192, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (auto i = static_cast<Index>(begin); i < static_cast<Index>(end); ++i) {
      const bool corner = is_corner(i);
      // Not a corner: a crease candidate only where it is the strongest across (set above for candidates).
      if (!corner && !ridge_maximum[static_cast<std::size_t>(i)]) continue;
      if (confirm && result.confirm_strength[i] < threshold[i]) {
        result.labels[static_cast<std::size_t>(i)] = VertexLabel::Noise;  // not a crease at the ball's scale
        continue;
      }
      core[static_cast<std::size_t>(i)] = 1;
    }
  });
  // Two core vertices on adjacent contours' slices within link_radius of each other (through vertices
  // within it) belong to one line when the segment between them runs along the crease at both ends (a
  // corner has no crease direction): a crease oblique to the slices meets adjacent contours at vertices
  // that share no edge. Only across one slice, so that folds and noise within a slice or on a cap,
  // whose directions are random, are not strung together.
  const bool linking = options.link_radius > 0.0 && mesh.has_contour_ids();
  const double link_cos = std::cos(options.link_angle_degrees * std::numbers::pi / 180.0);
  const auto along_crease = [&](Index v, const Eigen::Vector3d& unit) {
    return is_corner(v) || std::abs(unit.dot(along.col(v))) >= link_cos;
  };
  std::vector<Index> link_offsets, links;
  if (linking) {
    link_partners(mesh, adjacency, core, options.link_radius, along_crease, scratch_pool, link_offsets, links);
  }
  std::vector<Index> group;
  detail::assign_huge(group, static_cast<std::size_t>(n), Index{-1});
  std::vector<Index> kept, kept_corners, members, stack;
  const auto join = [&](Index j, Index seed) {
    if (core[static_cast<std::size_t>(j)] && group[static_cast<std::size_t>(j)] < 0) {
      group[static_cast<std::size_t>(j)] = seed;
      stack.push_back(j);
    }
  };
  for (Index seed = 0; seed < n; ++seed) {
    if (!core[static_cast<std::size_t>(seed)] || group[static_cast<std::size_t>(seed)] >= 0) continue;
    members.clear();
    stack.assign(1, seed);
    group[static_cast<std::size_t>(seed)] = seed;
    Eigen::AlignedBox3d box;
    while (!stack.empty()) {
      const Index v = stack.back();
      stack.pop_back();
      members.push_back(v);
      box.extend(mesh.positions.col(v));
      for (Index j : adjacency.ring(v)) join(j, seed);
      if (!linking) continue;
      const auto vu = static_cast<std::size_t>(v);
      for (Index r = link_offsets[vu]; r < link_offsets[vu + 1]; ++r) join(links[static_cast<std::size_t>(r)], seed);
    }
    const bool line = box.diagonal().norm() >= options.min_extent;
    for (Index v : members) {
      if (!line) {
        result.labels[static_cast<std::size_t>(v)] = VertexLabel::Noise;
        continue;
      }
      kept.push_back(v);
      if (is_corner(v)) kept_corners.push_back(v);
    }
  }
  result.core_vertices = kept.size();

  // 3. The band around the kept core vertices.
  std::vector<double> to_core, to_corner;  // the two searches side by side
  detail::parallel_chunks(2, 1, [&](std::size_t k, std::size_t, std::size_t) {
    (k == 0 ? to_core : to_corner) = distances_from(mesh, adjacency, k == 0 ? kept : kept_corners, options.band);
  });
  for (Index i = 0; i < n; ++i) {
    auto& label = result.labels[static_cast<std::size_t>(i)];
    if (to_corner[static_cast<std::size_t>(i)] <= options.band) {
      label = VertexLabel::Corner;
    } else if (to_core[static_cast<std::size_t>(i)] <= options.band) {
      label = VertexLabel::Edge;
    }
    result.edges += label == VertexLabel::Edge;
    result.corners += label == VertexLabel::Corner;
    result.noise += label == VertexLabel::Noise;
  }
  return result;
}

}  // namespace contourmesh
