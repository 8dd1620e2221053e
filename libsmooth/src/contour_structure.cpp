// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/contour_structure.h"

#include "contourmesh/smooth/errors.h"

#include "contourmesh/internal/huge_pages.h"
#include "contourmesh/internal/union_find.h"
#include "detail/parallel.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>
#include <string>

namespace contourmesh {

std::vector<Index> ContourNeighbours::window(Index i, int size) const {
  std::vector<Index> left, right;
  const int half = std::max(0, (size - 1) / 2);
  // Walk both ways from i.
  for (int side = 0; side < 2; ++side) {
    std::vector<Index>& out = side == 0 ? left : right;
    Index prev = i;
    Index cur = of[i][side];
    while (cur >= 0 && static_cast<int>(out.size()) < half && cur != i) {
      out.push_back(cur);
      const auto& n = of[cur];
      const Index next = n[0] == prev ? n[1] : n[0];
      if (n[0] != prev && n[1] != prev) break;  // inconsistent links
      prev = cur;
      cur = next;
    }
  }
  // Drop vertices seen from both sides (a contour shorter than the window).
  std::vector<Index> result(left.rbegin(), left.rend());
  result.push_back(i);
  for (Index v : right) {
    if (std::find(result.begin(), result.end(), v) == result.end()) result.push_back(v);
  }
  return result;
}

ContourNeighbours contour_neighbours(const Mesh& mesh, const MeshAdjacency& adj) {
  if (!mesh.has_contour_ids()) throw InvalidInputError("contour_neighbours: the mesh has no contour ids");
  const Index n = mesh.num_vertices();
  ContourNeighbours out;
  detail::assign_huge(out.of, static_cast<std::size_t>(n), {-1, -1});
  const auto& slice = mesh.slice_ids;
  const auto& contour = mesh.contour_ids;
  // Each vertex reads its own ring only: fixed chunks on every core.
  detail::parallel_chunks(static_cast<std::size_t>(n), 8192, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (auto i = static_cast<Index>(begin); i < static_cast<Index>(end); ++i) {
      if (slice[i] == kNoId) continue;
      std::array<Index, 2> found{-1, -1};
      int count = 0;
      for (Index j : adj.ring(i)) {
        if (slice[j] != slice[i] || contour[j] != contour[i]) continue;
        // A contour edge has a triangle reaching off the slice; a cap chord has none.
        bool off_slice = false;
        for (Index f : adj.incident_faces(i)) {
          const Triangle& t = mesh.triangles[f];
          if (std::find(t.begin(), t.end(), j) == t.end()) continue;
          for (Index v : t) off_slice = off_slice || slice[v] != slice[i];
        }
        if (!off_slice) continue;
        if (count < 2) found[count] = j;
        ++count;
      }
      if (count == 2) out.of[i] = found;
    }
  });
  return out;
}

