// SPDX-License-Identifier: BSD-3-Clause
// render_phantom: a phantom's solid sampled into a CT-like volume (partial volume by supersampling, blur,
// noise).
#include "contourmesh/reconstruct/phantom.h"

#include "contourmesh/reconstruct/volume.h"

#include "detail/contour_noise.h"

#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/limits.h>

#include <itkDiscreteGaussianImageFilter.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace contourmesh {

namespace {

using Vec3 = Eigen::Vector3d;

constexpr int kMaxSamples = 16;  // supersamples per voxel along an axis, at most

struct Renderer {
  const ScalarField& sdf;
  const std::vector<detail::ContourNoiseField>* fields;  // contour noise per slice, or null
  Vec3 origin;  // centre of voxel (0, 0, 0)
  Vec3 spacing;
  std::array<std::int64_t, 3> size;
  std::array<int, 3> samples;  // supersamples per voxel along each axis
  float* buffer;
  float bone;
  float tissue;

  using Range = std::array<std::int64_t, 6>;  // [x0, x1) [y0, y1) [z0, z1)

  // Splits `r` in halves along every axis that has more than one element and is at least half as
  // long (physically, with cell size `cell`) as the longest such axis.
  static int split(const Range& r, const Vec3& cell, std::array<Range, 8>& out) {
    double longest = 0.0;
    for (int a = 0; a < 3; ++a) {
      if (r[2 * a + 1] - r[2 * a] > 1) longest = std::max(longest, (r[2 * a + 1] - r[2 * a]) * cell[a]);
    }
    int count = 1;
    out[0] = r;
    for (int a = 0; a < 3; ++a) {
      const std::int64_t n = r[2 * a + 1] - r[2 * a];
      if (n <= 1 || n * cell[a] < 0.5 * longest) continue;
      const std::int64_t mid = r[2 * a] + n / 2;
      for (int i = 0; i < count; ++i) {
        out[count + i] = out[i];
        out[i][2 * a + 1] = mid;
        out[count + i][2 * a] = mid;
      }
      count *= 2;
    }
    return count;
  }

  // Whether g(p) = |grad sdf(p)| projected on the slice plane exceeds t in [0, 1), by forward
  // differences from d = sdf(p) (the x derivative alone often decides). g is how much of a
  // displacement of the contour within the slice moves the surface along its normal: 1 on a wall
  // parallel to the slice axis, 0 on a face parallel to the slices.
  bool in_plane_slope_exceeds(const Vec3& p, double d, double t) const {
    constexpr double h = 1e-4;
    const double gx = (sdf(p + Vec3(h, 0.0, 0.0)) - d) / h;
    if (gx * gx > t * t) return true;
    const double gy = (sdf(p + Vec3(0.0, h, 0.0)) - d) / h;
    return gx * gx + gy * gy > t * t;
  }

  // The contour noise of one voxel: f at its columns of supersamples (x fastest), and its extremes.
  struct VoxelNoise {
    const double* f = nullptr;  // null: no contour noise
    double low = 0.0;           // min(0, min f)
    double high = 0.0;          // max(0, max f)
  };

