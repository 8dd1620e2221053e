// SPDX-License-Identifier: BSD-3-Clause
// The original seven phantoms: bone-like solids with ridges and corners, branching, several objects and
// a cavity.
#include "detail/phantom_shapes.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <vector>

namespace contourmesh::detail {

ShapeBuild build_ridge_box() {
  // Pentagonal prism: the block [-20,20] x [-15,15] under the roof y + 0.6|x| <= 15, z in [-25, 25].
  const std::vector<Vec2> section = {{-20.0, -15.0}, {20.0, -15.0}, {20.0, 3.0}, {0.0, 15.0}, {-20.0, 3.0}};
  constexpr double kHalfLength = 25.0;
  ShapeBuild s;
  s.sdf = [section](const Vec3& p) {
    return sd_extrude(polygon_signed_distance(section, p.head<2>()), p.z(), kHalfLength);
  };
  s.bounds = box_of({-20.0, -15.0, -kHalfLength}, {20.0, 15.0, kHalfLength});
  s.volume = polygon_signed_area(section) * 2.0 * kHalfLength;  // 960 * 50 = 48000 mm^3
  for (std::size_t i = 0, j = section.size() - 1; i < section.size(); j = i, ++i) {
    const Vec3 a(section[i].x(), section[i].y(), 0.0);
    const Vec3 b(section[j].x(), section[j].y(), 0.0);
    sample_segment(a - kHalfLength * Vec3::UnitZ(), a + kHalfLength * Vec3::UnitZ(), s.sdf, s.features);
    for (double z : {-kHalfLength, kHalfLength}) {
      sample_segment(a + z * Vec3::UnitZ(), b + z * Vec3::UnitZ(), s.sdf, s.features);
    }
  }
  return s;
}

ShapeBuild build_femur() {
  std::vector<Primitive> parts;
  // Shaft: a capsule along z, radius 12, z in [-46, 46].
  const Vec3 shaft_a(0.0, 0.0, -34.0), shaft_b(0.0, 0.0, 34.0);
  parts.push_back(
      {[=](const Vec3& p) { return sd_capsule(p, shaft_a, shaft_b, 12.0); }, capsule_box(shaft_a, shaft_b, 12.0)});
  // Posterior ridge (linea aspera): a triangular prism along z whose apex stands 4 mm off the shaft.
  const std::vector<Vec2> ridge = {{-3.5, 9.0}, {3.5, 9.0}, {0.0, 16.0}};
  constexpr double kRidgeHalf = 25.0;
  parts.push_back(
      {[ridge](const Vec3& p) { return sd_extrude(polygon_signed_distance(ridge, p.head<2>()), p.z(), kRidgeHalf); },
       box_of({-3.5, 9.0, -kRidgeHalf}, {3.5, 16.0, kRidgeHalf})});
  // Neck (capsule, radius 8, about 126 degrees to the shaft) and spherical head (radius 15).
  const Vec3 neck_a(0.0, 0.0, 28.0), head_centre(-28.0, 0.0, 48.0);
  parts.push_back(
      {[=](const Vec3& p) { return sd_capsule(p, neck_a, head_centre, 8.0); }, capsule_box(neck_a, head_centre, 8.0)});
  parts.push_back(
      {[=](const Vec3& p) { return sd_sphere(p, head_centre, 15.0); }, capsule_box(head_centre, head_centre, 15.0)});
  // Two condyles (spheres, radius 13) at the bottom, 5 mm apart.
  for (double x : {-15.5, 15.5}) {
    const Vec3 c(x, 3.0, -44.0);
    parts.push_back({[=](const Vec3& p) { return sd_sphere(p, c, 13.0); }, capsule_box(c, c, 13.0)});
  }
  ShapeBuild s;
  s.sdf = union_of(parts);
  for (const Primitive& part : parts) s.bounds.extend(part.bounds);
  union_creases(parts, s.sdf, s.features);
  // The ridge's own edges: the apex line and the end triangles (the parts outside the shaft).
  for (std::size_t i = 0, j = ridge.size() - 1; i < ridge.size(); j = i, ++i) {
    const Vec3 a(ridge[i].x(), ridge[i].y(), 0.0);
    const Vec3 b(ridge[j].x(), ridge[j].y(), 0.0);
    sample_segment(a - kRidgeHalf * Vec3::UnitZ(), a + kRidgeHalf * Vec3::UnitZ(), s.sdf, s.features);
    for (double z : {-kRidgeHalf, kRidgeHalf}) {
      sample_segment(a + z * Vec3::UnitZ(), b + z * Vec3::UnitZ(), s.sdf, s.features);
    }
  }
  return s;
}

ShapeBuild build_pelvis() {
  // Cross-section in (r, z) with a sharp crest at (41, 15); revolved about the ring axis, which is
  // tilted by 22 degrees about x.
  const std::vector<Vec2> section = {{32.0, -9.0}, {44.0, -9.0}, {47.0, 0.0}, {41.0, 15.0}, {33.0, 3.0}};
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(22.0 * kPi / 180.0, Vec3::UnitX()).toRotationMatrix();
  ShapeBuild s;
  s.sdf = [section, rotation](const Vec3& p) {
    const Vec3 q = rotation.transpose() * p;
    return polygon_signed_distance(section, Vec2(length2(q.x(), q.y()), q.z()));
  };
  // Pappus: volume = area * 2 pi * (r of the centroid).
  double moment = 0.0;  // integral of r over the section
  for (std::size_t i = 0, j = section.size() - 1; i < section.size(); j = i, ++i) {
    const double cross = section[j].x() * section[i].y() - section[i].x() * section[j].y();
    moment += (section[j].x() + section[i].x()) * cross / 6.0;
  }
  s.volume = 2.0 * kPi * std::abs(moment);
  s.surface_components = 1;
  s.euler_characteristic = 0;
  const Vec3 axis = rotation * Vec3::UnitZ();
  for (const Vec2& v : section) {
    const Vec3 centre = rotation * Vec3(0.0, 0.0, v.y());
    // The bounding box of a circle: centre +- r sqrt(1 - axis_k^2) along each axis k.
    const Vec3 extent = v.x() * (Vec3::Ones() - axis.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt();
    s.bounds.extend(centre - extent);
    s.bounds.extend(centre + extent);
    sample_closed_curve(
        [&](double t) { return Vec3(rotation * Vec3(v.x() * std::cos(t), v.x() * std::sin(t), v.y())); }, v.x(), s.sdf,
        s.features);
  }
  return s;
}

ShapeBuild build_skull() {
  // A 6 mm ellipsoidal shell, cut open by the plane z = -35, with two orbits drilled through the front
  // (-y): cylinders of radius 9 along y that end inside the cranial cavity.
  const Ellipsoid outer = SkullGeometry::outer(), inner = SkullGeometry::inner();
  constexpr double kCut = SkullGeometry::kCut;
  constexpr double kOrbitRadius = SkullGeometry::kOrbitRadius, kOrbitZ = SkullGeometry::kOrbitZ,
                   kOrbitX = SkullGeometry::kOrbitX;
  constexpr double kOrbitYMid = SkullGeometry::kOrbitYMid, kOrbitHalf = SkullGeometry::kOrbitHalf;
  auto orbit = [=](const Vec3& p, double x) {
    return sd_extrude(length2(p.x() - x, p.z() - kOrbitZ) - kOrbitRadius, p.y() - kOrbitYMid, kOrbitHalf);
  };
  ShapeBuild s;
  s.sdf = [=](const Vec3& p) {
    // max(outer, -inner, cut, -orbits); an ellipsoid term is computed exactly only when its cheap upper
    // bound does not rule it out of the maximum (the result is the same, at half the cost).
    double d = std::max({kCut - p.z(), -orbit(p, kOrbitX), -orbit(p, -kOrbitX)});
    const auto [outer_lo, outer_hi] = outer.distance_bounds(p);
    const auto [inner_lo, inner_hi] = inner.distance_bounds(p);
    const double floor = std::max({d, outer_lo, -inner_hi});
    if (outer_hi >= floor) d = std::max(d, outer.signed_distance(p));
    if (-inner_lo >= floor) d = std::max(d, -inner.signed_distance(p));
    return d;
  };
  s.bounds = box_of({-54.0, -60.0, kCut}, {54.0, 60.0, -15.0 + 56.0});
  s.surface_components = 1;
  s.euler_characteristic = -2;
  // The rim: the two ellipses where the cut plane meets the outer and inner ellipsoids.
  for (const Ellipsoid* e : {&outer, &inner}) {
    const double t = (kCut - e->centre.z()) / e->axes.z();
    const double k = std::sqrt(1.0 - t * t);
    const double a = e->axes.x() * k, b = e->axes.y() * k;
    sample_closed_curve([&](double u) { return Vec3(a * std::cos(u), b * std::sin(u), kCut); }, std::max(a, b), s.sdf,
                        s.features);
  }
  // The orbit rims: each cylinder against each ellipsoid, on the front (y < 0).
  for (double x : {-kOrbitX, kOrbitX}) {
    for (const Ellipsoid* e : {&outer, &inner}) {
      auto rim = [&, x](double u) {
        const double px = x + kOrbitRadius * std::cos(u);
        const double pz = kOrbitZ + kOrbitRadius * std::sin(u);
        const double rx = (px - e->centre.x()) / e->axes.x();
        const double rz = (pz - e->centre.z()) / e->axes.z();
        return Vec3(px, e->centre.y() - e->axes.y() * std::sqrt(std::max(0.0, 1.0 - rx * rx - rz * rz)), pz);
      };
      sample_closed_curve(rim, 3.0 * kOrbitRadius, s.sdf, s.features);
    }
  }
  return s;
}

ShapeBuild build_branch() {
  std::vector<Primitive> parts;
  // Trunk: radius 10, flat bottom at z = -45, rounded top centred at z = -5.
  const Vec3 trunk_a(0.0, 0.0, -60.0), trunk_b(0.0, 0.0, -5.0);
  constexpr double kBottom = -45.0;
  parts.push_back({[=](const Vec3& p) { return std::max(sd_capsule(p, trunk_a, trunk_b, 10.0), kBottom - p.z()); },
                   box_of({-10.0, -10.0, kBottom}, {10.0, 10.0, 5.0})});
  // Two limbs (capsules, radius 8) from the top of the trunk up and out to rounded tips.
  for (double x : {-22.0, 22.0}) {
    const Vec3 tip(x, 0.0, 40.0);
    parts.push_back({[=](const Vec3& p) { return sd_capsule(p, trunk_b, tip, 8.0); }, capsule_box(trunk_b, tip, 8.0)});
  }
  ShapeBuild s;
  s.sdf = union_of(parts);
  s.bounds = box_of({-10.0, -10.0, kBottom}, {10.0, 10.0, 5.0});
  s.bounds.extend(parts[1].bounds);
  s.bounds.extend(parts[2].bounds);
  union_creases(parts, s.sdf, s.features);
  sample_closed_curve([&](double u) { return Vec3(10.0 * std::cos(u), 10.0 * std::sin(u), kBottom); }, 10.0, s.sdf,
                      s.features);
  return s;
}

ShapeBuild build_two_objects() {
  // A circular cylinder (radius 14, z in [-30, 30]) and an elliptic prism (semi-axes 10 x 16,
  // z in [-25, 25]), 18 mm apart.
  const Vec2 cylinder_centre(-22.0, 0.0);
  constexpr double kRadius = 14.0, kCylinderHalf = 30.0;
  const Ellipse ellipse{Vec2(20.0, 0.0), Vec2(10.0, 16.0)};
  constexpr double kPrismHalf = 25.0;
  ShapeBuild s;
  s.sdf = [=](const Vec3& p) {
    const double a = sd_extrude((p.head<2>() - cylinder_centre).norm() - kRadius, p.z(), kCylinderHalf);
    const double b = sd_extrude(ellipse.signed_distance(p.head<2>()), p.z(), kPrismHalf);
    return std::min(a, b);
  };
  s.bounds = box_of({-36.0, -16.0, -kCylinderHalf}, {30.0, 16.0, kCylinderHalf});
  s.volume = kPi * kRadius * kRadius * 2.0 * kCylinderHalf + kPi * ellipse.axes.prod() * 2.0 * kPrismHalf;
  s.surface_components = 2;
  s.euler_characteristic = 4;
  for (double z : {-kCylinderHalf, kCylinderHalf}) {
    sample_closed_curve(
        [&](double u) { return Vec3(cylinder_centre.x() + kRadius * std::cos(u), kRadius * std::sin(u), z); }, kRadius,
        s.sdf, s.features);
  }
  for (double z : {-kPrismHalf, kPrismHalf}) {
    sample_closed_curve(
        [&](double u) {
          return Vec3(ellipse.centre.x() + ellipse.axes.x() * std::cos(u), ellipse.axes.y() * std::sin(u), z);
        },
        ellipse.axes.maxCoeff(), s.sdf, s.features);
  }
  return s;
}

ShapeBuild build_cavity() {
  // A capped cylinder (radius 28, z in [-30, 30]) with a closed spherical cavity (radius 12) inside.
  constexpr double kRadius = 28.0, kHalf = 30.0, kCavityRadius = 12.0;
  const Vec3 cavity_centre(4.0, -3.0, 2.0);
  ShapeBuild s;
  s.sdf = [=](const Vec3& p) {
    const double solid = sd_extrude(p.head<2>().norm() - kRadius, p.z(), kHalf);
    return std::max(solid, -sd_sphere(p, cavity_centre, kCavityRadius));
  };
  s.bounds = box_of({-kRadius, -kRadius, -kHalf}, {kRadius, kRadius, kHalf});
  s.volume = kPi * kRadius * kRadius * 2.0 * kHalf - 4.0 / 3.0 * kPi * std::pow(kCavityRadius, 3);
  s.surface_components = 2;
  s.euler_characteristic = 4;
  for (double z : {-kHalf, kHalf}) {
    sample_closed_curve([&](double u) { return Vec3(kRadius * std::cos(u), kRadius * std::sin(u), z); }, kRadius, s.sdf,
                        s.features);
  }
  return s;
}

}  // namespace contourmesh::detail
