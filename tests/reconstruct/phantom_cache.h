// SPDX-License-Identifier: BSD-3-Clause
// The phantoms shared by the phantom tests, built once per process and shape (ctest runs each test in
// its own process, so a test builds only the shapes it uses).
#pragma once

#include "contourmesh/reconstruct/phantom.h"

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

namespace contourmesh::test {

inline const Phantom& phantom_of(PhantomShape shape) {
  static std::array<std::optional<Phantom>, 16> phantoms;
  std::optional<Phantom>& p = phantoms.at(static_cast<std::size_t>(shape));
  if (!p) p = make_phantom(shape);
  return *p;
}

/// Every voxel value of `image`, in ITK's buffer order (x fastest).
inline std::vector<float> values(const CtImage& image) {
  const float* data = image.GetBufferPointer();
  return {data, data + image.GetLargestPossibleRegion().GetNumberOfPixels()};
}

}  // namespace contourmesh::test
