// SPDX-License-Identifier: BSD-3-Clause
#include "detail/slab_remeshing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <numbers>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace contourmesh::detail {

namespace {

// A face whose smallest angle is under 10 degrees is a sliver.
const double kSliverCosine = std::cos(10.0 * std::numbers::pi / 180.0);
// A face whose longest edge is at least this share of the sum of the other two is flat, not thin.
constexpr double kFlatRatio = 0.97;

// Cosine of the smallest angle of a triangle (the angle opposite its shortest edge), in [0.5, 1]: a
// measure of shape that falls as the smallest angle grows, without trigonometry. 1 for a degenerate one.
double sharpness(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  double e[3] = {(b - c).squaredNorm(), (c - a).squaredNorm(), (a - b).squaredNorm()};
  std::sort(e, e + 3);
  const double denominator = 2.0 * std::sqrt(e[1] * e[2]);
  if (!(denominator > 0.0)) return 1.0;
  return std::clamp((e[1] + e[2] - e[0]) / denominator, -1.0, 1.0);
}

// The slab's faces over compact vertex indices, with a map from each directed edge to its face.
class SurfacePatch {
 public:
  // The faces `which` of `mesh`.
  SurfacePatch(SlabMesh& mesh, const std::vector<int>& which) : mesh_(mesh) {
    faces_.reserve(which.size());
    index_.reserve(which.size());
    for (const int w : which) {
      const Triangle& t = mesh.triangles[static_cast<std::size_t>(w)];
      std::array<int, 3> f{};
      for (int k = 0; k < 3; ++k) f[k] = compact(t[k]);
      faces_.push_back(f);
      roles_.push_back(mesh.roles[static_cast<std::size_t>(w)]);
      origin_.push_back(w);
    }
    original_vertices_ = static_cast<int>(points_.size());
    edges_.reserve(3 * faces_.size());
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      for (int k = 0; k < 3; ++k) {
        if (!edges_.emplace(key(faces_[f][k], faces_[f][(k + 1) % 3]), static_cast<int>(f)).second) valid_ = false;
      }
    }
  }

  // False when a directed edge occurs twice (a slab that is not an oriented surface): nothing is changed.
  [[nodiscard]] bool valid() const { return valid_; }
  [[nodiscard]] std::size_t size() const { return faces_.size(); }
  [[nodiscard]] double sharp(int f) const {
    const auto& t = faces_[static_cast<std::size_t>(f)];
    return sharpness(points_[t[0]], points_[t[1]], points_[t[2]]);
  }

  // The face across edge k of face f (from corner k to corner k + 1), or -1 on the slab's boundary or
  // where the faces' roles differ.
  [[nodiscard]] int across(int f, int k) const {
    const auto& t = faces_[static_cast<std::size_t>(f)];
    const auto it = edges_.find(key(t[(k + 1) % 3], t[k]));
    if (it == edges_.end()) return -1;
    return roles_[static_cast<std::size_t>(it->second)] == roles_[static_cast<std::size_t>(f)] ? it->second : -1;
  }

