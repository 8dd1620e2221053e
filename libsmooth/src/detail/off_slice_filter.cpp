// SPDX-License-Identifier: BSD-3-Clause
#include "detail/off_slice_filter.h"

#include "detail/parallel.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

namespace contourmesh::detail {

namespace {

// The axis coordinates of the slice planes, ascending (one per slice id of a contour vertex: the mean).
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

// The heights a vertex starting at height h may take: its slab between two slice planes, a twentieth of
// a spacing inside, and within `reach` of h. Beyond the outer planes (end caps) only the plane bounds.
std::pair<double, double> height_bounds(const std::vector<double>& levels, double h, double spacing, double reach) {
  double lo = h - reach, hi = h + reach;
  const double margin = 0.05 * spacing;
  if (levels.empty()) return {lo, hi};
  const auto above = std::upper_bound(levels.begin(), levels.end(), h);
  if (above != levels.begin()) lo = std::max(lo, std::min(h, *(above - 1) + margin));
  if (above != levels.end()) hi = std::min(hi, std::max(h, *above - margin));
  return {lo, hi};
}

template <typename Positions>
Eigen::Vector3d face_normal(const Positions& x, const Triangle& t, double* area = nullptr) {
  const Eigen::Vector3d c = (x.col(t[1]) - x.col(t[0])).cross(x.col(t[2]) - x.col(t[0]));
  const double len = c.norm();
  if (area) *area = 0.5 * len;
  return len > 0.0 ? Eigen::Vector3d(c / len) : Eigen::Vector3d::Zero();
}

// Everything the filter touches, numbered compactly and built once: the work is proportional to the
// region around the vertices without ids, not to the mesh (a few per cent of a large bone's vertices).
//
// Faces: the filtered ones (touching a moving vertex), and the faces sharing a vertex with one (their
// neighbourhoods), numbered in ascending mesh order. Vertices: those of the filtered faces, ascending.
struct Workspace {
  // Faces of the neighbourhoods, in mesh order; the filtered ones among them.
  std::vector<Index> faces;     ///< local face -> mesh face
  std::vector<Index> filtered;  ///< filtered face k -> local face (ascending)
  // Per filtered face: the corners (local vertices), and its neighbourhood in CSR (local faces, the face
  // itself included, ascending) with area x spatial kernel per entry.
  std::vector<Triangle> corners;
  std::vector<Index> ring_offsets;
  FillVector<Index> ring;
  FillVector<double> ring_weights;
  // The range kernel is symmetric: each pair of faces (a, b) that meet in a neighbourhood has one slot,
  // computed once per iteration however many of the two neighbourhoods it is in.
  FillVector<Index> ring_slot;       ///< per neighbourhood entry
  FillVector<Index> slot_a, slot_b;  ///< per slot: the faces (local), as first met: face a, entry b
  std::vector<Index> filtered_of;     ///< local face -> filtered face, or -1
  std::vector<Index> face_map;        ///< mesh face -> local face, or -1
  double sigma_s = 1.0;               ///< width of the spatial kernel, mm
  // Vertices.
  std::vector<Index> vertices;  ///< local vertex -> mesh vertex
  std::vector<std::uint8_t> moves;  ///< per local vertex
  std::vector<Index> moving;    ///< local ids of the moving vertices, ascending
  // Per moving vertex: its faces (filtered face ids, in the adjacency's order) in CSR, whether it is a
  // contour vertex, and for the others the heights it may take.
  std::vector<Index> incident_offsets, incident;
  std::vector<std::uint8_t> on_contour;
  std::vector<double> low, high;
};

// Two 3-vectors equal bit for bit (-0 and 0 differ): what the filter's iterations test to skip the work
// whose inputs did not change.
template <typename A, typename B>
bool same_bits(const A& a, const B& b) {
  return std::memcmp(a.data(), b.data(), 3 * sizeof(double)) == 0;
}

// The moving vertices (mesh ids, ascending) and the filtered faces (mesh ids, ascending).
void select_region(const ContourFrame& frame, std::size_t num_faces, const OffSliceFilterOptions& options,
                   std::vector<Index>& moving, std::vector<Index>& filtered) {
  const MeshAdjacency& adj = frame.adjacency;
  const Index n = adj.num_vertices();
  const bool contour_moves = options.contour_max_move > 0.0;
  std::vector<std::uint8_t> active(num_faces, 0);  // a byte per face: cheaper than sorting the faces' ids
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
  w.ring_slot.resize(w.ring.size());
  // In fixed chunks of filtered faces on every core: first each entry's mirror (the entry of an earlier
  // filtered face that it pairs with), or -1 where the entry opens a slot of its own (a mirror always does),
  // and each chunk's count of new slots; then the new slots are numbered in ring order (each chunk from
  // the count of the chunks before it), and the mirrors' slots copied.
  constexpr std::size_t kChunk = 4096;
  const std::size_t nk = w.filtered.size();
  FillVector<Index> mirror_of(w.ring.size());
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
  w.slot_a.resize(static_cast<std::size_t>(first_slot.back()));
  w.slot_b.resize(w.slot_a.size());
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

// Numbers the faces and vertices (see Workspace) and the neighbourhoods of the filtered faces.
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
  std::vector<Index> vertex_map(static_cast<std::size_t>(adj.num_vertices()), -1);
  for (Index f : filtered) {
    for (Index v : triangles[static_cast<std::size_t>(f)]) vertex_map[static_cast<std::size_t>(v)] = 0;
  }
  for (std::size_t v = 0; v < vertex_map.size(); ++v) {
    if (vertex_map[v] < 0) continue;
    vertex_map[v] = static_cast<Index>(w.vertices.size());
    w.vertices.push_back(static_cast<Index>(v));
  }
  std::vector<Index> face_map(triangles.size(), -1);
  for (Index v : w.vertices) {
    for (Index g : adj.incident_faces(v)) face_map[static_cast<std::size_t>(g)] = 0;
  }
  for (std::size_t g = 0; g < face_map.size(); ++g) {
    if (face_map[g] < 0) continue;
    face_map[g] = static_cast<Index>(w.faces.size());
    w.faces.push_back(static_cast<Index>(g));
  }
  w.filtered.resize(filtered.size());
  for (std::size_t k = 0; k < filtered.size(); ++k) w.filtered[k] = face_map[static_cast<std::size_t>(filtered[k])];

  // Per filtered face: its corners and its neighbourhood, the faces around its corners (local ids,
  // ascending as mesh ids are).
  w.corners.resize(filtered.size());
  w.ring_offsets.assign(filtered.size() + 1, 0);
  // In fixed chunks on every core, each into its own list; the lists are joined in chunk order.
  constexpr std::size_t kChunk = 4096;
  std::vector<std::vector<Index>> parts((filtered.size() + kChunk - 1) / kChunk);
  parallel_chunks(filtered.size(), kChunk, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    std::vector<Index>& part = parts[chunk];
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
  });
  for (std::size_t k = 0; k < filtered.size(); ++k) w.ring_offsets[k + 1] += w.ring_offsets[k];
  w.ring.resize(static_cast<std::size_t>(w.ring_offsets.back()));
  parallel_chunks(parts.size(), 1, [&](std::size_t chunk, std::size_t, std::size_t) {
    std::copy(parts[chunk].begin(), parts[chunk].end(), w.ring.begin() + w.ring_offsets[chunk * kChunk]);
  });
  // The filtered face of each local face (for the pair slots and the moving vertices' faces).
  std::vector<Index> filtered_of(w.faces.size(), -1);
  for (std::size_t k = 0; k < filtered.size(); ++k) {
    filtered_of[static_cast<std::size_t>(w.filtered[k])] = static_cast<Index>(k);
  }
  assign_pair_slots(filtered_of, w);
  w.filtered_of = std::move(filtered_of);
  w.face_map = std::move(face_map);
  w.moves.assign(w.vertices.size(), 0);
  w.incident_offsets.assign(moving.size() + 1, 0);
  w.on_contour.resize(moving.size());
  w.moving.resize(moving.size());
  for (std::size_t m = 0; m < moving.size(); ++m) {
    const Index i = moving[m];
    const Index li = vertex_map[static_cast<std::size_t>(i)];
    w.moving[m] = li;
    w.moves[static_cast<std::size_t>(li)] = 1;
    w.on_contour[m] = frame.is_contour_vertex(i) ? 1 : 0;
    w.incident_offsets[m + 1] = w.incident_offsets[m] + static_cast<Index>(adj.incident_faces(i).size());
  }
  w.incident.resize(static_cast<std::size_t>(w.incident_offsets.back()));
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

// The spatial part of the neighbourhoods' weights: area of the neighbour x a Gaussian of the distance
// between centroids, whose width is the mean such distance (fixed while the normals are filtered: nothing
// moves then).
void spatial_weights(const Eigen::Matrix3Xd& centroids, const Eigen::VectorXd& areas, Workspace& w) {
  // Per pair of faces (slot), once: the distance between the centroids and its Gaussian are symmetric bit
  // for bit (the difference only changes sign), as the range kernel is.
  const std::size_t ns = w.slot_a.size();
  FillVector<double> squared(ns), distance(ns);  // every element written by the loop below
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
  w.ring_weights.resize(w.ring.size());
  parallel_chunks(w.ring.size(), 16384, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t r = begin; r < end; ++r) {
      w.ring_weights[r] = areas[w.ring[r]] * kernel[static_cast<std::size_t>(w.ring_slot[r])];
    }
  });
}

