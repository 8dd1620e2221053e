// Mesh validation: every problem reported by kind and index, so a user can find it in their data.
#pragma once

#include "smooth/mesh.h"

#include <string>
#include <vector>

namespace contourmesh {

enum class MeshProblemKind {
  NonFiniteCoordinate,   ///< `index` = vertex with a NaN or Inf coordinate
  IndexOutOfRange,       ///< `index` = triangle referencing a vertex outside [0, n)
  DegenerateTriangle,    ///< `index` = triangle with a repeated vertex or (near) zero area
  DuplicateTriangle,     ///< `index` = triangle using the same three vertices as triangle `other`
  NonManifoldEdge,       ///< `index`, `other` = edge endpoints shared by more than two triangles
  NonManifoldVertex,     ///< `index` = vertex whose incident triangles form more than one fan
  IdSizeMismatch,        ///< contour-id arrays exist but do not hold one entry per vertex
};

struct MeshProblem {
  MeshProblemKind kind;
  Index index = -1;
  Index other = -1;
};

/// Short stable name of a problem kind ("non-manifold edge", ...).
[[nodiscard]] const char* to_string(MeshProblemKind kind);
/// One line naming the problem and its indices, e.g. "non-manifold edge (12, 40)".
[[nodiscard]] std::string describe(const MeshProblem& problem);

struct ValidationOptions {
  /// A triangle counts as degenerate when its area is below `relative_area_epsilon` times the squared
  /// mean edge length of the mesh (scale-free). 0 flags only exactly repeated vertices or zero area.
  double relative_area_epsilon = 1e-12;
  /// Stop collecting after this many problems (the count is still exact up to the limit).
  std::size_t max_problems = 1000;
};

/// Lists every problem of the mesh (up to `max_problems`), never throws for a bad mesh.
/// Index errors short-circuit the topological checks, which would be meaningless.
[[nodiscard]] std::vector<MeshProblem> find_mesh_problems(const Mesh& mesh, const ValidationOptions& options = {});

/// Throws if `find_mesh_problems` finds anything: InvalidInputError for non-finite coordinates, indices
/// out of range and id-size mismatches; TopologyError for degenerate, duplicate and non-manifold
/// elements. The message names the first few problems with their indices and the total count.
void validate_mesh(const Mesh& mesh, const ValidationOptions& options = {});

}  // namespace contourmesh
