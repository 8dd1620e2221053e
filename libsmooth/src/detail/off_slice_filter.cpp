// SPDX-License-Identifier: BSD-3-Clause
#include "detail/off_slice_filter.h"

#include "detail/parallel.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace contourmesh::detail {

namespace {

// The axis coordinates of the slice planes, ascending (one per slice id of a contour vertex: the mean).
std::vector<double> slice_levels(const ContourFrame& frame, const Eigen::Matrix3Xd& positions) {
  std::map<std::int32_t, std::pair<double, double>> sums;  // slice id -> (sum of heights, count)
  const Mesh& mesh = *frame.mesh;
  for (Index i = 0; i < static_cast<Index>(positions.cols()); ++i) {
    if (!frame.is_contour_vertex(i)) continue;
    auto& s = sums[mesh.slice_ids[static_cast<std::size_t>(i)]];
    s.first += frame.axis.dot(positions.col(i));
    s.second += 1.0;
  }
  std::vector<double> levels;
  levels.reserve(sums.size());
  for (const auto& [id, s] : sums) levels.push_back(s.first / s.second);
  std::sort(levels.begin(), levels.end());
  return levels;
}

// The heights a vertex starting at height h may take: its slab between two slice planes, a twentieth of
// a spacing inside, and within `reach` of h. Beyond the outer planes (end caps) only the plane bounds.
std::pair<double, double> height_bounds(const std::vector<double>& levels, double h, double spacing, double reach) {
  double lo = h - reach, hi = h + reach;
  const double margin = 0.05 * spacing;
  if (levels.empty()) return {lo, hi};
  const auto above = std::upper_bound(levels.begin(), levels.end(), h);
  if (above != levels.begin()) lo = std::max(lo, std::min(h, *(above - 1) + margin));
  if (above != levels.end()) hi = std::min(hi, std::max(h, *above - margin));
  return {lo, hi};
}

Eigen::Vector3d face_normal(const Eigen::Matrix3Xd& x, const Triangle& t, double* area = nullptr) {
  const Eigen::Vector3d c = (x.col(t[1]) - x.col(t[0])).cross(x.col(t[2]) - x.col(t[0]));
  const double len = c.norm();
  if (area) *area = 0.5 * len;
  return len > 0.0 ? Eigen::Vector3d(c / len) : Eigen::Vector3d::Zero();
}

// The vertices that move and the faces whose normals are filtered (those touching one).
struct Region {
  std::vector<Index> vertices, faces;
  std::vector<std::uint8_t> moves;  ///< per vertex of the mesh
};

Region select_region(const ContourFrame& frame, std::size_t num_faces, const OffSliceFilterOptions& options) {
  const MeshAdjacency& adj = frame.adjacency;
  const Index n = adj.num_vertices();
  Region r;
  r.moves.assign(static_cast<std::size_t>(n), 0);
  std::vector<std::uint8_t> active(num_faces, 0);
  const bool contour_moves = options.contour_max_move > 0.0;
  for (Index i = 0; i < n; ++i) {
    if ((!contour_moves && frame.is_contour_vertex(i)) || adj.valence(i) == 0) continue;
    r.vertices.push_back(i);
    r.moves[static_cast<std::size_t>(i)] = 1;
    for (Index f : adj.incident_faces(i)) active[static_cast<std::size_t>(f)] = 1;
  }
  for (std::size_t f = 0; f < num_faces; ++f) {
    if (active[f]) r.faces.push_back(static_cast<Index>(f));
  }
  return r;
}

// The neighbourhood of every filtered face in CSR: the faces sharing a vertex with it (itself included),
// each with its area times the spatial kernel (fixed while the normals are filtered: nothing moves then).
struct FaceRings {
  std::vector<Index> offsets, faces;
  std::vector<double> weights;
};

FaceRings face_rings(const MeshAdjacency& adj, const std::vector<Triangle>& triangles, const std::vector<Index>& faces,
                     const Eigen::Matrix3Xd& centroids, const Eigen::VectorXd& areas) {
  FaceRings rings;
  rings.offsets.assign(faces.size() + 1, 0);
  std::vector<Index> local;
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const Triangle& t = triangles[static_cast<std::size_t>(faces[k])];
    local.clear();
    for (int c = 0; c < 3; ++c) {
      for (Index g : adj.incident_faces(t[c])) local.push_back(g);
    }
    std::sort(local.begin(), local.end());
    local.erase(std::unique(local.begin(), local.end()), local.end());
    rings.faces.insert(rings.faces.end(), local.begin(), local.end());
    rings.offsets[k + 1] = static_cast<Index>(rings.faces.size());
  }
  // The spatial kernel's width: the mean distance between the centroids of neighbouring faces.
  double sum = 0.0;
  for (std::size_t k = 0; k < faces.size(); ++k) {
    for (Index r = rings.offsets[k]; r < rings.offsets[k + 1]; ++r) {
      sum += (centroids.col(rings.faces[static_cast<std::size_t>(r)]) - centroids.col(faces[k])).norm();
    }
  }
  const double sigma_s = sum > 0.0 ? sum / static_cast<double>(rings.faces.size()) : 1.0;
  const double inv_s = 1.0 / (2.0 * sigma_s * sigma_s);
  rings.weights.resize(rings.faces.size());
  for (std::size_t k = 0; k < faces.size(); ++k) {
    for (Index r = rings.offsets[k]; r < rings.offsets[k + 1]; ++r) {
      const Index g = rings.faces[static_cast<std::size_t>(r)];
      rings.weights[static_cast<std::size_t>(r)] =
          areas[g] * std::exp(-(centroids.col(g) - centroids.col(faces[k])).squaredNorm() * inv_s);
    }
  }
  return rings;
}

