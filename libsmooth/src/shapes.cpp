// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/shapes.h"

#include "contourmesh/smooth/errors.h"
#include "contourmesh/smooth/normals.h"

#include "contourmesh/internal/polygon2d.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <unordered_map>

namespace contourmesh {

Mesh make_icosphere(int subdivisions, double radius, const Eigen::Vector3d& center) {
  if (subdivisions < 0 || subdivisions > 10) throw InvalidInputError("icosphere subdivisions must be in [0, 10]");
  if (!(radius > 0.0)) throw InvalidInputError("icosphere radius must be > 0");
  const double p = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                                    {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  for (auto& x : v) x.normalize();
  std::vector<Triangle> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                             {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<Index, Index>, Index> midpoint;
    auto mid = [&](Index a, Index b) {
      const auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      const auto idx = static_cast<Index>(v.size() - 1);
      midpoint.emplace(key, idx);
      return idx;
    };
    std::vector<Triangle> next;
    next.reserve(f.size() * 4);
    for (const Triangle& t : f) {
      const Index a = mid(t[0], t[1]), b = mid(t[1], t[2]), c = mid(t[2], t[0]);
      next.push_back({t[0], a, c});
      next.push_back({t[1], b, a});
      next.push_back({t[2], c, b});
      next.push_back({a, b, c});
    }
    f.swap(next);
  }
  Mesh mesh;
  mesh.positions.resize(3, static_cast<Eigen::Index>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) mesh.positions.col(static_cast<Eigen::Index>(i)) = center + radius * v[i];
  mesh.triangles = std::move(f);
  return mesh;
}

Mesh make_cube(int n, double half) {
  if (n < 1) throw InvalidInputError("cube divisions must be >= 1");
  if (!(half > 0.0)) throw InvalidInputError("cube half size must be > 0");
  std::unordered_map<std::int64_t, Index> index_of;
  std::vector<Eigen::Vector3d> points;
  const std::int64_t m = n + 1;
  auto vertex = [&](const Eigen::Vector3i& lattice) {
    const std::int64_t key = (lattice[0] * m + lattice[1]) * m + lattice[2];
    auto it = index_of.find(key);
    if (it != index_of.end()) return it->second;
    points.push_back(lattice.cast<double>() * (2.0 * half / n) - Eigen::Vector3d::Constant(half));
    const auto idx = static_cast<Index>(points.size() - 1);
    index_of.emplace(key, idx);
    return idx;
  };
  std::vector<Triangle> tris;
  for (int a = 0; a < 3; ++a) {
    for (int side = 0; side < 2; ++side) {
      // (u, v) such that e_u x e_v points away from the cube on this face.
      const int u = side ? (a + 1) % 3 : (a + 2) % 3;
      const int w = side ? (a + 2) % 3 : (a + 1) % 3;
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          auto corner = [&](int di, int dj) {
            Eigen::Vector3i l;
            l[a] = side ? n : 0;
            l[u] = i + di;
            l[w] = j + dj;
            return vertex(l);
          };
          const Index p00 = corner(0, 0), p10 = corner(1, 0), p11 = corner(1, 1), p01 = corner(0, 1);
          tris.push_back({p00, p10, p11});
          tris.push_back({p00, p11, p01});
        }
      }
    }
  }
  Mesh mesh;
  mesh.positions.resize(3, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) mesh.positions.col(static_cast<Eigen::Index>(i)) = points[i];
  mesh.triangles = std::move(tris);
  return mesh;
}

namespace {

void check_spec(const ContourStackSpec& s) {
  if (!s.curve) throw InvalidInputError("contour stack: no curve given");
  if (s.slices < 2) throw InvalidInputError("contour stack: needs at least 2 slices, got " + std::to_string(s.slices));
  if (s.points_per_contour < 3) throw InvalidInputError("contour stack: needs at least 3 points per contour");
  if (!(s.slice_spacing > 0.0)) throw InvalidInputError("contour stack: slice spacing must be > 0");
}

}  // namespace

