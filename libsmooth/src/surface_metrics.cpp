// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/surface_metrics.h"

#include "detail/parallel.h"
#include "contourmesh/smooth/closest_point.h"
#include "contourmesh/smooth/errors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

namespace contourmesh {

double SurfaceSamples::area() const {
  double sum = 0.0;
  for (double w : weights) sum += w;
  return sum;
}

SurfaceSamples sample_mesh_surface(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                                   double density, std::uint64_t seed, std::size_t max_samples) {
  if (!(density > 0.0 && std::isfinite(density))) {
    throw InvalidInputError("surface sampling: the density must be > 0 samples per unit area");
  }
  const Index n = static_cast<Index>(positions.cols());
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<int> counts(triangles.size(), 0);
  std::size_t total = 0;
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    for (Index v : triangles[f]) {
      if (v < 0 || v >= n) {
        throw InvalidInputError("surface sampling: face " + std::to_string(f) + " names vertex " + std::to_string(v));
      }
    }
    const Triangle& t = triangles[f];
    const double area =
        0.5 * (positions.col(t[1]) - positions.col(t[0])).cross(positions.col(t[2]) - positions.col(t[0])).norm();
    const double expected = std::isfinite(area) ? area * density : 0.0;
    const double whole = std::floor(expected);
    const int k = static_cast<int>(std::min(whole, 1e9)) + (uniform(rng) < expected - whole ? 1 : 0);
    counts[f] = k;
    total += static_cast<std::size_t>(k);
    if (total > max_samples) {
      throw InvalidInputError("surface sampling: more than " + std::to_string(max_samples) +
                              " samples at this density; lower it");
    }
  }
  SurfaceSamples s;
  s.points.resize(3, static_cast<Index>(total));
  s.weights.assign(total, 1.0 / density);
  s.faces.resize(total);
  Index k = 0;
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    const Eigen::Vector3d a = positions.col(t[0]), b = positions.col(t[1]), c = positions.col(t[2]);
    for (int j = 0; j < counts[f]; ++j) {
      // Uniform in the triangle: sqrt of the first variate (Osada et al. 2002).
      const double r1 = std::sqrt(uniform(rng)), r2 = uniform(rng);
      s.points.col(k) = (1.0 - r1) * a + r1 * (1.0 - r2) * b + r1 * r2 * c;
      s.faces[static_cast<std::size_t>(k)] = static_cast<Index>(f);
      ++k;
    }
  }
  return s;
}

