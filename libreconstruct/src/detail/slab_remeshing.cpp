// SPDX-License-Identifier: BSD-3-Clause
#include "detail/slab_remeshing.h"

#include "contourmesh/internal/polygon2d.h"
#include "detail/edge_map.h"
#include "detail/face_shape.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <numbers>
#include <vector>

namespace contourmesh::detail {

namespace {

// A face whose longest edge is at least this share of the sum of the other two is flat, not thin.
constexpr double kFlatRatio = 0.97;
// A face whose normal is within 30 degrees of the slice axis (kLevelCosine) lies nearly in the slice
// planes: around it the slab is a height field over the (u, v) plane, where points can be inserted as in
// a plane.
// A point inserted into a sliver makes, with the sliver's shortest edge, a triangle with this angle at
// the new point (the off-centre of Ungor 2004: the circumcentre when that is nearer): 20 degrees, twice
// the angle that makes a sliver.
const double kOffCentreHeight = 0.5 / std::tan(10.0 * std::numbers::pi / 180.0);
// A point is inserted only inside its face, this share of the face's barycentric range from each edge.
constexpr double kMinBarycentric = 0.02;

// Twice the area of a face with normal n (its length) when the face is part of a shelf, else 0.
double shelf_area(const Eigen::Vector3d& n) {
  const double length = n.norm();
  return std::abs(n.z()) >= kShelfCosine * length ? length : 0.0;
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
    sharp_.resize(faces_.size());
    for (std::size_t f = 0; f < faces_.size(); ++f) update_sharp(static_cast<int>(f));
    edges_.reserve(3 * faces_.size());
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      for (int k = 0; k < 3; ++k) {
        if (!edges_.insert(key(faces_[f][k], faces_[f][(k + 1) % 3]), static_cast<int>(f))) valid_ = false;
      }
    }
  }

  // False when a directed edge occurs twice (a slab that is not an oriented surface): nothing is changed.
  [[nodiscard]] bool valid() const { return valid_; }
  [[nodiscard]] std::size_t size() const { return faces_.size(); }
  // sharpness of face f (kept per face: points do not move, and every changed face is linked again).
  [[nodiscard]] double sharp(int f) const { return sharp_[static_cast<std::size_t>(f)]; }

  // The face across edge k of face f (from corner k to corner k + 1), or -1 on the slab's boundary or
  // where the faces' roles differ.
  [[nodiscard]] int across(int f, int k, bool any_role = false) const {
    const auto& t = faces_[static_cast<std::size_t>(f)];
    const int* g = edges_.find(key(t[(k + 1) % 3], t[k]));
    if (g == nullptr) return -1;
    return any_role || roles_[static_cast<std::size_t>(*g)] == roles_[static_cast<std::size_t>(f)] ? *g : -1;
  }

  // +1 or -1 when face f lies nearly in the slice planes (its normal within 30 degrees of +w or -w), else 0.
  [[nodiscard]] int level_side(int f) const {
    const auto& t = faces_[static_cast<std::size_t>(f)];
    return side_of((points_[t[1]] - points_[t[0]]).cross(points_[t[2]] - points_[t[0]]));
  }
  static int side_of(const Eigen::Vector3d& n) {
    const double length = n.norm();
    if (!(length > 0.0)) return 0;
    return n.z() >= kLevelCosine * length ? 1 : n.z() <= -kLevelCosine * length ? -1 : 0;
  }

