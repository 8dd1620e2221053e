// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/adaptive_subdivision.h"

#include "contourmesh/smooth/adjacency.h"
#include "contourmesh/smooth/errors.h"
#include "contourmesh/smooth/normals.h"
#include "contourmesh/smooth/umbrella.h"

#include <algorithm>
#include <string>
#include <unordered_map>

namespace contourmesh {

namespace {

// Working memory per vertex of the adaptive mesh: positions and ids, about two triangles, the CSR
// adjacency, the midpoint table and the smoothing buffers.
constexpr double kBytesPerAdaptiveVertex = 320.0;

std::uint64_t edge_key(Index a, Index b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

// The 1-rings of the selected input vertices (index < selected.size()), sorted and without repeats as
// build_adjacency gives them, in an adjacency whose other rings are empty. Each level needs only these
// (the measure of the selected vertices, their valences, the edges to bisect), and building them is
// one pass over the triangles, where a full adjacency of the growing mesh at every level cost about
// ten times more.
MeshAdjacency selected_rings(const Mesh& m, std::span<const std::uint8_t> selected) {
  const Index n = m.num_vertices();
  const auto inputs = static_cast<Index>(selected.size());
  auto is_selected = [&](Index v) { return v < inputs && selected[v] != 0; };
  MeshAdjacency adj;
  std::vector<Index> offsets(static_cast<std::size_t>(n) + 1, 0);
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    const Triangle& t = m.triangles[f];
    for (Index v : t) {
      if (v < 0 || v >= n) {
        throw InvalidInputError("triangle " + std::to_string(f) + " references vertex " + std::to_string(v) +
                                ", outside [0, " + std::to_string(n) + ")");
      }
    }
    for (Index v : t) {
      if (is_selected(v)) offsets[v + 1] += (t[0] != v) + (t[1] != v) + (t[2] != v);
    }
  }
  for (Index i = 0; i < n; ++i) offsets[i + 1] += offsets[i];
  std::vector<Index> gathered(static_cast<std::size_t>(offsets[n]));
  {
    std::vector<Index> fill(offsets.begin(), offsets.end() - 1);
    for (const Triangle& t : m.triangles) {
      for (Index v : t) {
        if (!is_selected(v)) continue;
        for (Index w : t) {
          if (w != v) gathered[fill[v]++] = w;
        }
      }
    }
  }
  adj.neighbor_offsets.assign(static_cast<std::size_t>(n) + 1, 0);
  adj.neighbors.reserve(gathered.size() / 2);
  for (Index i = 0; i < n; ++i) {
    if (offsets[i + 1] > offsets[i]) {
      const auto begin = gathered.begin() + offsets[i];
      const auto end = gathered.begin() + offsets[i + 1];
      std::sort(begin, end);
      adj.neighbors.insert(adj.neighbors.end(), begin, std::unique(begin, end));
    }
    adj.neighbor_offsets[i + 1] = static_cast<Index>(adj.neighbors.size());
  }
  return adj;
}

}  // namespace

AdaptiveMesh subdivide_adaptively(const Mesh& input, std::span<const std::uint8_t> selected,
                                  const SubdivisionOptions& options) {
  if (selected.size() != static_cast<std::size_t>(input.num_vertices())) {
    throw InvalidInputError("subdivision: the selection has " + std::to_string(selected.size()) + " flags for " +
                            std::to_string(input.num_vertices()) + " vertices");
  }
  if (options.max_levels < 0) throw InvalidInputError("subdivision: max_levels must be >= 0");
  if (!(options.gamma >= 0.0)) throw InvalidInputError("subdivision: gamma must be >= 0");

  AdaptiveMesh out;
  out.mesh = input;
  out.original_vertices = input.num_vertices();
  const bool ids = input.has_contour_ids();
  std::vector<std::uint8_t> ever(selected.size(), 0);
  Mesh& m = out.mesh;

  std::vector<std::uint8_t> is_active(selected.size(), 0);
  for (int level = 0; level < options.max_levels; ++level) {
    const MeshAdjacency adj = selected_rings(m, selected);
    Eigen::VectorXd measure;
    if (options.measure == UmbrellaMeasure::Length) {
      measure = umbrella_norms(m.positions, adj);
    } else {
      measure = umbrella_normal_norms(m.positions, adj, vertex_normals(m.positions, m.triangles));
    }
    std::vector<Index> active;
    for (Index i = 0; i < out.original_vertices; ++i) {
      if (selected[i] && measure[i] > options.gamma && adj.valence(i) > 0) active.push_back(i);
    }
    if (active.empty()) break;
    out.per_level.push_back(active.size());
    {
      // At most one midpoint per edge at an active vertex; each splits at most two triangles into
      // four. The bytes cover this level's mesh and what the smoothing of it will allocate.
      double reach = m.num_vertices();
      for (Index v : active) reach += adj.valence(v);
      check_allocation("adaptive subdivision level " + std::to_string(level + 1), reach,
                       reach * kBytesPerAdaptiveVertex, options.limits);
    }

    // Midpoints of every edge incident to an active vertex.
    std::unordered_map<std::uint64_t, Index> midpoint;
    std::vector<Eigen::Vector3d> new_positions;
    std::vector<std::int32_t> new_slices, new_contours;
    const Index base = m.num_vertices();
    for (Index v : active) {
      ever[v] = 1;
      is_active[v] = 1;
      for (Index j : adj.ring(v)) {
        const auto [it, inserted] =
            midpoint.try_emplace(edge_key(v, j), base + static_cast<Index>(new_positions.size()));
        if (!inserted) continue;
        new_positions.push_back(0.5 * (m.positions.col(v) + m.positions.col(j)));
        if (ids) {
          const bool same = m.slice_ids[v] != kNoId && m.slice_ids[v] == m.slice_ids[j] &&
                            m.contour_ids[v] == m.contour_ids[j];
          new_slices.push_back(same ? m.slice_ids[v] : kNoId);
          new_contours.push_back(same ? m.contour_ids[v] : kNoId);
        }
      }
    }
    const auto added = static_cast<Index>(new_positions.size());
    m.positions.conservativeResize(3, base + added);
    for (Index k = 0; k < added; ++k) m.positions.col(base + k) = new_positions[k];
    if (ids) {
      m.slice_ids.insert(m.slice_ids.end(), new_slices.begin(), new_slices.end());
      m.contour_ids.insert(m.contour_ids.end(), new_contours.begin(), new_contours.end());
    }

    // Re-triangulate by the pattern of bisected edges, keeping orientation.
    auto mid = [&](Index a, Index b) {
      const auto it = midpoint.find(edge_key(a, b));
      return it == midpoint.end() ? Index{-1} : it->second;
    };
    auto dist2 = [&](Index a, Index b) { return (m.positions.col(a) - m.positions.col(b)).squaredNorm(); };
    std::vector<Triangle> next;
    next.reserve(m.triangles.size() + 3 * midpoint.size());
    // Bisected edges all have an active end: other triangles are kept without looking them up.
    auto touches_active = [&](const Triangle& t) {
      return std::any_of(t.begin(), t.end(), [&](Index v) { return v < out.original_vertices && is_active[v]; });
    };
    for (const Triangle& t : m.triangles) {
      if (!touches_active(t)) {
        next.push_back(t);
        continue;
      }
      const Index e[3] = {mid(t[0], t[1]), mid(t[1], t[2]), mid(t[2], t[0])};  // edge k: t[k] -> t[k+1]
      const int marked = (e[0] >= 0) + (e[1] >= 0) + (e[2] >= 0);
      if (marked == 0) {
        next.push_back(t);
      } else if (marked == 3) {
        next.push_back({t[0], e[0], e[2]});
        next.push_back({e[0], t[1], e[1]});
        next.push_back({e[2], e[1], t[2]});
        next.push_back({e[0], e[1], e[2]});
      } else if (marked == 1) {
        const int k = e[0] >= 0 ? 0 : e[1] >= 0 ? 1 : 2;  // bisected edge t[k] -> t[k+1]
        const Index a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3], mk = e[k];
        next.push_back({a, mk, c});
        next.push_back({mk, b, c});
      } else {
        const int u = e[0] < 0 ? 0 : e[1] < 0 ? 1 : 2;  // the unbisected edge t[u] -> t[u+1]
        const Index b = t[u], c = t[(u + 1) % 3], a = t[(u + 2) % 3];
        const Index m_ab = e[(u + 2) % 3];  // edge a -> b
        const Index m_ca = e[(u + 1) % 3];  // edge c -> a
        next.push_back({a, m_ab, m_ca});
        if (dist2(m_ab, c) <= dist2(b, m_ca)) {
          next.push_back({m_ab, b, c});
          next.push_back({m_ab, c, m_ca});
        } else {
          next.push_back({m_ab, b, m_ca});
          next.push_back({b, c, m_ca});
        }
      }
    }
    m.triangles = std::move(next);
    for (Index v : active) is_active[v] = 0;
  }
  for (Index i = 0; i < out.original_vertices; ++i) {
    if (ever[i]) out.subdivided.push_back(i);
  }
  return out;
}

}  // namespace contourmesh
