// SPDX-License-Identifier: BSD-3-Clause
#include "detail/flat_crossings.h"

#include "detail/slice_components.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace contourmesh::detail {

namespace {

// The median of |v - center| over v (reorders v).
double median_deviation(std::vector<float>& v, double center) {
  for (float& x : v) x = static_cast<float>(std::abs(x - center));
  auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

double median(std::vector<float>& v) {
  auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

std::vector<PixelValue> flat_crossing_values(const float* volume, int nx, int ny, int nz, int z, float threshold,
                                             float above, float below, const FlatCrossingOptions& options) {
  std::vector<PixelValue> out;
  if (z <= 0 || z >= nz - 1) return out;
  const std::size_t pixels = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  const float* lower = volume + static_cast<std::size_t>(z - 1) * pixels;
  const float* own = lower + pixels;
  const float* upper = own + pixels;
  std::vector<std::uint8_t> mask(pixels), changed(pixels, 0);
  std::vector<float> offset(pixels);  // (c - t) / (a - b): the share above the threshold's
  std::vector<PixelRun> runs;
  UnionFind<int> scratch;
  std::vector<std::vector<float>> values, differences, shares;  // per patch
  std::vector<float> scale;                                      // per patch: 1 / its median share; 0 outside
  for (const bool inside_below : {true, false}) {
    const float* in = inside_below ? lower : upper;
    const float* outside = inside_below ? upper : lower;
    const auto crosses = [&](std::size_t p) { return in[p] >= threshold && outside[p] < threshold; };
    bool any = false;
    for (std::size_t p = 0; p < pixels; ++p) {
      mask[p] = 0;
      if (!crosses(p)) continue;
      const double r = (static_cast<double>(own[p]) - threshold) / (static_cast<double>(in[p]) - outside[p]);
      if (std::abs(r) > options.band) continue;
      mask[p] = 1;
      offset[p] = static_cast<float>(r);
      any = true;
    }
    if (!any) continue;
    find_runs(mask.data(), nx, ny, runs);
    const std::size_t patches = static_cast<std::size_t>(label_runs(runs, Connectivity::Four, scratch));
    values.resize(std::max(values.size(), patches + 1));
    differences.resize(values.size());
    shares.resize(values.size());
    for (std::size_t l = 0; l <= patches; ++l) {
      values[l].clear();
      differences[l].clear();
      shares[l].clear();
    }
    // Each patch's values, their shares (c - b) / (a - b), and the second differences along x and y of the
    // pixels whose two neighbours on that axis are in it too: a linear trend cancels there, and
    // independent noise of standard deviation s gives them sqrt(6) s.
    for (const PixelRun& run : runs) {
      const std::size_t row = static_cast<std::size_t>(run.y) * nx;
      for (int x = run.x0; x < run.x1; ++x) {
        const std::size_t p = row + x;
        values[run.label].push_back(offset[p]);
        shares[run.label].push_back((own[p] - outside[p]) / (in[p] - outside[p]));
        if (x > run.x0 && x + 1 < run.x1) {
          differences[run.label].push_back(offset[p - 1] - 2 * offset[p] + offset[p + 1]);
        }
        if (run.y > 0 && run.y + 1 < ny && mask[p - nx] && mask[p + nx]) {
          differences[run.label].push_back(offset[p - nx] - 2 * offset[p] + offset[p + nx]);
        }
      }
    }
    // A patch is flat when its values spread no more than their noise: robust spreads (medians of
    // absolute deviations), so that the partial-volume pixels at a patch's rim do not count. Where the
    // noise fills much of the band, the band truncates every patch's spread to about the same: left
    // alone.
    scale.assign(patches + 1, -1.0f);  // < 0: each pixel its own side
    for (std::size_t l = 1; l <= patches; ++l) {
      std::vector<float>& v = values[l];
      std::vector<float>& d = differences[l];
      if (v.size() < options.min_pixels || 2 * d.size() < v.size()) continue;
      const double center = median(v);
      const double spread = median_deviation(v, center);
      const double noise = median_deviation(d, 0.0) / std::sqrt(6.0);
      if (noise > options.band / 3.0 || spread > options.flatness * noise) continue;
      // Inside when the face lies far enough beyond the slice's centre, whatever the threshold
      // (FlatCrossingOptions::inside_share).
      const double share = median(shares[l]);
      scale[l] = share > options.inside_share ? static_cast<float>(1.0 / share) : 0.0f;
    }
    // Outside: the pixels under the threshold. Inside: the slice as the patch's median share scales it
    // to a whole voxel, the pixels of the patch and those next to it (where the section's rim passes),
    // so that the contour follows the in-plane shares at the rim as on a slice wholly inside.
    const auto set = [&](std::size_t p, float value) {
      if (changed[p]) return;
      changed[p] = 1;
      if (value != own[p]) out.push_back({p, value});
    };
    for (const PixelRun& run : runs) {
      const float f = scale[run.label];
      if (f < 0.0f) continue;
      for (int x = run.x0; x < run.x1; ++x) {
        const std::size_t p = static_cast<std::size_t>(run.y) * nx + x;
        if (f == 0.0f) {
          set(p, std::min(own[p], below));
          continue;
        }
        set(p, std::max(outside[p] + (own[p] - outside[p]) * f, above));
        const int y = run.y;
        for (const auto& [dx, dy] : {std::pair{-1, 0}, std::pair{1, 0}, std::pair{0, -1}, std::pair{0, 1}}) {
          if (x + dx < 0 || x + dx >= nx || y + dy < 0 || y + dy >= ny) continue;
          const std::size_t q = p + static_cast<std::ptrdiff_t>(dy) * nx + dx;
          if (!mask[q] && in[q] > outside[q]) set(q, outside[q] + (own[q] - outside[q]) * f);
        }
      }
    }
  }
  return out;
}

}  // namespace contourmesh::detail
