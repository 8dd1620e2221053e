// SPDX-License-Identifier: BSD-3-Clause
// Mesh validation: every problem reported by kind and index, so a user can find it in their data.
#pragma once

#include "contourmesh/smooth/mesh.h"

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
/// One line naming the problem and its indices, e.g. "non-manifold edge between vertices 12 and 40 (more
/// than two triangles)".
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

/// Whether repair_mesh merges vertices.
enum class VertexMerging {
  Off,
  /// Vertices at exactly the same position (and with the same contour ids) become one: the usual fix
  /// for a file that stores a triangle soup or splits vertices along seams.
  Coincident,
};

struct RepairOptions {
  VertexMerging merging = VertexMerging::Coincident;
};

/// What repair_mesh changed.
struct MeshRepair {
  Index merged_vertices = 0;     ///< vertices merged into an earlier vertex at the same position
  Index dropped_degenerate = 0;  ///< triangles with a repeated vertex index (after merging)
  Index dropped_duplicates = 0;  ///< triangles on the same three vertices as an earlier one, either orientation
  /// When vertices were merged: the new index of every input vertex (merged ones share one); empty
  /// when none was, so that the indices are unchanged.
  std::vector<Index> vertex_map;
  [[nodiscard]] bool changed() const { return merged_vertices + dropped_degenerate + dropped_duplicates > 0; }
  /// One line, e.g. "merged 12 coincident vertices, dropped 3 triangles with a repeated vertex and 1
  /// duplicate triangle"; empty when nothing changed.
  [[nodiscard]] std::string describe() const;
};

/// Repairs what can be repaired without changing the surface: merges coincident vertices (optional),
/// then drops triangles with a repeated vertex index (zero area by construction) and repeated
/// triangles, keeping the first of each set. Vertices keep their order (merged ones are removed, the
/// others shift down); triangles with three distinct vertices but zero area are kept, since dropping
/// them would open a hole. Throws InvalidInputError for indices out of range; non-finite vertices are
/// never merged.
MeshRepair repair_mesh(Mesh& mesh, const RepairOptions& options = {});

}  // namespace contourmesh