Mesh make_contour_stack(const ContourStackSpec& spec) {
  check_spec(spec);
  const int S = spec.slices;
  const int P = spec.points_per_contour;
  std::vector<Eigen::Vector2d> ring(static_cast<std::size_t>(P));
  for (int i = 0; i < P; ++i) ring[i] = spec.curve(static_cast<double>(i) / P);

  Mesh mesh;
  mesh.positions.resize(3, static_cast<Eigen::Index>(S) * P);
  mesh.slice_ids.resize(static_cast<std::size_t>(S) * P);
  mesh.contour_ids.assign(static_cast<std::size_t>(S) * P, 0);
  for (int k = 0; k < S; ++k) {
    for (int i = 0; i < P; ++i) {
      const Index v = k * P + i;
      mesh.positions.col(v) << ring[i].x(), ring[i].y(), spec.z0 + k * spec.slice_spacing;
      mesh.slice_ids[v] = k;
    }
  }
  const auto caps = detail::triangulate_polygon(ring);
  mesh.triangles.reserve(static_cast<std::size_t>(2) * (S + 1) * P + 2 * caps.size());
  auto band = [&](Index lower, Index upper) {  // first vertex of each ring
    for (int i = 0; i < P; ++i) {
      const Index a = lower + i, b = lower + (i + 1) % P, c = upper + (i + 1) % P, d = upper + i;
      mesh.triangles.push_back({a, b, c});
      mesh.triangles.push_back({a, c, d});
    }
  };
  for (int k = 0; k + 1 < S; ++k) band(k * P, (k + 1) * P);
  Index bottom = 0;
  Index top = (S - 1) * P;
  if (spec.end_caps == EndCaps::HalfSpacing) {
    // Copies half a spacing beyond both ends, joined by straight bands.
    mesh.positions.conservativeResize(3, static_cast<Eigen::Index>(S + 2) * P);
    mesh.slice_ids.resize(static_cast<std::size_t>(S + 2) * P, kNoId);
    mesh.contour_ids.resize(static_cast<std::size_t>(S + 2) * P, kNoId);
    bottom = S * P;
    const Index above = (S + 1) * P;
    for (int i = 0; i < P; ++i) {
      mesh.positions.col(bottom + i) << ring[i].x(), ring[i].y(), spec.z0 - 0.5 * spec.slice_spacing;
      mesh.positions.col(above + i) << ring[i].x(), ring[i].y(), spec.z0 + (S - 0.5) * spec.slice_spacing;
    }
    band(bottom, 0);
    band(top, above);
    top = above;
  }
  for (const auto& t : caps) {
    mesh.triangles.push_back({bottom + t[0], bottom + t[2], bottom + t[1]});  // bottom: faces -z
    mesh.triangles.push_back({top + t[0], top + t[1], top + t[2]});           // top: faces +z
  }
  return mesh;
}

ScalarField contour_stack_sdf(const ContourStackSpec& spec, int curve_samples) {
  check_spec(spec);
  std::vector<Eigen::Vector2d> poly(static_cast<std::size_t>(std::max(curve_samples, 3)));
  for (std::size_t i = 0; i < poly.size(); ++i) poly[i] = spec.curve(static_cast<double>(i) / poly.size());
  const double zc = spec.z0 + 0.5 * (spec.slices - 1) * spec.slice_spacing;
  const double extension = spec.end_caps == EndCaps::HalfSpacing ? 0.5 * spec.slice_spacing : 0.0;
  const double half = 0.5 * (spec.slices - 1) * spec.slice_spacing + extension;
  return [poly = std::move(poly), zc, half](const Eigen::Vector3d& p) {
    const double d2 = detail::polygon_signed_distance(poly, p.head<2>());
    const double dz = std::abs(p.z() - zc) - half;
    const double outside = std::hypot(std::max(d2, 0.0), std::max(dz, 0.0));
    return outside + std::min(std::max(d2, dz), 0.0);
  };
}

PlanarCurve ridge_circle_curve(double radius, double height, double half_width) {
  if (!(radius > 0.0) || !(height >= 0.0) || !(half_width > 0.0 && half_width < std::numbers::pi)) {
    throw InvalidInputError("ridge circle: need radius > 0, height >= 0, 0 < half_width < pi");
  }
  return [=](double t) {
    const double theta = 2.0 * std::numbers::pi * t;
    const double from_ridge = std::abs(std::remainder(theta, 2.0 * std::numbers::pi));
    const double r = radius + height * std::max(0.0, 1.0 - from_ridge / half_width);
    return Eigen::Vector2d(r * std::cos(theta), r * std::sin(theta));
  };
}

void add_noise(Mesh& mesh, const NoiseOptions& options) {
  if (!(options.sigma >= 0.0)) throw InvalidInputError("noise sigma must be >= 0");
  std::mt19937_64 rng(options.seed);
  std::normal_distribution<double> gauss(0.0, options.sigma);
  Eigen::Matrix3Xd normals;
  if (options.direction == NoiseDirection::Normal) normals = vertex_normals(mesh.positions, mesh.triangles);
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    switch (options.direction) {
      case NoiseDirection::Isotropic:
        for (int c = 0; c < 3; ++c) mesh.positions(c, i) += gauss(rng);
        break;
      case NoiseDirection::InPlane:
        mesh.positions(0, i) += gauss(rng);
        mesh.positions(1, i) += gauss(rng);
        break;
      case NoiseDirection::Normal: mesh.positions.col(i) += gauss(rng) * normals.col(i); break;
    }
  }
}

}  // namespace contourmesh