Eigen::Vector3d estimate_slice_axis(const Mesh& mesh) {
  if (!mesh.has_contour_ids()) throw InvalidInputError("estimate_slice_axis: the mesh has no contour ids");
  // Vertices come slice by slice in a tiled mesh: the map is looked up only when the slice changes.
  std::map<std::int32_t, std::pair<Eigen::Vector3d, int>> centroid;
  {
    std::int32_t last = kNoId;
    std::pair<Eigen::Vector3d, int>* c = nullptr;
    for (Index i = 0; i < mesh.num_vertices(); ++i) {
      const std::int32_t s = mesh.slice_ids[i];
      if (s == kNoId) continue;
      if (s != last) {
        c = &centroid[s];
        last = s;
        if (c->second == 0) c->first.setZero();
      }
      c->first += mesh.positions.col(i);
      ++c->second;
    }
  }
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  {
    std::int32_t last = kNoId;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (Index i = 0; i < mesh.num_vertices(); ++i) {
      const std::int32_t s = mesh.slice_ids[i];
      if (s == kNoId) continue;
      if (s != last) {
        const auto& c = centroid[s];
        mean = c.first / c.second;
        last = s;
      }
      const Eigen::Vector3d d = mesh.positions.col(i) - mean;
      scatter += d * d.transpose();
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  if (eig.info() != Eigen::Success || !(eig.eigenvalues()[1] > 0.0)) {
    throw InvalidInputError("estimate_slice_axis: the slices do not span planes");
  }
  Eigen::Vector3d axis = eig.eigenvectors().col(0).normalized();  // smallest eigenvalue first
  if (centroid.size() >= 2) {
    const auto& lo = centroid.begin()->second;
    const auto& hi = centroid.rbegin()->second;
    if ((hi.first / hi.second - lo.first / lo.second).dot(axis) < 0.0) axis = -axis;
  }
  return axis;
}

bool assign_ids_by_slice_planes(Mesh& mesh, const MeshAdjacency& adj, const Eigen::Vector3d& axis_in,
                                double tolerance) {
  if (!(axis_in.norm() > 0.0)) throw InvalidInputError("slice axis must not be zero");
  const Eigen::Vector3d axis = axis_in.normalized();
  const Index n = mesh.num_vertices();
  if (n == 0) return false;
  std::vector<double> h;
  detail::resize_huge(h, static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) h[i] = mesh.positions.col(i).dot(axis);
  std::vector<Index> order;
  detail::resize_huge(order, static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return h[a] < h[b]; });
  const double extent = h[order.back()] - h[order.front()];
  const double tol = tolerance > 0.0 ? tolerance : 1e-4 * extent;
  std::vector<std::int32_t> slice;
  detail::resize_huge(slice, static_cast<std::size_t>(n));
  std::int32_t current = 0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k > 0 && h[order[k]] - h[order[k - 1]] > tol) ++current;
    slice[order[k]] = current;
  }
  // Contour-stack vertices lie on planes of many vertices; accept when 90% of them do (vertices of
  // branching copies or a few stray ones may not).
  {
    std::vector<Index> per_plane(static_cast<std::size_t>(current) + 1, 0);
    for (Index i = 0; i < n; ++i) ++per_plane[slice[i]];
    Index on_planes = 0;
    for (Index i = 0; i < n; ++i) on_planes += per_plane[slice[i]] >= 3 ? 1 : 0;
    if (on_planes < 0.9 * n) return false;
  }
  // Contours: components of same-plane edges.
  detail::UnionFind<Index> planes(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) {
    for (Index j : adj.ring(i)) {
      if (slice[j] == slice[i]) planes.unite(i, j);
    }
  }
  std::map<std::pair<std::int32_t, Index>, std::int32_t> contour_of;  // (slice, root) -> index in slice
  std::map<std::int32_t, std::int32_t> next_in_slice;
  std::vector<std::int32_t> contour;
  detail::resize_huge(contour, static_cast<std::size_t>(n));
  for (Index i : order) {
    const auto key = std::make_pair(slice[i], planes.find(i));
    auto it = contour_of.find(key);
    if (it == contour_of.end()) it = contour_of.emplace(key, next_in_slice[slice[i]]++).first;
    contour[i] = it->second;
  }
  mesh.slice_ids = std::move(slice);
  mesh.contour_ids = std::move(contour);
  return true;
}

std::size_t compact_slice_ids(Mesh& mesh) {
  if (!mesh.has_contour_ids()) return 0;
  std::vector<std::int32_t> used;
  for (std::int32_t s : mesh.slice_ids) {
    if (s >= 0) used.push_back(s);
  }
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  if (used.empty()) return 0;
  const auto span = static_cast<std::size_t>(used.back() - used.front()) + 1;
  if (span == used.size()) return 0;
  for (std::int32_t& s : mesh.slice_ids) {
    if (s >= 0)
      s = used.front() + static_cast<std::int32_t>(std::lower_bound(used.begin(), used.end(), s) - used.begin());
  }
  return span - used.size();
}

bool repair_contour_ids(Mesh& mesh, const MeshAdjacency& adjacency, const Eigen::Vector3d& axis) {
  if (!mesh.has_contour_ids()) return false;
  Mesh recovered = mesh;
  if (!assign_ids_by_slice_planes(recovered, adjacency, axis)) return false;
  // Each recovered plane takes the file's most common slice id among its vertices.
  std::map<std::int32_t, std::map<std::int32_t, Index>> votes;  // plane -> file id -> count
  for (Index i = 0; i < mesh.num_vertices(); ++i) ++votes[recovered.slice_ids[i]][mesh.slice_ids[i]];
  // A plane of the slices has a clear majority, and no two planes claim the same slice; otherwise the
  // planes along `axis` are not the file's slices.
  std::map<std::int32_t, std::int32_t> file_id;
  std::map<std::int32_t, int> claims;
  for (const auto& [plane, counts] : votes) {
    const auto best = std::max_element(counts.begin(), counts.end(),
                                       [](const auto& a, const auto& b) { return a.second < b.second; });
    Index total = 0;
    for (const auto& [id, count] : counts) total += count;
    if (2 * best->second <= total) return false;
    file_id[plane] = best->first < 0 ? kNoId : best->first;
    if (file_id[plane] != kNoId && ++claims[file_id[plane]] > 1) return false;
  }
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    const std::int32_t id = file_id[recovered.slice_ids[i]];
    recovered.slice_ids[i] = id;
    if (id == kNoId) recovered.contour_ids[i] = kNoId;
  }
  compact_slice_ids(recovered);
  if (!find_contour_id_problem(recovered, adjacency).empty()) return false;
  mesh = std::move(recovered);
  return true;
}