// Bilateral filtering of the normals of `faces` (Zheng et al. 2011, eq. 4), Jacobi style; the other
// faces' normals are read as they are.
void filter_normals(const std::vector<Index>& faces, const FaceRings& rings, const OffSliceFilterOptions& options,
                    Eigen::Matrix3Xd& normals) {
  const double sigma_r = 2.0 * std::sin(0.5 * options.sigma_angle_degrees * M_PI / 180.0);  // as |n_i - n_j|
  const double inv_r = 1.0 / (2.0 * sigma_r * sigma_r);
  Eigen::Matrix3Xd next = normals;
  for (int it = 0; it < options.normal_iterations; ++it) {
    parallel_chunks(faces.size(), 1024, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        const Index f = faces[k];
        Eigen::Vector3d acc = Eigen::Vector3d::Zero();
        for (Index r = rings.offsets[k]; r < rings.offsets[k + 1]; ++r) {
          const Index g = rings.faces[static_cast<std::size_t>(r)];
          // |n_g - n_f|^2 of unit normals; the range kernel in single precision (the hot spot).
          const double dr = 2.0 - 2.0 * normals.col(g).dot(normals.col(f));
          const auto range = static_cast<double>(std::exp(static_cast<float>(-dr * inv_r)));
          acc += rings.weights[static_cast<std::size_t>(r)] * range * normals.col(g);
        }
        const double len = acc.norm();
        if (len > 0.0) next.col(f) = acc / len;
      }
    });
    normals.swap(next);
  }
}

