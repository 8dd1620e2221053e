// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/off_slice_heights.h"

#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/normals.h>

#include "contourmesh/internal/union_find.h"

#include <Eigen/Core>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <string>
#include <tuple>
#include <vector>

namespace contourmesh {

namespace {

// The image in its own index frame: continuous (i, j, k) of a physical point, bilinear values in a slice.
class SliceSampler {
 public:
  explicit SliceSampler(const CtImage& image) : values_(image.GetBufferPointer()) {
    const auto size = image.GetLargestPossibleRegion().GetSize();
    for (int d = 0; d < 3; ++d) size_[d] = static_cast<long>(size[d]);
    const auto origin = image.GetOrigin();
    const auto spacing = image.GetSpacing();
    const auto dir = image.GetDirection();
    for (int d = 0; d < 3; ++d) {
      origin_[d] = origin[d];
      spacing_[d] = spacing[d];
      for (int r = 0; r < 3; ++r) axes_(r, d) = dir[r][d];
    }
  }
  [[nodiscard]] Eigen::Vector3d index_of(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d local = axes_.transpose() * (p - origin_);
    return local.cwiseQuotient(spacing_);
  }
  [[nodiscard]] Eigen::Vector3d axis(int d) const { return axes_.col(d); }
  [[nodiscard]] double spacing(int d) const { return spacing_[d]; }
  [[nodiscard]] long slices() const { return size_[2]; }
  [[nodiscard]] bool has_slice(long k) const { return k >= 0 && k < size_[2]; }
  // Bilinear value at continuous in-plane index (x, y) of slice k (clamped to the image).
  [[nodiscard]] double at(double x, double y, long k) const {
    const double fx = std::clamp(x, 0.0, static_cast<double>(size_[0] - 1));
    const double fy = std::clamp(y, 0.0, static_cast<double>(size_[1] - 1));
    const long ix = std::min(static_cast<long>(fx), std::max(size_[0] - 2, 0L));
    const long iy = std::min(static_cast<long>(fy), std::max(size_[1] - 2, 0L));
    const long jx = std::min(ix + 1, size_[0] - 1), jy = std::min(iy + 1, size_[1] - 1);
    const double tx = fx - static_cast<double>(ix), ty = fy - static_cast<double>(iy);
    auto v = [&](long x0, long y0) { return static_cast<double>(values_[(k * size_[1] + y0) * size_[0] + x0]); };
    return (1.0 - ty) * ((1.0 - tx) * v(ix, iy) + tx * v(jx, iy)) + ty * ((1.0 - tx) * v(ix, jy) + tx * v(jx, jy));
  }

