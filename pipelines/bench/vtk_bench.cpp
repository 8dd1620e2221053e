// SPDX-License-Identifier: BSD-3-Clause
// What a user would pick instead: VTK's smoothing filters and curvature filter, on the same meshes
// (their vtkPolyData copies, built outside the timed region, as the ContourMesh stages get a Mesh).
#include "bench_inputs.h"
#include "bench_stages.h"
#include "heap_counter.h"

#include <vtkCurvatures.h>
#include <vtkSmoothPolyDataFilter.h>
#include <vtkWindowedSincPolyDataFilter.h>

namespace contourmesh::bench {

// vtkWindowedSincPolyDataFilter with 3D Slicer's surface smoothing settings: 20 iterations, pass band
// 0.01, normalized coordinates, no boundary or feature-edge smoothing. Peak heap as for the full method.
void bm_vtk_windowed_sinc20(benchmark::State& state) {
  const BenchInput& input = bench_input(state.range(0));
  double peak = 0.0;
  for (auto _ : state) {
    peak = std::max(peak, peak_heap_bytes_during([&] {
      auto filter = vtkSmartPointer<vtkWindowedSincPolyDataFilter>::New();
      filter->SetInputData(input.polydata);
      filter->SetNumberOfIterations(20);
      filter->SetPassBand(0.01);
      filter->NormalizeCoordinatesOn();
      filter->BoundarySmoothingOff();
      filter->FeatureEdgeSmoothingOff();
      filter->NonManifoldSmoothingOn();
      filter->Update();
      benchmark::DoNotOptimize(filter->GetOutput()->GetNumberOfPoints());
    }));
  }
  set_vertex_rate(state, input.mesh.num_vertices());
  state.counters["peak_bytes_per_vertex"] = peak / input.mesh.num_vertices();
}

// vtkSmoothPolyDataFilter (Laplacian, relaxation factor 0.01), 20 iterations, feature-edge smoothing
// on (feature angle 45 degrees), as `contourmesh compare` runs it.
void bm_vtk_smooth20(benchmark::State& state) {
  const BenchInput& input = bench_input(state.range(0));
  for (auto _ : state) {
    auto filter = vtkSmartPointer<vtkSmoothPolyDataFilter>::New();
    filter->SetInputData(input.polydata);
    filter->SetNumberOfIterations(20);
    filter->SetConvergence(0.0);
    filter->FeatureEdgeSmoothingOn();
    filter->Update();
    benchmark::DoNotOptimize(filter->GetOutput()->GetNumberOfPoints());
  }
  set_vertex_rate(state, input.mesh.num_vertices());
}

namespace {

void run_vtk_curvatures(benchmark::State& state, int type) {
  const BenchInput& input = bench_input(state.range(0));
  for (auto _ : state) {
    auto filter = vtkSmartPointer<vtkCurvatures>::New();
    filter->SetInputData(input.polydata);
    filter->SetCurvatureType(type);
    filter->Update();
    benchmark::DoNotOptimize(filter->GetOutput()->GetNumberOfPoints());
  }
  set_vertex_rate(state, input.mesh.num_vertices());
}

}  // namespace

void bm_vtk_curvatures_mean(benchmark::State& state) { run_vtk_curvatures(state, VTK_CURVATURE_MEAN); }
void bm_vtk_curvatures_gaussian(benchmark::State& state) { run_vtk_curvatures(state, VTK_CURVATURE_GAUSS); }

}  // namespace contourmesh::bench
