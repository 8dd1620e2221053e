// SPDX-License-Identifier: BSD-3-Clause
#include "detail/sliver_collapse.h"

#include "detail/face_shape.h"

#include <contourmesh/smooth/mesh_quality.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

namespace contourmesh::detail {

namespace {

// A face's normal may turn by at most this much in a collapse.
const double kMaxTurnCosine = std::cos(45.0 * std::numbers::pi / 180.0);

// The slab's faces over compact vertex numbers (the slab's local vertices first, in order, then the
// contour vertices its faces use). Only the patch around the slivers takes part: the faces that touch a
// vertex within one edge of a sliver's corner. Those vertices are complete (every face of theirs is in the
// patch, so their rings are whole); the patch's other vertices never go and nothing goes onto them.
class Collapser {
 public:
  // `slivers`: the slab's sliver faces (indices into its faces).
  Collapser(SlabMesh& mesh, const std::vector<std::size_t>& slivers)
      : mesh_(mesh), locals_(mesh.vertices.size()) {
    for (const Triangle& t : mesh.triangles) {
      for (VertexRef r : t) {
        if (!is_local(r)) contour_refs_.push_back(r);
      }
    }
    std::sort(contour_refs_.begin(), contour_refs_.end());
    contour_refs_.erase(std::unique(contour_refs_.begin(), contour_refs_.end()), contour_refs_.end());
    // A slab's contour vertices are numbered slice by slice: their refs span a range little wider than
    // their count, where each one's rank is a table look-up.
    if (!contour_refs_.empty() &&
        static_cast<std::size_t>(contour_refs_.back() - contour_refs_.front()) < 4 * contour_refs_.size() + 64) {
      rank_.assign(static_cast<std::size_t>(contour_refs_.back() - contour_refs_.front()) + 1, -1);
      for (std::size_t k = 0; k < contour_refs_.size(); ++k) {
        rank_[static_cast<std::size_t>(contour_refs_[k] - contour_refs_.front())] = static_cast<int>(k);
      }
    }
    const std::size_t n = locals_ + contour_refs_.size();
    positions_.resize(n);
    for (std::size_t v = 0; v < n; ++v) positions_[v] = mesh.position(ref(static_cast<int>(v)));
    faces_.reserve(mesh.triangles.size());
    for (const Triangle& t : mesh.triangles) faces_.push_back({compact(t[0]), compact(t[1]), compact(t[2])});
    alive_.assign(faces_.size(), 1);
    // The patch: sliver corners, their neighbours (complete), and every face that touches one of those.
    std::vector<std::uint8_t> corner(n, 0);
    complete_.assign(n, 0);
    for (std::size_t f : slivers) {
      for (int v : faces_[f]) corner[static_cast<std::size_t>(v)] = 1;
    }
    for (const auto& t : faces_) {
      if (corner[static_cast<std::size_t>(t[0])] || corner[static_cast<std::size_t>(t[1])] ||
          corner[static_cast<std::size_t>(t[2])]) {
        for (int v : t) complete_[static_cast<std::size_t>(v)] = 1;
      }
    }
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      const auto& t = faces_[f];
      if (complete_[static_cast<std::size_t>(t[0])] || complete_[static_cast<std::size_t>(t[1])] ||
          complete_[static_cast<std::size_t>(t[2])]) {
        patch_.push_back(static_cast<int>(f));
      }
    }
    // Each vertex's faces, each list allocated once at its size.
    std::vector<int> degree(n, 0);
    for (int f : patch_) {
      for (int v : faces_[static_cast<std::size_t>(f)]) ++degree[static_cast<std::size_t>(v)];
    }
    around_.resize(n);
    for (std::size_t v = 0; v < n; ++v) {
      if (degree[v] > 0) around_[v].reserve(static_cast<std::size_t>(degree[v]));
    }
    for (int f : patch_) {
      for (int v : faces_[static_cast<std::size_t>(f)]) around_[static_cast<std::size_t>(v)].push_back(f);
    }
    // Contour vertices, vertices on the slab's boundary (an edge with one face, or more than two), the
    // corners of caps and the patch's incomplete vertices never go.
    fixed_.assign(n, 0);
    for (std::size_t v = 0; v < n; ++v) fixed_[v] = v >= locals_ || !complete_[v] ? 1 : 0;
    std::vector<std::uint64_t> edges;
    edges.reserve(3 * patch_.size());
    for (int f : patch_) {
      const auto& t = faces_[static_cast<std::size_t>(f)];
      for (int k = 0; k < 3; ++k) {
        edges.push_back(key(t[k], t[(k + 1) % 3]));
        if (mesh.roles[static_cast<std::size_t>(f)] == FaceRole::Cap) fixed_[static_cast<std::size_t>(t[k])] = 1;
      }
    }
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
      std::size_t j = i;
      while (j < edges.size() && edges[j] == edges[i]) ++j;
      // An edge of a complete vertex has all its faces in the patch; an incomplete vertex is fixed anyway.
      if (j - i != 2) {
        fixed_[static_cast<std::size_t>(edges[i] >> 32)] = 1;
        fixed_[static_cast<std::size_t>(edges[i] & 0xffffffffU)] = 1;
      }
      i = j;
    }
  }