  // Number of supersamples inside the solid among those of `r` (sample indices of the voxel whose
  // lower corner is `corner`); `d` is the sdf at `at`, the centre of the range. With contour noise a
  // sample p is inside when sdf(p) < f g(p), f the voxel's field at the sample's column and g(p) the
  // length of grad sdf projected on the slice plane: to first order, the section's contour moves by f
  // along its normal within the slice (the whole of f on a wall parallel to the slice axis, nothing on
  // a face parallel to the slices).
  int count_inside(const Vec3& corner, const Vec3& step, const Range& r, const Vec3& at, double d,
                   const VoxelNoise& noise) const {
    const Vec3 lo(r[0], r[2], r[4]);
    const Vec3 hi(r[1], r[3], r[5]);
    const int count = static_cast<int>((r[1] - r[0]) * (r[3] - r[2]) * (r[5] - r[4]));
    if (count == 1) {
      if (noise.f == nullptr) return d < 0.0 ? 1 : 0;
      const double f = noise.f[r[2] * samples[0] + r[0]];
      // Inside when sdf < f g, g = |grad_xy sdf| in [0, 1]: decided without g unless sdf lies between 0
      // and f. There, with t = sdf / f in [0, 1): inside when g > t for f > 0, when g < t for f < 0.
      if (d < std::min(0.0, f)) return 1;
      if (d >= std::max(0.0, f)) return 0;
      const bool steeper = in_plane_slope_exceeds(at, d, d / f);
      return (f > 0.0) == steeper ? 1 : 0;
    }
    const double half_diagonal = 0.5 * (hi - lo).cwiseProduct(step).norm();
    if (d >= half_diagonal + noise.high) return 0;
    if (d <= -half_diagonal + noise.low) return count;
    std::array<Range, 8> parts;
    const int n = split(r, step, parts);
    int inside = 0;
    for (int i = 0; i < n; ++i) {
      const Range& q = parts[static_cast<std::size_t>(i)];
      const Vec3 centre = corner + 0.5 * Vec3(q[0] + q[1], q[2] + q[3], q[4] + q[5]).cwiseProduct(step);
      inside += count_inside(corner, step, q, centre, sdf(centre), noise);
    }
    return inside;
  }

  void fill(const Range& r, float value) const {
    for (std::int64_t z = r[4]; z < r[5]; ++z) {
      for (std::int64_t y = r[2]; y < r[3]; ++y) {
        float* row = buffer + (z * size[1] + y) * size[0];
        std::fill(row + r[0], row + r[1], value);
      }
    }
  }

  // Bounds [low, high] of the displacement f g (g in [0, 1], see count_inside) over the voxels of `r`,
  // whose centre is `centre`; low <= 0 <= high (both 0 without contour noise). Within one slice f lies in
  // f(centre) -+ lipschitz * (the block's half-diagonal in x, y), clamped to the field's bound; over
  // several slices, within the largest bound.
  std::pair<double, double> noise_range(const Range& r, const Vec3& centre) const {
    if (fields == nullptr) return {0.0, 0.0};
    if (r[5] - r[4] == 1) {
      const detail::ContourNoiseField& f = (*fields)[static_cast<std::size_t>(r[4])];
      if (f.bound == 0.0) return {0.0, 0.0};
      const double half_xy = 0.5 * std::hypot(static_cast<double>(r[1] - r[0]) * spacing.x(),
                                              static_cast<double>(r[3] - r[2]) * spacing.y());
      const double value = f(centre.x(), centre.y());
      const double slack = f.lipschitz * half_xy + 1e-9;  // the constant covers rounding
      return {std::min(0.0, std::max(-f.bound, value - slack)), std::max(0.0, std::min(f.bound, value + slack))};
    }
    double bound = 0.0;
    for (std::int64_t z = r[4]; z < r[5]; ++z) bound = std::max(bound, (*fields)[static_cast<std::size_t>(z)].bound);
    return {-bound, bound};
  }

  // Renders the voxels of `r`. The culling margins grow by the range of the contour noise, so that a
  // block filled whole is whole after the displacement too.
  void block(const Range& r) const {
    const Vec3 lo(r[0], r[2], r[4]);
    const Vec3 hi(r[1], r[3], r[5]);
    const Vec3 centre = origin + (0.5 * (lo + hi) - Vec3::Constant(0.5)).cwiseProduct(spacing);
    const double half_diagonal = 0.5 * (hi - lo).cwiseProduct(spacing).norm();
    const double d = sdf(centre);
    const auto [low, high] = noise_range(r, centre);
    if (d >= half_diagonal + high) return fill(r, tissue);
    if (d <= -half_diagonal + low) return fill(r, bone);
    if (r[1] - r[0] == 1 && r[3] - r[2] == 1 && r[5] - r[4] == 1) return voxel(r, centre, d);
    std::array<Range, 8> parts;
    const int n = split(r, spacing, parts);
    for (int i = 0; i < n; ++i) block(parts[static_cast<std::size_t>(i)]);
  }