// Patches for guidance normals (OffSliceRange::PatchGuidance), per local face: the faces sharing a vertex
// with it, weighted as the filter weighs a neighbourhood (area x spatial kernel). A filtered face's patch
// is its neighbourhood; the other local faces' patches reach one ring further, to faces outside the
// workspace ("outer" faces: no moving corner, so their normals are fixed, as the other local faces' are).
struct GuidancePatches {
  std::vector<Index> offsets;           ///< per local face, CSR into entries
  FillVector<Index> entries;            ///< local faces; an entry >= the local faces' count is outer
  FillVector<double> weights;           ///< per entry
  Eigen::Matrix3Xd outer_normals;       ///< per outer face
};

constexpr std::size_t kPatchChunk = 2048;  // local faces per chunk of the patches' loops

// The patches' sizes into `offsets` (per local face, to be summed), and per chunk of kPatchChunk local faces
// the faces of the patches of those not filtered: the faces around their corners, mesh ids, ascending (a
// filtered face's patch is its neighbourhood).
std::vector<std::vector<Index>> faces_around(const MeshAdjacency& adj, const std::vector<Triangle>& triangles,
                                             const Workspace& w, std::vector<Index>& offsets) {
  const std::size_t nl = w.faces.size();
  std::vector<std::vector<Index>> around((nl + kPatchChunk - 1) / kPatchChunk);
  parallel_chunks(nl, kPatchChunk, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    std::vector<Index>& part = around[chunk];
    std::vector<Index> local;
    for (std::size_t l = begin; l < end; ++l) {
      const Index k = w.filtered_of[l];
      if (k >= 0) {
        const auto ku = static_cast<std::size_t>(k);
        offsets[l + 1] = w.ring_offsets[ku + 1] - w.ring_offsets[ku];
        continue;
      }
      local.clear();
      for (Index v : triangles[static_cast<std::size_t>(w.faces[l])]) {
        for (Index g : adj.incident_faces(v)) local.push_back(g);
      }
      std::sort(local.begin(), local.end());
      local.erase(std::unique(local.begin(), local.end()), local.end());
      part.insert(part.end(), local.begin(), local.end());
      offsets[l + 1] = static_cast<Index>(local.size());
    }
  });
  return around;
}

