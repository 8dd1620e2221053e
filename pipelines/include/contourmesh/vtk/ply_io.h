// SPDX-License-Identifier: BSD-3-Clause
// PLY codec that keeps per-vertex contour ids as integer vertex properties. VTK's vtkPLYWriter writes
// only colours, so the ids would be lost; this small codec reads ASCII and binary (both endians) PLY
// with any scalar types and writes binary little-endian.
#pragma once

#include "contourmesh/vtk/mesh_io.h"

#include <contourmesh/smooth/mesh.h>

#include <filesystem>
#include <istream>
#include <ostream>

namespace contourmesh {

/// Parses a PLY stream. Faces with more than three corners are fan-triangulated; extra elements and
/// properties are skipped. Throws InvalidInputError (without the file name; read_mesh adds it) for a
/// malformed header, unsupported type, truncated data, a non-finite coordinate or an out-of-range face
/// index; LimitError when the header announces more than `max_vertices` vertices.
[[nodiscard]] Mesh read_ply(std::istream& in, const ContourIdArrayNames& arrays = {},
                            Index max_vertices = kDefaultMaxVertices);

/// Writes binary little-endian PLY: double x y z, int ids when present, the extra arrays as double or
/// int vertex properties, uchar-count int-index faces.
void write_ply(std::ostream& out, const Mesh& mesh, const ContourIdArrayNames& arrays = {},
               const std::vector<PointScalars>& extra = {});

}  // namespace contourmesh
