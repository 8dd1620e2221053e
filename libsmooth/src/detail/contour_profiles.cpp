// SPDX-License-Identifier: BSD-3-Clause
#include "detail/contour_profiles.h"

#include "contourmesh/internal/huge_pages.h"
#include "detail/parallel.h"
#include "contourmesh/smooth/errors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace contourmesh::detail {

ContourFrame make_contour_frame(const Mesh& mesh) {
  if (!mesh.has_contour_ids()) {
    throw InvalidInputError("cross-slice smoothing needs contour ids (recover them from the slice planes first)");
  }
  ContourFrame f;
  f.mesh = &mesh;
  f.adjacency = build_adjacency(mesh);
  f.contour = contour_neighbours(mesh, f.adjacency);
  f.rings = split_rings_by_slice(mesh, f.adjacency);
  f.axis = estimate_slice_axis(mesh);
  const Index n = mesh.num_vertices();
  detail::assign_huge(f.on_contour, static_cast<std::size_t>(n), 0);
  std::vector<double> heights;
  std::map<std::int32_t, std::pair<double, double>> levels;  // slice id -> (sum of heights, count)
  double edge_sum = 0.0;
  std::size_t edges = 0;
  // Vertices come slice by slice in a tiled mesh: the map is looked up only when the slice changes.
  std::int32_t last_slice = kNoId;
  std::pair<double, double>* slice_level = nullptr;
  for (Index i = 0; i < n; ++i) {
    const auto& nb = f.contour.of[static_cast<std::size_t>(i)];
    if (mesh.slice_ids[static_cast<std::size_t>(i)] < 0 || nb[0] < 0 || nb[1] < 0) continue;
    f.on_contour[static_cast<std::size_t>(i)] = 1;
    edge_sum += (mesh.positions.col(nb[0]) - mesh.positions.col(i)).norm();
    ++edges;
    if (slice_level == nullptr || mesh.slice_ids[static_cast<std::size_t>(i)] != last_slice) {
      last_slice = mesh.slice_ids[static_cast<std::size_t>(i)];
      slice_level = &levels[last_slice];
    }
    slice_level->first += mesh.positions.col(i).dot(f.axis);
    slice_level->second += 1.0;
  }
  // The spacing from the slices' own heights, not from edges between them: a tiler that inserts
  // intermediate contours joins no contour vertex to the next slice directly.
  std::int32_t previous_id = -1;
  double previous_height = 0.0;
  for (const auto& [id, level] : levels) {
    const double height = level.first / level.second;
    if (previous_id >= 0) heights.push_back(std::abs(height - previous_height));
    previous_id = id;
    previous_height = height;
  }
  if (heights.empty() || edges == 0) {
    throw InvalidInputError("cross-slice smoothing: the mesh has contour vertices on fewer than two slices");
  }
  detail::assign_huge(f.above, static_cast<std::size_t>(n), -1);
  detail::assign_huge(f.below, static_cast<std::size_t>(n), -1);
  parallel_chunks(static_cast<std::size_t>(n), 8192, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (auto i = static_cast<Index>(begin); i < static_cast<Index>(end); ++i) {
      if (!f.is_contour_vertex(i)) continue;
      for (const bool upward : {true, false}) {
        double best = std::numeric_limits<double>::infinity();
        Index pick = -1;
        for (Index j : upward ? f.rings.above(i) : f.rings.below(i)) {
          if (!f.is_contour_vertex(j)) continue;
          const Eigen::Vector3d d = mesh.positions.col(j) - mesh.positions.col(i);
          const double in_plane = (d - d.dot(f.axis) * f.axis).squaredNorm();
          if (in_plane < best) {
            best = in_plane;
            pick = j;
          }
        }
        (upward ? f.above : f.below)[static_cast<std::size_t>(i)] = pick;
      }
    }
  });
  std::nth_element(heights.begin(), heights.begin() + static_cast<std::ptrdiff_t>(heights.size() / 2), heights.end());
  f.slice_spacing = heights[heights.size() / 2];
  f.point_spacing = edge_sum / static_cast<double>(edges);
  f.edges = SliceEdgeGrid(mesh, f.contour, f.on_contour, f.axis, 2.0 * f.point_spacing);
  if (!(f.slice_spacing > 0.0) || !(f.point_spacing > 0.0)) {
    throw InvalidInputError("cross-slice smoothing: the slices or the contour points are not apart");
  }
  return f;
}