// The faces of the patches outside the workspace, numbered in ascending mesh order (any order gives the
// same patches: an entry only names where its normal is read), with their areas, centroids and normals.
struct OuterFaces {
  std::vector<Index> of;  ///< mesh face -> outer face, or -1
  Eigen::Matrix3Xd centroids;
  Eigen::VectorXd areas;
};

OuterFaces outer_faces(const std::vector<Triangle>& triangles, const Eigen::Matrix3Xd& positions, const Workspace& w,
                       const std::vector<std::vector<Index>>& around, Eigen::Matrix3Xd& normals) {
  OuterFaces outer;
  outer.of.assign(triangles.size(), -1);
  for (const std::vector<Index>& part : around) {
    for (Index g : part) {
      if (w.face_map[static_cast<std::size_t>(g)] < 0) outer.of[static_cast<std::size_t>(g)] = 0;
    }
  }
  std::vector<Index> faces;  // outer face -> mesh face
  for (std::size_t g = 0; g < outer.of.size(); ++g) {
    if (outer.of[g] < 0) continue;
    outer.of[g] = static_cast<Index>(faces.size());
    faces.push_back(static_cast<Index>(g));
  }
  const auto no = static_cast<Index>(faces.size());
  outer.centroids.resize(3, no);
  outer.areas.resize(no);
  normals.resize(3, no);
  parallel_chunks(faces.size(), 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t o = begin; o < end; ++o) {
      const Triangle& t = triangles[static_cast<std::size_t>(faces[o])];
      const auto oo = static_cast<Index>(o);
      double a = 0.0;
      normals.col(oo) = face_normal(positions, t, &a);
      outer.areas[oo] = a;
      outer.centroids.col(oo) = (positions.col(t[0]) + positions.col(t[1]) + positions.col(t[2])) / 3.0;
    }
  });
  return outer;
}