  // Flips edge k of face f when that raises the two faces' smallest angle and is allowed (see
  // improve_slab_faces); returns by how much the larger sharpness falls (0: no flip; flipped only when `apply`).
  double flip(int f, int k, double max_deviation, bool apply) {
    const int g = across(f, k);
    if (g < 0) return 0.0;
    const auto& tf = faces_[static_cast<std::size_t>(f)];
    const int a = tf[k], b = tf[(k + 1) % 3], c = tf[(k + 2) % 3];
    const int d = third(g, b, a);
    if (c == d) return 0.0;
    const Eigen::Vector3d &A = points_[a], &B = points_[b], &C = points_[c], &D = points_[d];
    // The tests below only turn the flip down; the one that does so most often comes first.
    // sharpness depends on the sorted edge lengths only, so the faces' kept values are those of (A, B, C)
    // and (B, A, D).
    const double before = std::max(sharp(f), sharp(g));
    const double after = std::max(sharpness(C, A, D), sharpness(D, B, C));
    if (!(after < before - 1e-9)) return 0.0;
    if (edges_.contains(key(c, d)) || edges_.contains(key(d, c))) return 0.0;
    const int side_f = level_side(f), side_g = level_side(g);
    // A chord between two vertices the tiler put on one plane would lie in that plane, across a contour;
    // between two vertices without ids (composites, intermediate contours) it may where both faces lie
    // nearly in the slice planes on one side: the chord stays inside the ground the faces cover.
    const bool chord =
        c < original_vertices_ && d < original_vertices_ && std::abs(C.z() - D.z()) <= 1e-9 * (1.0 + std::abs(C.z()));
    if (chord) {
      const bool without_ids =
          is_local(refs_[static_cast<std::size_t>(c)]) && is_local(refs_[static_cast<std::size_t>(d)]);
      if (!without_ids || side_f == 0 || side_g != side_f) return 0.0;
    }
    // The surface moves by the distance between the old and the new diagonal.
    const Eigen::Vector3d n = (B - A).cross(D - C);
    if (!(n.norm() > 0.0) || std::abs((C - A).dot(n)) > max_deviation * n.norm()) return 0.0;
    const Eigen::Vector3d n_f = (B - A).cross(C - A), n_g = (A - B).cross(D - B);
    const Eigen::Vector3d n1 = (A - C).cross(D - C), n2 = (B - D).cross(C - D);
    // No flip may fold the surface (one face nearly in the slice planes facing up next to one facing
    // down) between the new faces or against the faces around them more than it was.
    const int side_1 = side_of(n1), side_2 = side_of(n2);
    if (side_1 != 0 && side_2 == -side_1) return 0.0;
    if (folds_outside(b, c, side_2) + folds_outside(c, a, side_1) + folds_outside(a, d, side_1) +
            folds_outside(d, b, side_2) >
        folds_outside(b, c, side_f) + folds_outside(c, a, side_f) + folds_outside(a, d, side_g) +
            folds_outside(d, b, side_g)) {
      return 0.0;
    }
    // A chord in a plane may not lay more area within 10 degrees of the slice planes (a shelf) than
    // there was.
    if (chord &&
        shelf_area(n1) + shelf_area(n2) > shelf_area(n_f) + shelf_area(n_g) + 1e-12 * (n_f.norm() + n_g.norm())) {
      return 0.0;
    }
    // Neither new face may turn over against either old one.
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

  // 1 when the face beyond the directed edge (u, v) lies nearly in the slice planes on the other side
  // than `side` (a face of that side holding the edge would fold against it), else 0.
  [[nodiscard]] int folds_outside(int u, int v, int side) const {
    if (side == 0) return 0;
    const int* g = edges_.find(key(v, u));
    return g != nullptr && level_side(*g) == -side ? 1 : 0;
  }

  // Splits edge k of face f at its midpoint; returns the faces made or changed (empty when the edge is
  // on the boundary).
  std::vector<int> split(int f, int k, bool any_role = false) {
    const int g = across(f, k, any_role);
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

  // The face that holds point p of the (u, v) plane, walking from face f across faces that lie nearly
  // in the slice planes on f's side; -1 when the walk leaves them (then `blocked` is the face and edge
  // it stopped at) or takes too long.
  int locate(int f, const Eigen::Vector2d& p, std::pair<int, int>& blocked) const {
    const int side = level_side(f);
    blocked = {-1, -1};
    for (int step = 0; step < 512; ++step) {
      const auto& t = faces_[static_cast<std::size_t>(f)];
      int next = -1;
      for (int k = 0; k < 3 && next < 0; ++k) {
        if (side * orient2d(points_[t[k]].head<2>(), points_[t[(k + 1) % 3]].head<2>(), p) >= 0.0) continue;
        const int g = across(f, k);
        if (g < 0 || level_side(g) != side) {
          blocked = {f, k};
          return -1;
        }
        next = g;
      }
      if (next < 0) return f;
      f = next;
    }
    return -1;
  }

  // Inserts the point of face f over p (u, v), on the face's plane (the surface does not move), and
  // returns the three faces around it; empty when p is too near an edge of f.
  std::vector<int> insert(int f, const Eigen::Vector2d& p) {
    const auto t = faces_[static_cast<std::size_t>(f)];
    const Eigen::Vector3d &A = points_[t[0]], &B = points_[t[1]], &C = points_[t[2]];
    const double whole = orient2d(A.head<2>(), B.head<2>(), C.head<2>());
    if (whole == 0.0) return {};
    const double la = orient2d(p, B.head<2>(), C.head<2>()) / whole, lb = orient2d(A.head<2>(), p, C.head<2>()) / whole;
    const double lc = 1.0 - la - lb;
    if (std::min({la, lb, lc}) < kMinBarycentric) return {};
    const Eigen::Vector3d point = la * A + lb * B + lc * C;
    const VertexRef ref = mesh_.add_vertex(point.head<2>(), point.z());
    const int m = static_cast<int>(points_.size());
    points_.push_back(point);
    refs_.push_back(ref);
    unlink(f);
    faces_[static_cast<std::size_t>(f)] = {t[0], t[1], m};
    const int f1 = static_cast<int>(faces_.size());
    faces_.push_back({t[1], t[2], m});
    const int f2 = static_cast<int>(faces_.size());
    faces_.push_back({t[2], t[0], m});
    for (int k = 0; k < 2; ++k) {
      roles_.push_back(roles_[static_cast<std::size_t>(f)]);
      origin_.push_back(-1);
    }
    for (int h : {f, f1, f2}) link(h);
    return {f, f1, f2};
  }

  // The corner of face f that is vertex v (0, 1 or 2), -1 when none is.
  [[nodiscard]] int corner(int f, int v) const {
    const auto& t = faces_[static_cast<std::size_t>(f)];
    for (int k = 0; k < 3; ++k) {
      if (t[k] == v) return k;
    }
    return -1;
  }
  [[nodiscard]] int vertex(int f, int k) const { return faces_[static_cast<std::size_t>(f)][k]; }
  [[nodiscard]] Eigen::Vector2d uv(int v) const { return points_[static_cast<std::size_t>(v)].head<2>(); }

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
  static std::uint64_t key(int a, int b) { return EdgeMap::key(a, b); }
  // The compact index of v, numbered in order of first use. A VertexRef is never -1, EdgeMap's one
  // forbidden key.
  int compact(VertexRef v) {
    const auto k = static_cast<std::uint64_t>(v);
    if (const std::int32_t* i = index_.find(k)) return *i;
    const int i = static_cast<int>(points_.size());
    index_.insert(k, i);
    points_.push_back(mesh_.position(v));
    refs_.push_back(v);
    return i;
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
    for (int k = 0; k < 3; ++k) edges_.assign(key(t[k], t[(k + 1) % 3]), f);
    update_sharp(f);
  }
  void update_sharp(int f) {
    const auto k = static_cast<std::size_t>(f);
    if (k >= sharp_.size()) sharp_.resize(k + 1);
    const auto& t = faces_[k];
    sharp_[k] = sharpness(points_[t[0]], points_[t[1]], points_[t[2]]);
  }

  SlabMesh& mesh_;
  EdgeMap index_;  // VertexRef -> compact index (a flat table: no node per vertex)
  std::vector<Eigen::Vector3d> points_;
  std::vector<VertexRef> refs_;
  std::vector<std::array<int, 3>> faces_;
  std::vector<FaceRole> roles_;
  std::vector<int> origin_;  // the face of the slab mesh, -1 for a face a split added
  EdgeMap edges_;  // directed edge -> the face holding it
  std::vector<double> sharp_;  // per face
  int original_vertices_ = 0;
  bool valid_ = true;
};

// Restores the max-min angle property around vertex m after it was inserted: the edges opposite m are
// flipped while that raises the smaller angle of their two faces.
void settle_around(SurfacePatch& patch, int m, std::vector<int> faces, double max_deviation, std::deque<int>& work) {
  std::size_t budget = 64;
  while (!faces.empty() && budget-- > 0) {
    const int f = faces.back();
    faces.pop_back();
    const int k = patch.corner(f, m);
    if (k < 0) continue;
    const int opposite = (k + 1) % 3;  // the edge from corner k + 1 to corner k + 2
    const int g = patch.across(f, opposite);
    if (g < 0 || !(patch.flip(f, opposite, max_deviation, false) > 0.0)) continue;
    patch.flip(f, opposite, max_deviation, true);
    faces.push_back(f);
    faces.push_back(g);
    work.push_back(f);
    work.push_back(g);
  }
}

// Puts a point into sliver f (lying nearly in the slice planes): on the perpendicular
// bisector of its shortest edge, at its off-centre (or circumcentre when nearer), in the face of the
// level region that holds it. When the point falls outside the region, the edge it leaves by is split
// at its midpoint instead, if that edge may be split and is longer than `min_split_length`. Returns 1
// for an insertion, -1 for a split, 0 when nothing was done.
int insert_into(SurfacePatch& patch, int f, double max_deviation, double min_split_length, std::deque<int>& work) {
  // The shortest edge (p, q) and the corner r opposite it.
  int shortest = 0;
  for (int k = 1; k < 3; ++k) {
    if (patch.length(f, k) < patch.length(f, shortest)) shortest = k;
  }
  const Eigen::Vector2d p = patch.uv(patch.vertex(f, shortest)), q = patch.uv(patch.vertex(f, (shortest + 1) % 3)),
                        r = patch.uv(patch.vertex(f, (shortest + 2) % 3));
  const double edge = (q - p).norm();
  // Edges much shorter than the spacing are not refined further: the fan's apex keeps its angle.
  if (!(edge > 0.25 * min_split_length)) return 0;
  const Eigen::Vector2d middle = 0.5 * (p + q);
  Eigen::Vector2d normal(-(q - p).y(), (q - p).x());
  normal /= normal.norm();
  if (normal.dot(r - middle) < 0.0) normal = -normal;
  // The circumcentre lies on the bisector, at this signed distance from the middle.
  const double d_pr = orient2d(p, q, r);
  if (d_pr == 0.0) return 0;
  const double bc = (r - p).squaredNorm(), ab = (q - p).squaredNorm();
  const Eigen::Vector2d u = q - p, v = r - p;
  const Eigen::Vector2d centre = p + Eigen::Vector2d(v.y() * ab - u.y() * bc, u.x() * bc - v.x() * ab) / (2.0 * d_pr);
  const double to_centre = (centre - middle).dot(normal);
  const double off = kOffCentreHeight * edge;
  const Eigen::Vector2d point = to_centre > 0.0 && to_centre < off ? centre : Eigen::Vector2d(middle + off * normal);
  std::pair<int, int> blocked;
  const int holder = patch.locate(f, point, blocked);
  if (holder >= 0) {
    const std::vector<int> around = patch.insert(holder, point);
    if (around.empty()) return 0;
    const int m = patch.vertex(around.front(), 2);
    for (int h : around) work.push_back(h);
    settle_around(patch, m, around, max_deviation, work);
    return 1;
  }
  if (blocked.first < 0 || !(patch.length(blocked.first, blocked.second) > min_split_length)) return 0;
  // The edge may be a composite's bridge (a Bridge face beyond it): both faces are split, each keeps its role.
  const std::vector<int> changed = patch.split(blocked.first, blocked.second, true);
  for (int h : changed) work.push_back(h);
  return changed.empty() ? 0 : -1;
}

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
  EdgeMap corners(3 * slivers.size());  // the corners as keys (a VertexRef is never -1)
  for (const int f : slivers) {
    for (const VertexRef v : mesh.triangles[static_cast<std::size_t>(f)]) {
      corners.insert(static_cast<std::uint64_t>(v), 0);
    }
  }
  auto corner = [&](VertexRef v) { return corners.contains(static_cast<std::uint64_t>(v)); };
  std::vector<int> which;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (mesh.roles[f] != FaceRole::Cap && (corner(t[0]) || corner(t[1]) || corner(t[2]))) {
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
  // Flips raise the angles and the splits are capped, so the work ends; the steps are capped all the
  // same.
  std::size_t steps = 64 * patch.size() + 1024;
  while (!work.empty() && steps-- > 0) {
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
    if (done.splits + done.insertions >= max_splits) continue;
    // No flip helps. A sliver that lies nearly in the slice planes gets a point inside, where the
    // region allows: its splits would only make smaller copies of a fan.
    if (patch.level_side(f) != 0) {
      const int inserted = insert_into(patch, f, max_deviation, min_split_length, work);
      if (inserted > 0) {
        ++done.insertions;
        continue;
      }
      if (inserted < 0) {
        ++done.splits;
        continue;
      }
    }
    // Split the longest edge, unless a face on it is flat rather than thin (its longest
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
