// SPDX-License-Identifier: BSD-3-Clause
// Test helpers: CT-like volumes from a per-pixel function, or of a solid given by its signed distance with
// partial-volume values.
#pragma once

#include <contourmesh/reconstruct/volume.h>

#include <Eigen/Core>

#include <array>
#include <functional>

namespace contourmesh::test {

/// A volume from a per-pixel function of (i, j, k), spacing `spacing`, origin 0.
inline CtImage::Pointer pixel_volume(const std::array<int, 3>& n, const Eigen::Vector3d& spacing,
                                     const std::function<float(int, int, int)>& value) {
  auto image = CtImage::New();
  CtImage::RegionType region;
  region.SetSize({{static_cast<itk::SizeValueType>(n[0]), static_cast<itk::SizeValueType>(n[1]),
                   static_cast<itk::SizeValueType>(n[2])}});
  image->SetRegions(region);
  image->SetSpacing(spacing.data());
  image->Allocate();
  for (int k = 0; k < n[2]; ++k) {
    for (int j = 0; j < n[1]; ++j) {
      for (int i = 0; i < n[0]; ++i) image->SetPixel({{i, j, k}}, value(i, j, k));
    }
  }
  return image;
}

/// Voxel value: 1000 times the fraction of the voxel (4 x 4 x `depth` supersamples, the slice's whole
/// thickness) where sdf < 0. Physical point of index (i, j, k) = spacing * index.
inline CtImage::Pointer partial_volume(const std::array<int, 3>& n, const Eigen::Vector3d& spacing,
                                       const std::function<double(const Eigen::Vector3d&)>& sdf, int depth = 8) {
  return pixel_volume(n, spacing, [&](int i, int j, int k) {
    int inside = 0;
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        for (int c = 0; c < depth; ++c) {
          const Eigen::Vector3d p((i - 0.375 + 0.25 * a) * spacing.x(), (j - 0.375 + 0.25 * b) * spacing.y(),
                                  (k - 0.5 + (c + 0.5) / depth) * spacing.z());
          inside += sdf(p) < 0.0;
        }
    return 1000.0f * static_cast<float>(inside) / static_cast<float>(16 * depth);
  });
}

}  // namespace contourmesh::test
