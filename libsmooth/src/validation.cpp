// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/validation.h"

#include "contourmesh/smooth/adjacency.h"
#include "contourmesh/smooth/errors.h"

#include "contourmesh/internal/union_find.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

namespace contourmesh {

const char* to_string(MeshProblemKind kind) {
  switch (kind) {
    case MeshProblemKind::NonFiniteCoordinate: return "non-finite coordinate";
    case MeshProblemKind::IndexOutOfRange: return "triangle index out of range";
    case MeshProblemKind::DegenerateTriangle: return "degenerate triangle";
    case MeshProblemKind::DuplicateTriangle: return "duplicate triangle";
    case MeshProblemKind::NonManifoldEdge: return "non-manifold edge";
    case MeshProblemKind::NonManifoldVertex: return "non-manifold vertex";
    case MeshProblemKind::IdSizeMismatch: return "contour-id array size mismatch";
  }
  return "unknown problem";
}

std::string describe(const MeshProblem& p) {
  std::ostringstream out;
  out << to_string(p.kind);
  switch (p.kind) {
    case MeshProblemKind::NonFiniteCoordinate: out << " at vertex " << p.index; break;
    case MeshProblemKind::NonManifoldVertex: out << " " << p.index << " (its triangles form separate fans)"; break;
    case MeshProblemKind::IndexOutOfRange: out << " at triangle " << p.index; break;
    case MeshProblemKind::DegenerateTriangle: out << " " << p.index << " (zero area)"; break;
    case MeshProblemKind::DuplicateTriangle: out << ": triangle " << p.index << " repeats triangle " << p.other; break;
    case MeshProblemKind::NonManifoldEdge:
      out << " between vertices " << p.index << " and " << p.other << " (more than two triangles)";
      break;
    case MeshProblemKind::IdSizeMismatch: out << " (" << p.index << " ids for " << p.other << " vertices)"; break;
  }
  return out.str();
}

namespace {

class ProblemList {
 public:
  explicit ProblemList(std::size_t limit) : limit_(limit) {}
  bool add(MeshProblemKind kind, Index index, Index other = -1) {
    if (problems_.size() >= limit_) return false;
    problems_.push_back({kind, index, other});
    return true;
  }
  [[nodiscard]] bool full() const { return problems_.size() >= limit_; }
  std::vector<MeshProblem> take() { return std::move(problems_); }

