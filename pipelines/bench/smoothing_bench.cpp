// SPDX-License-Identifier: BSD-3-Clause
// Connectivity and the two smoothing kernels: building the CSR adjacency, one umbrella pass (paper
// eq. 7) and one Taubin lambda|mu iteration (eq. 6, two umbrella steps).
#include "bench_inputs.h"
#include "bench_stages.h"

#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/smoothing.h>
#include <contourmesh/smooth/umbrella.h>

#include <ctime>

namespace contourmesh::bench {

namespace {

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

void bm_adjacency(benchmark::State& state) {
  const Mesh& mesh = bench_input(state.range(0)).mesh;
  for (auto _ : state) {
    const MeshAdjacency adj = build_adjacency(mesh);
    benchmark::DoNotOptimize(adj.neighbors.data());
  }
  set_vertex_rate(state, mesh.num_vertices());
}

void bm_umbrella_pass(benchmark::State& state) {
  const Mesh& mesh = bench_input(state.range(0)).mesh;
  const MeshAdjacency adj = build_adjacency(mesh);
  Eigen::Matrix3Xd u;
  for (auto _ : state) {
    umbrella(mesh.positions, adj, u);
    benchmark::DoNotOptimize(u.data());
    benchmark::ClobberMemory();
  }
  set_vertex_rate(state, mesh.num_vertices());
}

// taubin_smooth with kTaubinIterationsPerCall iterations on a prebuilt adjacency; the reported manual
// time is the process CPU time per iteration, so the per-call setup (copy of the positions, lock mask)
// is amortised as in a real 20- or 40-iteration run. vertices_per_s counts one update per vertex per
// iteration (each iteration is two umbrella steps, lambda then mu).
void bm_taubin_iteration(benchmark::State& state) {
  const Mesh& mesh = bench_input(state.range(0)).mesh;
  const MeshAdjacency adj = build_adjacency(mesh);
  SmoothingOptions o;
  o.method = SmoothingMethod::Taubin;
  o.iterations = kTaubinIterationsPerCall;
  for (auto _ : state) {
    const double start = process_cpu_seconds();
    Eigen::Matrix3Xd out = taubin_smooth(mesh, adj, o);
    benchmark::DoNotOptimize(out.data());
    state.SetIterationTime((process_cpu_seconds() - start) / kTaubinIterationsPerCall);
  }
  set_vertex_rate(state, mesh.num_vertices());
}

}  // namespace contourmesh::bench