  // Flips edge k of face f when that raises the two faces' smallest angle and is allowed (see
  // improve_slab_faces); returns by how much the larger sharpness falls (0: no flip; flipped only when `apply`).
  double flip(int f, int k, double max_deviation, bool apply) {
    const int g = across(f, k);
    if (g < 0) return 0.0;
    const auto& tf = faces_[static_cast<std::size_t>(f)];
    const int a = tf[k], b = tf[(k + 1) % 3], c = tf[(k + 2) % 3];
    const int d = third(g, b, a);
    if (c == d || edges_.count(key(c, d)) || edges_.count(key(d, c))) return 0.0;
    const Eigen::Vector3d &A = points_[a], &B = points_[b], &C = points_[c], &D = points_[d];
    // A chord between two vertices the tiler put on one plane would lie in that plane, across a contour.
    if (c < original_vertices_ && d < original_vertices_ && std::abs(C.z() - D.z()) <= 1e-9 * (1.0 + std::abs(C.z())))
      return 0.0;
    const double before = std::max(sharpness(A, B, C), sharpness(B, A, D));
    const double after = std::max(sharpness(C, A, D), sharpness(D, B, C));
    if (!(after < before - 1e-9)) return 0.0;
    // The surface moves by the distance between the old and the new diagonal.
    const Eigen::Vector3d n = (B - A).cross(D - C);
    if (!(n.norm() > 0.0) || std::abs((C - A).dot(n)) > max_deviation * n.norm()) return 0.0;
    // Neither new face may turn over against either old one.
    const Eigen::Vector3d n_f = (B - A).cross(C - A), n_g = (A - B).cross(D - B);
    const Eigen::Vector3d n1 = (A - C).cross(D - C), n2 = (B - D).cross(C - D);
    if (!(n1.dot(n_f) > 0.0 && n1.dot(n_g) > 0.0 && n2.dot(n_f) > 0.0 && n2.dot(n_g) > 0.0)) return 0.0;
    if (apply) {
      unlink(f);
      unlink(g);
      faces_[static_cast<std::size_t>(f)] = {c, a, d};
      faces_[static_cast<std::size_t>(g)] = {d, b, c};
      link(f);
      link(g);
    }
    return before - after;
  }

  // Splits edge k of face f at its midpoint; returns the faces made or changed (empty when the edge is
  // on the boundary).
  std::vector<int> split(int f, int k) {
    const int g = across(f, k);
    if (g < 0) return {};
    const auto tf = faces_[static_cast<std::size_t>(f)];
    const int a = tf[k], b = tf[(k + 1) % 3], c = tf[(k + 2) % 3];
    const int d = third(g, b, a);
    // Neither face may be flat rather than thin (its corner nearly on the edge): the halves would have no area.
    const double ab = (points_[b] - points_[a]).norm();
    for (const int e : {c, d}) {
      if (ab >= kFlatRatio * ((points_[e] - points_[a]).norm() + (points_[b] - points_[e]).norm())) return {};
    }
    const Eigen::Vector3d mid = 0.5 * (points_[a] + points_[b]);
    const VertexRef ref = mesh_.add_vertex(mid.head<2>(), mid.z());
    const int m = static_cast<int>(points_.size());
    points_.push_back(mid);
    refs_.push_back(ref);
    unlink(f);
    unlink(g);
    faces_[static_cast<std::size_t>(f)] = {a, m, c};
    faces_[static_cast<std::size_t>(g)] = {b, m, d};
    const int f2 = static_cast<int>(faces_.size());
    faces_.push_back({m, b, c});
    roles_.push_back(roles_[static_cast<std::size_t>(f)]);
    origin_.push_back(-1);
    const int g2 = static_cast<int>(faces_.size());
    faces_.push_back({m, a, d});
    roles_.push_back(roles_[static_cast<std::size_t>(g)]);
    origin_.push_back(-1);
    for (int h : {f, g, f2, g2}) link(h);
    return {f, g, f2, g2};
  }

  [[nodiscard]] double length(int f, int k) const {
    const auto& t = faces_[static_cast<std::size_t>(f)];
    return (points_[t[(k + 1) % 3]] - points_[t[k]]).norm();
  }

