// SPDX-License-Identifier: BSD-3-Clause
// Contour noise of render_phantom: each slice's boundary is displaced along its normal by the slice's own
// random field, with the requested RMS over the true boundary, independently from slice to slice.
#include "contourmesh/reconstruct/phantom.h"
#include "reconstruct/phantom_cache.h"

#include <contourmesh/smooth/errors.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <numbers>
#include <vector>

namespace contourmesh {
namespace {

using Vec3 = Eigen::Vector3d;

using std::numbers::pi;

using test::values;

// Bilinear interpolation of slice k at the physical point (x, y).
double sample(const CtImage& image, std::int64_t k, double x, double y) {
  const auto size = image.GetLargestPossibleRegion().GetSize();
  const double u = (x - image.GetOrigin()[0]) / image.GetSpacing()[0];
  const double v = (y - image.GetOrigin()[1]) / image.GetSpacing()[1];
  const auto i = static_cast<std::int64_t>(std::floor(u));
  const auto j = static_cast<std::int64_t>(std::floor(v));
  const double fu = u - static_cast<double>(i), fv = v - static_cast<double>(j);
  auto at = [&](std::int64_t a, std::int64_t b) {
    a = std::clamp<std::int64_t>(a, 0, static_cast<std::int64_t>(size[0]) - 1);
    b = std::clamp<std::int64_t>(b, 0, static_cast<std::int64_t>(size[1]) - 1);
    CtImage::IndexType index = {{a, b, k}};
    return static_cast<double>(image.GetPixel(index));
  };
  return (1 - fv) * ((1 - fu) * at(i, j) + fu * at(i + 1, j)) + fv * ((1 - fu) * at(i, j + 1) + fu * at(i + 1, j + 1));
}

// The cavity phantom's section away from its spherical cavity is the circle of radius 28 about the z
// axis: its boundary displacement at angle theta is where the partial-volume iso-level crosses the ray,
// minus 28 (the crossing nearest the true circle).
constexpr double kRadius = 28.0;

std::vector<double> radial_displacement(const CtImage& image, std::int64_t k, double level, int angles) {
  std::vector<double> d;
  for (int a = 0; a < angles; ++a) {
    const double theta = 2.0 * pi * (a + 0.5) / angles;
    const double c = std::cos(theta), s = std::sin(theta);
    double best = std::nan("");
    double previous = sample(image, k, (kRadius - 5.0) * c, (kRadius - 5.0) * s) - level;
    for (double r = kRadius - 5.0 + 0.02; r <= kRadius + 5.0; r += 0.02) {
      const double value = sample(image, k, r * c, r * s) - level;
      if ((previous >= 0.0) != (value >= 0.0)) {
        const double crossing = r - 0.02 * value / (value - previous);
        if (std::isnan(best) || std::abs(crossing - kRadius) < std::abs(best - kRadius)) best = crossing;
      }
      previous = value;
    }
    d.push_back(best - kRadius);
  }
  return d;
}

double rms(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x * x;
  return std::sqrt(sum / static_cast<double>(v.size()));
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double ma = 0.0, mb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ma += a[i];
    mb += b[i];
  }
  ma /= static_cast<double>(a.size());
  mb /= static_cast<double>(b.size());
  double ab = 0.0, aa = 0.0, bb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ab += (a[i] - ma) * (b[i] - mb);
    aa += (a[i] - ma) * (a[i] - ma);
    bb += (b[i] - mb) * (b[i] - mb);
  }
  return ab / std::sqrt(aa * bb);
}

// The slices of the default grid whose section is the circle alone (the cavity spans z in [-10, 14]),
// away from the end faces at z = +-30.
std::vector<std::int64_t> circle_slices(const CtImage& image) {
  std::vector<std::int64_t> slices;
  const auto n = static_cast<std::int64_t>(image.GetLargestPossibleRegion().GetSize()[2]);
  for (std::int64_t k = 0; k < n; ++k) {
    const double z = image.GetOrigin()[2] + static_cast<double>(k) * image.GetSpacing()[2];
    if (std::abs(z) < 27.0 && (z < -13.0 || z > 17.0)) slices.push_back(k);
  }
  return slices;
}