GuidancePatches make_patches(const ContourFrame& frame, const std::vector<Triangle>& triangles,
                             const Eigen::Matrix3Xd& positions, const Workspace& w, const Eigen::Matrix3Xd& centroids,
                             const Eigen::VectorXd& areas) {
  const std::size_t nl = w.faces.size();
  const double inv_s = 1.0 / (2.0 * w.sigma_s * w.sigma_s);
  GuidancePatches p;
  p.offsets.assign(nl + 1, 0);
  const std::vector<std::vector<Index>> around = faces_around(frame.adjacency, triangles, w, p.offsets);
  for (std::size_t l = 0; l < nl; ++l) p.offsets[l + 1] += p.offsets[l];
  const OuterFaces outer = outer_faces(triangles, positions, w, around, p.outer_normals);
  // The entries and their weights (area x spatial kernel), on every core, in the chunks of faces_around.
  p.entries.resize(static_cast<std::size_t>(p.offsets.back()));
  p.weights.resize(p.entries.size());
  parallel_chunks(nl, kPatchChunk, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    const std::vector<Index>& part = around[chunk];
    std::size_t next = 0;  // in part
    for (std::size_t l = begin; l < end; ++l) {
      auto e = static_cast<std::size_t>(p.offsets[l]);
      const Index k = w.filtered_of[l];
      if (k >= 0) {
        for (Index r = w.ring_offsets[static_cast<std::size_t>(k)]; r < w.ring_offsets[static_cast<std::size_t>(k) + 1];
             ++r, ++e) {
          p.entries[e] = w.ring[static_cast<std::size_t>(r)];
          p.weights[e] = w.ring_weights[static_cast<std::size_t>(r)];
        }
        continue;
      }
      const Eigen::Vector3d c = centroids.col(static_cast<Index>(l));
      for (; e < static_cast<std::size_t>(p.offsets[l + 1]); ++e) {
        const Index g = part[next++];
        const Index local = w.face_map[static_cast<std::size_t>(g)];
        Eigen::Vector3d cg;
        double area = 0.0;
        Index entry = local;
        if (local >= 0) {
          cg = centroids.col(local);
          area = areas[local];
        } else {
          const Index o = outer.of[static_cast<std::size_t>(g)];
          cg = outer.centroids.col(o);
          area = outer.areas[o];
          entry = static_cast<Index>(nl) + o;
        }
        p.entries[e] = entry;
        p.weights[e] = area * std::exp(-(cg - c).squaredNorm() * inv_s);
      }
    }
  });
  return p;
}

// Guidance normals (after Zhang, Deng, Zhang, Bouaziz, Liu, "Guided mesh normal filtering", Pacific
// Graphics 2015): a patch's consistency is the length of its weighted mean normal over its weights (1 when
// its normals agree). Each filtered face takes the mean normal of the most consistent patch that holds it,
// among its own and the patches of the faces sharing a vertex with it whose mean normal lies within
// `min_cos` of its own normal (next to a crease, not a patch of the other side); the other local faces keep
// their own normals (in `guidance` already). `normals` holds the local faces' normals.
struct GuidanceState {
  Eigen::Matrix3Xd mean;                 ///< per local face: its patch's mean normal
  std::vector<double> consistency;       ///< per local face
  std::vector<std::uint8_t> recomputed;  ///< per local face: its patch was recomputed this time
};