SurfaceSamples sample_implicit_surface(const ScalarField& sdf, const VectorField& normal,
                                       const Eigen::AlignedBox3d& box, double spacing) {
  if (!(spacing > 0.0 && std::isfinite(spacing))) {
    throw InvalidInputError("implicit surface sampling: the grid spacing must be > 0");
  }
  if (box.isEmpty() || !box.min().allFinite() || !box.max().allFinite()) {
    throw InvalidInputError("implicit surface sampling: empty or infinite box");
  }
  if (!sdf || !normal) throw InvalidInputError("implicit surface sampling: no distance or normal function");
  constexpr int kBlock = 8;  // grid cells per block side
  std::array<std::int64_t, 3> nodes{};
  double count = 1.0;
  for (int a = 0; a < 3; ++a) {
    nodes[static_cast<std::size_t>(a)] = static_cast<std::int64_t>(std::ceil(box.sizes()[a] / spacing)) + 1;
    count *= static_cast<double>(nodes[static_cast<std::size_t>(a)]);
  }
  if (count > 68719476736.0) throw InvalidInputError("implicit surface sampling: the grid would exceed 2^36 nodes");
  std::array<std::int64_t, 3> blocks{};
  for (std::size_t a = 0; a < 3; ++a) blocks[a] = (nodes[a] - 1 + kBlock - 1) / kBlock;
  const std::size_t block_count = static_cast<std::size_t>(blocks[0] * blocks[1] * blocks[2]);
  const Eigen::Vector3d origin = box.min();
  const double half_diagonal = 0.5 * std::sqrt(3.0) * kBlock * spacing;

  // Per block, its samples; concatenated in block order afterwards (reproducible on any core count).
  std::vector<SurfaceSamples> parts(block_count);
  detail::parallel_chunks(block_count, 1, [&](std::size_t b, std::size_t, std::size_t) {
    const std::int64_t bx = static_cast<std::int64_t>(b) % blocks[0];
    const std::int64_t by = (static_cast<std::int64_t>(b) / blocks[0]) % blocks[1];
    const std::int64_t bz = static_cast<std::int64_t>(b) / (blocks[0] * blocks[1]);
    const std::array<std::int64_t, 3> first{bx * kBlock, by * kBlock, bz * kBlock};
    const Eigen::Vector3d centre =
        origin + spacing * (Eigen::Vector3d(first[0], first[1], first[2]) + Eigen::Vector3d::Constant(0.5 * kBlock));
    if (std::abs(sdf(centre)) > half_diagonal) return;
    // Nodes of the block, one more layer on the high sides (clipped to the grid).
    std::array<std::int64_t, 3> size{};
    for (std::size_t a = 0; a < 3; ++a) size[a] = std::min<std::int64_t>(kBlock + 1, nodes[a] - first[a]);
    std::vector<double> value(static_cast<std::size_t>(size[0] * size[1] * size[2]));
    const auto at = [&](std::int64_t x, std::int64_t y, std::int64_t z) { return (z * size[1] + y) * size[0] + x; };
    const auto node = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
      return Eigen::Vector3d(origin + spacing * Eigen::Vector3d(static_cast<double>(first[0] + x),
                                                                static_cast<double>(first[1] + y),
                                                                static_cast<double>(first[2] + z)));
    };
    for (std::int64_t z = 0; z < size[2]; ++z) {
      for (std::int64_t y = 0; y < size[1]; ++y) {
        for (std::int64_t x = 0; x < size[0]; ++x) value[static_cast<std::size_t>(at(x, y, z))] = sdf(node(x, y, z));
      }
    }
    SurfaceSamples& out = parts[b];
    std::vector<Eigen::Vector3d> points;
    // The block owns the edges that start at its first kBlock nodes along each axis.
    const std::array<std::int64_t, 3> own{std::min<std::int64_t>(kBlock, size[0]),
                                          std::min<std::int64_t>(kBlock, size[1]),
                                          std::min<std::int64_t>(kBlock, size[2])};
    for (std::int64_t z = 0; z < own[2]; ++z) {
      for (std::int64_t y = 0; y < own[1]; ++y) {
        for (std::int64_t x = 0; x < own[0]; ++x) {
          const double v0 = value[static_cast<std::size_t>(at(x, y, z))];
          const std::array<std::int64_t, 3> p{x, y, z};
          for (std::size_t a = 0; a < 3; ++a) {
            std::array<std::int64_t, 3> q = p;
            ++q[a];
            if (q[a] >= size[a]) continue;
            const double v1 = value[static_cast<std::size_t>(at(q[0], q[1], q[2]))];
            if ((v0 < 0.0) == (v1 < 0.0)) continue;
            const double t = v0 / (v0 - v1);
            Eigen::Vector3d point = node(x, y, z) + t * spacing * Eigen::Vector3d::Unit(static_cast<Index>(a));
            Eigen::Vector3d n = normal(point);
            point -= sdf(point) * n;
            n = normal(point);
            const double l1 = n.cwiseAbs().sum();
            if (!(l1 > 0.0) || !point.allFinite()) continue;
            points.push_back(point);
            out.weights.push_back(spacing * spacing / l1);
          }
        }
      }
    }
    out.points.resize(3, static_cast<Index>(points.size()));
    for (std::size_t k = 0; k < points.size(); ++k) out.points.col(static_cast<Index>(k)) = points[k];
  });
  SurfaceSamples all;
  std::size_t total = 0;
  for (const SurfaceSamples& p : parts) total += p.weights.size();
  all.points.resize(3, static_cast<Index>(total));
  all.weights.reserve(total);
  Index k = 0;
  for (const SurfaceSamples& p : parts) {
    if (p.weights.empty()) continue;
    all.points.middleCols(k, p.size()) = p.points;
    all.weights.insert(all.weights.end(), p.weights.begin(), p.weights.end());
    k += p.size();
  }
  return all;
}

