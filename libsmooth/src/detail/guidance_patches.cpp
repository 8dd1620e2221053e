// SPDX-License-Identifier: BSD-3-Clause
#include "detail/guidance_patches.h"

#include "contourmesh/internal/huge_pages.h"

#include <algorithm>
#include <cmath>

namespace contourmesh::detail {

namespace {

constexpr std::size_t kPatchChunk = 2048;  // local faces per chunk of the patches' loops

// The patches' sizes into `offsets` (per local face, to be summed), and per chunk of kPatchChunk local faces
// the faces of the patches of those not filtered: the faces around their corners, mesh ids, ascending (a
// filtered face's patch is its neighbourhood).
std::vector<std::vector<Index>> faces_around(const MeshAdjacency& adj, const std::vector<Triangle>& triangles,
                                             const Workspace& w, std::vector<Index>& offsets) {
  const std::size_t nl = w.faces.size();
  return map_chunks<std::vector<Index>>(nl, kPatchChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
    std::vector<Index> part;
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
    return part;
  });
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
  detail::assign_huge(outer.of, triangles.size(), -1);
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
  outer.centroids = detail::huge_matrix<Eigen::Matrix3Xd>(3, no);
  outer.areas = detail::huge_matrix<Eigen::VectorXd>(no, 1);
  normals = detail::huge_matrix<Eigen::Matrix3Xd>(3, no);
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

}  // namespace

GuidancePatches make_patches(const ContourFrame& frame, const std::vector<Triangle>& triangles,
                             const Eigen::Matrix3Xd& positions, const Workspace& w, const Eigen::Matrix3Xd& centroids,
                             const Eigen::VectorXd& areas) {
  const std::size_t nl = w.faces.size();
  const double inv_s = 1.0 / (2.0 * w.sigma_s * w.sigma_s);
  GuidancePatches p;
  detail::assign_huge(p.offsets, nl + 1, 0);
  const std::vector<std::vector<Index>> around = faces_around(frame.adjacency, triangles, w, p.offsets);
  for (std::size_t l = 0; l < nl; ++l) p.offsets[l + 1] += p.offsets[l];
  const OuterFaces outer = outer_faces(triangles, positions, w, around, p.outer_normals);
  // The entries and their weights (area x spatial kernel), on every core, in the chunks of faces_around.
  detail::resize_huge(p.entries, static_cast<std::size_t>(p.offsets.back()));
  detail::resize_huge(p.weights, p.entries.size());
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
        p.weights[e] = static_cast<float>(area * std::exp(-(cg - c).squaredNorm() * inv_s));
      }
    }
  });
  return p;
}

void guidance_normals(const Workspace& w, const GuidancePatches& p, const Eigen::Matrix3Xd& normals,
                      const std::vector<std::uint8_t>& changed, bool first, double min_cos,
                      GuidanceState& state, const Eigen::Matrix3Xd& last_guidance, Eigen::Matrix3Xd& guidance,
                      std::vector<std::uint8_t>& guided_changed) {
  const std::size_t nl = w.faces.size(), nk = w.filtered.size();
  std::vector<std::uint8_t>& recomputed = state.recomputed;
  parallel_chunks(nl, 1024, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t l = begin; l < end; ++l) {
      bool stale = first;
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
        const auto we = static_cast<double>(p.weights[eu]);
        acc += we * (g < local ? normals.col(g) : p.outer_normals.col(g - local));
        weight += we;
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

}  // namespace contourmesh::detail
