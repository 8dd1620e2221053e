// SPDX-License-Identifier: BSD-3-Clause
#include "detail/region_boundaries.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>

namespace contourmesh::detail {

namespace {

// The sides of a square whose top-left pixel is (x, y): T between (x, y) and (x + 1, y), B between
// (x, y + 1) and (x + 1, y + 1), L between (x, y) and (x, y + 1), R between (x + 1, y) and (x + 1, y + 1).
enum Side : std::int8_t { T = 0, B = 1, L = 2, R = 3, None = -1 };

// The side through which a boundary leaves a square after entering through another, with the region
// on its right. Square case: bit 0 top-left, bit 1 top-right, bit 2 bottom-left, bit 3 bottom-right
// pixel in the region. In the saddles (6, 9) the region's two pixels stay apart: two segments.
constexpr std::array<std::array<Side, 4>, 16> make_exits() {
  std::array<std::array<Side, 4>, 16> e{};
  for (auto& c : e) c = {None, None, None, None};
  auto set = [&](int c, Side from, Side to) { e[c][from] = to; };
  set(1, T, L);
  set(2, R, T);
  set(3, R, L);
  set(4, L, B);
  set(5, T, B);
  set(6, R, T);
  set(6, L, B);
  set(7, R, B);
  set(8, B, R);
  set(9, T, L);
  set(9, B, R);
  set(10, B, T);
  set(11, B, L);
  set(12, L, R);
  set(13, T, R);
  set(14, L, T);
  return e;
}
constexpr auto kExits = make_exits();

// A crossing in the padded grid: the edge's first pixel (left or top), its direction, and which of
// its two pixels is the region's (0: the first).
struct Crossing {
  std::size_t pixel;
  bool horizontal;
  int side;
  bool operator==(const Crossing&) const = default;
};

std::uint8_t visit_bit(const Crossing& c) {
  return static_cast<std::uint8_t>(1u << ((c.horizontal ? 0 : 2) + c.side));
}

void trace_loop(const std::vector<int>& own, std::size_t width, std::vector<std::uint8_t>& visited,
                const Crossing start, RegionLoop& loop) {
  const std::size_t w = width;
  const int region = own[start.side == 0 ? start.pixel : start.pixel + (start.horizontal ? 1 : w)];
  loop.region = region;
  std::int64_t min_key = std::numeric_limits<std::int64_t>::max(), max_key = -1;
  std::size_t max_at = 0;
  Crossing c = start;
  do {
    // The square the boundary enters next: the region's pixel of this edge stays on the right.
    std::size_t s = 0;
    Side in = None;
    if (c.horizontal) {
      s = c.side == 0 ? c.pixel : c.pixel - w;
      in = c.side == 0 ? T : B;
    } else {
      s = c.side == 0 ? c.pixel - 1 : c.pixel;
      in = c.side == 0 ? R : L;
    }
    const int square = (own[s] == region) | (own[s + 1] == region) << 1 | (own[s + w] == region) << 2 |
                       (own[s + w + 1] == region) << 3;
    // Marching-squares order of this segment: its square's raster index. A loop holding both segments
    // of a saddle square also passes the square above it and the one below, so the saddle is neither
    // its first nor its last square: the order of the two segments never decides anything.
    const auto key = static_cast<std::int64_t>(s);
    switch (kExits[square][in]) {
      case T: c = {s, true, own[s] == region ? 0 : 1}; break;
      case B: c = {s + w, true, own[s + w] == region ? 0 : 1}; break;
      case L: c = {s, false, own[s] == region ? 0 : 1}; break;
      case R: c = {s + 1, false, own[s + 1] == region ? 0 : 1}; break;
      case None: return;  // cannot happen: every crossing has one square to leave through
    }
    visited[c.pixel] |= visit_bit(c);
    min_key = std::min(min_key, key);
    if (key > max_key) {
      max_key = key;
      max_at = loop.crossings.size();
    }
    const int x = static_cast<int>(c.pixel % w) - 1, y = static_cast<int>(c.pixel / w) - 1;
    loop.crossings.push_back({x, y, c.horizontal});
  } while (!(c == start));
  loop.first_key = min_key;
  std::rotate(loop.crossings.begin(), loop.crossings.begin() + static_cast<std::ptrdiff_t>(max_at),
              loop.crossings.end());
}

}  // namespace

void trace_region_boundaries(const RegionImage& regions, std::span<const PixelRun> owned,
                             std::vector<std::uint8_t>& visited, std::vector<RegionLoop>& loops) {
  loops.clear();
  const std::vector<int>& own = regions.padded();
  const std::size_t w = static_cast<std::size_t>(regions.nx()) + 2;
  visited.assign(own.size(), 0);
  auto start = [&](const Crossing& c) {
    if (visited[c.pixel] & visit_bit(c)) return;
    loops.emplace_back();
    trace_loop(own, w, visited, c, loops.back());
  };
  // Every loop crosses some horizontal edge at the end of a run of its region.
  for (const PixelRun& r : owned) {
    const std::size_t first = static_cast<std::size_t>(r.y + 1) * w + static_cast<std::size_t>(r.x0 + 1);
    const std::size_t last = first + static_cast<std::size_t>(r.x1 - r.x0) - 1;
    if (own[first - 1] != own[first]) start({first - 1, true, 1});
    if (own[last + 1] != own[last]) start({last, true, 0});
  }
  std::sort(loops.begin(), loops.end(), [](const RegionLoop& a, const RegionLoop& b) {
    return a.region != b.region ? a.region < b.region : a.first_key < b.first_key;
  });
}

}  // namespace contourmesh::detail