bool in_slice_normal(const ContourFrame& frame, const Eigen::Vector3d& surface_normal, Eigen::Vector3d& m) {
  m = surface_normal - surface_normal.dot(frame.axis) * frame.axis;
  const double len = m.norm();
  // Below ~3 degrees from the slice plane the in-slice direction is noise.
  if (!(len > 0.05)) return false;
  m /= len;
  return true;
}

namespace {

// Contour vertices of the next slice (upward or downward) joined to `from`.
template <typename Out>
void next_slice(const ContourFrame& f, Index from, bool upward, Out&& out) {
  for (Index j : upward ? f.rings.above(from) : f.rings.below(from)) {
    if (f.is_contour_vertex(j)) out(j);
  }
}

}  // namespace

namespace {

// Where the plane (through `origin`, normal `plane_normal`) crosses the contour of the start vertices:
// from the start vertex nearest to the plane, along the contour towards the plane, at most `max_steps`
// edges. Start vertices that are not contour vertices (an end of a contour broken by a vertex without
// ids) are passed over. Returns false when it does not cross there.
bool cut_contour(const ContourFrame& f, const Eigen::Matrix3Xd& x, const Index* start, int starts,
                 const Eigen::Vector3d& origin, const Eigen::Vector3d& plane_normal, Eigen::Vector3d& cut,
                 Index& edge_a, Index& edge_b) {
  constexpr int kMaxSteps = 24;
  Index j = -1;
  double sj = std::numeric_limits<double>::infinity();
  for (int k = 0; k < starts; ++k) {
    if (!f.is_contour_vertex(start[k])) continue;  // it has no two contour neighbours to walk to
    const double s = (x.col(start[k]) - origin).dot(plane_normal);
    if (std::abs(s) < std::abs(sj)) {
      sj = s;
      j = start[k];
    }
  }
  if (j < 0) return false;
  const auto signed_distance = [&](Index v) { return (x.col(v) - origin).dot(plane_normal); };
  // Of j's two contour neighbours, walk towards the one on the other side of the plane, or nearer to it.
  const auto& nb = f.contour.of[static_cast<std::size_t>(j)];
  const double s0 = signed_distance(nb[0]), s1 = signed_distance(nb[1]);
  const auto crosses = [&](double a, double b) { return (a <= 0.0) != (b <= 0.0); };
  Index prev = j, cur = -1;
  double sp = sj, sc = 0.0;
  if (crosses(sj, s0) && crosses(sj, s1)) {
    // Both edges cross (j sits on a fold): take the nearer crossing.
    cur = std::abs(sj / (sj - s0)) <= std::abs(sj / (sj - s1)) ? nb[0] : nb[1];
    sc = cur == nb[0] ? s0 : s1;
  } else if (crosses(sj, s0)) {
    cur = nb[0];
    sc = s0;
  } else if (crosses(sj, s1)) {
    cur = nb[1];
    sc = s1;
  } else {
    // No crossing next to j: walk towards the plane.
    cur = std::abs(s0) < std::abs(s1) ? nb[0] : nb[1];
    sc = cur == nb[0] ? s0 : s1;
    for (int step = 0; step < kMaxSteps && !crosses(sp, sc); ++step) {
      const auto& nc = f.contour.of[static_cast<std::size_t>(cur)];
      const Index next = nc[0] == prev ? nc[1] : nc[0];
      if (next < 0 || next == j) return false;
      prev = cur;
      cur = next;
      sp = sc;
      sc = signed_distance(cur);
    }
    if (!crosses(sp, sc)) return false;
  }
  const double t = sp / (sp - sc);
  cut = x.col(prev) + t * (x.col(cur) - x.col(prev));
  edge_a = prev;
  edge_b = cur;
  return true;
}

}  // namespace

