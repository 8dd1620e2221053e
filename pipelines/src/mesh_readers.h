// SPDX-License-Identifier: BSD-3-Clause
// Private: strict STL and OBJ parsers. VTK's readers accept a truncated binary STL without a word
// (they read until the end of the file) and turn an OBJ coordinate "nan" into 0, so these formats are
// parsed here, with errors that say where the file is wrong. Messages omit the file name (read_mesh
// adds it).
#pragma once

#include <contourmesh/smooth/mesh.h>

#include <string>

namespace contourmesh::detail {

/// Binary or ASCII STL. Binary when the size is 84 + 50 x the header's triangle count (or the file
/// does not start with "solid"); a header count of zero or below the data is corrected as VTK does,
/// one above it is a truncated file. Bit-identical corners are merged into shared vertices; triangles
/// are kept as stored (repeated corners included). Throws InvalidInputError for truncation, a parse
/// error (with the line), or a non-finite coordinate (with the triangle and corner); LimitError when
/// the merged vertices exceed `max_vertices`.
[[nodiscard]] Mesh read_stl(const std::string& bytes, Index max_vertices);

/// Wavefront OBJ: `v x y z [...]` and `f a b c ...` (corners `i`, `i/t`, `i//n`, `i/t/n`, negative =
/// relative); polygons are fan-triangulated, other statements ignored. Throws InvalidInputError naming
/// the line for binary data, a malformed or non-finite number, index 0, or an index beyond the
/// vertices; LimitError when the vertices exceed `max_vertices`.
[[nodiscard]] Mesh read_obj(const std::string& bytes, Index max_vertices);

}  // namespace contourmesh::detail
