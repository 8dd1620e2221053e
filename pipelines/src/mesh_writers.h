// SPDX-License-Identifier: BSD-3-Clause
// Private: STL and OBJ writers. VTK's OBJ writer does not check its stream (a full disk gave a
// truncated file and success) and its STL writer turns coordinates beyond float range into inf, so
// these formats are written here, every write checked. Messages omit the file name (write_mesh adds it).
#pragma once

#include <contourmesh/smooth/mesh.h>

#include <filesystem>

namespace contourmesh::detail {

/// Binary (80-byte header, count, 50 bytes per triangle) or ASCII STL: 32-bit float coordinates and
/// facet normals. Throws InvalidInputError naming the vertex when a coordinate lies beyond the float
/// range (|x| > 3.4e38: STL cannot hold it), or when a write fails (disk full, file size limit).
void write_stl(const std::filesystem::path& file, const Mesh& mesh, bool binary);

/// Wavefront OBJ: `v x y z` with the shortest text that reads back to the same double, then `f a b c`
/// (1-based). Throws InvalidInputError when a write fails.
void write_obj(const std::filesystem::path& file, const Mesh& mesh);

}  // namespace contourmesh::detail