// Only what changed is recomputed. `every_patch`: every patch is (otherwise one none of whose normals
// changed in the last iteration, `changed`, keeps its mean and consistency); `first`: every guidance normal
// is, and counts as changed. Otherwise a filtered face whose own normal and candidate patches all stayed
// keeps its guidance, copied from `last_guidance` (that of the last computation); `guided_changed` gets, per
// filtered face, whether its guidance differs from the last, bit for bit.
void guidance_normals(const Workspace& w, const GuidancePatches& p, const Eigen::Matrix3Xd& normals,
                      const std::vector<std::uint8_t>& changed, bool every_patch, bool first, double min_cos,
                      GuidanceState& state, const Eigen::Matrix3Xd& last_guidance, Eigen::Matrix3Xd& guidance,
                      std::vector<std::uint8_t>& guided_changed) {
  const std::size_t nl = w.faces.size(), nk = w.filtered.size();
  std::vector<std::uint8_t>& recomputed = state.recomputed;
  parallel_chunks(nl, 1024, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t l = begin; l < end; ++l) {
      bool stale = every_patch || first;
      for (Index e = p.offsets[l]; e < p.offsets[l + 1] && !stale; ++e) {
        const Index g = p.entries[static_cast<std::size_t>(e)];
        stale = g < static_cast<Index>(nl) && changed[static_cast<std::size_t>(g)] != 0;
      }
      recomputed[l] = stale ? 1 : 0;
      if (!stale) continue;
      Eigen::Vector3d acc = Eigen::Vector3d::Zero();
      double weight = 0.0;
      for (Index e = p.offsets[l]; e < p.offsets[l + 1]; ++e) {
        const auto eu = static_cast<std::size_t>(e);
        const Index g = p.entries[eu];
        const auto local = static_cast<Index>(nl);
        acc += p.weights[eu] * (g < local ? normals.col(g) : p.outer_normals.col(g - local));
        weight += p.weights[eu];
      }
      const double len = acc.norm();
      state.mean.col(static_cast<Index>(l)) = len > 0.0 ? Eigen::Vector3d(acc / len) : Eigen::Vector3d::Zero();
      state.consistency[l] = weight > 0.0 ? len / weight : 0.0;
    }
  });
  parallel_chunks(nk, 1024, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const Index f = w.filtered[k];
      const auto fu = static_cast<std::size_t>(f);
      bool stale = first || changed[fu] != 0;  // the neighbourhood holds the face itself
      for (Index r = w.ring_offsets[k]; r < w.ring_offsets[k + 1] && !stale; ++r) {
        stale = recomputed[static_cast<std::size_t>(w.ring[static_cast<std::size_t>(r)])] != 0;
      }
      if (!stale) {
        guidance.col(f) = last_guidance.col(f);
        guided_changed[fu] = 0;
        continue;
      }
      const Eigen::Vector3d own = normals.col(f);
      Index best = f;
      for (Index r = w.ring_offsets[k]; r < w.ring_offsets[k + 1]; ++r) {
        const Index g = w.ring[static_cast<std::size_t>(r)];
        if (state.consistency[static_cast<std::size_t>(g)] > state.consistency[static_cast<std::size_t>(best)] &&
            state.mean.col(g).dot(own) >= min_cos) {
          best = g;
        }
      }
      guidance.col(f) =
          state.consistency[static_cast<std::size_t>(best)] > 0.0 ? Eigen::Vector3d(state.mean.col(best)) : own;
      guided_changed[fu] = first || !same_bits(guidance.col(f), last_guidance.col(f)) ? 1 : 0;
    }
  });
}

// The filtered faces that take the rim iterations (OffSliceFilterOptions::rim_iterations): those whose
// neighbourhood holds two faces whose `normals` are more than the rim angle apart, and `rim_rings` rings of
// filtered faces around them.
std::vector<std::uint8_t> rim_faces(const Workspace& w, const OffSliceFilterOptions& options,
                                    const Eigen::Matrix3Xd& normals) {
  const std::size_t nk = w.filtered.size();
  const double rim_cos = std::cos(options.rim_angle_degrees * M_PI / 180.0);
  std::vector<std::uint8_t> rim(nk, 0);
  parallel_chunks(nk, 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const Index f = w.filtered[k];
      for (Index r = w.ring_offsets[k]; r < w.ring_offsets[k + 1] && !rim[k]; ++r) {
        rim[k] = normals.col(f).dot(normals.col(w.ring[static_cast<std::size_t>(r)])) < rim_cos ? 1 : 0;
      }
    }
  });
  std::vector<std::uint8_t> grown(nk, 0);
  for (int round = 0; round < options.rim_rings; ++round) {
    parallel_chunks(nk, 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        grown[k] = rim[k];
        for (Index r = w.ring_offsets[k]; r < w.ring_offsets[k + 1] && !grown[k]; ++r) {
          const Index kg = w.filtered_of[static_cast<std::size_t>(w.ring[static_cast<std::size_t>(r)])];
          grown[k] = kg >= 0 && rim[static_cast<std::size_t>(kg)] ? 1 : 0;
        }
      }
    });
    rim.swap(grown);
  }
  return rim;
}