  /// The faces of the patch (indices into the slab's faces).
  [[nodiscard]] const std::vector<int>& patch() const { return patch_; }
  [[nodiscard]] bool alive(int f) const { return alive_[static_cast<std::size_t>(f)] != 0; }

  [[nodiscard]] bool sliver(int f) const {
    const auto& t = faces_[static_cast<std::size_t>(f)];
    return is_sliver(pos(t[0]), pos(t[1]), pos(t[2]));
  }
  [[nodiscard]] double min_angle(int f) const {
    const auto& t = faces_[static_cast<std::size_t>(f)];
    return minimum_angle_degrees(pos(t[0]), pos(t[1]), pos(t[2]));
  }
  [[nodiscard]] bool removable(int v) const { return fixed_[static_cast<std::size_t>(v)] == 0; }

  // The smallest angle (degrees) of the faces around v.
  [[nodiscard]] double smallest_angle_around(int v) const {
    double smallest = 180.0;
    for (int f : around_[static_cast<std::size_t>(v)]) smallest = std::min(smallest, min_angle(f));
    return smallest;
  }

  // The smallest angle (degrees) of the faces around `gone` after it moves onto `kept`, or -1 when the
  // collapse is not allowed. `gone_ring`: ring(gone); `before`: smallest_angle_around(gone), or NaN
  // until a candidate needs it (then set). The geometric tests come first: they are cheap and turn most
  // candidates down; the angles (two arc tangents each) only when they pass.
  [[nodiscard]] double try_collapse(int gone, const std::vector<int>& gone_ring, double& before, int kept,
                                    double max_length, double max_deviation) const {
    if (fixed_[static_cast<std::size_t>(gone)] || !complete_[static_cast<std::size_t>(kept)] ||
        (pos(kept) - pos(gone)).norm() > max_length) {
      return -1.0;
    }
    double flat_before = 0.0, flat_after = 0.0;  // twice the area within 10 degrees of the slice planes
    std::array<int, 2> opposite{-1, -1};
    int shared = 0;  // faces that hold the edge
    const Eigen::Vector3d from = pos(gone), target = pos(kept);
    for (int f : around_[static_cast<std::size_t>(gone)]) {
      const auto& t = faces_[static_cast<std::size_t>(f)];
      std::array<Eigen::Vector3d, 3> p{pos(t[0]), pos(t[1]), pos(t[2])};
      const Eigen::Vector3d n0 = (p[1] - p[0]).cross(p[2] - p[0]);
      const double n0n = n0.norm();
      if (std::abs(n0.z()) >= kShelfCosine * n0n) flat_before += n0n;
      // The kept vertex lies near the plane of every face the vertex that goes had.
      if (n0n > 0.0 && std::abs(n0.dot(target - p[0])) > max_deviation * n0n) return -1.0;
      if (std::find(t.begin(), t.end(), kept) != t.end()) {
        if (shared == 2) return -1.0;
        for (int v : t) {
          if (v != gone && v != kept) opposite[static_cast<std::size_t>(shared)] = v;
        }
        ++shared;
        continue;
      }
      for (int k = 0; k < 3; ++k) {
        if (t[k] == gone) p[k] = target;
      }
      const Eigen::Vector3d n1 = (p[1] - p[0]).cross(p[2] - p[0]);
      const double n1n = n1.norm();
      if (!(n1n > 0.0) || n0.dot(n1) < kMaxTurnCosine * n0n * n1n) return -1.0;
      // ... and the vertex that goes lies near the plane of every new face.
      if (std::abs(n1.dot(from - p[0])) > max_deviation * n1n) return -1.0;
      if (std::abs(n1.z()) >= kShelfCosine * n1n) flat_after += n1n;
    }
    // A collapse adds no area lying nearly in the slice planes (a shelf), and raises the smallest angle.
    if (flat_after > flat_before) return -1.0;
    if (std::isnan(before)) before = smallest_angle_around(gone);
    double after = 180.0;
    for (int f : around_[static_cast<std::size_t>(gone)]) {
      const auto& t = faces_[static_cast<std::size_t>(f)];
      if (std::find(t.begin(), t.end(), kept) != t.end()) continue;
      std::array<Eigen::Vector3d, 3> p{pos(t[0]), pos(t[1]), pos(t[2])};
      for (int k = 0; k < 3; ++k) {
        if (t[k] == gone) p[k] = pos(kept);
      }
      after = std::min(after, minimum_angle_degrees(p[0], p[1], p[2]));
    }
    if (!(after > before)) return -1.0;
    // Exactly two faces hold the edge, and its ends share no neighbour but their third corners (the link
    // condition).
    if (shared != 2 || opposite[0] == opposite[1]) return -1.0;
    std::vector<int>& kept_ring = kept_ring_;
    ring(kept, kept_ring);
    std::vector<int>& common = common_;
    common.clear();
    std::set_intersection(gone_ring.begin(), gone_ring.end(), kept_ring.begin(), kept_ring.end(),
                          std::back_inserter(common));
    std::sort(opposite.begin(), opposite.end());
    if (common.size() != 2 || common[0] != opposite[0] || common[1] != opposite[1]) return -1.0;
    // No new chord between two contour vertices of one slice: it would lie in the slice's plane, and the
    // next slab may hold the same edge.
    if (!is_local(ref(kept))) {
      for (int v : gone_ring) {
        if (v != kept && !is_local(ref(v)) && pos(v).z() == pos(kept).z() &&
            !std::binary_search(kept_ring.begin(), kept_ring.end(), v)) {
          return -1.0;
        }
      }
    }
    return after;
  }

