// SPDX-License-Identifier: BSD-3-Clause
// The body of the mesh-reader fuzz targets: the bytes go to a scratch file with the format's extension
// and through read_mesh, the CLI's entry point, then through what every command does next (repair,
// validation, the topology summary, the adjacency). read_mesh may only return a sane mesh or throw an
// InvalidInputError (LimitError included) whose one-line message starts with the file name.
#pragma once

#include "fuzz_support.h"

#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/topology.h>
#include <contourmesh/smooth/validation.h>

#include <exception>
#include <new>
#include <string>

namespace contourmesh::fuzz {

/// Far below the default: the fuzzer should find the limit checks, not spend its time on big meshes.
inline constexpr Index kFuzzMaxVertices = 100'000;

inline int fuzz_read_mesh(const std::uint8_t* data, std::size_t size, const std::string& extension) {
  const std::filesystem::path& path = scratch_file(extension);
  write_file(path, data, size);
  MeshReadOptions options;
  options.max_vertices = kFuzzMaxVertices;
  Mesh mesh;
  try {
    mesh = read_mesh(path, options);
  } catch (const InvalidInputError& e) {
    const std::string what = e.what();
    check_message_is_one_line(what, "read_mesh");
    if (what.rfind(path.string() + ": ", 0) != 0) fail("read_mesh error does not start with the file name: " + what);
    if (verbose()) std::fprintf(stderr, "rejected: %s\n", what.c_str());
    return 0;
  } catch (const std::bad_alloc&) {
    fail("read_mesh ran out of memory (a size check is missing)");
  } catch (const std::exception& e) {
    fail(std::string("read_mesh threw an untyped exception: ") + e.what());
  }
  check_mesh_is_sane(mesh, "read_mesh");
  if (mesh.num_faces() == 0) fail("read_mesh returned a mesh without triangles");
  if (mesh.num_vertices() > kFuzzMaxVertices) fail("read_mesh returned more vertices than the limit");
  if (verbose()) {
    std::fprintf(stderr, "read: %d vertices, %d triangles, %s\n", mesh.num_vertices(), mesh.num_faces(),
                 mesh.has_contour_ids() ? "contour ids" : "no ids");
  }

  Mesh repaired = mesh;
  const MeshRepair repair = repair_mesh(repaired);
  check_mesh_is_sane(repaired, "repair_mesh");
  if (repaired.num_vertices() != mesh.num_vertices() - repair.merged_vertices) fail("repair_mesh: vertex count");
  if (repaired.num_faces() != mesh.num_faces() - repair.dropped_degenerate - repair.dropped_duplicates) {
    fail("repair_mesh: triangle count");
  }
  for (const Triangle& t : repaired.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) fail("repair_mesh left a triangle with a repeated vertex");
  }
  (void)find_mesh_problems(repaired);
  const TopologySummary topology = summarize_topology(repaired);
  if (topology.components < 0) fail("summarize_topology: negative component count");
  const MeshAdjacency adjacency = build_adjacency(repaired);
  if (adjacency.num_vertices() != repaired.num_vertices()) fail("build_adjacency: vertex count");
  return 0;
}

}  // namespace contourmesh::fuzz
