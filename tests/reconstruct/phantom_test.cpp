// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/phantom.h"

#include "reconstruct/phantom_cache.h"

#include <contourmesh/smooth/errors.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <queue>
#include <random>
#include <string>
#include <vector>

namespace contourmesh {
namespace {

using Vec3 = Eigen::Vector3d;

using std::numbers::pi;

struct ShapeCase {
  PhantomShape shape;
  std::vector<Vec3> inside;   // known interior points, the first one used as a ray origin
  std::vector<Vec3> outside;  // known exterior points, some of them inside the bounding box
  int surface_components;
  int euler_characteristic;
};

// tilted-box: points given in the slab's own frame (u, w, v), tilted and turned as the phantom is. The
// bevel cuts the corner u > 10, v > 10 - 0.92 drop with drop > 4.6 mm.
std::vector<Vec3> tilted_box_points(bool inside) {
  const Eigen::Matrix3d rotation =
      (Eigen::AngleAxisd(20.0 * pi / 180.0, Vec3::UnitZ()) *
       Eigen::AngleAxisd(4.0 * pi / 180.0, Vec3(std::cos(pi / 3.0), std::sin(pi / 3.0), 0.0)))
          .toRotationMatrix();
  const std::vector<Vec3> frame = inside ? std::vector<Vec3>{{0, 0, 0}, {30, 20, -8}, {-34, -24, 9.5}, {12, 0, 9}}
                                         : std::vector<Vec3>{{33, 0, 9.5}, {0, 0, 10.5}, {0, 25.5, 0}, {35.5, 0, 0}};
  std::vector<Vec3> points;
  for (const Vec3& f : frame) points.push_back(rotation * f);
  return points;
}

// in-slice-ridge: points given as (x', y', z) in the prism's frame, turned by 25 degrees about z.
std::vector<Vec3> in_slice_ridge_points(bool inside) {
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(25.0 * pi / 180.0, Vec3::UnitZ()).toRotationMatrix();
  const std::vector<Vec3> frame =
      inside ? std::vector<Vec3>{{0, 0, -10}, {0, 12, 9.5}, {10, -10, 14.5}, {-24, 0, -14.5}, {0, 23.5, 1.5}}
             : std::vector<Vec3>{{0, 2, 6}, {0, -10, 15.5}, {25.5, 0, 0}, {0, 20, 10}, {0, 12, 10.5}};
  std::vector<Vec3> points;
  for (const Vec3& f : frame) points.push_back(turn * f);
  return points;
}

const std::vector<ShapeCase>& shape_cases() {
  static const std::vector<ShapeCase> cases = {
      {PhantomShape::RidgeBox,
       {{0, 0, 0}, {0, 14, 20}, {19, -14, -24}},
       {{0, 15.5, 0}, {15, 7, 0}, {0, 0, 25.5}},
       1,
       2},
      {PhantomShape::Femur,
       {{0, 0, 0}, {0, 15, 0}, {-28, 0, 48}, {-14, 0, 38}, {15.5, 3, -50}, {-15.5, 3, -50}},
       {{0, 0, -52}, {0, 16.5, 0}, {-10, 0, 55}},
       1,
       2},
      {PhantomShape::Pelvis, {{40, 0, 1}, {-40, 0, -1}}, {{0, 0, 0}, {50, 0, 0}, {0, 20, 0}}, 1, 0},
      {PhantomShape::Skull,
       {{0, 0, 38}, {51, 0, -15}, {0, 57, -15}},
       {{0, 0, 0}, {22, -50, -5}, {-22, -50, -5}, {52, 0, -36}},
       1,
       -2},
      {PhantomShape::Branch, {{0, 0, -30}, {18, 0, 32}, {-18, 0, 32}}, {{0, 0, 25}, {0, 0, -45.5}}, 1, 2},
      {PhantomShape::TwoObjects, {{-22, 0, 0}, {20, 0, 0}, {20, 15, 24}}, {{0, 0, 0}, {20, 0, 27}}, 2, 4},
      {PhantomShape::Cavity, {{20, 0, 0}, {0, 0, 28}}, {{4, -3, 2}, {0, 0, 31}}, 2, 4},
      {PhantomShape::TiltedBox, tilted_box_points(true), tilted_box_points(false), 1, 2},
      {PhantomShape::InSliceRidge, in_slice_ridge_points(true), in_slice_ridge_points(false), 1, 2},
      {PhantomShape::EndFaceOnSlice,
       {{-20, 0, 0}, {20, 0, 0}, {-20, 13, 12.5}, {20, 0, 19.5}},
       {{0, 0, 0}, {-20, 0, 13.5}, {-20, 0, -15.5}, {20, 0, 20.5}, {-8, 13, 0}},
       2,
       4},
  };
  return cases;
}

using test::phantom_of;

Vec3 gradient(const ScalarField& f, const Vec3& p, double h) {
  Vec3 g;
  for (int i = 0; i < 3; ++i) {
    Vec3 e = Vec3::Zero();
    e[i] = h;
    g[i] = (f(p + e) - f(p - e)) / (2.0 * h);
  }
  return g;
}

// Points on the surface: from `origin` (inside) along random directions to the first sign change,
// refined by bisection.
std::vector<Vec3> surface_points(const Phantom& phantom, const Vec3& origin, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<Vec3> points;
  for (int n = 0; n < count; ++n) {
    const Vec3 dir = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    double inside = 0.0, t = 0.0;
    while (phantom.sdf(origin + t * dir) < 0.0 && t < 300.0) {
      inside = t;
      t += 0.2;
    }
    if (t >= 300.0) continue;
    double outside = t;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (inside + outside);
      (phantom.sdf(origin + mid * dir) < 0.0 ? inside : outside) = mid;
    }
    points.push_back(origin + 0.5 * (inside + outside) * dir);
  }
  return points;
}

TEST(PhantomNames, RoundTripAndErrors) {
  const std::vector<PhantomShape> shapes = all_phantom_shapes();
  ASSERT_EQ(shapes.size(), 10u);
  const std::vector<std::string> names = {"ridge-box", "femur",      "pelvis",         "skull",
                                          "branch",    "two-objects", "cavity",        "tilted-box",
                                          "in-slice-ridge", "end-face-on-slice"};
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    EXPECT_EQ(static_cast<std::size_t>(shapes[i]), i);
    EXPECT_EQ(std::string(to_string(shapes[i])), names[i]);
    EXPECT_EQ(parse_phantom_shape(names[i]), shapes[i]);
  }
  // The extra shapes are reachable by name but are not part of `all`.
  ASSERT_EQ(extra_phantom_shapes().size(), 1u);
  EXPECT_EQ(extra_phantom_shapes()[0], PhantomShape::SkullDiploe);
  EXPECT_EQ(std::string(to_string(PhantomShape::SkullDiploe)), "skull-diploe");
  EXPECT_EQ(parse_phantom_shape("skull-diploe"), PhantomShape::SkullDiploe);
  EXPECT_EQ(std::find(shapes.begin(), shapes.end(), PhantomShape::SkullDiploe), shapes.end());
  try {
    (void)parse_phantom_shape("sphere");
    FAIL() << "expected InvalidInputError";
  } catch (const InvalidInputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("sphere"), std::string::npos) << message;
    EXPECT_NE(message.find("two-objects"), std::string::npos) << message;
  }
}

