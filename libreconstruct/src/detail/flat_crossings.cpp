// SPDX-License-Identifier: BSD-3-Clause
#include "detail/flat_crossings.h"

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

// One slice's columns for one way of crossing: its own values and those of the neighbour slices on the
// inside and on the outside.
struct Columns {
  const float* own;
  const float* in;
  const float* outside;
  int nx, ny;
  std::size_t pixels;
};

// Marks the undecided pixels, labels their patches and gathers each patch's values, their shares
// (c - b) / (a - b), and the second differences along x and y of the pixels whose two neighbours on that
// axis are in it too (a linear trend cancels there; independent noise of standard deviation s gives them
// sqrt(6) s). Returns the number of patches.
std::size_t find_patches(const Columns& c, float threshold, double band, FlatCrossingScratch& out) {
  bool any = false;
  for (std::size_t p = 0; p < c.pixels; ++p) {
    out.mask[p] = 0;
    if (!(c.in[p] >= threshold && c.outside[p] < threshold)) continue;
    const double r = (static_cast<double>(c.own[p]) - threshold) / (static_cast<double>(c.in[p]) - c.outside[p]);
    if (std::abs(r) > band) continue;
    out.mask[p] = 1;
    out.offset[p] = static_cast<float>(r);
    any = true;
  }
  if (!any) return 0;
  find_runs(out.mask.data(), c.nx, c.ny, out.runs);
  const std::size_t patches = static_cast<std::size_t>(label_runs(out.runs, Connectivity::Four, out.labels));
  out.values.resize(std::max(out.values.size(), patches + 1));
  out.differences.resize(out.values.size());
  out.shares.resize(out.values.size());
  for (std::size_t l = 0; l <= patches; ++l) {
    out.values[l].clear();
    out.differences[l].clear();
    out.shares[l].clear();
  }
  const std::vector<float>& r = out.offset;
  for (const PixelRun& run : out.runs) {
    const std::size_t row = static_cast<std::size_t>(run.y) * c.nx;
    for (int x = run.x0; x < run.x1; ++x) {
      const std::size_t p = row + x;
      out.values[run.label].push_back(r[p]);
      out.shares[run.label].push_back((c.own[p] - c.outside[p]) / (c.in[p] - c.outside[p]));
      if (x > run.x0 && x + 1 < run.x1) out.differences[run.label].push_back(r[p - 1] - 2 * r[p] + r[p + 1]);
      if (run.y > 0 && run.y + 1 < c.ny && out.mask[p - c.nx] && out.mask[p + c.nx]) {
        out.differences[run.label].push_back(r[p - c.nx] - 2 * r[p] + r[p + c.nx]);
      }
    }
  }
  return patches;
}

// Per patch: -1 when its pixels keep their own sides, 0 when it is outside, else the factor 1 / its
// median share that scales it to whole voxels inside. A patch is flat when its values spread no more
// than their noise: robust spreads (medians of absolute deviations), so that the partial-volume pixels
// at a patch's rim do not count. Where the noise fills much of the band, the band truncates every
// patch's spread to about the same: left alone.
std::vector<float> patch_scales(FlatCrossingScratch& patches, std::size_t count, const FlatCrossingOptions& options) {
  std::vector<float> scale(count + 1, -1.0f);
  for (std::size_t l = 1; l <= count; ++l) {
    std::vector<float>& v = patches.values[l];
    std::vector<float>& d = patches.differences[l];
    if (v.size() < options.min_pixels || 2 * d.size() < v.size()) continue;
    const double center = median(v);
    const double spread = median_deviation(v, center);
    const double noise = median_deviation(d, 0.0) / std::sqrt(6.0);
    if (noise > options.band / 3.0 || spread > options.flatness * noise) continue;
    // Inside when the face lies far enough beyond the slice's centre, whatever the threshold
    // (FlatCrossingOptions::inside_share).
    const double share = median(patches.shares[l]);
    scale[l] = share > options.inside_share ? static_cast<float>(1.0 / share) : 0.0f;
  }
  return scale;
}

// Outside: the patch's pixels under the threshold. Inside: the slice as the patch's median share scales
// it to a whole voxel, the pixels of the patch and those next to it (where the section's rim passes),
// so that the contour follows the in-plane shares at the rim as on a slice wholly inside. A pixel gets
// at most one new value (`patches.changed`); those that keep theirs are not listed.
void set_sides(const Columns& c, FlatCrossingScratch& patches, const std::vector<float>& scale, float above,
               float below, std::vector<PixelValue>& out) {
  std::vector<std::uint8_t>& changed = patches.changed;
  const auto set = [&](std::size_t p, float value) {
    if (changed[p]) return;
    changed[p] = 1;
    if (value != c.own[p]) out.push_back({p, value});
  };
  for (const PixelRun& run : patches.runs) {
    const float f = scale[run.label];
    if (f < 0.0f) continue;
    for (int x = run.x0; x < run.x1; ++x) {
      const std::size_t p = static_cast<std::size_t>(run.y) * c.nx + x;
      if (f == 0.0f) {
        set(p, std::min(c.own[p], below));
        continue;
      }
      set(p, std::max(c.outside[p] + (c.own[p] - c.outside[p]) * f, above));
      const int y = run.y;
      for (const auto& [dx, dy] : {std::pair{-1, 0}, std::pair{1, 0}, std::pair{0, -1}, std::pair{0, 1}}) {
        if (x + dx < 0 || x + dx >= c.nx || y + dy < 0 || y + dy >= c.ny) continue;
        const std::size_t q = p + static_cast<std::ptrdiff_t>(dy) * c.nx + dx;
        if (!patches.mask[q] && c.in[q] > c.outside[q]) set(q, c.outside[q] + (c.own[q] - c.outside[q]) * f);
      }
    }
  }
}

}  // namespace

std::vector<PixelValue> flat_crossing_values(const float* volume, int nx, int ny, int nz, int z, float threshold,
                                             float above, float below, const FlatCrossingOptions& options,
                                             FlatCrossingScratch& scratch) {
  std::vector<PixelValue> out;
  if (z <= 0 || z >= nz - 1) return out;
  const std::size_t pixels = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  const float* lower = volume + static_cast<std::size_t>(z - 1) * pixels;
  const float* own = lower + pixels;
  const float* upper = own + pixels;
  scratch.mask.resize(pixels);
  scratch.offset.resize(pixels);
  scratch.changed.assign(pixels, 0);
  for (const bool inside_below : {true, false}) {
    const Columns c{own, inside_below ? lower : upper, inside_below ? upper : lower, nx, ny, pixels};
    const std::size_t count = find_patches(c, threshold, options.band, scratch);
    if (count == 0) continue;
    set_sides(c, scratch, patch_scales(scratch, count, options), above, below, out);
  }
  return out;
}

std::vector<PixelValue> flat_crossing_values(const float* volume, int nx, int ny, int nz, int z, float threshold,
                                             float above, float below, const FlatCrossingOptions& options) {
  FlatCrossingScratch scratch;
  return flat_crossing_values(volume, nx, ny, nz, z, threshold, above, below, options, scratch);
}

}  // namespace contourmesh::detail
