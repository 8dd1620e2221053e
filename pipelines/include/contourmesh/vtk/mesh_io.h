// SPDX-License-Identifier: BSD-3-Clause
// Mesh file I/O for ContourMesh: STL (binary, ASCII), PLY, VTP and OBJ. STL, OBJ and PLY go through the
// project's own parsers and writers (strict: VTK's accept truncated files, read "nan" as 0 and do not
// check their writes); VTP through VTK's XML reader (wrapped to check what it trusts) and writer.
#pragma once

#include <contourmesh/smooth/limits.h>
#include <contourmesh/smooth/mesh.h>
#include <contourmesh/smooth/progress.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace contourmesh {

enum class MeshFormat {
  Auto,       ///< from the file extension (.stl -> binary STL)
  StlBinary,
  StlAscii,
  Ply,        ///< binary little-endian when writing; ASCII and both binaries when reading
  Vtp,        ///< VTK XML PolyData, appended binary, zlib-compressed
  Obj,
};

/// The coordinate system of written meshes: LPS, the physical space ITK reads volumes in (patient left,
/// posterior, superior). STL files carry it in their header and PLY files in a comment, in the form
/// 3D Slicer writes and reads ("SPACE=LPS"), so that Slicer places the mesh on its volume.
inline constexpr const char* kCoordinateSystemTag = "SPACE=LPS";
/// The header of written STL files (binary: the 80-byte header; ASCII: the solid's name).
inline constexpr const char* kStlHeader = "ContourMesh output. SPACE=LPS";

/// "stl", "stl-ascii", "ply", "vtp", "obj" (and "auto").
[[nodiscard]] std::string_view to_string(MeshFormat format);
/// Inverse of to_string; throws InvalidInputError naming the accepted values.
[[nodiscard]] MeshFormat parse_mesh_format(std::string_view name);
/// The format implied by the extension of `path` (case-insensitive); throws InvalidInputError naming
/// the file when the extension is not one of .stl .ply .vtp .obj.
[[nodiscard]] MeshFormat format_from_extension(const std::filesystem::path& path);
/// True when the format stores per-vertex contour ids (PLY, VTP).
[[nodiscard]] bool format_keeps_contour_ids(MeshFormat format);

/// Names of the per-vertex id arrays (the slice and contour ids of contourmesh/smooth/mesh.h).
struct ContourIdArrayNames {
  std::string slice = "ContourId";       ///< c(i), the slice index
  std::string contour = "ContourIndex";  ///< which contour of that slice
};

struct MeshReadOptions {
  MeshFormat format = MeshFormat::Auto;
  ContourIdArrayNames arrays;
  /// Files with more vertices are refused with a LimitError (checked as early as the format allows:
  /// from the PLY and VTP headers, while parsing STL and OBJ).
  Index max_vertices = kDefaultMaxVertices;
};

/// Storage type of an extra per-vertex array.
enum class ScalarType { Float64, Int32 };

/// A named per-vertex scalar array written with the mesh (feature labels, curvatures, ...). Only VTP
/// and PLY can carry it; NaN values are written as they are (VTP) or as NaN doubles (PLY).
struct PointScalars {
  std::string name;
  std::vector<double> values;  ///< one per vertex
  ScalarType type = ScalarType::Float64;
};

struct MeshWriteOptions {
  MeshFormat format = MeshFormat::Auto;
  ContourIdArrayNames arrays;
  /// Extra point arrays; writing them to STL or OBJ is an InvalidInputError.
  std::vector<PointScalars> point_scalars;
  /// Called with ("write", 1) once the file is complete, before it replaces `path`: return false to
  /// cancel (CancelledError; nothing is replaced, no temporary is left).
  ProgressCallback progress;
};

/// Reads a triangle mesh. Polygons with more than three corners are triangulated; lines and vertices
/// are ignored. STL corners at bit-identical positions are merged into shared vertices (STL stores each
/// triangle's corners separately). Contour ids are read from the named point arrays when present
/// (both or neither). The mesh is returned as stored otherwise: no triangle is dropped (see
/// repair_mesh in contourmesh/smooth/validation.h).
/// Throws InvalidInputError whose message starts with the file name and says what is wrong and where:
/// missing, empty or unreadable file, unknown extension, a truncated or malformed file (STL, PLY, OBJ:
/// with the byte count, line or element; VTP: VTK's parser message), a non-finite coordinate (after
/// reading any format), a triangle index out of range ("triangle 12 references vertex 9001 but the
/// file has 500 vertices"), no triangles, id arrays of the wrong size; LimitError (an
/// InvalidInputError) beyond `options.max_vertices`.
[[nodiscard]] Mesh read_mesh(const std::filesystem::path& path, const MeshReadOptions& options = {});

/// Writes a mesh atomically (contourmesh/smooth/atomic_file.h): to a temporary file next to the destination, flushed
/// to disk and renamed over it only once complete, so a failure never leaves a partial file nor
/// truncates an existing one; symbolic links are written through; only a regular file is replaced.
/// Contour ids are written for PLY and VTP when the mesh has them. Throws InvalidInputError naming the
/// file on failure (missing directory, no permission, a device, disk full or a file size limit: every
/// write is checked), for a non-finite coordinate (any format), a coordinate beyond float range in
/// STL, or an extra array of the wrong size or that the format cannot carry.
void write_mesh(const Mesh& mesh, const std::filesystem::path& path, const MeshWriteOptions& options = {});

}  // namespace contourmesh
