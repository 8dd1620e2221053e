// SPDX-License-Identifier: BSD-3-Clause
// The phantoms of the contour stacks' failure classes (tilted-box, in-slice-ridge, end-face-on-slice):
// their volume, their sharp edges, the tilt of the tilted box's faces and the slice alignment that
// each one claims for the default volume grid.
#include "contourmesh/reconstruct/phantom.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace contourmesh {
namespace {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

using std::numbers::pi;

double degrees(double d) { return d * pi / 180.0; }

// Stratified Monte Carlo: one uniformly random point in each cube of side h over the bounds.
double integrated_volume(const Phantom& p, double h) {
  const Vec3 lo = p.bounds.min() - Vec3::Constant(0.5);
  const Vec3 hi = p.bounds.max() + Vec3::Constant(0.5);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> jitter(0.0, h);
  std::int64_t inside = 0;
  for (double z = lo.z(); z < hi.z(); z += h) {
    for (double y = lo.y(); y < hi.y(); y += h) {
      for (double x = lo.x(); x < hi.x(); x += h) {
        inside += p.sdf(Vec3(x + jitter(rng), y + jitter(rng), z + jitter(rng))) < 0.0 ? 1 : 0;
      }
    }
  }
  return static_cast<double>(inside) * h * h * h;
}

// Where the segment from `inside` to `outside` crosses the surface (bisection).
Vec3 crossing(const Phantom& p, Vec3 inside, Vec3 outside) {
  for (int i = 0; i < 80; ++i) {
    const Vec3 mid = 0.5 * (inside + outside);
    (p.sdf(mid) < 0.0 ? inside : outside) = mid;
  }
  return 0.5 * (inside + outside);
}

// Every point of the segment ab is on the surface and within 0.3 mm of a feature point.
void expect_edge_covered(const Phantom& p, const Vec3& a, const Vec3& b, const std::string& what) {
  const int steps = std::max(2, static_cast<int>(std::ceil((b - a).norm() / 0.05)));
  for (int i = 0; i <= steps; ++i) {
    const Vec3 q = a + (b - a) * (static_cast<double>(i) / steps);
    ASSERT_LT(std::abs(p.sdf(q)), 1e-6) << what << " at " << q.transpose() << " is not on the surface";
    ASSERT_LE(distance_to_features(p, q), 0.3) << what << " at " << q.transpose();
  }
}

// The edges of a polygonal section (in the plane spanned by u and v through `origin`) extruded along
// `axis` over |t| <= half.
void expect_prism_edges_covered(const Phantom& p, const std::vector<Vec2>& section, const Vec3& origin, const Vec3& u,
                                const Vec3& v, const Vec3& axis, double half, const std::string& what) {
  for (std::size_t i = 0, j = section.size() - 1; i < section.size(); j = i, ++i) {
    const Vec3 a = origin + section[i].x() * u + section[i].y() * v;
    const Vec3 b = origin + section[j].x() * u + section[j].y() * v;
    expect_edge_covered(p, a - half * axis, a + half * axis, what + " lateral edge " + std::to_string(i));
    for (double t : {-half, half})
      expect_edge_covered(p, a + t * axis, b + t * axis, what + " end edge " + std::to_string(i));
  }
}

// The voxel slice centres of the default volume grid, from the rendered volume's own geometry.
std::vector<double> default_slice_centres(const Phantom& p) {
  const PhantomVolumeOptions options;
  const CtImage::Pointer image = render_phantom(p, options);
  std::vector<double> z;
  for (std::size_t k = 0; k < image->GetLargestPossibleRegion().GetSize()[2]; ++k) {
    z.push_back(image->GetOrigin()[2] + static_cast<double>(k) * image->GetSpacing()[2]);
  }
  return z;
}

double distance_to_nearest(const std::vector<double>& centres, double z) {
  double best = 1e9;
  for (double c : centres) best = std::min(best, std::abs(c - z));
  return best;
}

TEST(PhantomSliceShapes, VolumesMatchNumericIntegration) {
  for (PhantomShape shape : {PhantomShape::TiltedBox, PhantomShape::InSliceRidge, PhantomShape::EndFaceOnSlice}) {
    SCOPED_TRACE(std::string(to_string(shape)));
    const Phantom p = make_phantom(shape);
    EXPECT_NEAR(integrated_volume(p, 0.5), p.volume, 1e-3 * p.volume);
  }
  // The analytic values themselves.
  EXPECT_NEAR(make_phantom(PhantomShape::InSliceRidge).volume, 1102.0 * 50.0, 1e-9);  // section area 1102 mm^2
  EXPECT_NEAR(make_phantom(PhantomShape::EndFaceOnSlice).volume, pi * 14.0 * 14.0 * 28.0 + 26.0 * 20.0 * 40.0, 1e-9);
}

// tilted-box: the large faces 4 degrees and the bevel 15 degrees off the slice planes; its 15 edges
// (found from the surface itself) sampled as features, the faces' middles not.
TEST(PhantomSliceShapes, TiltedBoxFacesAndEdges) {
  const Phantom p = make_phantom(PhantomShape::TiltedBox);
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(degrees(20.0), Vec3::UnitZ()) *
                             Eigen::AngleAxisd(degrees(4.0), Vec3(std::cos(pi / 3.0), std::sin(pi / 3.0), 0.0)))
                                .toRotationMatrix();
  const Vec3 u = r.col(0), w = r.col(1), v = r.col(2);
  auto tilt = [&](const Vec3& q) { return std::acos(std::abs(p.normal(q).z())) * 180.0 / pi; };
  const Vec3 top = crossing(p, -10.0 * u, -10.0 * u + 12.0 * v);
  const Vec3 bottom = crossing(p, -10.0 * u, -10.0 * u - 12.0 * v);
  EXPECT_NEAR((top - bottom).norm(), 20.0, 1e-9);
  EXPECT_NEAR(tilt(top), 4.0, 1e-5);
  EXPECT_NEAR(tilt(bottom), 4.0, 1e-5);
  EXPECT_GT(distance_to_features(p, top), 9.0);
  // The bevel: two points of it, then the line in the (u, v) frame through them.
  const Vec3 b1 = crossing(p, 15.0 * u, 15.0 * u + 12.0 * v);
  const Vec3 b2 = crossing(p, 30.0 * u, 30.0 * u + 12.0 * v);
  EXPECT_NEAR(tilt(b1), 15.0, 1e-5);
  EXPECT_NEAR(tilt(b2), 15.0, 1e-5);
  const double slope = (b2 - b1).dot(v) / (b2 - b1).dot(u);  // dv/du < 0
  const double v_at_10 = b1.dot(v) + slope * (10.0 - b1.dot(u));
  EXPECT_NEAR(v_at_10, 10.0, 1e-6) << "the bevel starts 25 mm from the end";
  const double drop = 10.0 - (b1.dot(v) + slope * (35.0 - b1.dot(u)));
  EXPECT_GT(drop, 3.0);
  EXPECT_LT(drop, 15.0);
  // Every edge oblique to the slice planes: none runs at constant z.
  const std::vector<Vec2> section = {{-35.0, -10.0}, {35.0, -10.0}, {35.0, 10.0 - drop}, {10.0, 10.0}, {-35.0, 10.0}};
  for (std::size_t i = 0, j = section.size() - 1; i < section.size(); j = i, ++i) {
    const Vec3 edge = (section[i].x() - section[j].x()) * u + (section[i].y() - section[j].y()) * v;
    EXPECT_GT(std::abs(edge.normalized().z()), std::sin(degrees(1.0))) << "end edge " << i;
  }
  EXPECT_GT(std::abs(w.z()), std::sin(degrees(1.0))) << "lateral edges";
  expect_prism_edges_covered(p, section, Vec3::Zero(), u, v, w, 25.0, "tilted-box");
}