// Bilateral filtering of the normals of the filtered faces (Zheng et al. 2011, eq. 4), Jacobi style; the
// other local faces' normals are read as they are. `normals` holds every local face's normal. The range
// kernel compares the normals themselves or, with `patches`, guidance normals.
void filter_normals(const Workspace& w, const OffSliceFilterOptions& options, const GuidancePatches* patches,
                    Eigen::Matrix3Xd& normals) {
  const double sigma_r = 2.0 * std::sin(0.5 * options.sigma_angle_degrees * M_PI / 180.0);  // as |n_i - n_j|
  const double inv_r = 1.0 / (2.0 * sigma_r * sigma_r);
  // Where a sum vanishes, a face keeps the normal of two iterations before (that of `next`).
  Eigen::Matrix3Xd next = normals;
  FillVector<float> range(w.slot_a.size());  // every slot is computed in the first iteration
  // Only what changed is recomputed. A face's sum reads the normals of its neighbourhood only (the face's
  // own included) and each pair's range kernel, which reads the pair's two compared normals: where none of
  // them changed bit for bit in the last iteration, the sum and its normal are those of the last iteration,
  // and so is a kernel whose two faces kept their compared normals. The filtered normals start moving near
  // the region's features and spread a ring per iteration; flat caps keep theirs. Guidance normals read
  // two rings of normals: where they are computed, they are compared bit for bit with the last ones, which
  // widens the set of faces recomputed to what they reach.
  const std::size_t nl = w.faces.size(), nk = w.filtered.size();
  const bool full = full_recompute();
  // Per local face: its normal changed in the last iteration (never, for the faces not filtered); the first
  // iteration computes everything.
  std::vector<std::uint8_t> changed(nl, 0), changes(nl, 0);
  std::vector<std::uint8_t> summed(nk, 0);  // per filtered face: its last sum was not zero (its normal set)
  // Guidance: per local face, the compared normal and whether it changed since it was last computed. It
  // is computed every `guidance_interval` iterations; in between, it and the range kernels stay.
  const double min_cos = std::cos(options.sigma_angle_degrees * M_PI / 180.0);
  Eigen::Matrix3Xd guidance, last_guidance;
  GuidanceState state;
  std::vector<std::uint8_t> guided_changed(nl, 0);
  if (patches) {
    guidance = normals;
    state.mean.resize(3, static_cast<Index>(nl));
    state.consistency.assign(nl, 0.0);
    state.recomputed.assign(nl, 0);
  }
  const int interval = std::max(options.guidance_interval, 1);
  // After the normal iterations, the rim iterations update the rim faces only (the others' normals stay).
  const bool rims = options.normal_iterations > 0 && options.rim_iterations > 0;
  const std::vector<std::uint8_t> rim = rims ? rim_faces(w, options, normals) : std::vector<std::uint8_t>{};
  const int iterations = options.normal_iterations + (rims ? options.rim_iterations : 0);
  for (int it = 0; it < iterations; ++it) {
    const bool all = it == 0 || full;
    const bool rim_only = it >= options.normal_iterations;
    const bool refresh = !patches || it % interval == 0;  // the guidance (and so the range kernels) recomputed
    if (!refresh) {
      std::fill(guided_changed.begin(), guided_changed.end(), 0);
    } else if (patches) {
      last_guidance.swap(guidance);
      // From the second computation on, the buffer of two computations before: its columns of the faces
      // not filtered hold their normals, which never change, and guidance_normals writes every filtered one.
      if (it == 0) guidance = normals;
      // The faces not filtered: their guidance is their normal, new in the first iteration only.
      if (all || it == interval) std::fill(guided_changed.begin(), guided_changed.end(), all ? 1 : 0);
      // After iterations without guidance, any patch may have changed since it was last computed.
      guidance_normals(w, *patches, normals, changed, interval > 1, all, min_cos, state, last_guidance, guidance,
                       guided_changed);
    }
    const Eigen::Matrix3Xd& compared = patches ? guidance : normals;
    const std::vector<std::uint8_t>& compared_changed = patches ? guided_changed : changed;
    // The range kernel of every pair, from |n_b - n_a|^2 of unit normals, in single precision (the hot
    // spot). The dot product is symmetric, bit for bit.
    parallel_chunks(refresh ? range.size() : 0, 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t s = begin; s < end; ++s) {
        const auto a = static_cast<std::size_t>(w.slot_a[s]), b = static_cast<std::size_t>(w.slot_b[s]);
        if (!all && !compared_changed[a] && !compared_changed[b]) continue;
        const double dr = 2.0 - 2.0 * compared.col(w.slot_b[s]).dot(compared.col(w.slot_a[s]));
        range[s] = std::exp(static_cast<float>(-dr * inv_r));
      }
    });
    parallel_chunks(nk, 1024, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        const Index f = w.filtered[k];
        if (rim_only && !rim[k]) {  // not a rim face: its normal stays
          next.col(f) = normals.col(f);
          changes[static_cast<std::size_t>(f)] = 0;
          continue;
        }
        bool stale = all || summed[k] == 0;  // a face whose last sum vanished is summed again
        for (Index r = w.ring_offsets[k]; r < w.ring_offsets[k + 1] && !stale; ++r) {
          const auto g = static_cast<std::size_t>(w.ring[static_cast<std::size_t>(r)]);
          stale = changed[g] != 0 || (patches && guided_changed[g] != 0);
        }
        if (!stale) {  // the last sum again: the normal stays
          next.col(f) = normals.col(f);
          changes[static_cast<std::size_t>(f)] = 0;
          continue;
        }
        Eigen::Vector3d acc = Eigen::Vector3d::Zero();
        for (Index r = w.ring_offsets[k]; r < w.ring_offsets[k + 1]; ++r) {
          const auto ru = static_cast<std::size_t>(r);
          const auto kernel = static_cast<double>(range[static_cast<std::size_t>(w.ring_slot[ru])]);
          acc += w.ring_weights[ru] * kernel * normals.col(w.ring[ru]);
        }
        const double len = acc.norm();
        summed[k] = len > 0.0 ? 1 : 0;
        if (len > 0.0) next.col(f) = acc / len;
        changes[static_cast<std::size_t>(f)] = same_bits(next.col(f), normals.col(f)) ? 0 : 1;
      }
    });
    normals.swap(next);
    changed.swap(changes);
  }
}