TEST(PhantomContourNoise, BoundaryDisplacementHasTheRequestedRmsAndAdjacentSlicesAreIndependent) {
  const Phantom phantom = make_phantom(PhantomShape::Cavity);
  PhantomVolumeOptions options;  // 0.7 x 0.7 x 2 mm, no blur, no CT noise
  const double level = 0.5 * (options.bone_hu + options.tissue_hu);
  const CtImage::Pointer clean = render_phantom(phantom, options);
  options.contour_noise = 0.5;
  options.seed = 7;
  const CtImage::Pointer noisy = render_phantom(phantom, options);
  const std::vector<std::int64_t> slices = circle_slices(*noisy);
  ASSERT_GE(slices.size(), 8u);

  std::vector<std::vector<double>> displacement;
  double sum_rms = 0.0;
  for (std::int64_t k : slices) {
    SCOPED_TRACE("slice " + std::to_string(k));
    // The measurement itself: the unperturbed circle is found within a few hundredths of a mm.
    const std::vector<double> truth = radial_displacement(*clean, k, level, 720);
    EXPECT_LT(rms(truth), 0.05);
    displacement.push_back(radial_displacement(*noisy, k, level, 720));
    for (double d : displacement.back()) ASSERT_FALSE(std::isnan(d));
    const double r = rms(displacement.back());
    EXPECT_NEAR(r, 0.5, 0.05);
    sum_rms += r;
  }
  EXPECT_NEAR(sum_rms / static_cast<double>(slices.size()), 0.5, 0.025);

  // Adjacent slices (consecutive indices) are uncorrelated.
  double sum_abs = 0.0, sum = 0.0;
  int pairs = 0;
  for (std::size_t i = 0; i + 1 < slices.size(); ++i) {
    if (slices[i + 1] != slices[i] + 1) continue;
    const double rho = correlation(displacement[i], displacement[i + 1]);
    sum_abs += std::abs(rho);
    sum += rho;
    ++pairs;
  }
  ASSERT_GE(pairs, 6);
  EXPECT_LT(sum_abs / pairs, 0.35) << "mean |correlation| of adjacent slices";
  EXPECT_LT(std::abs(sum / pairs), 0.25) << "mean correlation of adjacent slices";
}

// The contour moves within the slice plane: walls parallel to the slice axis move, faces parallel to
// the slices do not. The cylinder of end-face-on-slice ends exactly on slice centres, so its end slices
// are half bone inside the rim, with or without contour noise (a displacement of the face along z would
// change them, and punch holes in them where f < 0).
TEST(PhantomContourNoise, FacesParallelToTheSlicesStayWallsMove) {
  const Phantom phantom = make_phantom(PhantomShape::EndFaceOnSlice);
  PhantomVolumeOptions options;
  options.contour_noise = 0.8;
  options.seed = 2;
  const CtImage::Pointer image = render_phantom(phantom, options);
  const CtImage::Pointer clean = render_phantom(phantom, PhantomVolumeOptions{});
  const float iso = static_cast<float>(0.5 * (options.bone_hu + options.tissue_hu));
  auto index_of = [&](double x, double y, double z) {
    CtImage::PointType point;
    point[0] = x;
    point[1] = y;
    point[2] = z;
    CtImage::IndexType index;
    EXPECT_TRUE(image->TransformPhysicalPointToIndex(point, index));
    return index;
  };
  int face = 0, wall_moved = 0;
  for (double z : {-15.0, 13.0}) {
    for (double x = -30.0; x <= -10.0; x += 0.7) {
      for (double y = -10.0; y <= 10.0; y += 0.7) {
        if (std::hypot(x + 20.0, y) > 10.0) continue;  // 4 mm inside the rim, clear of the moving wall
        EXPECT_EQ(image->GetPixel(index_of(x, y, z)), iso) << x << " " << y << " " << z;
        ++face;
      }
    }
  }
  for (double t = 0.0; t < 2.0 * pi; t += 0.05) {
    const auto index = index_of(-20.0 + 14.0 * std::cos(t), 14.0 * std::sin(t), 1.0);
    wall_moved += image->GetPixel(index) != clean->GetPixel(index) ? 1 : 0;
  }
  EXPECT_GT(face, 300);
  EXPECT_GT(wall_moved, 100);
}