namespace {

// Weighted sums of one region on one side.
struct Sums {
  double weight = 0.0, sq = 0.0, max = 0.0, signed_sum = 0.0, angle = 0.0, angle_weight = 0.0;
  void add(double w, double d) {
    weight += w;
    sq += w * d * d;
    signed_sum += w * d;
    max = std::max(max, std::abs(d));
  }
  void merge(const Sums& o) {
    weight += o.weight;
    sq += o.sq;
    max = std::max(max, o.max);
    signed_sum += o.signed_sum;
    angle += o.angle;
    angle_weight += o.angle_weight;
  }
};

enum Region : std::size_t { kFeature = 0, kSmooth = 1 };
using RegionSums = std::array<Sums, 2>;

RegionAccuracy finish(const Sums& mesh, const Sums& truth, bool signed_distance, bool normals) {
  RegionAccuracy r;
  r.mesh_area = mesh.weight;
  r.truth_area = truth.weight;
  if (mesh.weight > 0.0) {
    r.mesh_to_truth_rms = std::sqrt(mesh.sq / mesh.weight);
    r.mesh_to_truth_max = mesh.max;
    if (signed_distance) r.mean_signed = mesh.signed_sum / mesh.weight;
    if (normals && mesh.angle_weight > 0.0) r.normal_error_degrees = mesh.angle / mesh.angle_weight;
  }
  if (truth.weight > 0.0) {
    r.truth_to_mesh_rms = std::sqrt(truth.sq / truth.weight);
    r.truth_to_mesh_max = truth.max;
  }
  if (mesh.weight > 0.0 && truth.weight > 0.0) {
    r.rms = std::sqrt(0.5 * (r.mesh_to_truth_rms * r.mesh_to_truth_rms + r.truth_to_mesh_rms * r.truth_to_mesh_rms));
    r.hausdorff = std::max(r.mesh_to_truth_max, r.truth_to_mesh_max);
  } else if (mesh.weight > 0.0) {
    r.hausdorff = r.mesh_to_truth_max;
  } else if (truth.weight > 0.0) {
    r.hausdorff = r.truth_to_mesh_max;
  }
  return r;
}

}  // namespace