// The vertex update (eq. 6), Jacobi style: each moving vertex goes towards the planes of its faces with
// the filtered normals `normals` (per filtered face), within its bounds (see filter_off_slice_normals).
// `x` and `start` hold the local vertices.
void update_vertices(const ContourFrame& frame, const Workspace& w, const Eigen::Matrix3Xd& normals,
                     const OffSliceFilterOptions& options, const Eigen::Matrix3Xd& start, Eigen::Matrix3Xd& x) {
  const double reach = options.max_move * frame.slice_spacing;
  const Eigen::Vector3d& axis = frame.axis;
  const std::size_t nk = w.filtered.size(), nm = w.moving.size();
  Eigen::Matrix3Xd centroids(3, static_cast<Index>(nk));
  Eigen::Matrix3Xd updated(3, static_cast<Index>(nm));
  // Only what changed is recomputed: a vertex's update reads the corners of its faces (through their
  // centroids) and fixed data. Where none of them moved, bit for bit, in the last iteration, the update is
  // the last one again, which is where the vertex is; a centroid whose corners stayed is the same too.
  std::vector<std::uint8_t> moved(static_cast<std::size_t>(x.cols()), 0);  // per local vertex, last iteration
  std::vector<std::uint8_t> face_moved(nk, 0);  // per filtered face: a corner moved (its centroid is new)
  const bool full = full_recompute();
  for (int it = 0; it < options.vertex_iterations; ++it) {
    parallel_chunks(nk, 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        const Triangle& t = w.corners[k];
        const auto c0 = static_cast<std::size_t>(t[0]), c1 = static_cast<std::size_t>(t[1]),
                   c2 = static_cast<std::size_t>(t[2]);
        face_moved[k] = it == 0 || full || moved[c0] || moved[c1] || moved[c2] ? 1 : 0;
        if (face_moved[k]) centroids.col(static_cast<Index>(k)) = (x.col(t[0]) + x.col(t[1]) + x.col(t[2])) / 3.0;
      }
    });
    parallel_chunks(nm, 2048, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t m = begin; m < end; ++m) {
        const Index i = w.moving[m];
        const Index first = w.incident_offsets[m], last = w.incident_offsets[m + 1];
        bool stale = false;
        for (Index r = first; r < last && !stale; ++r) {
          stale = face_moved[static_cast<std::size_t>(w.incident[static_cast<std::size_t>(r)])] != 0;
        }
        if (!stale) {  // the last update again
          updated.col(static_cast<Index>(m)) = x.col(i);
          continue;
        }
        Eigen::Vector3d step = Eigen::Vector3d::Zero();
        for (Index r = first; r < last; ++r) {
          const Index f = w.incident[static_cast<std::size_t>(r)];
          step += normals.col(f) * normals.col(f).dot(centroids.col(f) - x.col(i));
        }
        step /= static_cast<double>(last - first);
        const Eigen::Vector3d x0 = start.col(i);
        Eigen::Vector3d d;
        if (w.on_contour[m]) {
          // A contour vertex stays in its slice plane, within the fidelity bound of where it was.
          step -= axis * axis.dot(step);
          d = x.col(i) + step - x0;
          if (d.norm() > options.contour_max_move) d *= options.contour_max_move / d.norm();
        } else {
          if (options.motion == OffSliceMotion::AlongAxis) step = axis * axis.dot(step);
          // Within `reach` of the start, and in the start's slab.
          d = x.col(i) + step - x0;
          if (d.norm() > reach) d *= reach / d.norm();
          const double h0 = axis.dot(x0);
          const double h = std::clamp(h0 + axis.dot(d), w.low[m], w.high[m]);
          d += axis * (h - h0 - axis.dot(d));
        }
        updated.col(static_cast<Index>(m)) = x0 + d;
      }
    });
    parallel_chunks(nm, 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t m = begin; m < end; ++m) {
        const Index i = w.moving[m];
        const auto u = updated.col(static_cast<Index>(m));
        moved[static_cast<std::size_t>(i)] = same_bits(u, x.col(i)) ? 0 : 1;
        x.col(i) = u;
      }
    });
  }
}