  void collapse(int gone, int kept) {
    for (int f : around_[static_cast<std::size_t>(gone)]) {
      auto& t = faces_[static_cast<std::size_t>(f)];
      if (std::find(t.begin(), t.end(), kept) != t.end()) {
        alive_[static_cast<std::size_t>(f)] = 0;
        for (int v : t) {
          if (v == gone) continue;
          auto& list = around_[static_cast<std::size_t>(v)];
          list.erase(std::remove(list.begin(), list.end(), f), list.end());
        }
        continue;
      }
      for (int& v : t) {
        if (v == gone) v = kept;
      }
      around_[static_cast<std::size_t>(kept)].push_back(f);
    }
    around_[static_cast<std::size_t>(gone)].clear();
    removed_.push_back(gone);
  }

  [[nodiscard]] const std::array<int, 3>& face(int f) const { return faces_[static_cast<std::size_t>(f)]; }

  // Writes the faces that remain back to the slab and drops the local vertices that went.
  void store() {
    if (removed_.empty()) return;
    std::vector<std::uint8_t> gone_local(mesh_.vertices.size(), 0);
    for (int v : removed_) gone_local[static_cast<std::size_t>(v)] = 1;  // only local vertices go
    std::vector<Index> renumber(mesh_.vertices.size(), -1);
    std::vector<Eigen::Vector3d> vertices;
    vertices.reserve(mesh_.vertices.size() - removed_.size());
    for (std::size_t k = 0; k < mesh_.vertices.size(); ++k) {
      if (gone_local[k]) continue;
      renumber[k] = static_cast<Index>(vertices.size());
      vertices.push_back(mesh_.vertices[k]);
    }
    std::vector<Triangle> triangles;
    std::vector<FaceRole> roles;
    triangles.reserve(faces_.size());
    roles.reserve(faces_.size());
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      if (!alive_[f]) continue;
      Triangle t{};
      for (int k = 0; k < 3; ++k) {
        const VertexRef r = ref(faces_[f][k]);
        t[k] = is_local(r) ? local_ref(static_cast<std::size_t>(renumber[local_index(r)])) : r;
      }
      triangles.push_back(t);
      roles.push_back(mesh_.roles[f]);
    }
    mesh_.vertices = std::move(vertices);
    mesh_.triangles = std::move(triangles);
    mesh_.roles = std::move(roles);
  }

  // The vertices that share a face with v, sorted, without v, into `out` (its storage reused).
  void ring(int v, std::vector<int>& out) const {
    out.clear();
    for (int f : around_[static_cast<std::size_t>(v)]) {
      for (int u : faces_[static_cast<std::size_t>(f)]) {
        if (u != v) out.push_back(u);
      }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }

 private:
  static std::uint64_t key(int a, int b) {
    if (a > b) std::swap(a, b);
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
  }

  [[nodiscard]] int compact(VertexRef r) const {
    if (is_local(r)) return static_cast<int>(local_index(r));
    if (!rank_.empty()) {
      return static_cast<int>(locals_) + rank_[static_cast<std::size_t>(r - contour_refs_.front())];
    }
    const auto it = std::lower_bound(contour_refs_.begin(), contour_refs_.end(), r);
    return static_cast<int>(locals_ + static_cast<std::size_t>(it - contour_refs_.begin()));
  }
  [[nodiscard]] VertexRef ref(int v) const {
    const auto k = static_cast<std::size_t>(v);
    return k < locals_ ? local_ref(k) : contour_refs_[k - locals_];
  }

  [[nodiscard]] const Eigen::Vector3d& pos(int v) const { return positions_[static_cast<std::size_t>(v)]; }

  SlabMesh& mesh_;
  std::size_t locals_;
  std::vector<VertexRef> contour_refs_;  // sorted
  std::vector<int> rank_;  // where their span is narrow: rank_[r - contour_refs_.front()], else empty
  std::vector<Eigen::Vector3d> positions_;
  std::vector<std::array<int, 3>> faces_;
  std::vector<std::uint8_t> alive_;
  std::vector<std::vector<int>> around_;
  // Scratch for try_collapse (the kept vertex's ring, the rings' common vertices): storage reused.
  mutable std::vector<int> kept_ring_, common_;
  std::vector<std::uint8_t> fixed_;
  std::vector<std::uint8_t> complete_;
  std::vector<int> patch_;
  std::vector<int> removed_;
};

}  // namespace

