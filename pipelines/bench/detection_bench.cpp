// SPDX-License-Identifier: BSD-3-Clause
// Feature detection by contour continuity (the paper's Algorithm 2, feature_detection.h), and crease
// detection (crease_detection.h, the default smoothing's labels), default options.
#include "bench_inputs.h"
#include "bench_stages.h"

#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/crease_detection.h>
#include <contourmesh/smooth/feature_detection.h>

namespace contourmesh::bench {

// On a prebuilt adjacency; includes the curvature estimation detect_features runs first. The label
// counts show that the inputs do have features (the ridges) and noise.
void bm_feature_detection(benchmark::State& state) {
  const Mesh& mesh = bench_input(state.range(0)).mesh;
  const MeshAdjacency adj = build_adjacency(mesh);
  std::size_t candidates = 0, edges = 0, corners = 0, noise = 0;
  for (auto _ : state) {
    const FeatureDetection d = detect_features(mesh, adj);
    benchmark::DoNotOptimize(d.labels.data());
    candidates = d.candidates;
    edges = d.edges;
    corners = d.corners;
    noise = d.noise;
  }
  set_vertex_rate(state, mesh.num_vertices());
  state.counters["candidates"] = static_cast<double>(candidates);
  state.counters["edges"] = static_cast<double>(edges);
  state.counters["corners"] = static_cast<double>(corners);
  state.counters["noise"] = static_cast<double>(noise);
}

// On a prebuilt adjacency, of the unsmoothed contour mesh (whose in-plane noise makes about half its
// vertices candidates, each confirmed over its ball: more work than on a smoothed mesh). Runs on every
// core; the process CPU time counts all its threads.
void bm_crease_detection(benchmark::State& state) {
  const Mesh& mesh = bench_input(state.range(0)).mesh;
  const MeshAdjacency adj = build_adjacency(mesh);
  std::size_t edges = 0, corners = 0, noise = 0;
  for (auto _ : state) {
    const CreaseDetection d = detect_creases(mesh, adj);
    benchmark::DoNotOptimize(d.labels.data());
    edges = d.edges;
    corners = d.corners;
    noise = d.noise;
  }
  set_vertex_rate(state, mesh.num_vertices());
  state.counters["edges"] = static_cast<double>(edges);
  state.counters["corners"] = static_cast<double>(corners);
  state.counters["noise"] = static_cast<double>(noise);
}

}  // namespace contourmesh::bench
