// SPDX-License-Identifier: BSD-3-Clause
#include "detail/off_slice_workspace.h"

#include "contourmesh/internal/huge_pages.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace contourmesh::detail {

namespace {

// The moving vertices (mesh ids, ascending) and the filtered faces (mesh ids, ascending).
void select_region(const ContourFrame& frame, std::size_t num_faces, const OffSliceFilterOptions& options,
                   std::vector<Index>& moving, std::vector<Index>& filtered) {
  const MeshAdjacency& adj = frame.adjacency;
  const Index n = adj.num_vertices();
  const bool contour_moves = options.contour_max_move > 0.0;
  std::vector<std::uint8_t> active;  // a byte per face: cheaper than sorting the faces' ids
  detail::assign_huge(active, num_faces, 0);
  for (Index i = 0; i < n; ++i) {
    if ((!contour_moves && frame.is_contour_vertex(i)) || adj.valence(i) == 0) continue;
    moving.push_back(i);
    for (Index f : adj.incident_faces(i)) active[static_cast<std::size_t>(f)] = 1;
  }
  for (std::size_t f = 0; f < num_faces; ++f) {
    if (active[f]) filtered.push_back(static_cast<Index>(f));
  }
}

// One slot per pair of faces met in the neighbourhoods: entry g of filtered face f shares the slot of
// entry f of g's neighbourhood when g is a filtered face already seen (neighbourhoods are symmetric:
// two faces share a vertex or not).
void assign_pair_slots(const std::vector<Index>& filtered_of, Workspace& w) {
  detail::resize_huge(w.ring_slot, w.ring.size());
  // In fixed chunks of filtered faces on every core: first each entry's mirror (the entry of an earlier
  // filtered face that it pairs with), or -1 where the entry opens a slot of its own (a mirror always does),
  // and each chunk's count of new slots; then the new slots are numbered in ring order (each chunk from
  // the count of the chunks before it), and the mirrors' slots copied.
  constexpr std::size_t kChunk = 4096;
  const std::size_t nk = w.filtered.size();
  FillVector<Index> mirror_of;
  detail::resize_huge(mirror_of, w.ring.size());
  std::vector<Index> first_slot((nk + kChunk - 1) / kChunk + 1, 0);  // per chunk, then its prefix sums
  parallel_chunks(nk, kChunk, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    Index opened = 0;
    for (std::size_t k = begin; k < end; ++k) {
      const Index f = w.filtered[k];
      for (Index r = w.ring_offsets[k]; r < w.ring_offsets[k + 1]; ++r) {
        const Index g = w.ring[static_cast<std::size_t>(r)];
        const Index kg = filtered_of[static_cast<std::size_t>(g)];
        mirror_of[static_cast<std::size_t>(r)] = -1;
        if (kg >= 0 && static_cast<std::size_t>(kg) < k) {
          const auto first = w.ring.begin() + w.ring_offsets[static_cast<std::size_t>(kg)];
          const auto last = w.ring.begin() + w.ring_offsets[static_cast<std::size_t>(kg) + 1];
          const auto mirror = std::lower_bound(first, last, f);
          if (mirror != last && *mirror == f) {
            mirror_of[static_cast<std::size_t>(r)] = static_cast<Index>(mirror - w.ring.begin());
            continue;
          }
        }
        ++opened;
      }
    }
    first_slot[chunk + 1] = opened;
  });
  for (std::size_t c = 1; c < first_slot.size(); ++c) first_slot[c] += first_slot[c - 1];
  detail::resize_huge(w.slot_a, static_cast<std::size_t>(first_slot.back()));
  detail::resize_huge(w.slot_b, w.slot_a.size());
  parallel_chunks(nk, kChunk, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    Index slot = first_slot[chunk];
    for (std::size_t k = begin; k < end; ++k) {
      const Index f = w.filtered[k];
      for (Index r = w.ring_offsets[k]; r < w.ring_offsets[k + 1]; ++r) {
        if (mirror_of[static_cast<std::size_t>(r)] >= 0) continue;
        w.ring_slot[static_cast<std::size_t>(r)] = slot;
        w.slot_a[static_cast<std::size_t>(slot)] = f;
        w.slot_b[static_cast<std::size_t>(slot)] = w.ring[static_cast<std::size_t>(r)];
        ++slot;
      }
    }
  });
  parallel_chunks(w.ring.size(), 16384, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t r = begin; r < end; ++r) {
      const Index m = mirror_of[r];
      if (m >= 0) w.ring_slot[r] = w.ring_slot[static_cast<std::size_t>(m)];
    }
  });
}

}  // namespace

