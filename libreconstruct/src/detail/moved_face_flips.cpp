// SPDX-License-Identifier: BSD-3-Clause
#include "detail/moved_face_flips.h"

#include "detail/edge_map.h"
#include "detail/face_shape.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <utility>

namespace contourmesh::detail {

namespace {

class Flipper {
 public:
  // Only faces marked `inner` are flipped; the edge map covers `faces`, which must hold every face that
  // shares an edge with an inner one.
  Flipper(Mesh& mesh, const std::vector<FaceRole>& roles, const Eigen::Vector3d& axis, double max_deviation,
          const std::vector<Index>& faces, std::vector<std::uint8_t> inner)
      : mesh_(mesh), roles_(roles), axis_(axis), max_deviation_(max_deviation), inner_(std::move(inner)) {
    edges_.reserve(3 * faces.size());
    for (const Index f : faces) link(f);
  }

  [[nodiscard]] bool sliver(Index f) const {
    const Triangle& t = face(f);
    return roles_[static_cast<std::size_t>(f)] != FaceRole::Cap && sharpness(p(t[0]), p(t[1]), p(t[2])) > kSliverCosine;
  }

  // The face across edge k of face f (corner k to k + 1), -1 when none.
  [[nodiscard]] Index across(Index f, int k) const {
    const Triangle& t = face(f);
    const Index* g = edges_.find(key(t[(k + 1) % 3], t[k]));
    return g == nullptr ? -1 : *g;
  }

  // The gain of flipping edge k of face f (0 when not allowed); flips when `apply`.
  double flip(Index f, int k, bool apply) {
    const Index g = across(f, k);
    if (g < 0 || !inner_[static_cast<std::size_t>(f)] || !inner_[static_cast<std::size_t>(g)] ||
        roles_[static_cast<std::size_t>(g)] != roles_[static_cast<std::size_t>(f)] ||
        roles_[static_cast<std::size_t>(f)] == FaceRole::Cap) {
      return 0.0;
    }
    const Triangle tf = face(f);
    const Index a = tf[k], b = tf[(k + 1) % 3], c = tf[(k + 2) % 3];
    Index d = -1;
    for (const Index v : face(g)) {
      if (v != a && v != b) d = v;
    }
    if (d < 0 || c == d || edges_.contains(key(c, d)) || edges_.contains(key(d, c))) return 0.0;
    if (same_contour(a, b) || same_contour(c, d)) return 0.0;
    const Eigen::Vector3d &A = p(a), &B = p(b), &C = p(c), &D = p(d);
    const double before = std::max(sharpness(A, B, C), sharpness(B, A, D));
    const double after = std::max(sharpness(C, A, D), sharpness(D, B, C));
    if (!(after < before - 1e-9)) return 0.0;
    const Eigen::Vector3d n = (B - A).cross(D - C);
    if (!(n.norm() > 0.0) || std::abs((C - A).dot(n)) > max_deviation_ * n.norm()) return 0.0;
    const Eigen::Vector3d n_f = (B - A).cross(C - A), n_g = (A - B).cross(D - B);
    const Eigen::Vector3d n1 = (A - C).cross(D - C), n2 = (B - D).cross(C - D);
    if (!(n1.dot(n_f) > 0.0 && n1.dot(n_g) > 0.0 && n2.dot(n_f) > 0.0 && n2.dot(n_g) > 0.0)) return 0.0;
    const int side_f = side_of(n_f), side_g = side_of(n_g), side_1 = side_of(n1), side_2 = side_of(n2);
    if (side_1 != 0 && side_2 == -side_1) return 0.0;
    if (folds(b, c, side_2) + folds(c, a, side_1) + folds(a, d, side_1) + folds(d, b, side_2) >
        folds(b, c, side_f) + folds(c, a, side_f) + folds(a, d, side_g) + folds(d, b, side_g)) {
      return 0.0;
    }
    if (shelf(n1) + shelf(n2) > shelf(n_f) + shelf(n_g) + 1e-12 * (n_f.norm() + n_g.norm())) return 0.0;
    if (apply) {
      unlink(f);
      unlink(g);
      mesh_.triangles[static_cast<std::size_t>(f)] = {c, a, d};
      mesh_.triangles[static_cast<std::size_t>(g)] = {d, b, c};
      link(f);
      link(g);
    }
    return before - after;
  }

