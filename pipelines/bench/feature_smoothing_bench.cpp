// SPDX-License-Identifier: BSD-3-Clause
// The paper's method end to end (feature_smoothing.h, default options: detection by contour
// continuity, up to 3 subdivision levels, 40 Taubin iterations, original resolution), with its peak
// heap per input vertex and the library's own per-stage timings.
#include "bench_inputs.h"
#include "bench_stages.h"
#include "heap_counter.h"

#include <contourmesh/smooth/cross_slice.h>
#include <contourmesh/smooth/feature_smoothing.h>

#include <optional>

namespace contourmesh::bench {

// The time includes everything feature_preserving_smooth does from a bare mesh (it builds its own
// adjacencies). peak_bytes_per_vertex: the highest live heap above what was live before the call,
// returned result included, divided by the input's vertex count (heap_counter.h).
void bm_full_method(benchmark::State& state) {
  const Mesh& mesh = bench_input(state.range(0)).mesh;
  double peak = 0.0;
  StageTimings sum;
  Index adaptive_vertices = 0;
  for (auto _ : state) {
    std::optional<FeatureSmoothingResult> result;
    peak = std::max(peak, peak_heap_bytes_during([&] { result.emplace(feature_preserving_smooth(mesh)); }));
    benchmark::DoNotOptimize(result->mesh.positions.data());
    sum.detect += result->seconds.detect;
    sum.subdivide += result->seconds.subdivide;
    sum.smooth += result->seconds.smooth;
    adaptive_vertices = result->adaptive_vertices;
  }
  set_vertex_rate(state, mesh.num_vertices());
  const auto runs = static_cast<double>(state.iterations());
  state.counters["peak_bytes_per_vertex"] = peak / mesh.num_vertices();
  state.counters["detect_ms"] = 1e3 * sum.detect / runs;
  state.counters["subdivide_ms"] = 1e3 * sum.subdivide / runs;
  state.counters["smooth_ms"] = 1e3 * sum.smooth / runs;
  state.counters["adaptive_vertices"] = static_cast<double>(adaptive_vertices);
}

}  // namespace contourmesh::bench

namespace contourmesh::bench {

// The default smoothing (cross_slice.h, default options) from a bare mesh: frame, noise estimates,
// both profile stages, the extension and its labels. It runs its profiles and crease tensors on every
// core; the benchmark reports the process CPU time of all its threads (and the wall time).
void bm_default_method(benchmark::State& state) {
  const Mesh& mesh = bench_input(state.range(0)).mesh;
  double detect = 0.0, smooth = 0.0, noise = 0.0;
  int reach = 0;
  for (auto _ : state) {
    const CrossSliceResult result = cross_slice_smooth(mesh);
    benchmark::DoNotOptimize(result.mesh.positions.data());
    detect += result.seconds_detect;
    smooth += result.seconds_smooth;
    noise = result.noise_across;
    reach = result.reach;
  }
  set_vertex_rate(state, mesh.num_vertices());
  const auto runs = static_cast<double>(state.iterations());
  state.counters["detect_ms"] = 1e3 * detect / runs;
  state.counters["smooth_ms"] = 1e3 * smooth / runs;
  // The windows the noise level chose (the reach across the slices follows it).
  state.counters["noise_across_um"] = 1e3 * noise;
  state.counters["reach"] = reach;
}

}  // namespace contourmesh::bench
