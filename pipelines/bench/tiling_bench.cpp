// SPDX-License-Identifier: BSD-3-Clause
// Tiling (libreconstruct tiling.h): the synthetic contour stack of each size into a closed mesh with
// contour ids, default options (minimum-area dynamic programme, refined caps half a spacing out).
#include "bench_inputs.h"
#include "bench_stages.h"

#include <contourmesh/reconstruct/tiling.h>

namespace contourmesh::bench {

// vertices_per_s counts the vertices of the tiled mesh. The first result becomes the size's input
// mesh for the other stages (keep_tiled_mesh), outside the timed region.
void bm_tiling(benchmark::State& state) {
  const std::int64_t size = state.range(0);
  const ContourStack& stack = bench_stack(size);
  Index vertices = 0;
  for (auto _ : state) {
    TilingResult r = tile_contours(stack);
    benchmark::DoNotOptimize(r.mesh.positions.data());
    state.PauseTiming();
    vertices = r.mesh.num_vertices();
    keep_tiled_mesh(size, std::move(r.mesh));
    state.ResumeTiming();
  }
  set_vertex_rate(state, vertices);
  std::size_t points = 0;
  for (const SliceContours& s : stack.slices) {
    for (const Contour& c : s.contours) points += c.points.size();
  }
  state.counters["contour_points"] = static_cast<double>(points);
  state.counters["contours"] = static_cast<double>(stack.num_contours());
}

}  // namespace contourmesh::bench
