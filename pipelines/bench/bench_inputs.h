// SPDX-License-Identifier: BSD-3-Clause
// Shared inputs of the benchmark programs: deterministic synthetic contour stacks that look like a
// segmented CT study (bone-like tubes with sharp ridges, per-slice point counts, segmentation noise),
// the meshes the project's tiler makes of them (with contour ids), and their VTK copies.
#pragma once

#include <contourmesh/reconstruct/contours.h>
#include <contourmesh/smooth/mesh.h>

#include <benchmark/benchmark.h>

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <array>
#include <cstdint>

namespace contourmesh::bench {

/// The benchmark sizes, in target vertices of the tiled mesh.
inline constexpr std::array<std::int64_t, 4> kSizes{10'000, 100'000, 1'000'000, 4'000'000};

/// How a stack of a given size is laid out.
struct StackLayout {
  int objects = 1;              ///< separate tubes side by side in the same slices (bones of one study)
  int points_per_contour = 0;   ///< mean points per contour (the count varies with the slice)
  int slices = 0;
  double point_spacing = 0.5;   ///< mm between contour points
  double slice_spacing = 1.0;   ///< mm between slices
};

/// Layout whose tiled mesh has about `target_vertices` vertices (contour points plus end-cap vertices).
[[nodiscard]] StackLayout stack_layout(std::int64_t target_vertices);

/// A contour stack with `layout.objects` tubes. Each tube's contours are star-shaped (simple by
/// construction): an elliptic section whose radius swells along the slice axis, one sharp ridge that
/// runs straight across the slices and one that spirals a quarter turn along the tube (oblique to the
/// slices), radial Gaussian noise of 0.2 point spacings and a jitter of the point angles. Points per
/// contour follow the perimeter, so adjacent contours have different counts, as after resampling a
/// segmentation. Bit-for-bit reproducible: every contour draws from its own splitmix64 stream.
[[nodiscard]] ContourStack make_bench_stack(const StackLayout& layout);

/// One size's inputs: the stack, the tiled mesh (default TilingOptions: refined caps half a spacing
/// beyond the end slices) and its vtkPolyData.
struct BenchInput {
  std::int64_t target = 0;
  ContourStack stack;
  Mesh mesh;
  vtkSmartPointer<vtkPolyData> polydata;
};

/// The contour stack for a size, built on first use. Only the most recent size is kept (stack and
/// mesh): the benchmarks run size by size, and the 4M-vertex inputs are large.
[[nodiscard]] const ContourStack& bench_stack(std::int64_t target_vertices);

/// The stack with its tiled mesh and polydata, tiled on first use unless the tiling benchmark handed
/// over its result with keep_tiled_mesh (tiling a 4M-vertex stack takes a minute).
[[nodiscard]] const BenchInput& bench_input(std::int64_t target_vertices);

/// Keeps `mesh`, tiled from bench_stack(target_vertices) with default options, as that size's mesh if
/// none is cached yet.
void keep_tiled_mesh(std::int64_t target_vertices, Mesh&& mesh);

/// Records the input's vertex count and `vertices_per_s`, a kIsRate counter of `vertices` processed
/// per benchmark iteration.
void set_vertex_rate(benchmark::State& state, double vertices);

}  // namespace contourmesh::bench