// The vertex update (eq. 6), Jacobi style: each moving vertex goes towards the planes of its faces with
// the filtered normals, within its bounds (see filter_off_slice_normals).
void update_vertices(const ContourFrame& frame, const std::vector<Triangle>& triangles, const Region& region,
                     const Eigen::Matrix3Xd& normals, const OffSliceFilterOptions& options,
                     const Eigen::Matrix3Xd& start, Eigen::Matrix3Xd& positions) {
  const MeshAdjacency& adj = frame.adjacency;
  const std::vector<double> levels = slice_levels(frame, start);
  const double spacing = frame.slice_spacing, reach = options.max_move * frame.slice_spacing;
  const Eigen::Vector3d& axis = frame.axis;
  Eigen::Matrix3Xd centroids(3, static_cast<Index>(triangles.size()));
  Eigen::Matrix3Xd updated(3, static_cast<Index>(region.vertices.size()));
  for (int it = 0; it < options.vertex_iterations; ++it) {
    parallel_chunks(region.faces.size(), 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        const Index f = region.faces[k];
        const Triangle& t = triangles[static_cast<std::size_t>(f)];
        centroids.col(f) = (positions.col(t[0]) + positions.col(t[1]) + positions.col(t[2])) / 3.0;
      }
    });
    parallel_chunks(region.vertices.size(), 2048, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        const Index i = region.vertices[k];
        Eigen::Vector3d step = Eigen::Vector3d::Zero();
        const auto incident = adj.incident_faces(i);
        for (Index f : incident) step += normals.col(f) * normals.col(f).dot(centroids.col(f) - positions.col(i));
        step /= static_cast<double>(incident.size());
        const Eigen::Vector3d x0 = start.col(i);
        Eigen::Vector3d d;
        if (frame.is_contour_vertex(i)) {
          // A contour vertex stays in its slice plane, within the fidelity bound of where it was.
          step -= axis * axis.dot(step);
          d = positions.col(i) + step - x0;
          if (d.norm() > options.contour_max_move) d *= options.contour_max_move / d.norm();
        } else {
          if (options.motion == OffSliceMotion::AlongAxis) step = axis * axis.dot(step);
          // Within `reach` of the start, and in the start's slab.
          d = positions.col(i) + step - x0;
          if (d.norm() > reach) d *= reach / d.norm();
          const double h0 = axis.dot(x0);
          const auto [lo, hi] = height_bounds(levels, h0, spacing, reach);
          const double h = std::clamp(h0 + axis.dot(d), lo, hi);
          d += axis * (h - h0 - axis.dot(d));
        }
        updated.col(static_cast<Index>(k)) = x0 + d;
      }
    });
    for (std::size_t k = 0; k < region.vertices.size(); ++k) {
      positions.col(region.vertices[k]) = updated.col(static_cast<Index>(k));
    }
  }
}

// A face that turned over (its normal against its unfiltered one) gets its moving vertices back, until
// none does.
void undo_turned_faces(const std::vector<Triangle>& triangles, const Region& region,
                       const Eigen::Matrix3Xd& initial_normals, const Eigen::Matrix3Xd& start,
                       Eigen::Matrix3Xd& positions) {
  for (int round = 0; round < 8; ++round) {
    bool any = false;
    for (Index f : region.faces) {
      const Triangle& t = triangles[static_cast<std::size_t>(f)];
      if (initial_normals.col(f).isZero() || face_normal(positions, t).dot(initial_normals.col(f)) > 0.0) continue;
      for (int c = 0; c < 3; ++c) {
        const Index v = t[c];
        if (region.moves[static_cast<std::size_t>(v)] && positions.col(v) != start.col(v)) {
          positions.col(v) = start.col(v);
          any = true;
        }
      }
    }
    if (!any) break;
  }
}

}  // namespace

std::size_t filter_off_slice_normals(const ContourFrame& frame, const std::vector<Triangle>& triangles,
                                     const OffSliceFilterOptions& options, Eigen::Matrix3Xd& positions) {
  if (options.filter == OffSliceFilter::None) return 0;
  const Region region = select_region(frame, triangles.size(), options);
  if (region.vertices.empty()) return 0;

  // Face normals, areas and centroids of the whole mesh.
  const auto nf = static_cast<Index>(triangles.size());
  Eigen::Matrix3Xd normals(3, nf), centroids(3, nf);
  Eigen::VectorXd areas(nf);
  for (Index f = 0; f < nf; ++f) {
    const Triangle& t = triangles[static_cast<std::size_t>(f)];
    double a = 0.0;
    normals.col(f) = face_normal(positions, t, &a);
    areas[f] = a;
    centroids.col(f) = (positions.col(t[0]) + positions.col(t[1]) + positions.col(t[2])) / 3.0;
  }
  const Eigen::Matrix3Xd initial_normals = normals;
  const Eigen::Matrix3Xd start = positions;

  filter_normals(region.faces, face_rings(frame.adjacency, triangles, region.faces, centroids, areas), options,
                 normals);
  update_vertices(frame, triangles, region, normals, options, start, positions);
  undo_turned_faces(triangles, region, initial_normals, start, positions);
  std::size_t moved = 0;
  for (Index i : region.vertices) moved += positions.col(i) != start.col(i) ? 1 : 0;
  return moved;
}

}  // namespace contourmesh::detail