SurfaceAccuracy surface_accuracy(const Eigen::Matrix3Xd& positions, const std::vector<Triangle>& triangles,
                                 const SurfaceTruth& truth, const SurfaceMetricsOptions& options) {
  if (!truth.distance) throw InvalidInputError("surface accuracy: the truth has no distance function");
  if (truth.samples.size() == 0) throw InvalidInputError("surface accuracy: the truth has no surface samples");
  if (!(options.feature_radius >= 0.0 && std::isfinite(options.feature_radius))) {
    throw InvalidInputError("surface accuracy: the feature radius must be a finite number >= 0");
  }
  const SurfaceSamples mesh_samples = sample_mesh_surface(positions, triangles, options.density, options.seed);
  const TriangleLocator locator(positions, triangles);
  const bool has_features = static_cast<bool>(truth.feature_distance);
  const bool normals = static_cast<bool>(truth.normal);
  const auto region_of = [&](const Eigen::Vector3d& p) {
    return has_features && truth.feature_distance(p) < options.feature_radius ? kFeature : kSmooth;
  };
  // Unit face normals (zero for degenerate faces, which then carry no normal error).
  std::vector<Eigen::Vector3d> face_normal(triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    const Eigen::Vector3d c =
        (positions.col(t[1]) - positions.col(t[0])).cross(positions.col(t[2]) - positions.col(t[0]));
    const double len = c.norm();
    face_normal[f] = len > 0.0 ? Eigen::Vector3d(c / len) : Eigen::Vector3d::Zero();
  }

  constexpr std::size_t kChunk = 4096;
  const auto reduce = [&](std::size_t n, const auto& one) {
    const std::vector<RegionSums> partial =
        detail::map_chunks<RegionSums>(n, kChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
          RegionSums sums;
          for (std::size_t k = begin; k < end; ++k) one(k, sums);
          return sums;
        });
    RegionSums total;
    for (const RegionSums& p : partial) {
      total[0].merge(p[0]);
      total[1].merge(p[1]);
    }
    return total;
  };

  RegionSums mesh_side = reduce(static_cast<std::size_t>(mesh_samples.size()), [&](std::size_t k, RegionSums& s) {
    const Eigen::Vector3d p = mesh_samples.points.col(static_cast<Index>(k));
    const double w = mesh_samples.weights[k];
    Sums& r = s[region_of(p)];
    r.add(w, truth.distance(p));
    if (normals) {
      const Eigen::Vector3d& n = face_normal[static_cast<std::size_t>(mesh_samples.faces[k])];
      if (n.squaredNorm() > 0.0) {
        const Eigen::Vector3d t = truth.normal(p);
        const double len = t.norm();
        if (len > 0.0) {
          r.angle += w * std::acos(std::clamp(n.dot(t) / len, -1.0, 1.0)) * 180.0 / std::numbers::pi;
          r.angle_weight += w;
        }
      }
    }
  });
  const RegionSums truth_side =
      reduce(static_cast<std::size_t>(truth.samples.size()), [&](std::size_t k, RegionSums& s) {
        const Eigen::Vector3d p = truth.samples.points.col(static_cast<Index>(k));
        s[region_of(p)].add(truth.samples.weights[k], locator.closest(p).distance);
      });

  // Vertex distances weighted by vertex area (the secondary column).
  std::vector<double> vertex_area(static_cast<std::size_t>(positions.cols()), 0.0);
  for (const Triangle& t : triangles) {
    const double area =
        0.5 * (positions.col(t[1]) - positions.col(t[0])).cross(positions.col(t[2]) - positions.col(t[0])).norm();
    for (Index v : t) vertex_area[static_cast<std::size_t>(v)] += area / 3.0;
  }
  const RegionSums vertices = reduce(vertex_area.size(), [&](std::size_t i, RegionSums& s) {
    if (!(vertex_area[i] > 0.0)) return;
    const Eigen::Vector3d p = positions.col(static_cast<Index>(i));
    s[region_of(p)].add(vertex_area[i], truth.distance(p));
  });
  // The mesh's one-sided maximum also looks at the vertices: corners and spikes are where it usually
  // is, and random samples almost never land on them.
  for (std::size_t r = 0; r < 2; ++r) {
    if (mesh_side[r].weight > 0.0) mesh_side[r].max = std::max(mesh_side[r].max, vertices[r].max);
  }

  SurfaceAccuracy a;
  a.feature = finish(mesh_side[kFeature], truth_side[kFeature], truth.signed_distance, normals);
  a.smooth = finish(mesh_side[kSmooth], truth_side[kSmooth], truth.signed_distance, normals);
  Sums mesh_all = mesh_side[kFeature], truth_all = truth_side[kFeature];
  mesh_all.merge(mesh_side[kSmooth]);
  truth_all.merge(truth_side[kSmooth]);
  a.all = finish(mesh_all, truth_all, truth.signed_distance, normals);
  Sums all_vertices = vertices[kFeature];
  all_vertices.merge(vertices[kSmooth]);
  if (all_vertices.weight > 0.0) a.vertex_rms = std::sqrt(all_vertices.sq / all_vertices.weight);
  if (vertices[kFeature].weight > 0.0)
    a.feature_vertex_rms = std::sqrt(vertices[kFeature].sq / vertices[kFeature].weight);
  return a;
}

SurfaceAccuracy surface_accuracy(const Mesh& mesh, const SurfaceTruth& truth, const SurfaceMetricsOptions& options) {
  return surface_accuracy(mesh.positions, mesh.triangles, truth, options);
}

}  // namespace contourmesh