  // Writes the faces back to the slab mesh: changed faces in place, new ones at the end.
  void store() {
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      const Triangle t{refs_[faces_[f][0]], refs_[faces_[f][1]], refs_[faces_[f][2]]};
      if (origin_[f] >= 0) {
        mesh_.triangles[static_cast<std::size_t>(origin_[f])] = t;
      } else {
        mesh_.triangles.push_back(t);
        mesh_.roles.push_back(roles_[f]);
      }
    }
  }

 private:
  static std::uint64_t key(int a, int b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
  }
  int compact(VertexRef v) {
    const auto [it, inserted] = index_.emplace(v, static_cast<int>(points_.size()));
    if (inserted) {
      points_.push_back(mesh_.position(v));
      refs_.push_back(v);
    }
    return it->second;
  }
  [[nodiscard]] int third(int g, int b, int a) const {
    const auto& t = faces_[static_cast<std::size_t>(g)];
    for (int k = 0; k < 3; ++k) {
      if (t[k] != a && t[k] != b) return t[k];
    }
    return t[0];
  }
  void unlink(int f) {
    const auto& t = faces_[static_cast<std::size_t>(f)];
    for (int k = 0; k < 3; ++k) edges_.erase(key(t[k], t[(k + 1) % 3]));
  }
  void link(int f) {
    const auto& t = faces_[static_cast<std::size_t>(f)];
    for (int k = 0; k < 3; ++k) edges_[key(t[k], t[(k + 1) % 3])] = f;
  }

  SlabMesh& mesh_;
  std::unordered_map<VertexRef, int> index_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<VertexRef> refs_;
  std::vector<std::array<int, 3>> faces_;
  std::vector<FaceRole> roles_;
  std::vector<int> origin_;  // the face of the slab mesh, -1 for a face a split added
  std::unordered_map<std::uint64_t, int> edges_;
  int original_vertices_ = 0;
  bool valid_ = true;
};

}  // namespace

SlabRemeshing improve_slab_faces(SlabMesh& mesh, double max_deviation, double min_split_length) {
  SlabRemeshing done;
  std::vector<int> slivers;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (mesh.roles[f] != FaceRole::Cap && is_sliver(mesh.position(t[0]), mesh.position(t[1]), mesh.position(t[2]))) {
      slivers.push_back(static_cast<int>(f));
    }
  }
  if (slivers.empty()) return done;
  // The patch: the faces around the slivers' corners (a fan's faces all share its apex), caps left out
  // (they are planar and triangulated as CapRefinement asks). Its edges to the faces outside stay.
  std::unordered_set<VertexRef> corners;
  corners.reserve(3 * slivers.size());
  for (const int f : slivers) corners.insert(mesh.triangles[static_cast<std::size_t>(f)].begin(),
                                             mesh.triangles[static_cast<std::size_t>(f)].end());
  std::vector<int> which;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (mesh.roles[f] != FaceRole::Cap && (corners.count(t[0]) || corners.count(t[1]) || corners.count(t[2]))) {
      which.push_back(static_cast<int>(f));
    }
  }
  SurfacePatch patch(mesh, which);
  if (!patch.valid()) return done;
  std::deque<int> work;
  for (std::size_t f = 0; f < patch.size(); ++f) {
    if (patch.sharp(static_cast<int>(f)) > kSliverCosine) work.push_back(static_cast<int>(f));
  }
  // Each sliver may be split a few times over (a fan across a wide band needs a row of vertices per few
  // contour spacings); the cap only stops a runaway.
  const std::size_t max_splits = 8 * work.size() + 64;
  while (!work.empty()) {
    const int f = work.front();
    work.pop_front();
    if (!(patch.sharp(f) > kSliverCosine)) continue;
    // The flip that gains most, if any.
    int best_k = -1;
    double best_gain = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double gain = patch.flip(f, k, max_deviation, false);
      if (gain > best_gain) {
        best_gain = gain;
        best_k = k;
      }
    }
    if (best_k >= 0) {
      const int g = patch.across(f, best_k);
      patch.flip(f, best_k, max_deviation, true);
      ++done.flips;
      work.push_back(f);
      work.push_back(g);
      continue;
    }
    if (done.splits >= max_splits) continue;
    // No flip helps: split the longest edge, unless a face on it is flat rather than thin (its longest
    // edge nearly the sum of the others: the split would make two slivers).
    int longest = 0;
    for (int k = 1; k < 3; ++k) {
      if (patch.length(f, k) > patch.length(f, longest)) longest = k;
    }
    if (!(patch.length(f, longest) > min_split_length)) continue;
    const std::vector<int> changed = patch.split(f, longest);
    if (changed.empty()) continue;
    ++done.splits;
    for (int h : changed) work.push_back(h);
  }
  patch.store();
  return done;
}

}  // namespace contourmesh::detail
