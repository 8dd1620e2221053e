// SPDX-License-Identifier: BSD-3-Clause
// Adaptive subdivision around the detected feature vertices (adaptive_subdivision.h), as the full
// method runs it: edge and corner labels selected, gamma from the detection, at most 3 levels.
#include "bench_inputs.h"
#include "bench_stages.h"

#include <contourmesh/smooth/adaptive_subdivision.h>
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/feature_detection.h>

namespace contourmesh::bench {

void bm_adaptive_subdivision(benchmark::State& state) {
  const Mesh& mesh = bench_input(state.range(0)).mesh;
  std::vector<std::uint8_t> selected(static_cast<std::size_t>(mesh.num_vertices()), 0);
  SubdivisionOptions options;
  {
    const FeatureDetection d = detect_features(mesh, build_adjacency(mesh));
    for (std::size_t i = 0; i < selected.size(); ++i) {
      selected[i] = d.labels[i] == VertexLabel::Edge || d.labels[i] == VertexLabel::Corner;
    }
    options.gamma = d.gamma;
  }
  options.max_levels = 3;
  Index adaptive_vertices = 0;
  for (auto _ : state) {
    const AdaptiveMesh a = subdivide_adaptively(mesh, selected, options);
    benchmark::DoNotOptimize(a.mesh.positions.data());
    adaptive_vertices = a.mesh.num_vertices();
  }
  set_vertex_rate(state, mesh.num_vertices());
  state.counters["adaptive_vertices"] = static_cast<double>(adaptive_vertices);
}

}  // namespace contourmesh::bench