void cross_slice_profile(const ContourFrame& f, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& normals, Index i,
                         const Eigen::Vector3d& m, int reach, Profile& out) {
  constexpr int kMaxStarts = 16;
  const Eigen::Vector3d v = x.col(i);
  const Eigen::Vector3d plane_normal = f.axis.cross(m);
  const double max_offset = 6.0 * f.slice_spacing;
  const double search_radius = 1.5 * f.slice_spacing;
  const std::int32_t own_slice = f.mesh->slice_ids[static_cast<std::size_t>(i)];
  std::array<Index, kMaxStarts> start{};
  // Samples of each side, nearest first; written out in increasing height at the end (no sort). Left
  // uninitialised: only the count[dir] pairs written are read (zeroing the 2 KB was a sixth of a
  // chained profile's instructions).
  std::array<std::array<double, 2 * kMaxProfile>, 2> side;
  std::array<int, 2> count{0, 0};
  reach = std::min(reach, kMaxProfile / 2 - 1);
  for (int dir = 0; dir < 2; ++dir) {
    const bool upward = dir == 1;
    int starts = 0;
    const auto add = [&](Index j) {
      if (starts < kMaxStarts) start[static_cast<std::size_t>(starts++)] = j;
    };
    const std::vector<Index>& next = upward ? f.above : f.below;
    next_slice(f, i, upward, add);
    Eigen::Vector3d previous = v;
    for (int k = 1; k <= reach; ++k) {
      Eigen::Vector3d cut = Eigen::Vector3d::Zero();
      Index edge_a = -1, edge_b = -1;
      if (starts == 0 || !cut_contour(f, x, start.data(), starts, v, plane_normal, cut, edge_a, edge_b)) {
        EdgeCut found;
        const std::int32_t slice = own_slice + (upward ? k : -k);
        if (!f.edges.cut(slice, x, normals, v, plane_normal, previous, m, search_radius, found)) break;
        cut = found.point;
        edge_a = found.a;
        edge_b = found.b;
      }
      const Eigen::Vector3d r = cut - v;
      if ((r - r.dot(f.axis) * f.axis).squaredNorm() > max_offset * max_offset) break;
      auto& s = side[static_cast<std::size_t>(dir)];
      const int c = count[static_cast<std::size_t>(dir)]++;
      s[static_cast<std::size_t>(2 * c)] = r.dot(f.axis) / f.slice_spacing;
      s[static_cast<std::size_t>(2 * c + 1)] = r.dot(m);
      previous = cut;
      // The next cut starts from the nearest neighbours of the cut edge's ends in the next slice.
      starts = 0;
      for (Index e : {edge_a, edge_b}) {
        const Index j = next[static_cast<std::size_t>(e)];
        if (j >= 0 && (starts == 0 || start[0] != j)) add(j);
      }
    }
  }
  out.clear();
  for (int c = count[0] - 1; c >= 0; --c)
    out.push(side[0][static_cast<std::size_t>(2 * c)], side[0][static_cast<std::size_t>(2 * c + 1)]);
  out.push(0.0, 0.0);
  for (int c = 0; c < count[1]; ++c)
    out.push(side[1][static_cast<std::size_t>(2 * c)], side[1][static_cast<std::size_t>(2 * c + 1)]);
  // Heights increase along each side but a folded contour could break the order: check, sort if so.
  for (int k = 1; k < out.size; ++k) {
    if (out.x[static_cast<std::size_t>(k)] < out.x[static_cast<std::size_t>(k - 1)]) {
      out.sort();
      break;
    }
  }
}