  // Renders one voxel that the surface may cross, by supersampling. Every supersample uses the contour
  // noise of the voxel's own slice, as a segmentation of that slice would.
  void voxel(const Range& r, const Vec3& centre, double d) const {
    const Vec3 step = spacing.cwiseQuotient(Vec3(samples[0], samples[1], samples[2]));
    const Vec3 corner = centre - 0.5 * spacing;
    const Range all{0, samples[0], 0, samples[1], 0, samples[2]};
    const int total = samples[0] * samples[1] * samples[2];
    VoxelNoise noise;
    std::array<double, kMaxSamples * kMaxSamples> f;  // written before it is read
    const detail::ContourNoiseField* field = fields ? &(*fields)[static_cast<std::size_t>(r[4])] : nullptr;
    if (field != nullptr && field->bound > 0.0) {
      for (int j = 0; j < samples[1]; ++j) {
        for (int i = 0; i < samples[0]; ++i) {
          const double x = corner.x() + 0.5 * (2 * i + 1) * step.x();
          const double y = corner.y() + 0.5 * (2 * j + 1) * step.y();
          const double value = (*field)(x, y);
          f[static_cast<std::size_t>(j * samples[0] + i)] = value;
          noise.low = std::min(noise.low, value);
          noise.high = std::max(noise.high, value);
        }
      }
      noise.f = f.data();
    }
    const double fraction = static_cast<double>(count_inside(corner, step, all, centre, d, noise)) / total;
    buffer[(r[4] * size[1] + r[2]) * size[0] + r[0]] =
        static_cast<float>(tissue + (static_cast<double>(bone) - tissue) * fraction);
  }
};

void check_option(bool ok, const std::string& message) {
  if (!ok) throw InvalidInputError("render_phantom: " + message);
}

}  // namespace

