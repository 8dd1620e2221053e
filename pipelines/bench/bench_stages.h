// SPDX-License-Identifier: BSD-3-Clause
// The benchmark functions of each stage. bench_main.cpp registers every one of them at every size of
// kSizes (state.range(0) is the target vertex count), size by size.
#pragma once

#include <benchmark/benchmark.h>

namespace contourmesh::bench {

// smoothing_bench.cpp
void bm_adjacency(benchmark::State& state);
void bm_umbrella_pass(benchmark::State& state);
void bm_taubin_iteration(benchmark::State& state);
/// Taubin iterations per call in bm_taubin_iteration; its time is reported per iteration.
inline constexpr int kTaubinIterationsPerCall = 10;

// curvature_bench.cpp
void bm_curvature(benchmark::State& state);

// detection_bench.cpp
void bm_feature_detection(benchmark::State& state);
void bm_crease_detection(benchmark::State& state);

// subdivision_bench.cpp
void bm_adaptive_subdivision(benchmark::State& state);

// feature_smoothing_bench.cpp
void bm_full_method(benchmark::State& state);
/// The default smoothing (cross-slice), wall-clock.
void bm_default_method(benchmark::State& state);

// tiling_bench.cpp
void bm_tiling(benchmark::State& state);

// vtk_bench.cpp: the VTK counterparts
void bm_vtk_windowed_sinc20(benchmark::State& state);
void bm_vtk_smooth20(benchmark::State& state);
void bm_vtk_curvatures_mean(benchmark::State& state);
void bm_vtk_curvatures_gaussian(benchmark::State& state);

}  // namespace contourmesh::bench