TEST(PhantomContourNoise, SameSeedSameVolumeOtherSeedOtherVolume) {
  const Phantom phantom = make_phantom(PhantomShape::RidgeBox);
  PhantomVolumeOptions options;
  options.spacing = Vec3(1.5, 1.5, 3.0);
  const std::vector<float> clean = values(*render_phantom(phantom, options));
  options.contour_noise = 0.4;
  options.seed = 11;
  const std::vector<float> a = values(*render_phantom(phantom, options));
  const std::vector<float> again = values(*render_phantom(phantom, options));
  options.seed = 12;
  const std::vector<float> b = values(*render_phantom(phantom, options));
  EXPECT_EQ(a, again);
  EXPECT_NE(a, b);
  EXPECT_NE(a, clean);
  // Only voxels near the surface change: the displacement is a few tenths of a mm.
  std::size_t changed = 0;
  for (std::size_t i = 0; i < a.size(); ++i) changed += a[i] != clean[i] ? 1 : 0;
  EXPECT_LT(changed, a.size() / 5);
}

TEST(PhantomContourNoise, ZeroIsTheUnperturbedVolumeWhateverTheSeed) {
  const Phantom phantom = make_phantom(PhantomShape::Branch);
  PhantomVolumeOptions options;
  options.spacing = Vec3(2.0, 2.0, 3.0);
  const std::vector<float> reference = values(*render_phantom(phantom, options));
  options.contour_noise = 0.0;
  options.seed = 99;
  EXPECT_EQ(values(*render_phantom(phantom, options)), reference);
}

// The two noises draw from independent streams: adding contour noise leaves the CT noise of every
// voxel as it was.
TEST(PhantomContourNoise, CtNoiseStreamIsUnchangedByContourNoise) {
  const Phantom phantom = make_phantom(PhantomShape::Branch);
  PhantomVolumeOptions options;
  options.spacing = Vec3(1.5, 1.5, 2.0);
  options.seed = 5;
  const std::vector<float> clean = values(*render_phantom(phantom, options));
  options.noise = 30.0;
  const std::vector<float> ct = values(*render_phantom(phantom, options));
  options.contour_noise = 0.6;
  const std::vector<float> both = values(*render_phantom(phantom, options));
  options.noise = 0.0;
  const std::vector<float> contour = values(*render_phantom(phantom, options));
  ASSERT_EQ(both.size(), clean.size());
  std::size_t moved = 0;
  for (std::size_t i = 0; i < clean.size(); ++i) {
    EXPECT_NEAR(both[i] - contour[i], ct[i] - clean[i], 1e-3) << i;
    moved += contour[i] != clean[i] ? 1 : 0;
  }
  EXPECT_GT(moved, 1000u);
}

// The solid grows where f > 0 and shrinks where f < 0, by a few tenths of a mm: the partial volume of
// the whole volume stays within a few percent of the truth, which itself is unchanged.
TEST(PhantomContourNoise, TruthIsUnchangedAndTheVolumeStaysClose) {
  const Phantom phantom = make_phantom(PhantomShape::TwoObjects);
  const double truth = phantom.volume;
  PhantomVolumeOptions options;
  options.spacing = Vec3(1.0, 1.0, 2.0);
  options.contour_noise = 0.4;
  double sum = 0.0;
  for (float v : values(*render_phantom(phantom, options))) {
    sum += (v - options.tissue_hu) / (options.bone_hu - options.tissue_hu);
  }
  EXPECT_EQ(phantom.volume, truth);
  // |delta V| <= perimeter * RMS per unit height (about 190 mm * 0.4 mm / 3000 mm^2 = 2.5 %).
  EXPECT_NEAR(sum * options.spacing.prod(), truth, 0.03 * truth);
}

TEST(PhantomContourNoise, RejectsBadValues) {
  const Phantom phantom = make_phantom(PhantomShape::RidgeBox);
  for (double bad : {-0.1, std::nan(""), std::numeric_limits<double>::infinity(), kMaxContourNoise + 0.5}) {
    PhantomVolumeOptions options;
    options.spacing = Vec3(2.0, 2.0, 2.0);
    options.contour_noise = bad;
    EXPECT_THROW((void)render_phantom(phantom, options), InvalidInputError) << bad;
  }
}

}  // namespace
}  // namespace contourmesh