TEST(Phantom, KnownInsideAndOutsidePoints) {
  for (const ShapeCase& c : shape_cases()) {
    SCOPED_TRACE(std::string(to_string(c.shape)));
    const Phantom& p = phantom_of(c.shape);
    EXPECT_EQ(p.shape, c.shape);
    EXPECT_EQ(p.surface_components, c.surface_components);
    EXPECT_EQ(p.euler_characteristic, c.euler_characteristic);
    ASSERT_FALSE(p.bounds.isEmpty());
    EXPECT_LE(p.bounds.sizes().maxCoeff(), 130.0);
    for (const Vec3& q : c.inside) {
      EXPECT_LT(p.sdf(q), 0.0) << q.transpose();
      EXPECT_TRUE(p.bounds.contains(q)) << q.transpose();
    }
    for (const Vec3& q : c.outside) EXPECT_GT(p.sdf(q), 0.0) << q.transpose();
    // Corners, edge midpoints and face centres of the bounding box grown by 1 mm are all outside.
    const Vec3 lo = p.bounds.min() - Vec3::Constant(1.0);
    const Vec3 hi = p.bounds.max() + Vec3::Constant(1.0);
    for (int i = 0; i < 27; ++i) {
      if (i == 13) continue;
      const Vec3 t(i % 3, (i / 3) % 3, i / 9);
      const Vec3 q = lo + (0.5 * t).cwiseProduct(hi - lo);
      EXPECT_GT(p.sdf(q), 0.0) << q.transpose();
    }
  }
}