 private:
  std::size_t limit_;
  std::vector<MeshProblem> problems_;
};

// Number of connected fans formed by the faces around vertex v (1 for a manifold vertex).
// Two incident faces are connected when they share an edge through v.
int count_fans(const Mesh& mesh, const MeshAdjacency& adj, Index v, detail::UnionFind<Index>& fans_of) {
  const auto faces = adj.incident_faces(v);
  const auto k = static_cast<Index>(faces.size());
  fans_of.reset(faces.size());
  for (Index a = 0; a < k; ++a) {
    const Triangle& ta = mesh.triangles[faces[a]];
    for (Index b = a + 1; b < k; ++b) {
      const Triangle& tb = mesh.triangles[faces[b]];
      // Shared vertices other than v.
      for (Index x : ta) {
        if (x == v) continue;
        if (std::find(tb.begin(), tb.end(), x) != tb.end()) {
          fans_of.unite(a, b);
          break;
        }
      }
    }
  }
  int fans = 0;
  for (Index a = 0; a < k; ++a) fans += (fans_of.find(a) == a) ? 1 : 0;
  return fans;
}

}  // namespace

std::vector<MeshProblem> find_mesh_problems(const Mesh& mesh, const ValidationOptions& options) {
  ProblemList problems(options.max_problems);
  const Index n = mesh.num_vertices();
  const Index nf = mesh.num_faces();

  if (!mesh.slice_ids.empty() || !mesh.contour_ids.empty()) {
    if (mesh.slice_ids.size() != static_cast<std::size_t>(n)) {
      problems.add(MeshProblemKind::IdSizeMismatch, static_cast<Index>(mesh.slice_ids.size()), n);
    } else if (mesh.contour_ids.size() != static_cast<std::size_t>(n)) {
      problems.add(MeshProblemKind::IdSizeMismatch, static_cast<Index>(mesh.contour_ids.size()), n);
    }
  }
  for (Index i = 0; i < n; ++i) {
    if (!mesh.positions.col(i).allFinite()) problems.add(MeshProblemKind::NonFiniteCoordinate, i);
  }
  bool indices_ok = true;
  for (Index f = 0; f < nf; ++f) {
    for (Index v : mesh.triangles[f]) {
      if (v < 0 || v >= n) {
        problems.add(MeshProblemKind::IndexOutOfRange, f);
        indices_ok = false;
        break;
      }
    }
  }
  if (!indices_ok) return problems.take();

  // Degenerate triangles, relative to the mean edge length.
  double edge_sum = 0.0;
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) edge_sum += (mesh.positions.col(t[k]) - mesh.positions.col(t[(k + 1) % 3])).norm();
  }
  const double mean_edge = nf > 0 ? edge_sum / (3.0 * nf) : 0.0;
  const double area_floor = options.relative_area_epsilon * mean_edge * mean_edge;
  for (Index f = 0; f < nf; ++f) {
    const Triangle& t = mesh.triangles[f];
    bool bad = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if (!bad) {
      const Eigen::Vector3d e1 = mesh.positions.col(t[1]) - mesh.positions.col(t[0]);
      const Eigen::Vector3d e2 = mesh.positions.col(t[2]) - mesh.positions.col(t[0]);
      const double area = 0.5 * e1.cross(e2).norm();
      bad = !(area > area_floor);  // also catches NaN
    }
    if (bad) problems.add(MeshProblemKind::DegenerateTriangle, f);
  }

  // Duplicate triangles: same vertex set, whatever the order.
  {
    std::vector<std::pair<Triangle, Index>> keyed(static_cast<std::size_t>(nf));
    for (Index f = 0; f < nf; ++f) {
      Triangle t = mesh.triangles[f];
      std::sort(t.begin(), t.end());
      keyed[f] = {t, f};
    }
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t k = 1; k < keyed.size(); ++k) {
      if (keyed[k].first == keyed[k - 1].first) {
        problems.add(MeshProblemKind::DuplicateTriangle, keyed[k].second, keyed[k - 1].second);
      }
    }
  }

  const MeshAdjacency adj = build_adjacency(mesh);
  for (Index i = 0; i < n && !problems.full(); ++i) {
    for (Index k = adj.neighbor_offsets[i]; k < adj.neighbor_offsets[i + 1]; ++k) {
      const Index j = adj.neighbors[k];
      if (j > i && adj.edge_face_count[k] > 2) problems.add(MeshProblemKind::NonManifoldEdge, i, j);
    }
  }
  detail::UnionFind<Index> scratch;
  for (Index i = 0; i < n && !problems.full(); ++i) {
    if (adj.valence(i) > 0 && count_fans(mesh, adj, i, scratch) > 1) {
      problems.add(MeshProblemKind::NonManifoldVertex, i);
    }
  }
  return problems.take();
}

void validate_mesh(const Mesh& mesh, const ValidationOptions& options) {
  const std::vector<MeshProblem> problems = find_mesh_problems(mesh, options);
  if (problems.empty()) return;
  std::ostringstream msg;
  msg << problems.size() << (problems.size() >= options.max_problems ? "+" : "") << " mesh problem"
      << (problems.size() == 1 ? "" : "s") << ": ";
  const std::size_t shown = std::min<std::size_t>(problems.size(), 5);
  for (std::size_t k = 0; k < shown; ++k) msg << (k ? "; " : "") << describe(problems[k]);
  if (shown < problems.size()) msg << "; ...";
  bool input_error = false;
  for (const MeshProblem& p : problems) {
    input_error = input_error || p.kind == MeshProblemKind::NonFiniteCoordinate ||
                  p.kind == MeshProblemKind::IndexOutOfRange || p.kind == MeshProblemKind::IdSizeMismatch;
  }
  if (input_error) throw InvalidInputError(msg.str());
  throw TopologyError(msg.str());
}

std::string MeshRepair::describe() const {
  std::vector<std::string> parts;
  auto plural = [](Index n, const std::string& one, const std::string& many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
  };
  if (merged_vertices) parts.push_back("merged " + plural(merged_vertices, "coincident vertex", "coincident vertices"));
  if (dropped_degenerate) {
    parts.push_back("dropped " + plural(dropped_degenerate, "triangle", "triangles") + " with a repeated vertex");
  }
  if (dropped_duplicates) {
    parts.push_back((dropped_degenerate ? "" : "dropped ") +
                    plural(dropped_duplicates, "duplicate triangle", "duplicate triangles"));
  }
  std::string out;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    out += (k == 0 ? "" : k + 1 == parts.size() ? " and " : ", ") + parts[k];
  }
  return out;
}