// in-slice-ridge: the ridges and every long edge lie at one z; ridge A on a slice centre of the default
// grid and ridge B (the top) half-way between two.
TEST(PhantomSliceShapes, InSliceRidgeEdgesAndAlignment) {
  const Phantom p = make_phantom(PhantomShape::InSliceRidge);
  const std::vector<Vec2> section = {{-24.0, -15.0}, {24.0, -15.0}, {24.0, 2.0}, {12.0, 10.0},
                                     {2.0, 4.0},     {-10.0, 15.0}, {-24.0, 3.0}};
  const Vec3 along(std::cos(degrees(25.0)), std::sin(degrees(25.0)), 0.0);
  const Vec3 across(-along.y(), along.x(), 0.0);
  expect_prism_edges_covered(p, section, Vec3::Zero(), across, Vec3::UnitZ(), along, 25.0, "in-slice-ridge");
  EXPECT_NEAR(p.bounds.min().z(), -15.0, 1e-12);
  EXPECT_NEAR(p.bounds.max().z(), 15.0, 1e-12);
  // The ridges are sharp: the faces meeting there differ in normal by over 60 degrees.
  for (const Vec2& ridge : {section[3], section[5]}) {
    const Vec3 apex = ridge.x() * across + ridge.y() * Vec3::UnitZ();
    const Vec3 left = p.normal(apex + 1.0 * across - 0.5 * Vec3::UnitZ());
    const Vec3 right = p.normal(apex - 1.0 * across - 0.5 * Vec3::UnitZ());
    EXPECT_GT(std::acos(left.dot(right)) * 180.0 / pi, 60.0) << ridge.transpose();
  }
  const std::vector<double> centres = default_slice_centres(p);
  const double half = 0.5 * PhantomVolumeOptions{}.spacing.z();
  EXPECT_LT(distance_to_nearest(centres, 10.0), 1e-9) << "ridge A on a slice centre";
  EXPECT_NEAR(distance_to_nearest(centres, 15.0), half, 1e-9) << "ridge B half-way between slices";
  EXPECT_LT(distance_to_nearest(centres, 4.0), 1e-9) << "the valley on a slice centre";
}

