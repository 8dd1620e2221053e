// SPDX-License-Identifier: BSD-3-Clause
// The phantoms of the failure classes of contour stacks: flat faces nearly parallel to the slices, sharp
// ridges lying within a slice plane, and end faces on a slice centre or half-way between two. Where a
// claim depends on the slice grid it is for render_phantom's default spacing (0.7, 0.7, 2) and margin
// (6 mm): the voxel slice centres are then at z = c + 2j for the centre c of the z range of the bounds
// and integer j when the number of slices is odd, at c + 1 + 2j when it is even.
#include "detail/phantom_shapes.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <vector>

namespace contourmesh::detail {

namespace {

double degrees(double d) { return d * kPi / 180.0; }

Box3 bounds_of(const std::vector<Vec3>& points) {
  Box3 box;
  for (const Vec3& p : points) box.extend(p);
  return box;
}

}  // namespace

ShapeBuild build_tilted_box() {
  // A 70 x 50 x 20 mm slab whose large faces are 4 degrees off the slice planes, with one end bevelled
  // by a face 15 degrees off them. In its own frame (u along the 70 mm, w along the 50 mm, v its
  // thickness) it is a pentagonal prism along w: the rectangle [-35, 35] x [-10, 10] in (u, v) with the
  // corner (35, 10) cut over 25 mm of u. The frame is tilted by 4 degrees about a horizontal axis 60
  // degrees from u (so u rises 3.5 and w 2 degrees across the slices: every edge is oblique to the slice
  // planes) and turned 20 degrees about z (oblique to the pixel rows too).
  constexpr double kHalfU = 35.0, kHalfV = 10.0, kHalfW = 25.0, kBevel = 25.0;
  const Eigen::Matrix3d rotation =
      (Eigen::AngleAxisd(degrees(20.0), Vec3::UnitZ()) *
       Eigen::AngleAxisd(degrees(4.0), Vec3(std::cos(degrees(60.0)), std::sin(degrees(60.0)), 0.0)))
          .toRotationMatrix();
  const Vec3 u = rotation.col(0), w = rotation.col(1), v = rotation.col(2);
  // The bevel's normal in the frame is (sin a, 0, cos a) in (u, w, v) order, rotated: choose a so that it
  // makes 15 degrees with z. rotation(2, 0) sin a + rotation(2, 2) cos a = cos 15.
  const double rho = std::hypot(rotation(2, 0), rotation(2, 2));
  const double phi = std::atan2(rotation(2, 0), rotation(2, 2));
  const double a = phi + std::acos(std::cos(degrees(15.0)) / rho);
  const double drop = kBevel * std::tan(a);  // how far the bevel comes down the end face
  const std::vector<Vec2> section = {
      {-kHalfU, -kHalfV}, {kHalfU, -kHalfV}, {kHalfU, kHalfV - drop}, {kHalfU - kBevel, kHalfV}, {-kHalfU, kHalfV}};
  ShapeBuild s;
  s.sdf = [=](const Vec3& p) {
    const Vec3 q = rotation.transpose() * p;
    return sd_extrude(polygon_signed_distance(section, Vec2(q.x(), q.z())), q.y(), kHalfW);
  };
  std::vector<Vec3> corners;
  for (const Vec2& c : section) {
    for (double t : {-kHalfW, kHalfW}) corners.push_back(c.x() * u + c.y() * v + t * w);
  }
  s.bounds = bounds_of(corners);
  s.volume = polygon_signed_area(section) * 2.0 * kHalfW;
  sample_prism_edges(section, Vec3::Zero(), u, v, w, kHalfW, s.sdf, s.features);
  return s;
}

ShapeBuild build_in_slice_ridge() {
  // A prism lying across the slice axis: its section in (y', z) is a roof with two ridges and a valley
  // between them, extruded 50 mm along x'; (x', y') is (x, y) turned by -25 degrees about z, so the ridges
  // are oblique to the pixel rows but every long edge stays at one z, within a slice plane. The bounds
  // span z in [-15, 15]: with the default grid the slice centres are the even z, so ridge A (z = 10),
  // the valley (z = 4) and the edge at z = 2 lie on slice centres, and ridge B (z = 15, the top), the
  // edge at z = 3 and the bottom (z = -15) half-way between two.
  const std::vector<Vec2> section = {{-24.0, -15.0}, {24.0, -15.0}, {24.0, 2.0}, {12.0, 10.0},
                                     {2.0, 4.0},     {-10.0, 15.0}, {-24.0, 3.0}};
  constexpr double kHalfLength = 25.0;
  const double turn = degrees(25.0);
  const Vec3 along(std::cos(turn), std::sin(turn), 0.0);    // x'
  const Vec3 across(-std::sin(turn), std::cos(turn), 0.0);  // y'
  ShapeBuild s;
  s.sdf = [=](const Vec3& p) {
    return sd_extrude(polygon_signed_distance(section, Vec2(across.dot(p), p.z())), along.dot(p), kHalfLength);
  };
  std::vector<Vec3> corners;
  for (const Vec2& c : section) {
    for (double t : {-kHalfLength, kHalfLength}) corners.push_back(c.x() * across + c.y() * Vec3::UnitZ() + t * along);
  }
  s.bounds = bounds_of(corners);
  s.volume = polygon_signed_area(section) * 2.0 * kHalfLength;
  sample_prism_edges(section, Vec3::Zero(), across, Vec3::UnitZ(), along, kHalfLength, s.sdf, s.features);
  return s;
}

ShapeBuild build_end_face_on_slice() {
  // Two objects side by side. A cylinder (radius 14 about (-20, 0), z in [-15, 13]) and a box (26 x 20 mm
  // turned by 30 degrees about z, centred at (20, 0), z in [-20, 20]). The bounds span z in [-20, 20]:
  // with the default grid the slice centres are the odd z, so both of the cylinder's end faces lie
  // exactly on a slice centre (its end slices are half bone: the partial-volume iso-level) and both of
  // the box's half-way between two slices.
  const Vec2 cylinder_centre(-20.0, 0.0);
  constexpr double kRadius = 14.0, kBottom = -15.0, kTop = 13.0;
  const Vec2 box_centre(20.0, 0.0);
  constexpr double kBoxHalf = 20.0;
  const double turn = degrees(30.0);
  const Vec2 bu(std::cos(turn), std::sin(turn)), bv(-std::sin(turn), std::cos(turn));
  std::vector<Vec2> rectangle;  // in the world's (x, y)
  for (const Vec2& c : {Vec2(-13.0, -10.0), Vec2(13.0, -10.0), Vec2(13.0, 10.0), Vec2(-13.0, 10.0)}) {
    rectangle.push_back(box_centre + c.x() * bu + c.y() * bv);
  }
  ShapeBuild s;
  s.sdf = [=](const Vec3& p) {
    const double cylinder = sd_extrude((p.head<2>() - cylinder_centre).norm() - kRadius, p.z() - 0.5 * (kBottom + kTop),
                                       0.5 * (kTop - kBottom));
    const double box = sd_extrude(polygon_signed_distance(rectangle, p.head<2>()), p.z(), kBoxHalf);
    return std::min(cylinder, box);  // disjoint solids: exact
  };
  s.bounds = box_of(Vec3(cylinder_centre.x() - kRadius, -kRadius, kBottom),
                    Vec3(cylinder_centre.x() + kRadius, kRadius, kTop));
  for (const Vec2& c : rectangle) {
    for (double z : {-kBoxHalf, kBoxHalf}) s.bounds.extend(Vec3(c.x(), c.y(), z));
  }
  s.volume = kPi * kRadius * kRadius * (kTop - kBottom) + 26.0 * 20.0 * 2.0 * kBoxHalf;
  s.surface_components = 2;
  s.euler_characteristic = 4;
  for (double z : {kBottom, kTop}) {
    sample_closed_curve(
        [&](double t) {
          return Vec3(cylinder_centre.x() + kRadius * std::cos(t), cylinder_centre.y() + kRadius * std::sin(t), z);
        },
        kRadius, s.sdf, s.features);
  }
  std::vector<Vec2> local;
  for (const Vec2& c : rectangle) local.push_back(c - box_centre);
  sample_prism_edges(local, Vec3(box_centre.x(), box_centre.y(), 0.0), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(),
                     kBoxHalf, s.sdf, s.features);
  return s;
}

}  // namespace contourmesh::detail