NextCuts next_cuts(const ContourFrame& f, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& normals) {
  constexpr int kMaxStarts = 16;
  const Index n = static_cast<Index>(x.cols());
  NextCuts cuts;
  detail::assign_huge(cuts.up, static_cast<std::size_t>(n), EdgePoint{});
  detail::assign_huge(cuts.down, static_cast<std::size_t>(n), EdgePoint{});
  const double max_offset = 6.0 * f.slice_spacing;
  const double search_radius = 1.5 * f.slice_spacing;
  // Each vertex's cuts read the positions only: independent, in fixed chunks on every core.
  parallel_chunks(static_cast<std::size_t>(n), 4096, [&](std::size_t, std::size_t chunk_begin, std::size_t chunk_end) {
    std::array<Index, kMaxStarts> start{};
    for (auto i = static_cast<Index>(chunk_begin); i < static_cast<Index>(chunk_end); ++i) {
      Eigen::Vector3d m;
      if (!f.is_contour_vertex(i) || !in_slice_normal(f, normals.col(i), m)) continue;
      const Eigen::Vector3d v = x.col(i);
      const Eigen::Vector3d plane_normal = f.axis.cross(m);
      for (const bool upward : {true, false}) {
        int starts = 0;
        next_slice(f, i, upward, [&](Index j) {
          if (starts < kMaxStarts) start[static_cast<std::size_t>(starts++)] = j;
        });
        Eigen::Vector3d cut = Eigen::Vector3d::Zero();
        Index a = -1, b = -1;
        if (starts == 0 || !cut_contour(f, x, start.data(), starts, v, plane_normal, cut, a, b)) {
          EdgeCut found;
          const std::int32_t slice = f.mesh->slice_ids[static_cast<std::size_t>(i)] + (upward ? 1 : -1);
          if (!f.edges.cut(slice, x, normals, v, plane_normal, v, m, search_radius, found)) continue;
          cut = found.point;
          a = found.a;
          b = found.b;
        }
        const Eigen::Vector3d r = cut - v;
        if ((r - r.dot(f.axis) * f.axis).squaredNorm() > max_offset * max_offset) continue;
        const Eigen::Vector3d e = x.col(b) - x.col(a);
        const double len2 = e.squaredNorm();
        const double t = len2 > 0.0 ? std::clamp((cut - x.col(a)).dot(e) / len2, 0.0, 1.0) : 0.0;
        (upward ? cuts.up : cuts.down)[static_cast<std::size_t>(i)] = EdgePoint{a, b, t};
      }
    }
  });
  return cuts;
}

void chained_profile(const ContourFrame& f, const Eigen::Matrix3Xd& x, const NextCuts& cuts, Index i,
                     const Eigen::Vector3d& m, int reach, Profile& out) {
  const Eigen::Vector3d v = x.col(i);
  const Eigen::Vector3d plane_normal = f.axis.cross(m);
  const double max_offset2 = 36.0 * f.slice_spacing * f.slice_spacing;
  std::array<std::array<double, 2 * kMaxProfile>, 2> side;  // as in cross_slice_profile: not zeroed
  std::array<int, 2> count{0, 0};
  reach = std::min(reach, kMaxProfile / 2 - 1);
  // The chains below (dir 0) and above (dir 1) are independent: they advance in turn, step by step, so
  // that the processor overlaps one's dependent loads and divisions with the other's.
  struct Chain {
    EdgePoint at;
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    bool going = false;
  };
  std::array<Chain, 2> chain;
  for (std::size_t dir = 0; dir < 2; ++dir) {
    chain[dir].at = (dir == 1 ? cuts.up : cuts.down)[static_cast<std::size_t>(i)];
    chain[dir].going = chain[dir].at.valid();
    if (chain[dir].going) chain[dir].point = chain[dir].at.on(x);
  }
  for (int k = 1; k <= reach && (chain[0].going || chain[1].going); ++k) {
    for (std::size_t dir = 0; dir < 2; ++dir) {
      Chain& ch = chain[dir];
      if (!ch.going) continue;
      const std::vector<EdgePoint>& next = dir == 1 ? cuts.up : cuts.down;
      EdgePoint& at = ch.at;
      Eigen::Vector3d& point = ch.point;
      const Eigen::Vector3d r = point - v;
      if ((r - r.dot(f.axis) * f.axis).squaredNorm() > max_offset2) {
        ch.going = false;
        continue;
      }
      auto& s = side[dir];
      const int c = count[dir]++;
      s[static_cast<std::size_t>(2 * c)] = r.dot(f.axis) / f.slice_spacing;
      s[static_cast<std::size_t>(2 * c + 1)] = r.dot(m);
      if (k == reach) {
        ch.going = false;
        continue;
      }
      // The next point: the edge's ends' own next cuts lead to the next contour; there the vertex's own
      // plane is cut, from the nearer of the two (a step or two along the contour), so the chain does
      // not drift along the contours. Where that fails, the interpolation of the two cuts serves.
      const EdgePoint& from_a = next[static_cast<std::size_t>(at.a)];
      const EdgePoint& from_b = next[static_cast<std::size_t>(at.b)];
      if (!from_a.valid() && !from_b.valid()) {
        ch.going = false;
        continue;
      }
      const EdgePoint& nearer = !from_b.valid() || (from_a.valid() && at.t < 0.5) ? from_a : from_b;
      const std::array<Index, 2> starts{nearer.a, nearer.b};
      Eigen::Vector3d cut = Eigen::Vector3d::Zero();
      Index ea = -1, eb = -1;
      if (cut_contour(f, x, starts.data(), 2, v, plane_normal, cut, ea, eb)) {
        point = cut;
        const Eigen::Vector3d e = x.col(eb) - x.col(ea);
        const double len2 = e.squaredNorm();
        at = EdgePoint{ea, eb, len2 > 0.0 ? std::clamp((cut - x.col(ea)).dot(e) / len2, 0.0, 1.0) : 0.0};
      } else if (from_a.valid() && from_b.valid()) {
        point = (1.0 - at.t) * from_a.on(x) + at.t * from_b.on(x);
        at = nearer;
      } else {
        at = nearer;
        point = at.on(x);
      }
    }
  }
  out.clear();
  for (int c = count[0] - 1; c >= 0; --c)
    out.push(side[0][static_cast<std::size_t>(2 * c)], side[0][static_cast<std::size_t>(2 * c + 1)]);
  out.push(0.0, 0.0);
  for (int c = 0; c < count[1]; ++c)
    out.push(side[1][static_cast<std::size_t>(2 * c)], side[1][static_cast<std::size_t>(2 * c + 1)]);
  for (int k = 1; k < out.size; ++k) {
    if (out.x[static_cast<std::size_t>(k)] < out.x[static_cast<std::size_t>(k - 1)]) {
      out.sort();
      break;
    }
  }
}