std::size_t collapse_slivers(SlabMesh& mesh, double max_length, double max_deviation) {
  if (!(max_length > 0.0 && max_deviation > 0.0)) return 0;
  std::vector<std::size_t> slivers;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (is_sliver(mesh.position(t[0]), mesh.position(t[1]), mesh.position(t[2]))) slivers.push_back(f);
  }
  if (slivers.empty()) return 0;
  Collapser c(mesh, slivers);
  std::size_t collapses = 0;
  // The sharpest slivers first; a collapse changes the faces around it, so each is checked again when
  // its turn comes, and further sweeps take what the first one left or made.
  std::vector<int> ring;  // of the corner that would go, reused
  for (int sweep = 0; sweep < 3; ++sweep) {
    std::vector<std::pair<double, int>> work;
    for (int f : c.patch()) {
      if (c.alive(f) && c.sliver(f)) work.emplace_back(c.min_angle(f), f);
    }
    std::sort(work.begin(), work.end());
    const std::size_t before_sweep = collapses;
    for (const auto& [angle, f] : work) {
      if (!c.alive(f) || !c.sliver(f)) continue;
      // Of the sliver's corners that may go, onto any neighbour: the collapse that leaves the best
      // smallest angle.
      int best_gone = -1, best_kept = -1;
      double best = -1.0;
      for (int gone : c.face(f)) {
        if (!c.removable(gone)) continue;
        c.ring(gone, ring);
        double before = std::numeric_limits<double>::quiet_NaN();  // smallest_angle_around(gone), when needed
        for (int kept : ring) {
          const double after = c.try_collapse(gone, ring, before, kept, max_length, max_deviation);
          if (after > best) {
            best = after;
            best_gone = gone;
            best_kept = kept;
          }
        }
      }
      if (best_gone < 0) continue;
      c.collapse(best_gone, best_kept);
      ++collapses;
    }
    if (collapses == before_sweep) break;
  }
  c.store();
  return collapses;
}

}  // namespace contourmesh::detail