std::string find_contour_id_problem(const Mesh& mesh, const MeshAdjacency& adj) {
  if (!mesh.has_contour_ids()) return {};
  const Index n = mesh.num_vertices();
  const auto& slice = mesh.slice_ids;
  const auto& contour = mesh.contour_ids;
  std::ostringstream msg;
  for (Index i = 0; i < n; ++i) {
    if (slice[i] < kNoId || contour[i] < kNoId) {
      msg << "vertex " << i << " has slice id " << slice[i] << " and contour id " << contour[i]
          << " (ids are >= 0, or -1 for none)";
      return msg.str();
    }
    if ((slice[i] == kNoId) != (contour[i] == kNoId)) {
      msg << "vertex " << i << " has slice id " << slice[i] << " but contour id " << contour[i];
      return msg.str();
    }
  }
  for (Index i = 0; i < n; ++i) {
    if (slice[i] == kNoId) continue;
    for (Index j : adj.ring(i)) {
      if (j > i && slice[j] != kNoId && std::abs(slice[j] - slice[i]) > 1) {
        msg << "the edge between vertex " << i << " (slice " << slice[i] << ") and vertex " << j << " (slice "
            << slice[j] << ") skips " << std::abs(slice[j] - slice[i]) - 1 << " slice"
            << (std::abs(slice[j] - slice[i]) == 2 ? "" : "s");
        return msg.str();
      }
    }
  }
  // Geometry: the heights of the slice planes along the estimated axis.
  std::map<std::int32_t, std::pair<double, Index>> height;  // slice -> (sum, count)
  for (Index i = 0; i < n; ++i) {
    if (slice[i] != kNoId) height[slice[i]].second += 1;
  }
  if (height.size() < 2) return {};
  Eigen::Vector3d axis;
  try {
    axis = estimate_slice_axis(mesh);
  } catch (const InvalidInputError&) {
    return "the slice ids do not describe slice planes (the vertices of a slice span no plane)";
  }
  for (Index i = 0; i < n; ++i) {
    if (slice[i] != kNoId) height[slice[i]].first += mesh.positions.col(i).dot(axis);
  }
  std::map<std::int32_t, double> plane;
  for (const auto& [s, sum_count] : height) plane[s] = sum_count.first / sum_count.second;
  for (auto it = std::next(plane.begin()); it != plane.end(); ++it) {
    const auto prev = std::prev(it);
    if (!(it->second > prev->second)) {
      msg << "slice " << it->first << " does not lie above slice " << prev->first << " along the slice axis";
      return msg.str();
    }
  }
  for (Index i = 0; i < n; ++i) {
    if (slice[i] == kNoId) continue;
    const auto it = plane.find(slice[i]);
    const double h = mesh.positions.col(i).dot(axis);
    const double off = h - it->second;
    // Half the gap to the adjacent plane on the side the vertex strays to.
    double half_gap = std::numeric_limits<double>::infinity();
    if (off > 0.0 && std::next(it) != plane.end()) half_gap = 0.5 * (std::next(it)->second - it->second);
    if (off < 0.0 && it != plane.begin()) half_gap = 0.5 * (it->second - std::prev(it)->second);
    if (std::abs(off) > half_gap) {
      const std::int32_t nearer = off > 0.0 ? std::next(it)->first : std::prev(it)->first;
      msg << "vertex " << i << " has slice id " << slice[i] << " but lies " << std::abs(off)
          << " from that slice's plane, nearer to slice " << nearer;
      return msg.str();
    }
  }
  return {};
}

}  // namespace contourmesh