void along_contour_profile(const ContourFrame& f, const Eigen::Matrix3Xd& x, Index i, const Eigen::Vector3d& m,
                           int reach, Profile& out) {
  const Eigen::Vector3d v = x.col(i);
  const Eigen::Vector3d tangent = f.axis.cross(m);
  // Walk both ways, but never meet: on a short contour each side takes half of the other vertices.
  std::array<std::array<Index, 2>, 2> cursor{};
  for (int side = 0; side < 2; ++side)
    cursor[static_cast<std::size_t>(side)] = {
        i, f.contour.of[static_cast<std::size_t>(i)][static_cast<std::size_t>(side)]};
  std::array<double, 2> arc{0.0, 0.0};
  std::array<double, 2> sign{1.0, 1.0};
  for (int side = 0; side < 2; ++side) {
    const Index first = cursor[static_cast<std::size_t>(side)][1];
    sign[static_cast<std::size_t>(side)] = (x.col(first) - v).dot(tangent) >= 0.0 ? 1.0 : -1.0;
  }
  if (sign[0] == sign[1]) sign[1] = -sign[0];  // a cusp: keep the two sides apart
  // Each side's samples in walking order; a side stops where the profile is full (kMaxProfile samples
  // with the centre).
  std::array<std::array<double, kMaxProfile>, 2> sx, sy;  // not zeroed: only count[side] entries are read
  std::array<int, 2> count{0, 0};
  int taken = 1;  // the centre
  for (int k = 1; k <= reach; ++k) {
    for (int side = 0; side < 2; ++side) {
      auto& [prev, cur] = cursor[static_cast<std::size_t>(side)];
      if (cur < 0 || cur == i) continue;
      // The other side already holds this vertex: the contour is used up.
      const auto& other = cursor[static_cast<std::size_t>(1 - side)];
      if (cur == other[1] || cur == other[0]) {
        cur = -1;
        continue;
      }
      arc[static_cast<std::size_t>(side)] += (x.col(cur) - x.col(prev)).norm();
      if (taken == kMaxProfile) {
        cur = -1;
        continue;
      }
      ++taken;
      const auto c = static_cast<std::size_t>(count[static_cast<std::size_t>(side)]++);
      const auto sd = static_cast<std::size_t>(side);
      sx[sd][c] = sign[sd] * arc[sd] / f.point_spacing;
      sy[static_cast<std::size_t>(side)][c] = (x.col(cur) - v).dot(m);
      const auto& nb = f.contour.of[static_cast<std::size_t>(cur)];
      const Index next = nb[0] == prev ? nb[1] : nb[0];
      prev = cur;
      cur = next;
    }
  }
  // In increasing x: the negative side from its far end, the centre, the positive side. Where that is
  // not strictly increasing (a zero-length edge, a contour folding back), the samples go in as they were
  // taken (centre, then both sides step by step) and are sorted, stably, as before.
  const std::size_t neg = sign[0] < 0.0 ? 0 : 1, pos = 1 - neg;
  out.clear();
  for (int c = count[neg] - 1; c >= 0; --c) {
    out.push(sx[neg][static_cast<std::size_t>(c)], sy[neg][static_cast<std::size_t>(c)]);
  }
  out.push(0.0, 0.0);
  for (int c = 0; c < count[pos]; ++c) {
    out.push(sx[pos][static_cast<std::size_t>(c)], sy[pos][static_cast<std::size_t>(c)]);
  }
  for (int k = 1; k < out.size; ++k) {
    if (!(out.x[static_cast<std::size_t>(k - 1)] < out.x[static_cast<std::size_t>(k)])) {
      out.clear();
      out.push(0.0, 0.0);
      for (int c = 0; c < std::max(count[0], count[1]); ++c) {
        for (std::size_t side = 0; side < 2; ++side) {
          if (c < count[side]) out.push(sx[side][static_cast<std::size_t>(c)], sy[side][static_cast<std::size_t>(c)]);
        }
      }
      out.sort();
      break;
    }
  }
}