CtImage::Pointer render_phantom(const Phantom& phantom, const PhantomVolumeOptions& options) {
  check_option(static_cast<bool>(phantom.sdf), "the phantom has no signed distance function");
  check_option(!phantom.bounds.isEmpty() && phantom.bounds.min().allFinite() && phantom.bounds.max().allFinite(),
               "the phantom has an empty or infinite bounding box");
  for (int a = 0; a < 3; ++a) {
    check_option(std::isfinite(options.spacing[a]) && options.spacing[a] > 0.0,
                 "spacing must be three finite numbers > 0 mm");
  }
  check_option(std::isfinite(options.margin) && options.margin >= 0.0, "margin must be a finite number >= 0 mm");
  check_option(std::isfinite(options.blur) && options.blur >= 0.0, "blur must be a finite sigma >= 0 mm");
  check_option(std::isfinite(options.noise) && options.noise >= 0.0, "noise must be a finite sigma >= 0 HU");
  check_option(std::isfinite(options.contour_noise) && options.contour_noise >= 0.0 &&
                   options.contour_noise <= kMaxContourNoise,
               "contour noise must be an RMS in [0, " + std::to_string(static_cast<int>(kMaxContourNoise)) + "] mm");
  check_option(std::isfinite(options.bone_hu) && std::isfinite(options.tissue_hu), "bone and tissue HU must be finite");

  const Vec3 lo = phantom.bounds.min() - Vec3::Constant(options.margin);
  const Vec3 hi = phantom.bounds.max() + Vec3::Constant(options.margin);
  std::array<std::int64_t, 3> size{};
  double voxels = 1.0;
  for (int a = 0; a < 3; ++a) {
    const double n = std::max(1.0, std::ceil((hi[a] - lo[a]) / options.spacing[a] - 1e-9));
    voxels *= n;
    check_option(voxels <= 2147483648.0, "the volume would have over 2^31 voxels; use a coarser spacing");
    size[static_cast<std::size_t>(a)] = static_cast<std::int64_t>(n);
  }
  // The image, the blur's output and the segmentation's copies of it (values, mask, labels).
  check_allocation("render_phantom: a volume of " + std::to_string(size[0]) + " x " + std::to_string(size[1]) + " x " +
                       std::to_string(size[2]) + " voxels",
                   0.0, voxels * kVolumeBytesPerVoxel, ResourceLimits{});
  // Voxel centres symmetric about the centre of the box.
  Vec3 origin;
  for (int a = 0; a < 3; ++a) {
    origin[a] =
        0.5 * (lo[a] + hi[a]) - 0.5 * static_cast<double>(size[static_cast<std::size_t>(a)] - 1) * options.spacing[a];
  }

  auto image = CtImage::New();
  CtImage::RegionType region;
  CtImage::SizeType itk_size;
  CtImage::SpacingType itk_spacing;
  CtImage::PointType itk_origin;
  for (unsigned a = 0; a < 3; ++a) {
    itk_size[a] = static_cast<itk::SizeValueType>(size[a]);
    itk_spacing[a] = options.spacing[a];
    itk_origin[a] = origin[a];
  }
  region.SetSize(itk_size);
  image->SetRegions(region);
  image->SetSpacing(itk_spacing);
  image->SetOrigin(itk_origin);
  CtImage::DirectionType direction;
  direction.SetIdentity();
  image->SetDirection(direction);
  image->Allocate();

  std::array<int, 3> samples{};
  for (int a = 0; a < 3; ++a) {
    samples[static_cast<std::size_t>(a)] =
        std::clamp(static_cast<int>(std::ceil(options.spacing[a] / 0.25 - 1e-9)), 4, kMaxSamples);
  }
  // The contour noise of each slice, drawn on the slice's true boundary.
  std::vector<detail::ContourNoiseField> fields;
  if (options.contour_noise > 0.0) {
    std::vector<double> slice_z(static_cast<std::size_t>(size[2]));
    for (std::size_t k = 0; k < slice_z.size(); ++k)
      slice_z[k] = origin.z() + static_cast<double>(k) * options.spacing.z();
    fields = detail::contour_noise_fields(phantom.sdf, phantom.bounds, slice_z, options.spacing.z(),
                                          options.contour_noise, options.seed);
  }
  const Renderer renderer{phantom.sdf,
                          fields.empty() ? nullptr : &fields,
                          origin,
                          options.spacing,
                          size,
                          samples,
                          image->GetBufferPointer(),
                          static_cast<float>(options.bone_hu),
                          static_cast<float>(options.tissue_hu)};
  // Slabs of slices, handed out to the worker threads one at a time.
  const std::int64_t slab = std::max<std::int64_t>(1, std::min<std::int64_t>(8, size[2] / 16));
  const std::int64_t slabs = (size[2] + slab - 1) / slab;
  std::atomic<std::int64_t> next{0};
  auto work = [&] {
    for (std::int64_t s = next++; s < slabs; s = next++) {
      renderer.block({0, size[0], 0, size[1], s * slab, std::min(size[2], (s + 1) * slab)});
    }
  };
  const unsigned threads = std::clamp(std::thread::hardware_concurrency(), 1u, 16u);
  if (threads <= 1 || slabs == 1) {
    work();
  } else {
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(work);
    for (std::thread& t : pool) t.join();
  }

  if (options.blur > 0.0) {
    using Blur = itk::DiscreteGaussianImageFilter<CtImage, CtImage>;
    auto blur = Blur::New();
    blur->SetInput(image);
    blur->SetVariance(options.blur * options.blur);
    blur->SetUseImageSpacingOn();
    blur->SetMaximumError(0.01);
    const double finest = options.spacing.minCoeff();
    blur->SetMaximumKernelWidth(std::max(32, 2 * static_cast<int>(std::ceil(4.0 * options.blur / finest)) + 3));
    try {
      blur->Update();
    } catch (const itk::ExceptionObject& e) {
      throw InvalidInputError(std::string("render_phantom: blur failed: ") + e.GetDescription());
    }
    image = blur->GetOutput();
    image->DisconnectPipeline();
  }

  if (options.noise > 0.0) {
    std::mt19937_64 rng(options.seed);
    std::normal_distribution<double> normal(0.0, options.noise);
    float* data = image->GetBufferPointer();
    const std::size_t count = image->GetLargestPossibleRegion().GetNumberOfPixels();
    for (std::size_t i = 0; i < count; ++i) data[i] = static_cast<float>(data[i] + normal(rng));
  }
  return image;
}

}  // namespace contourmesh