std::vector<double> slice_levels(const ContourFrame& frame, const Eigen::Matrix3Xd& positions) {
  std::map<std::int32_t, std::pair<double, double>> sums;  // slice id -> (sum of heights, count)
  const Mesh& mesh = *frame.mesh;
  // Vertices of one slice come in runs: look the map up once per run (the sums keep their order).
  std::int32_t last_id = 0;
  std::pair<double, double>* s = nullptr;
  for (Index i = 0; i < static_cast<Index>(positions.cols()); ++i) {
    if (!frame.is_contour_vertex(i)) continue;
    const std::int32_t id = mesh.slice_ids[static_cast<std::size_t>(i)];
    if (s == nullptr || id != last_id) {
      s = &sums[id];
      last_id = id;
    }
    s->first += frame.axis.dot(positions.col(i));
    s->second += 1.0;
  }
  std::vector<double> levels;
  levels.reserve(sums.size());
  for (const auto& [id, sum] : sums) levels.push_back(sum.first / sum.second);
  std::sort(levels.begin(), levels.end());
  return levels;
}

std::pair<double, double> height_bounds(const std::vector<double>& levels, double h, double spacing, double reach) {
  double lo = h - reach, hi = h + reach;
  const double margin = 0.05 * spacing;
  if (levels.empty()) return {lo, hi};
  const auto above = std::upper_bound(levels.begin(), levels.end(), h);
  if (above != levels.begin()) lo = std::max(lo, std::min(h, *(above - 1) + margin));
  if (above != levels.end()) hi = std::min(hi, std::max(h, *above - margin));
  return {lo, hi};
}