MeshRepair repair_mesh(Mesh& mesh, const RepairOptions& options) {
  const Index n = mesh.num_vertices();
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (Index v : mesh.triangles[f]) {
      if (v < 0 || v >= n) {
        throw InvalidInputError("triangle " + std::to_string(f) + " references vertex " + std::to_string(v) +
                                " but the mesh has " + std::to_string(n) + " vertices");
      }
    }
  }
  MeshRepair report;
  const bool ids = mesh.has_contour_ids();

  if (options.merging == VertexMerging::Coincident && n > 1) {
    // Sort the finite vertices by (x, y, z, ids); equal runs merge into their smallest index.
    std::vector<Index> order;
    order.reserve(static_cast<std::size_t>(n));
    for (Index i = 0; i < n; ++i) {
      if (mesh.positions.col(i).allFinite()) order.push_back(i);
    }
    auto key_less = [&](Index a, Index b) {
      for (int k = 0; k < 3; ++k) {
        if (mesh.positions(k, a) != mesh.positions(k, b)) return mesh.positions(k, a) < mesh.positions(k, b);
      }
      if (ids && mesh.slice_ids[a] != mesh.slice_ids[b]) return mesh.slice_ids[a] < mesh.slice_ids[b];
      if (ids && mesh.contour_ids[a] != mesh.contour_ids[b]) return mesh.contour_ids[a] < mesh.contour_ids[b];
      return a < b;
    };
    auto same = [&](Index a, Index b) {
      return mesh.positions.col(a) == mesh.positions.col(b) &&
             (!ids || (mesh.slice_ids[a] == mesh.slice_ids[b] && mesh.contour_ids[a] == mesh.contour_ids[b]));
    };
    std::sort(order.begin(), order.end(), key_less);
    std::vector<Index> representative(static_cast<std::size_t>(n));
    for (Index i = 0; i < n; ++i) representative[i] = i;
    for (std::size_t k = 1; k < order.size(); ++k) {
      if (same(order[k], order[k - 1])) representative[order[k]] = representative[order[k - 1]];
    }
    std::vector<Index> new_index(static_cast<std::size_t>(n), -1);
    Index kept = 0;
    for (Index i = 0; i < n; ++i) {
      if (representative[i] == i) new_index[i] = kept++;
    }
    if (kept < n) {
      report.merged_vertices = n - kept;
      Mesh merged;
      merged.positions.resize(3, kept);
      for (Index i = 0; i < n; ++i) {
        if (new_index[i] < 0) continue;
        merged.positions.col(new_index[i]) = mesh.positions.col(i);
        if (ids) {
          merged.slice_ids.push_back(mesh.slice_ids[i]);
          merged.contour_ids.push_back(mesh.contour_ids[i]);
        }
      }
      merged.triangles = std::move(mesh.triangles);
      for (Triangle& t : merged.triangles) {
        for (Index& v : t) v = new_index[representative[v]];
      }
      mesh = std::move(merged);
      report.vertex_map.resize(static_cast<std::size_t>(n));
      for (Index i = 0; i < n; ++i) report.vertex_map[i] = new_index[representative[i]];
    }
  }

  // Triangles with a repeated vertex, then repeats of a vertex set (first occurrence kept).
  const Index nf = mesh.num_faces();
  std::vector<std::uint8_t> drop(static_cast<std::size_t>(nf), 0);
  std::vector<std::pair<Triangle, Index>> keyed;
  keyed.reserve(static_cast<std::size_t>(nf));
  for (Index f = 0; f < nf; ++f) {
    Triangle t = mesh.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      drop[f] = 1;
      ++report.dropped_degenerate;
      continue;
    }
    std::sort(t.begin(), t.end());
    keyed.emplace_back(t, f);
  }
  std::sort(keyed.begin(), keyed.end());
  for (std::size_t k = 1; k < keyed.size(); ++k) {
    if (keyed[k].first == keyed[k - 1].first) {
      drop[keyed[k].second] = 1;
      ++report.dropped_duplicates;
    }
  }
  if (report.dropped_degenerate + report.dropped_duplicates > 0) {
    std::vector<Triangle> kept;
    kept.reserve(static_cast<std::size_t>(nf));
    for (Index f = 0; f < nf; ++f) {
      if (!drop[f]) kept.push_back(mesh.triangles[f]);
    }
    mesh.triangles = std::move(kept);
  }
  return report;
}

}  // namespace contourmesh