// end-face-on-slice: the cylinder's end faces on slice centres (its end slices are exactly half bone),
// the box's half-way between slices (its end slices are whole).
TEST(PhantomSliceShapes, EndFacesAlignedAsClaimed) {
  const Phantom p = make_phantom(PhantomShape::EndFaceOnSlice);
  for (double z : {-15.0, 13.0}) {
    std::vector<Vec3> rim;
    for (double t = 0.0; t < 2.0 * pi; t += 0.01) rim.emplace_back(-20.0 + 14.0 * std::cos(t), 14.0 * std::sin(t), z);
    for (std::size_t i = 0; i + 1 < rim.size(); ++i) expect_edge_covered(p, rim[i], rim[i + 1], "cylinder rim");
  }
  const Vec2 bu(std::cos(degrees(30.0)), std::sin(degrees(30.0))), bv(-bu.y(), bu.x());
  const std::vector<Vec2> rectangle = {{-13.0, -10.0}, {13.0, -10.0}, {13.0, 10.0}, {-13.0, 10.0}};
  expect_prism_edges_covered(p, rectangle, Vec3(20.0, 0.0, 0.0), Vec3(bu.x(), bu.y(), 0.0), Vec3(bv.x(), bv.y(), 0.0),
                             Vec3::UnitZ(), 20.0, "box");
  EXPECT_GT(distance_to_features(p, Vec3(-20.0, 0.0, 13.0)), 13.9);

  const PhantomVolumeOptions options;  // the default grid, no blur, no noise
  const CtImage::Pointer image = render_phantom(p, options);
  std::vector<double> centres;
  for (std::size_t k = 0; k < image->GetLargestPossibleRegion().GetSize()[2]; ++k) {
    centres.push_back(image->GetOrigin()[2] + static_cast<double>(k) * image->GetSpacing()[2]);
  }
  const double half = 0.5 * options.spacing.z();
  for (double z : {-15.0, 13.0}) EXPECT_LT(distance_to_nearest(centres, z), 1e-9) << "cylinder face " << z;
  for (double z : {-20.0, 20.0}) EXPECT_NEAR(distance_to_nearest(centres, z), half, 1e-9) << "box face " << z;
  auto value = [&](double x, double y, double z) {
    CtImage::PointType point;
    point[0] = x;
    point[1] = y;
    point[2] = z;
    CtImage::IndexType index;
    EXPECT_TRUE(image->TransformPhysicalPointToIndex(point, index));
    return image->GetPixel(index);
  };
  const float iso = static_cast<float>(0.5 * (options.bone_hu + options.tissue_hu));
  EXPECT_EQ(value(-20.0, 0.0, 13.0), iso) << "the cylinder's top slice is half bone";
  EXPECT_EQ(value(-20.0, 0.0, -15.0), iso) << "the cylinder's bottom slice is half bone";
  EXPECT_EQ(value(20.0, 0.0, 19.0), static_cast<float>(options.bone_hu)) << "the box's top slice is whole";
  EXPECT_EQ(value(20.0, 0.0, 21.0), static_cast<float>(options.tissue_hu)) << "above the box";
}

}  // namespace
}  // namespace contourmesh