TEST(Phantom, SurfacePointsHaveZeroSdfAndUnitOutwardNormals) {
  for (const ShapeCase& c : shape_cases()) {
    SCOPED_TRACE(std::string(to_string(c.shape)));
    const Phantom& p = phantom_of(c.shape);
    const std::vector<Vec3> points = surface_points(p, c.inside.front(), 300, 11);
    ASSERT_GT(points.size(), 250u);
    int checked = 0;
    for (const Vec3& q : points) {
      EXPECT_LT(std::abs(p.sdf(q)), 1e-9) << q.transpose();
      const Vec3 n = p.normal(q);
      EXPECT_NEAR(n.norm(), 1.0, 1e-9) << q.transpose();
      if (distance_to_features(p, q) < 1.0) continue;
      // Away from creases the sdf is the distance: +-h along the normal gives +-h.
      EXPECT_NEAR(p.sdf(q + 0.05 * n), 0.05, 1e-6) << q.transpose();
      EXPECT_NEAR(p.sdf(q - 0.05 * n), -0.05, 1e-6) << q.transpose();
      ++checked;
    }
    EXPECT_GT(checked, 150);
  }
}

TEST(Phantom, GradientIsUnitAwayFromCreases) {
  for (const ShapeCase& c : shape_cases()) {
    SCOPED_TRACE(std::string(to_string(c.shape)));
    const Phantom& p = phantom_of(c.shape);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const Vec3 lo = p.bounds.min() - Vec3::Constant(5.0);
    const Vec3 size = p.bounds.sizes() + Vec3::Constant(10.0);
    int unit = 0, total = 0;
    for (int n = 0; n < 600; ++n) {
      const Vec3 q = lo + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(size);
      if (distance_to_features(p, q) < 1.0) continue;
      const double g = gradient(p.sdf, q, 1e-5).norm();
      EXPECT_LE(g, 1.0 + 1e-4) << q.transpose();  // 1-Lipschitz everywhere
      unit += std::abs(g - 1.0) < 1e-4 ? 1 : 0;
      ++total;
    }
    EXPECT_GE(unit, total * 98 / 100) << unit << " of " << total;
  }
}

TEST(Phantom, RidgeBoxVolumeIsAnalytic) {
  const Phantom& p = phantom_of(PhantomShape::RidgeBox);
  EXPECT_NEAR(p.volume, 48000.0, 48000.0 * 1e-3);
}

// Jittered voxel count: one uniformly random sample in each cube of side h (stratified Monte Carlo).
// Unbiased, also for faces parallel to the grid, where a regular grid is off by up to h / 2 times the
// face's area (the end faces of end-face-on-slice made a regular count 1.2 % low).
double voxel_count_volume(const Phantom& p, double h) {
  const Vec3 lo = p.bounds.min() - Vec3::Constant(1.0);
  const Vec3 hi = p.bounds.max() + Vec3::Constant(1.0);
  std::mt19937_64 rng(17);
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

TEST(Phantom, VolumeAgreesWithVoxelCount) {
  for (const ShapeCase& c : shape_cases()) {
    SCOPED_TRACE(std::string(to_string(c.shape)));
    const Phantom& p = phantom_of(c.shape);
    EXPECT_GT(p.volume, 1e4);
    const double counted = voxel_count_volume(p, 1.25);
    EXPECT_NEAR(p.volume, counted, 0.01 * counted);
  }
}

TEST(Phantom, FeaturePointsLieOnTheSurfaceDensely) {
  for (const ShapeCase& c : shape_cases()) {
    SCOPED_TRACE(std::string(to_string(c.shape)));
    const Phantom& p = phantom_of(c.shape);
    ASSERT_GT(p.feature_points.size(), 100u);
    for (std::size_t i = 0; i < p.feature_points.size(); ++i) {
      const Vec3& q = p.feature_points[i];
      EXPECT_LT(std::abs(p.sdf(q)), 0.05) << q.transpose();
      // No isolated samples: the next sample along the feature is at most 0.5 mm away.
      double nearest = std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < p.feature_points.size(); ++j) {
        if (j != i) nearest = std::min(nearest, (p.feature_points[j] - q).norm());
      }
      EXPECT_LE(nearest, 0.5) << q.transpose();
      EXPECT_NEAR(distance_to_features(p, q), 0.0, 1e-12);
    }
  }
}

// Every point of the given polyline is within 0.3 mm of a feature point.
void expect_covered(const Phantom& p, const std::vector<Vec3>& curve, const std::string& what) {
  for (const Vec3& q : curve) {
    ASSERT_LT(std::abs(p.sdf(q)), 1e-6) << what << " " << q.transpose() << " is not on the surface";
    EXPECT_LE(distance_to_features(p, q), 0.3) << what << " at " << q.transpose();
  }
}

