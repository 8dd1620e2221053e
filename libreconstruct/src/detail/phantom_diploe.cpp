// SPDX-License-Identifier: BSD-3-Clause
// The skull with a diploe: the skull phantom's shell holding small closed cavities, as the spongy layer
// between a real skull's two tables does. Every slab of a CT stack through it holds holes that start or
// end inside the shell's ring while the ring itself hardly changes.
#include "detail/phantom_shapes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

namespace contourmesh::detail {

namespace {

// The skull's ellipsoids and orbits.
const Ellipsoid kOuter = SkullGeometry::outer(), kInner = SkullGeometry::inner();
constexpr double kCut = SkullGeometry::kCut;
constexpr double kOrbitRadius = SkullGeometry::kOrbitRadius, kOrbitZ = SkullGeometry::kOrbitZ,
                 kOrbitX = SkullGeometry::kOrbitX;

constexpr double kCavityRadius = 1.5;  // mm: a hole of 2.2-3 mm across on one or two 2 mm slices
constexpr double kMinWall =
    1.4;  // mm (two pixels at 0.7 mm) of bone between a cavity and either surface, the cut or an orbit
constexpr double kMinGap = 1.5;  // mm of bone between two cavities
constexpr int kCavities = 120;

// A fixed 64-bit linear congruential generator (Knuth's MMIX constants): the phantom is the same on every
// platform and standard library.
class Lcg {
 public:
  double uniform() {  // in [0, 1)
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state_ >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t state_ = 0x5eed'd1b1'0e00'0001ULL;
};

// Cavity centres: points of the shell's middle surface, far enough from both surfaces, the cut, the
// orbits and each other (rejection sampling, in a fixed order).
std::vector<Vec3> cavity_centres() {
  const Vec3 mid_axes = 0.5 * (kOuter.axes + kInner.axes);
  const double clearance = kCavityRadius + kMinWall;
  std::vector<Vec3> centres;
  Lcg rng;
  for (int attempt = 0; attempt < 200000 && static_cast<int>(centres.size()) < kCavities; ++attempt) {
    // A uniform direction (Archimedes: z uniform, angle uniform), on the middle ellipsoid.
    const double z = 2.0 * rng.uniform() - 1.0, phi = 2.0 * 3.14159265358979323846 * rng.uniform();
    const double r = std::sqrt(1.0 - z * z);
    const Vec3 c = kOuter.centre + Vec3(r * std::cos(phi), r * std::sin(phi), z).cwiseProduct(mid_axes);
    if (c.z() - kCut < clearance) continue;
    if (-kOuter.signed_distance(c) < clearance || kInner.signed_distance(c) < clearance) continue;
    bool clear = true;
    for (double x : {-kOrbitX, kOrbitX}) {
      clear = clear && std::hypot(c.x() - x, c.z() - kOrbitZ) - kOrbitRadius >= clearance;
    }
    for (const Vec3& o : centres) clear = clear && (o - c).norm() >= 2.0 * kCavityRadius + kMinGap;
    if (clear) centres.push_back(c);
  }
  return centres;
}

// The cavities bucketed by cells of `kCell` mm: a cell lists every cavity within kCell of it, so that a
// point's nearest cavity, where it is nearer than kCell - kCavityRadius, is among its cell's.
constexpr double kCell = 6.0;

struct CavityIndex {
  std::vector<Vec3> centres;
  std::unordered_map<std::int64_t, std::vector<int>> cells;

  static std::int64_t key(long i, long j, long k) { return (i + 512) * 1024 * 1024 + (j + 512) * 1024 + (k + 512); }
  static long cell(double x) { return static_cast<long>(std::floor(x / kCell)); }

  explicit CavityIndex(std::vector<Vec3> c) : centres(std::move(c)) {
    for (int n = 0; n < static_cast<int>(centres.size()); ++n) {
      const Vec3& p = centres[static_cast<std::size_t>(n)];
      for (long i = cell(p.x()) - 1; i <= cell(p.x()) + 1; ++i) {
        for (long j = cell(p.y()) - 1; j <= cell(p.y()) + 1; ++j) {
          for (long k = cell(p.z()) - 1; k <= cell(p.z()) + 1; ++k) cells[key(i, j, k)].push_back(n);
        }
      }
    }
  }

  // The signed distance to the union of the cavities where it is below kCell - kCavityRadius; a value at
  // least that large elsewhere.
  [[nodiscard]] double distance(const Vec3& p) const {
    double best = kCell;
    const auto it = cells.find(key(cell(p.x()), cell(p.y()), cell(p.z())));
    if (it == cells.end()) return best;
    for (int n : it->second) best = std::min(best, (p - centres[static_cast<std::size_t>(n)]).norm() - kCavityRadius);
    return best;
  }
};

}  // namespace

ShapeBuild build_skull_diploe() {
  ShapeBuild s = build_skull();
  const auto index = std::make_shared<const CavityIndex>(cavity_centres());
  // Every point of the shell lies within 3 mm of a surface, so where no cavity is within kCell - radius =
  // 4.4 mm the cavity term cannot win the maximum: the bucketed distance gives the exact field.
  const ScalarField skull = s.sdf;
  s.sdf = [skull, index](const Vec3& p) { return std::max(skull(p), -index->distance(p)); };
  s.volume.reset();
  const int n = static_cast<int>(index->centres.size());
  s.surface_components = 1 + n;         // each closed cavity is a sphere of its own
  s.euler_characteristic = -2 + 2 * n;  // the skull's genus 2 surface and n spheres
  return s;
}

}  // namespace contourmesh::detail