 private:
  const float* values_;
  std::array<long, 3> size_{};
  Eigen::Vector3d origin_, spacing_;
  Eigen::Matrix3d axes_;
};

void check(const Mesh& mesh, const OffSliceOptions& o) {
  if (!mesh.has_contour_ids()) throw InvalidInputError("off-slice heights: the mesh carries no slice ids");
  if (!(o.smoothness > 0.0) || !std::isfinite(o.smoothness)) {
    throw InvalidInputError("off-slice heights: smoothness must be > 0, got " + std::to_string(o.smoothness));
  }
  if (o.iterations < 1) throw InvalidInputError("off-slice heights: iterations must be >= 1");
  if (!(o.min_fraction >= 0.0 && o.min_fraction < 0.5)) {
    throw InvalidInputError("off-slice heights: min_fraction must be in [0, 0.5), got " +
                            std::to_string(o.min_fraction));
  }
  if (!(o.cap_far_fraction >= 0.0 && o.cap_far_fraction < 0.5)) {
    throw InvalidInputError("off-slice heights: cap_far_fraction must be in [0, 0.5), got " +
                            std::to_string(o.cap_far_fraction));
  }
  if (!(o.inward_pixels >= 0.0) || !std::isfinite(o.inward_pixels)) {
    throw InvalidInputError("off-slice heights: inward_pixels must be >= 0");
  }
}

// Where between slices k (t = 0) and k + 1 (t = 1) the column at in-plane index (x, y) crosses the
// threshold; false without a crossing. With the levels one slice further inside and outside, the two
// values are normalised by them to the shares a', b' in [0, 1] of the voxels that lie inside, and the
// boundary is where those shares put it: a voxel value is the mean over the voxel's slice profile, and
// profiles that tile the axis (a box as wide as the spacing, or its blur) make a' + b' grow linearly
// with the boundary's height, so t = a' + b' - 1/2 (inside towards slice k; 3/2 - a' - b' the other
// way). Interpolating the threshold linearly between the slice centres instead reads a step's height
// with half the slope around the mid-plane and twice near the slices, and lays a gently tilted wall
// out as flat terraces at the mid-planes. Without those levels (the image's first or last slices), the
// linear interpolation of the threshold.
bool crossing(const SliceSampler& s, double x, double y, long k, double threshold, double& t) {
  const double va = s.at(x, y, k), vb = s.at(x, y, k + 1);
  const double a = va - threshold, b = vb - threshold;
  if (a * b >= 0.0) return false;
  const long inside = a > 0.0 ? k - 1 : k + 2, outside = a > 0.0 ? k + 2 : k - 1;
  if (s.has_slice(inside) && s.has_slice(outside)) {
    const double vin = s.at(x, y, inside), vout = s.at(x, y, outside);
    if (vin > threshold && vout < threshold) {
      const double share_a = std::clamp((va - vout) / (vin - vout), 0.0, 1.0);
      const double share_b = std::clamp((vb - vout) / (vin - vout), 0.0, 1.0);
      const double sum = share_a + share_b;
      t = a > 0.0 ? sum - 0.5 : 1.5 - sum;
      return true;
    }
  }
  t = a / (a - b);
  return true;
}

// Calls fn(v) for every vertex v < n, in blocks on every core (as many as TBB's global limit allows); fn
// must write only what belongs to v.
template <class Fn>
void for_each_vertex(Index n, const Fn& fn) {
  tbb::parallel_for(tbb::blocked_range<Index>(0, n, 1024), [&](const tbb::blocked_range<Index>& range) {
    for (Index v = range.begin(); v < range.end(); ++v) fn(v);
  });
}

Eigen::Vector3d face_normal(const Eigen::Matrix3Xd& x, const Triangle& t) {
  return (x.col(t[1]) - x.col(t[0])).cross(x.col(t[2]) - x.col(t[0]));
}

// 1 for the vertices of end caps (faces of role Cap), else 0.
std::vector<std::uint8_t> cap_vertices(const Mesh& mesh, const std::vector<FaceRole>& face_roles) {
  std::vector<std::uint8_t> on_cap(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (std::size_t f = 0; f < face_roles.size(); ++f) {
    if (face_roles[f] != FaceRole::Cap) continue;
    for (Index v : mesh.triangles[f]) on_cap[static_cast<std::size_t>(v)] = 1;
  }
  return on_cap;
}

// Per vertex of an end cap (`on_cap`, from cap_vertices): +1 when its cap closes a contour below it
// (along w), so that the slice it may come near is the one above; -1 the reverse; 0 off the caps or
// where no cap vertex of its cap (connected through cap faces) neighbours a contour vertex. Outer caps
// face away from their contour and the caps of holes towards it, so the side comes from the contour,
// not the normal.
std::vector<signed char> cap_sides(const Mesh& mesh, const std::vector<FaceRole>& face_roles,
                                   const std::vector<std::uint8_t>& on_cap, const MeshAdjacency& adjacency,
                                   const Eigen::Vector3d& w) {
  const std::size_t n = static_cast<std::size_t>(mesh.num_vertices());
  std::vector<signed char> side(n, 0);
  detail::UnionFind<Index> caps(n);
  for (std::size_t f = 0; f < face_roles.size(); ++f) {
    if (face_roles[f] != FaceRole::Cap) continue;
    const auto& t = mesh.triangles[f];
    caps.unite(t[0], t[1]);
    caps.unite(t[0], t[2]);
  }
  std::vector<signed char> root_side(n, 0);
  for (std::size_t v = 0; v < n; ++v) {
    if (!on_cap[v] || mesh.slice_ids[static_cast<Index>(v)] >= 0) continue;
    for (Index u : adjacency.ring(static_cast<Index>(v))) {
      if (mesh.slice_ids[u] < 0 || on_cap[static_cast<std::size_t>(u)]) continue;
      const double dw = (mesh.positions.col(static_cast<Index>(v)) - mesh.positions.col(u)).dot(w);
      if (dw != 0.0) root_side[static_cast<std::size_t>(caps.find(static_cast<Index>(v)))] = dw > 0.0 ? 1 : -1;
    }
  }
  for (std::size_t v = 0; v < n; ++v) {
    if (on_cap[v]) side[v] = root_side[static_cast<std::size_t>(caps.find(static_cast<Index>(v)))];
  }
  return side;
}

}  // namespace

OffSliceResult fit_off_slice_heights(Mesh mesh, const CtImage& image, double threshold,
                                     const OffSliceOptions& options, const std::vector<FaceRole>& face_roles) {
  check(mesh, options);
  if (!face_roles.empty() && face_roles.size() != mesh.triangles.size()) {
    throw InvalidInputError("off-slice heights: " + std::to_string(face_roles.size()) + " face roles for " +
                            std::to_string(mesh.triangles.size()) + " faces");
  }
  OffSliceResult result;
  if (options.placement == OffSlicePlacement::Tiled || mesh.num_vertices() == 0) {
    result.mesh = std::move(mesh);
    return result;
  }
  const SliceSampler sampler(image);
  const Index n = mesh.num_vertices();
  const Eigen::Vector3d w = sampler.axis(2);
  const double h = sampler.spacing(2);
  const Eigen::Matrix3Xd normals = vertex_normals(mesh.positions, mesh.triangles);
  const MeshAdjacency adjacency = build_adjacency(mesh);

  // Which vertices read the whole step inwards: those of end caps (every vertex without roles, or when
  // asked); the others a step that shrinks as the surface there turns towards the slices.
  const std::vector<std::uint8_t> on_cap = cap_vertices(mesh, face_roles);
  const std::vector<signed char> cap_side = cap_sides(mesh, face_roles, on_cap, adjacency, w);
  std::vector<std::uint8_t> reads_inward(static_cast<std::size_t>(n), 1);
  if (options.inward_read == InwardRead::ScaledOffCaps && !face_roles.empty()) reads_inward = on_cap;

  // Data term and bounds per vertex, all as displacements along w in mm.
  std::vector<double> target(n, 0.0), weight(n, 0.0), low(n, 0.0), high(n, 0.0);
  std::vector<std::uint8_t> free_vertex(n, 0), fitted(n, 0);
  // Each vertex reads the image and writes its own entries: in blocks on every core.
  auto data_term = [&](Index v) {
    if (mesh.slice_ids[v] >= 0) return;
    const Eigen::Vector3d index = sampler.index_of(mesh.positions.col(v));
    const double kz = index.z();
    const long k = static_cast<long>(std::floor(kz));
    const double frac = kz - static_cast<double>(k);
    if (k < 0 || k + 1 >= sampler.slices() || frac < 1e-6 || frac > 1.0 - 1e-6) return;
    free_vertex[v] = 1;
    const Eigen::Vector3d nv = normals.col(v);
    const double nu = nv.dot(sampler.axis(0)), nw = nv.dot(w), nvv = nv.dot(sampler.axis(1));
    // A cap that closes a contour of slice k may come near slice k + 1, and the reverse.
    const signed char cap = cap_side[static_cast<std::size_t>(v)];
    const double far = std::min(options.cap_far_fraction, options.min_fraction);
    const double lowest = cap < 0 ? far : options.min_fraction;
    const double highest = 1.0 - (cap > 0 ? far : options.min_fraction);
    low[v] = (lowest - frac) * h;
    high[v] = (highest - frac) * h;
    const double tilt = std::abs(nw) / std::max(nv.norm(), 1e-12);  // |cos| of the angle to the slice axis
    const double inward = reads_inward[static_cast<std::size_t>(v)]
                              ? options.inward_pixels
                              : options.inward_pixels * std::sqrt(std::max(0.0, 1.0 - tilt));
    const double x = index.x() - inward * nu, y = index.y() - inward * nvv;
    double t = 0.0;
    if (!crossing(sampler, x, y, k, threshold, t)) return;
    t = std::clamp(t, lowest, highest);
    target[v] = (t - frac) * h;
    weight[v] = std::abs(nw);
    fitted[v] = 1;
  };
  for_each_vertex(n, data_term);
  result.report.candidates = static_cast<std::size_t>(std::count(free_vertex.begin(), free_vertex.end(), 1));
  result.report.fitted = static_cast<std::size_t>(std::count(fitted.begin(), fitted.end(), 1));

  // Membrane fit (Jacobi): vertices with ids hold still at 0.
  std::vector<double> d(n, 0.0), next(n, 0.0);
  const double lambda = options.smoothness;
  for (int it = 0; it < options.iterations; ++it) {
    for_each_vertex(n, [&](Index v) {
      if (!free_vertex[v]) return;
      double sum = weight[v] * target[v], den = weight[v];
      for (Index u : adjacency.ring(v)) {
        sum += lambda * d[u];
        den += lambda;
      }
      next[v] = den > 0.0 ? std::clamp(sum / den, low[v], high[v]) : 0.0;
    });
    d.swap(next);
  }

  // Vertices on one column of the image between the same two slices (a composite's copy and a point
  // the tiler put on a face below it, in a strip that stands straight between them) have the same data
  // term: where the fit would make two of them meet or pass each other, the column keeps the tiler's
  // heights.
  // Entries (column, height, vertex) sorted: each column is a run, its vertices by height.
  struct ColumnEntry {
    std::array<long long, 3> key;
    double z;
    Index v;
    bool operator<(const ColumnEntry& o) const { return std::tie(key, z, v) < std::tie(o.key, o.z, o.v); }
  };
  std::vector<ColumnEntry> columns;
  columns.reserve(result.report.candidates);
  for (Index v = 0; v < n; ++v) {
    if (!free_vertex[v]) continue;
    const Eigen::Vector3d index = sampler.index_of(mesh.positions.col(v));
    columns.push_back({{std::llround(index.x() * 1e6), std::llround(index.y() * 1e6),
                        static_cast<long long>(std::floor(index.z()))},
                       index.z() * h,
                       v});
  }
  std::sort(columns.begin(), columns.end());
  // Two vertices of one column must keep at least this share of the gap the tiler left between them:
  // nearer, their faces are all but degenerate (a zero-area face on the headsq scan once the vertices
  // off the caps read their own columns, which gives the two the same data term).
  constexpr double kMinGapShare = 0.3;
  for (std::size_t begin = 0, end = 0; begin < columns.size(); begin = end) {
    end = begin + 1;
    while (end < columns.size() && columns[end].key == columns[begin].key) ++end;
    if (end - begin < 2) continue;
    bool apart = true;
    for (std::size_t k = begin; k + 1 < end; ++k) {
      const ColumnEntry& a = columns[k];
      const ColumnEntry& b = columns[k + 1];
      apart = apart && (b.z + d[b.v]) - (a.z + d[a.v]) > kMinGapShare * (b.z - a.z);
    }
    if (!apart) {
      for (std::size_t k = begin; k < end; ++k) d[columns[k].v] = 0.0;
    }
  }

  // Apply, then halve the moves around faces that would turn over (a steep face whose ends went
  // different ways), a few rounds at most; what is left unmoved is the tiler's placement.
  const Eigen::Matrix3Xd before = mesh.positions;
  auto place = [&](Index v) { mesh.positions.col(v) = before.col(v) + d[v] * w; };
  for (Index v = 0; v < n; ++v)
    if (d[v] != 0.0) place(v);
  // A face is checked again only when it may have turned since its last check: it turned then (its moves
  // were halved), or one of its corners moved after that check (faces are checked in order, round after
  // round, so "after" is a later round, or the same round and a later face). The rest keep their state,
  // bit for bit, so the outcome is that of checking every face every round.
  std::vector<std::uint8_t> damped(n, 0);
  const auto num_faces = static_cast<long long>(mesh.triangles.size());
  std::vector<long long> moved_at(n, -1);  // round * faces + face of the last move, -1: none since the start
  std::vector<std::uint8_t> turned(mesh.triangles.size(), 1);  // round 0 checks every moved face
  for (int round = 0; round < 8; ++round) {
    bool any = false;
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
      const Triangle& t = mesh.triangles[f];
      if (d[t[0]] == 0.0 && d[t[1]] == 0.0 && d[t[2]] == 0.0) continue;  // unmoved: it cannot have turned
      const long long last_check = (round - 1) * num_faces + static_cast<long long>(f);
      if (!turned[f] && moved_at[t[0]] <= last_check && moved_at[t[1]] <= last_check &&
          moved_at[t[2]] <= last_check) {
        continue;
      }
      const Eigen::Vector3d n0 = face_normal(before, t), n1 = face_normal(mesh.positions, t);
      turned[f] = 0;
      if (n0.squaredNorm() < 1e-24 || n0.dot(n1) > 0.17 * n0.norm() * n1.norm()) continue;
      turned[f] = 1;
      for (Index v : t) {
        if (d[v] == 0.0) continue;
        d[v] = round == 7 ? 0.0 : 0.5 * d[v];
        damped[v] = 1;
        place(v);
        moved_at[v] = round * num_faces + static_cast<long long>(f);
        any = true;
      }
    }
    if (!any) break;
  }
  result.report.damped = static_cast<std::size_t>(std::count(damped.begin(), damped.end(), std::uint8_t{1}));
  result.mesh = std::move(mesh);
  return result;
}

}  // namespace contourmesh