// A face that turned over (its normal against its unfiltered one) gets its moving vertices back, until
// none does.
void undo_turned_faces(const Workspace& w, const Eigen::Matrix3Xd& initial_normals, const Eigen::Matrix3Xd& start,
                       Eigen::Matrix3Xd& x) {
  for (int round = 0; round < 8; ++round) {
    bool any = false;
    for (std::size_t k = 0; k < w.filtered.size(); ++k) {
      const Triangle& t = w.corners[k];
      const auto kk = static_cast<Index>(k);
      if (initial_normals.col(kk).isZero() || face_normal(x, t).dot(initial_normals.col(kk)) > 0.0) continue;
      for (int c = 0; c < 3; ++c) {
        const Index v = t[static_cast<std::size_t>(c)];
        if (w.moves[static_cast<std::size_t>(v)] && x.col(v) != start.col(v)) {
          x.col(v) = start.col(v);
          any = true;
        }
      }
    }
    if (!any) break;
  }
}

}  // namespace

std::size_t filter_off_slice_normals(const ContourFrame& frame, const std::vector<Triangle>& triangles,
                                     const OffSliceFilterOptions& options, Eigen::Matrix3Xd& positions) {
  if (options.filter == OffSliceFilter::None) return 0;
  Workspace w = make_workspace(frame, triangles, options);
  if (w.moving.empty()) return 0;

  // Normals, areas and centroids of the local faces, from the mesh's positions.
  const auto nl = static_cast<Index>(w.faces.size());
  Eigen::Matrix3Xd normals(3, nl), centroids(3, nl);
  Eigen::VectorXd areas(nl);
  parallel_chunks(w.faces.size(), 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t l = begin; l < end; ++l) {
      const Triangle& t = triangles[static_cast<std::size_t>(w.faces[l])];
      const auto ll = static_cast<Index>(l);
      double a = 0.0;
      normals.col(ll) = face_normal(positions, t, &a);
      areas[ll] = a;
      centroids.col(ll) = (positions.col(t[0]) + positions.col(t[1]) + positions.col(t[2])) / 3.0;
    }
  });
  const auto nk = static_cast<Index>(w.filtered.size());
  Eigen::Matrix3Xd initial_normals(3, nk);
  parallel_chunks(w.filtered.size(), 8192, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) initial_normals.col(static_cast<Index>(k)) = normals.col(w.filtered[k]);
  });

  // The local vertices where they start, and the heights each moving vertex off the contours may take.
  const auto nv = static_cast<Index>(w.vertices.size());
  Eigen::Matrix3Xd start(3, nv);
  parallel_chunks(w.vertices.size(), 8192, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) start.col(static_cast<Index>(v)) = positions.col(w.vertices[v]);
  });
  {
    const std::vector<double> levels = slice_levels(frame, positions);
    const double reach = options.max_move * frame.slice_spacing;
    w.low.assign(w.moving.size(), 0.0);
    w.high.assign(w.moving.size(), 0.0);
    parallel_chunks(w.moving.size(), 8192, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t m = begin; m < end; ++m) {
        if (w.on_contour[m]) continue;
        const double h0 = frame.axis.dot(start.col(w.moving[m]));
        std::tie(w.low[m], w.high[m]) = height_bounds(levels, h0, frame.slice_spacing, reach);
      }
    });
  }

  spatial_weights(centroids, areas, w);
  GuidancePatches patches;
  const bool guided = options.range == OffSliceRange::PatchGuidance;
  if (guided) patches = make_patches(frame, triangles, positions, w, centroids, areas);
  filter_normals(w, options, guided ? &patches : nullptr, normals);
  Eigen::Matrix3Xd filtered_normals(3, nk);
  for (Index k = 0; k < nk; ++k) filtered_normals.col(k) = normals.col(w.filtered[static_cast<std::size_t>(k)]);

  Eigen::Matrix3Xd x = start;
  update_vertices(frame, w, filtered_normals, options, start, x);
  undo_turned_faces(w, initial_normals, start, x);
  std::size_t moved = 0;
  for (Index v : w.moving) {
    if (x.col(v) == start.col(v)) continue;
    positions.col(w.vertices[static_cast<std::size_t>(v)]) = x.col(v);
    ++moved;
  }
  return moved;
}

}  // namespace contourmesh::detail