NoiseEstimate profile_noise(const ContourFrame& f, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& normals,
                            bool across, Index stride) {
  // The sampled vertices in fixed chunks on every core; each chunk's differences are joined in chunk
  // order, so the list (and its median) is the one a single thread makes.
  stride = std::max<Index>(stride, 1);
  const auto samples = static_cast<std::size_t>((x.cols() + stride - 1) / stride);
  constexpr std::size_t kChunk = 2048;
  struct Part {
    std::vector<double> d4;   // the chunk's fourth differences
    std::size_t sampled = 0;  // its contour vertices
  };
  const std::vector<Part> parts =
      map_chunks<Part>(samples, kChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
        Part part;
        std::vector<double>& d4 = part.d4;
        Profile p;
        Eigen::Vector3d m;
        for (std::size_t s = begin; s < end; ++s) {
          const Index i = static_cast<Index>(s) * stride;
          if (!f.is_contour_vertex(i)) continue;
          ++part.sampled;
          if (!in_slice_normal(f, normals.col(i), m)) continue;
          if (across) {
            cross_slice_profile(f, x, normals, i, m, 2, p);
          } else {
            along_contour_profile(f, x, i, m, 2, p);
          }
          if (p.size != 5) continue;
          // Samples should sit near -2..2; a gap (a missing slice) would make the difference meaningless.
          bool regular = true;
          for (int k = 0; k < 5; ++k) regular = regular && std::abs(p.x[static_cast<std::size_t>(k)] - (k - 2)) < 0.5;
          if (!regular) continue;
          d4.push_back(std::abs(p.y[0] - 4.0 * p.y[1] + 6.0 * p.y[2] - 4.0 * p.y[3] + p.y[4]));
        }
        return part;
      });
  NoiseEstimate estimate;
  for (const Part& part : parts) {
    estimate.sampled += part.sampled;
    estimate.profiles += part.d4.size();
  }
  std::vector<double> d4;
  d4.reserve(estimate.profiles);
  for (const Part& part : parts) d4.insert(d4.end(), part.d4.begin(), part.d4.end());
  if (d4.empty()) return estimate;
  std::nth_element(d4.begin(), d4.begin() + static_cast<std::ptrdiff_t>(d4.size() / 2), d4.end());
  estimate.sigma = 1.4826 * d4[d4.size() / 2] / std::sqrt(70.0);
  return estimate;
}

}  // namespace contourmesh::detail