// Where the surface `surface(u, v)` (u, v in [0, 1]) of one primitive crosses the zero set of another
// primitive's sdf `other`: sign changes along u, refined by bisection, kept when on the phantom's surface.
template <typename Surface>
std::vector<Vec3> crossing_curve(const Phantom& p, const Surface& surface, const ScalarField& other) {
  std::vector<Vec3> points;
  constexpr int kSteps = 400;
  for (int j = 0; j < kSteps; ++j) {
    const double v = (j + 0.5) / kSteps;
    for (int i = 0; i < kSteps; ++i) {
      double a = static_cast<double>(i) / kSteps, b = static_cast<double>(i + 1) / kSteps;
      const bool inside_a = other(surface(a, v)) < 0.0;
      if (inside_a == (other(surface(b, v)) < 0.0)) continue;
      for (int k = 0; k < 50; ++k) {
        const double m = 0.5 * (a + b);
        ((other(surface(m, v)) < 0.0) == inside_a ? a : b) = m;
      }
      const Vec3 q = surface(0.5 * (a + b), v);
      if (std::abs(p.sdf(q)) < 1e-6) points.push_back(q);
    }
  }
  return points;
}

double capsule_sdf(const Vec3& q, const Vec3& a, const Vec3& b, double r) {
  const double h = std::clamp((q - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (q - a - h * (b - a)).norm() - r;
}

TEST(Phantom, CreasesBetweenPrimitivesAreSampled) {
  {
    // Femur: the condyles (spheres of radius 13) against the shaft (capsule of radius 12).
    const Phantom& p = phantom_of(PhantomShape::Femur);
    const ScalarField shaft = [](const Vec3& q) {
      return capsule_sdf(q, Vec3(0.0, 0.0, -34.0), Vec3(0.0, 0.0, 34.0), 12.0);
    };
    for (double x : {-15.5, 15.5}) {
      const Vec3 c(x, 3.0, -44.0);
      const auto sphere = [&](double u, double v) {
        const double theta = pi * u, phi = 2.0 * pi * v;
        return Vec3(c + 13.0 * Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
      };
      const std::vector<Vec3> curve = crossing_curve(p, sphere, shaft);
      EXPECT_GT(curve.size(), 150u);
      expect_covered(p, curve, "femur condyle junction");
    }
    // The ridge's flanks meet the shaft cylinder along two lines.
    const auto flank = [](double u, double v) { return Vec3(3.5 - 3.5 * u, 9.0 + 7.0 * u, -24.9 + 49.8 * v); };
    const std::vector<Vec3> line = crossing_curve(p, flank, shaft);
    EXPECT_GT(line.size(), 300u);
    expect_covered(p, line, "femur ridge flank");
  }
  {
    // Branch: each limb (capsule of radius 8) against the trunk.
    const Phantom& p = phantom_of(PhantomShape::Branch);
    const ScalarField trunk = [](const Vec3& q) {
      return std::max(capsule_sdf(q, Vec3(0.0, 0.0, -60.0), Vec3(0.0, 0.0, -5.0), 10.0), -45.0 - q.z());
    };
    for (double x : {-22.0, 22.0}) {
      const Vec3 a(0.0, 0.0, -5.0), b(x, 0.0, 40.0);
      const Vec3 axis = (b - a).normalized();
      const Vec3 e1 = axis.cross(Vec3::UnitY()).normalized(), e2 = axis.cross(e1);
      const auto limb = [&](double u, double v) {
        const double phi = 2.0 * pi * v;
        return Vec3(a + u * (b - a) + 8.0 * (std::cos(phi) * e1 + std::sin(phi) * e2));
      };
      const std::vector<Vec3> curve = crossing_curve(p, limb, trunk);
      EXPECT_GT(curve.size(), 200u);
      expect_covered(p, curve, "branch limb junction");
    }
  }
}

TEST(Phantom, KnownCreasesAreSampled) {
  {
    const Phantom& p = phantom_of(PhantomShape::RidgeBox);
    std::vector<Vec3> ridge, corner_edge;
    for (double z = -25.0; z <= 25.0; z += 0.05) ridge.emplace_back(0.0, 15.0, z);
    for (double x = -20.0; x <= 0.0; x += 0.05) corner_edge.emplace_back(x, 15.0 + 0.6 * x, 25.0);
    expect_covered(p, ridge, "ridge-box ridge");
    expect_covered(p, corner_edge, "ridge-box roof edge");
    EXPECT_GT(distance_to_features(p, Vec3(0.0, -15.0, 0.0)), 19.9);  // middle of the bottom face
  }
  {
    const Phantom& p = phantom_of(PhantomShape::Femur);
    std::vector<Vec3> apex, neck_head;
    for (double z = -25.0; z <= 25.0; z += 0.05) apex.emplace_back(0.0, 16.0, z);
    // The neck (radius 8 about the axis through the head centre) meets the head (radius 15) on a circle.
    const Vec3 head(-28.0, 0.0, 48.0);
    const Vec3 axis = (Vec3(0.0, 0.0, 28.0) - head).normalized();
    const Vec3 e1 = axis.cross(Vec3::UnitY()).normalized();
    const Vec3 e2 = axis.cross(e1);
    const double along = std::sqrt(15.0 * 15.0 - 8.0 * 8.0);
    for (double t = 0.0; t < 2.0 * pi; t += 0.005) {
      neck_head.push_back(head + along * axis + 8.0 * (std::cos(t) * e1 + std::sin(t) * e2));
    }
    expect_covered(p, apex, "femur ridge apex");
    expect_covered(p, neck_head, "femur head-neck junction");
  }
  {
    const Phantom& p = phantom_of(PhantomShape::Pelvis);
    // The crest: vertex (41, 15) of the section revolved, tilted by 22 degrees about x.
    const Eigen::Matrix3d rotation = Eigen::AngleAxisd(22.0 * pi / 180.0, Vec3::UnitX()).toRotationMatrix();
    std::vector<Vec3> crest;
    for (double t = 0.0; t < 2.0 * pi; t += 0.002) {
      crest.push_back(rotation * Vec3(41.0 * std::cos(t), 41.0 * std::sin(t), 15.0));
    }
    expect_covered(p, crest, "pelvis crest");
  }
  {
    const Phantom& p = phantom_of(PhantomShape::Branch);
    // The crotch between the limbs lies in the plane x = 0: y^2 + (1 - d_z^2) (z + 5)^2 = 64.
    const double dz = 45.0 / std::hypot(22.0, 45.0);
    std::vector<Vec3> crotch, rim;
    for (double y = -7.0; y <= 7.0; y += 0.05) {
      crotch.emplace_back(0.0, y, -5.0 + std::sqrt((64.0 - y * y) / (1.0 - dz * dz)));
    }
    for (double t = 0.0; t < 2.0 * pi; t += 0.01) rim.emplace_back(10.0 * std::cos(t), 10.0 * std::sin(t), -45.0);
    expect_covered(p, crotch, "branch crotch");
    expect_covered(p, rim, "branch bottom rim");
  }
  {
    const Phantom& p = phantom_of(PhantomShape::Cavity);
    std::vector<Vec3> rim;
    for (double t = 0.0; t < 2.0 * pi; t += 0.005) rim.emplace_back(28.0 * std::cos(t), 28.0 * std::sin(t), 30.0);
    expect_covered(p, rim, "cavity top rim");
    EXPECT_GT(distance_to_features(p, Vec3(4.0, -3.0, 14.0)), 10.0);  // top of the smooth cavity
  }
}

TEST(Phantom, DistanceToFeaturesWithoutFeaturesIsInfinite) {
  const Phantom empty;
  EXPECT_TRUE(std::isinf(distance_to_features(empty, Vec3::Zero())));
}

// The skull with a diploe is the skull less 120 disjoint balls of radius 1.5 mm inside its wall: the
// volumes differ by theirs, each ball is a surface of its own, and the balls' centres are outside.
TEST(Phantom, TheDiploeIsTheSkullLessItsCavities) {
  const Phantom& skull = phantom_of(PhantomShape::Skull);
  const Phantom& diploe = phantom_of(PhantomShape::SkullDiploe);
  const int cavities = diploe.surface_components - 1;
  EXPECT_EQ(cavities, 120);
  EXPECT_EQ(diploe.euler_characteristic, skull.euler_characteristic + 2 * cavities);
  const double balls = cavities * 4.0 / 3.0 * std::numbers::pi * 1.5 * 1.5 * 1.5;
  // Both volumes are integrated to about 3e-4 of the skull's (the balls' own share of the error is larger:
  // 2.5 % of their volume, at leaves of 0.5 mm on balls 3 mm across).
  EXPECT_NEAR(skull.volume - diploe.volume, balls, 5e-4 * skull.volume);
  EXPECT_EQ(diploe.feature_points.size(), skull.feature_points.size());
  // Outside the wall (in the cranial cavity, beyond the outer table) both fields agree.
  for (const Vec3& p : {Vec3(0, 0, -15), Vec3(0, 0, 45), Vec3(60, 0, 0), Vec3(0, -70, 0)}) {
    EXPECT_DOUBLE_EQ(diploe.sdf(p), skull.sdf(p));
  }
}

}  // namespace
}  // namespace contourmesh