 private:
  static std::uint64_t key(Index a, Index b) { return EdgeMap::key(a, b); }
  [[nodiscard]] const Triangle& face(Index f) const { return mesh_.triangles[static_cast<std::size_t>(f)]; }
  [[nodiscard]] Eigen::Vector3d p(Index v) const { return mesh_.positions.col(v); }
  // Two vertices of one slice contour: an edge between them is the contour's or a chord in its plane.
  [[nodiscard]] bool same_contour(Index u, Index v) const {
    const auto su = mesh_.slice_ids[static_cast<std::size_t>(u)], sv = mesh_.slice_ids[static_cast<std::size_t>(v)];
    return su >= 0 && su == sv;
  }
  [[nodiscard]] int side_of(const Eigen::Vector3d& n) const {
    const double length = n.norm(), z = n.dot(axis_);
    if (!(length > 0.0)) return 0;
    return z >= kLevelCosine * length ? 1 : z <= -kLevelCosine * length ? -1 : 0;
  }
  [[nodiscard]] double shelf(const Eigen::Vector3d& n) const {
    const double length = n.norm();
    return std::abs(n.dot(axis_)) >= kShelfCosine * length ? length : 0.0;
  }
  // 1 when the face beyond the directed edge (u, v) lies within 30 degrees of the slice planes on the
  // other side than `side`.
  [[nodiscard]] int folds(Index u, Index v, int side) const {
    if (side == 0) return 0;
    const Index* g = edges_.find(key(v, u));
    if (g == nullptr) return 0;
    const Triangle& t = face(*g);
    return side_of((p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0]))) == -side ? 1 : 0;
  }
  void unlink(Index f) {
    const Triangle& t = face(f);
    for (int k = 0; k < 3; ++k) edges_.erase(key(t[k], t[(k + 1) % 3]));
  }
  void link(Index f) {
    const Triangle& t = face(f);
    for (int k = 0; k < 3; ++k) edges_.assign(key(t[k], t[(k + 1) % 3]), f);
  }

  Mesh& mesh_;
  const std::vector<FaceRole>& roles_;
  Eigen::Vector3d axis_;
  double max_deviation_;
  std::vector<std::uint8_t> inner_;
  EdgeMap edges_;  // directed edge -> the face holding it
};

}  // namespace

std::size_t flip_moved_slivers(Mesh& mesh, const std::vector<FaceRole>& roles, const Eigen::Vector3d& axis,
                               double max_deviation) {
  // Without ids the contour edges are unknown: nothing may be flipped.
  if (!mesh.has_contour_ids() || roles.size() != mesh.triangles.size()) return 0;
  std::deque<Index> work;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (roles[f] != FaceRole::Cap &&
        sharpness(mesh.positions.col(t[0]), mesh.positions.col(t[1]), mesh.positions.col(t[2])) > kSliverCosine) {
      work.push_back(static_cast<Index>(f));
    }
  }
  if (work.empty()) return 0;
  // Inner faces share a corner with a sliver (a fan's faces share its apex); the edge map also holds the
  // faces around them, for the fold test.
  const std::size_t n = static_cast<std::size_t>(mesh.num_vertices());
  std::vector<std::uint8_t> corner(n, 0), ring(n, 0), inner(mesh.triangles.size(), 0);
  for (const Index f : work) {
    for (const Index v : mesh.triangles[static_cast<std::size_t>(f)]) corner[static_cast<std::size_t>(v)] = 1;
  }
  auto touches = [&mesh](std::size_t f, const std::vector<std::uint8_t>& mark) {
    const Triangle& t = mesh.triangles[f];
    return mark[static_cast<std::size_t>(t[0])] || mark[static_cast<std::size_t>(t[1])] ||
           mark[static_cast<std::size_t>(t[2])];
  };
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    if (!touches(f, corner)) continue;
    inner[f] = 1;
    for (const Index v : mesh.triangles[f]) ring[static_cast<std::size_t>(v)] = 1;
  }
  std::vector<Index> faces;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    if (touches(f, ring)) faces.push_back(static_cast<Index>(f));
  }
  Flipper flipper(mesh, roles, axis, max_deviation, faces, std::move(inner));
  std::size_t flips = 0;
  // Every flip raises the smaller angle of its pair, so the work ends; the steps are capped all the same.
  std::size_t steps = 16 * work.size() + 1024;
  while (!work.empty() && steps-- > 0) {
    const Index f = work.front();
    work.pop_front();
    if (!flipper.sliver(f)) continue;
    int best_k = -1;
    double best_gain = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double gain = flipper.flip(f, k, false);
      if (gain > best_gain) {
        best_gain = gain;
        best_k = k;
      }
    }
    if (best_k < 0) continue;
    const Index g = flipper.across(f, best_k);
    flipper.flip(f, best_k, true);
    ++flips;
    work.push_back(f);
    work.push_back(g);
  }
  return flips;
}

}  // namespace contourmesh::detail
