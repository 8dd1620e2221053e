// SPDX-License-Identifier: BSD-3-Clause
// Curvature estimation: principal curvatures and directions by weighted quadric fitting (curvature.h).
#include "bench_inputs.h"
#include "bench_stages.h"

#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/curvature.h>

namespace contourmesh::bench {

// On a prebuilt adjacency (the adjacency stage times its construction separately).
void bm_curvature(benchmark::State& state) {
  const Mesh& mesh = bench_input(state.range(0)).mesh;
  const MeshAdjacency adj = build_adjacency(mesh);
  for (auto _ : state) {
    const PrincipalCurvatures c = principal_curvatures(mesh.positions, mesh.triangles, adj);
    benchmark::DoNotOptimize(c.kappa_max.data());
  }
  set_vertex_rate(state, mesh.num_vertices());
}

}  // namespace contourmesh::bench
