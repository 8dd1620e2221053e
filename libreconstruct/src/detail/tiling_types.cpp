// SPDX-License-Identifier: BSD-3-Clause
#include "detail/tiling_types.h"

#include "detail/face_shape.h"

#include "contourmesh/reconstruct/contours.h"

#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/mesh_quality.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace contourmesh::detail {

double LevelContour::spacing() const {
  return points.empty() ? 0.0 : perimeter(points) / static_cast<double>(points.size());
}

void finish_contour(LevelContour& c) {
  c.area = std::abs(signed_area(c.points));
  c.box = Eigen::AlignedBox2d();
  for (const Eigen::Vector2d& p : c.points) c.box.extend(p);
}

std::vector<int> positions_in(const std::vector<int>& which, std::size_t size) {
  std::vector<int> to(size, -1);
  for (std::size_t k = 0; k < which.size(); ++k) to[static_cast<std::size_t>(which[k])] = static_cast<int>(k);
  return to;
}

Level restrict_level(const Level& level, const std::vector<int>& which) {
  Level out;
  out.w = level.w;
  const std::vector<int> renumber = positions_in(which, level.contours.size());
  for (int c : which) {
    LevelContour copy = level.contours[static_cast<std::size_t>(c)];
    copy.parent = copy.parent >= 0 ? renumber[static_cast<std::size_t>(copy.parent)] : -1;
    out.contours.push_back(std::move(copy));
  }
  return out;
}

VertexRef SlabMesh::add_vertex(const Eigen::Vector2d& uv, double w) {
  if (first_local_ + vertices.size() >= static_cast<std::size_t>(vertex_budget)) {
    throw LimitError("tiling: the mesh would have more than " + std::to_string(vertex_limit) + " vertices");
  }
  vertices.emplace_back(uv.x(), uv.y(), w);
  return local_ref(first_local_ + vertices.size() - 1);
}

Eigen::Vector3d SlabMesh::position(VertexRef v) const {
  if (!is_local(v)) return (*stack_vertices)[static_cast<std::size_t>(v)];
  const std::size_t k = local_index(v);
  return k >= first_local_ ? vertices[k - first_local_] : parent_->position(v);
}

SlabMesh SlabMesh::scratch() const {
  SlabMesh child;
  child.stack_vertices = stack_vertices;
  child.vertex_budget = vertex_budget;
  child.vertex_limit = vertex_limit;
  child.shear = shear;
  child.first_local_ = first_local_ + vertices.size();
  child.parent_ = this;
  return child;
}

void SlabMesh::absorb(SlabMesh&& child) {
  vertices.insert(vertices.end(), child.vertices.begin(), child.vertices.end());
  triangles.insert(triangles.end(), child.triangles.begin(), child.triangles.end());
  roles.insert(roles.end(), child.roles.begin(), child.roles.end());
  stats += child.stats;
}

namespace {

const double kSliverCosineSquared = kSliverCosine * kSliverCosine;

// is_sliver from the triangle's edges ab = b - a, bc = c - b, ca = a - c and their squared lengths.
bool sliver_of_edges(const Eigen::Vector3d& ab, const Eigen::Vector3d& bc, const Eigen::Vector3d& ca, double lab,
                     double lbc, double lca) {
  // The smallest angle is opposite the shortest edge; it is under 10 degrees when its cosine, from the
  // other two edges, exceeds cos 10 degrees. Degenerate triangles are slivers.
  double d, uu, vv;  // the two edges leaving the corner opposite the shortest edge: their dot product and lengths
  if (lab <= lbc && lab <= lca) {
    d = -bc.dot(ca);  // corner c: c -> b and c -> a
    uu = lbc;
    vv = lca;
  } else if (lbc <= lca) {
    d = -ca.dot(ab);  // corner a: a -> c and a -> b
    uu = lca;
    vv = lab;
  } else {
    d = -ab.dot(bc);  // corner b: b -> a and b -> c
    uu = lab;
    vv = lbc;
  }
  if (uu == 0.0 || vv == 0.0) return true;
  return d > 0.0 && d * d > kSliverCosineSquared * uu * vv;
}

}  // namespace

bool is_sliver(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, bc = c - b, ca = a - c;
  return sliver_of_edges(ab, bc, ca, ab.squaredNorm(), bc.squaredNorm(), ca.squaredNorm());
}

TilingDefects measure_defects(const SlabMesh& mesh) {
  TilingDefects d;
  measure_more_defects(mesh, 0, d);
  return d;
}

void measure_more_defects(const SlabMesh& mesh, std::size_t first_face, TilingDefects& d) {
  double longest2 = 0.0;  // the longest edge's squared length: its root is the longest length
  for (std::size_t f = first_face; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    const Eigen::Vector3d a = mesh.judged_position(t[0]), b = mesh.judged_position(t[1]),
                          c = mesh.judged_position(t[2]);
    const Eigen::Vector3d ab = b - a, bc = c - b, ca = a - c;
    const double lab = ab.squaredNorm(), lbc = bc.squaredNorm(), lca = ca.squaredNorm();
    longest2 = std::max({longest2, lab, lbc, lca});
    const Eigen::Vector3d n = ab.cross(c - a);
    const double twice = n.norm();
    if (twice == 0.0) continue;
    const double area = 0.5 * twice;
    d.area += area;
    const bool flat = mesh.roles[f] != FaceRole::Cap && std::abs(n.z()) >= kShelfCosine * twice;
    const bool sliver = sliver_of_edges(ab, bc, ca, lab, lbc, lca);
    if (flat) d.flat_area += area;
    if (sliver) d.sliver_area += area;
    if (flat || sliver) d.poor_area += area;
    if (mesh.roles[f] == FaceRole::Bridge) d.bridge_area += area;
  }
  d.longest_edge = std::max(d.longest_edge, std::sqrt(longest2));
}

}  // namespace contourmesh::detail