Workspace make_workspace(const ContourFrame& frame, const std::vector<Triangle>& triangles,
                         const OffSliceFilterOptions& options) {
  const MeshAdjacency& adj = frame.adjacency;
  Workspace w;
  std::vector<Index> moving, filtered;
  select_region(frame, triangles.size(), options, moving, filtered);
  if (moving.empty()) return w;

  // Local vertices: the corners of the filtered faces; local faces: the faces around them, which are
  // the neighbourhoods' faces. Both numbered in mesh order, through scratch maps from mesh ids.
  // (Marks in maps over the mesh and a scan in mesh order: cheaper than sorting the ids.)
  std::vector<Index> vertex_map;
  detail::assign_huge(vertex_map, static_cast<std::size_t>(adj.num_vertices()), -1);
  for (Index f : filtered) {
    for (Index v : triangles[static_cast<std::size_t>(f)]) vertex_map[static_cast<std::size_t>(v)] = 0;
  }
  for (std::size_t v = 0; v < vertex_map.size(); ++v) {
    if (vertex_map[v] < 0) continue;
    vertex_map[v] = static_cast<Index>(w.vertices.size());
    w.vertices.push_back(static_cast<Index>(v));
  }
  std::vector<Index> face_map;
  detail::assign_huge(face_map, triangles.size(), -1);
  for (Index v : w.vertices) {
    for (Index g : adj.incident_faces(v)) face_map[static_cast<std::size_t>(g)] = 0;
  }
  for (std::size_t g = 0; g < face_map.size(); ++g) {
    if (face_map[g] < 0) continue;
    face_map[g] = static_cast<Index>(w.faces.size());
    w.faces.push_back(static_cast<Index>(g));
  }
  detail::resize_huge(w.filtered, filtered.size());
  for (std::size_t k = 0; k < filtered.size(); ++k) w.filtered[k] = face_map[static_cast<std::size_t>(filtered[k])];

  // Per filtered face: its corners and its neighbourhood, the faces around its corners (local ids,
  // ascending as mesh ids are).
  detail::resize_huge(w.corners, filtered.size());
  detail::assign_huge(w.ring_offsets, filtered.size() + 1, 0);
  // In fixed chunks on every core, each into its own list; the lists are joined in chunk order.
  constexpr std::size_t kChunk = 4096;
  const std::vector<std::vector<Index>> parts =
      map_chunks<std::vector<Index>>(filtered.size(), kChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
        std::vector<Index> part;
        std::vector<Index> local;
        for (std::size_t k = begin; k < end; ++k) {
          const Triangle& t = triangles[static_cast<std::size_t>(filtered[k])];
          local.clear();
          for (int c = 0; c < 3; ++c) {
            w.corners[k][static_cast<std::size_t>(c)] = vertex_map[static_cast<std::size_t>(t[c])];
            for (Index g : adj.incident_faces(t[c])) local.push_back(face_map[static_cast<std::size_t>(g)]);
          }
          std::sort(local.begin(), local.end());
          local.erase(std::unique(local.begin(), local.end()), local.end());
          part.insert(part.end(), local.begin(), local.end());
          w.ring_offsets[k + 1] = static_cast<Index>(local.size());
        }
        return part;
      });
  for (std::size_t k = 0; k < filtered.size(); ++k) w.ring_offsets[k + 1] += w.ring_offsets[k];
  detail::resize_huge(w.ring, static_cast<std::size_t>(w.ring_offsets.back()));
  parallel_chunks(parts.size(), 1, [&](std::size_t chunk, std::size_t, std::size_t) {
    std::copy(parts[chunk].begin(), parts[chunk].end(), w.ring.begin() + w.ring_offsets[chunk * kChunk]);
  });
  // The filtered face of each local face (for the pair slots and the moving vertices' faces).
  std::vector<Index> filtered_of;
  detail::assign_huge(filtered_of, w.faces.size(), -1);
  for (std::size_t k = 0; k < filtered.size(); ++k) {
    filtered_of[static_cast<std::size_t>(w.filtered[k])] = static_cast<Index>(k);
  }
  assign_pair_slots(filtered_of, w);
  w.filtered_of = std::move(filtered_of);
  w.face_map = std::move(face_map);
  detail::assign_huge(w.moves, w.vertices.size(), 0);
  detail::assign_huge(w.incident_offsets, moving.size() + 1, 0);
  detail::resize_huge(w.on_contour, moving.size());
  detail::resize_huge(w.moving, moving.size());
  for (std::size_t m = 0; m < moving.size(); ++m) {
    const Index i = moving[m];
    const Index li = vertex_map[static_cast<std::size_t>(i)];
    w.moving[m] = li;
    w.moves[static_cast<std::size_t>(li)] = 1;
    w.on_contour[m] = frame.is_contour_vertex(i) ? 1 : 0;
    w.incident_offsets[m + 1] = w.incident_offsets[m] + static_cast<Index>(adj.incident_faces(i).size());
  }
  detail::resize_huge(w.incident, static_cast<std::size_t>(w.incident_offsets.back()));
  parallel_chunks(moving.size(), 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t m = begin; m < end; ++m) {
      auto e = static_cast<std::size_t>(w.incident_offsets[m]);
      for (Index f : adj.incident_faces(moving[m])) {
        const Index local_f = w.face_map[static_cast<std::size_t>(f)];
        w.incident[e++] = w.filtered_of[static_cast<std::size_t>(local_f)];
      }
    }
  });
  return w;
}

void spatial_weights(const Eigen::Matrix3Xd& centroids, const Eigen::VectorXd& areas, Workspace& w) {
  // Per pair of faces (slot), once: the distance between the centroids and its Gaussian are symmetric bit
  // for bit (the difference only changes sign), as the range kernel is.
  const std::size_t ns = w.slot_a.size();
  FillVector<double> squared, distance;  // every element written by the loop below
  detail::resize_huge(squared, ns);
  detail::resize_huge(distance, ns);
  parallel_chunks(ns, 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t s = begin; s < end; ++s) {
      squared[s] = (centroids.col(w.slot_b[s]) - centroids.col(w.slot_a[s])).squaredNorm();
      distance[s] = std::sqrt(squared[s]);  // as norm()
    }
  });
  double sum = 0.0;  // in ring order, as one serial sum
  for (Index slot : w.ring_slot) sum += distance[static_cast<std::size_t>(slot)];
  w.sigma_s = sum > 0.0 ? sum / static_cast<double>(w.ring.size()) : 1.0;
  const double inv_s = 1.0 / (2.0 * w.sigma_s * w.sigma_s);
  FillVector<double>& kernel = distance;  // reused
  parallel_chunks(ns, 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t s = begin; s < end; ++s) kernel[s] = std::exp(-squared[s] * inv_s);
  });
  detail::resize_huge(w.ring_weights, w.ring.size());
  parallel_chunks(w.ring.size(), 16384, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t r = begin; r < end; ++r) {
      w.ring_weights[r] = static_cast<float>(areas[w.ring[r]] * kernel[static_cast<std::size_t>(w.ring_slot[r])]);
    }
  });
}

}  // namespace contourmesh::detail
