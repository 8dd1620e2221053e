// Smoothing benchmarks: ContourMesh's umbrella pass and Taubin smoothing against VTK's
// vtkWindowedSincPolyDataFilter (3D Slicer's default smoother) on the same contour-stack meshes.
//
//   build/release/pipelines/bench/contourmesh_bench                  # 10k, 100k, 1M vertices
//   build/release/pipelines/bench/contourmesh_bench --benchmark_filter=/1000000
//
// After the usual table it prints, per mesh size, the time of 20 Taubin iterations (with and without
// building the adjacency) as a ratio of VTK's 20 windowed-sinc iterations measured in the same run.
#include <pipelines/vtk_convert.h>
#include <smooth/adjacency.h>
#include <smooth/shapes.h>
#include <smooth/smoothing.h>
#include <smooth/umbrella.h>

#include <benchmark/benchmark.h>

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>

namespace {

using namespace contourmesh;

// A noisy contour stack with about n vertices: sqrt(n) slices of sqrt(n) points, a ridged cylinder.
const Mesh& stack_mesh(std::int64_t n) {
  static std::map<std::int64_t, std::unique_ptr<Mesh>> cache;
  auto& slot = cache[n];
  if (!slot) {
    const int side = static_cast<int>(std::lround(std::sqrt(static_cast<double>(n))));
    ContourStackSpec spec;
    spec.curve = ridge_circle_curve(0.7 * side / (2.0 * 3.14159265358979), 0.05 * side, 0.35);
    spec.slices = side;
    spec.points_per_contour = side;
    spec.slice_spacing = 2.0;
    slot = std::make_unique<Mesh>(make_contour_stack(spec));
    add_noise(*slot, {0.15, 1, NoiseDirection::InPlane});
  }
  return *slot;
}

void set_counters(benchmark::State& state, double vertex_updates_per_run) {
  state.counters["vertices"] = static_cast<double>(stack_mesh(state.range(0)).num_vertices());
  state.counters["updates_per_s"] =
      benchmark::Counter(vertex_updates_per_run * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_BuildAdjacency(benchmark::State& state) {
  const Mesh& mesh = stack_mesh(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(build_adjacency(mesh));
  set_counters(state, mesh.num_vertices());
}

void BM_UmbrellaPass(benchmark::State& state) {
  const Mesh& mesh = stack_mesh(state.range(0));
  const MeshAdjacency adj = build_adjacency(mesh);
  Eigen::Matrix3Xd u;
  for (auto _ : state) {
    umbrella(mesh.positions, adj, u);
    benchmark::DoNotOptimize(u.data());
  }
  set_counters(state, mesh.num_vertices());
}

// 20 Taubin iterations (40 umbrella steps) on a prebuilt adjacency.
void BM_Taubin20(benchmark::State& state) {
  const Mesh& mesh = stack_mesh(state.range(0));
  const MeshAdjacency adj = build_adjacency(mesh);
  SmoothingOptions o;
  o.method = SmoothingMethod::Taubin;
  o.iterations = 20;
  for (auto _ : state) benchmark::DoNotOptimize(taubin_smooth(mesh, adj, o));
  set_counters(state, 40.0 * mesh.num_vertices());
}

// The same including the adjacency build: what a one-shot call costs end to end.
void BM_Taubin20WithAdjacency(benchmark::State& state) {
  const Mesh& mesh = stack_mesh(state.range(0));
  SmoothingOptions o;
  o.method = SmoothingMethod::Taubin;
  o.iterations = 20;
  for (auto _ : state) benchmark::DoNotOptimize(smooth(mesh, o));
  set_counters(state, 40.0 * mesh.num_vertices());
}

// vtkWindowedSincPolyDataFilter with 3D Slicer's surface smoothing settings: 20 iterations, pass band
// 0.01, normalized coordinates, no boundary or feature-edge smoothing.
void BM_VtkWindowedSinc20(benchmark::State& state) {
  const Mesh& mesh = stack_mesh(state.range(0));
  const vtkSmartPointer<vtkPolyData> input = to_polydata(mesh);
  for (auto _ : state) {
    auto filter = vtkSmartPointer<vtkWindowedSincPolyDataFilter>::New();
    filter->SetInputData(input);
    filter->SetNumberOfIterations(20);
    filter->SetPassBand(0.01);
    filter->NormalizeCoordinatesOn();
    filter->BoundarySmoothingOff();
    filter->FeatureEdgeSmoothingOff();
    filter->NonManifoldSmoothingOn();
    filter->Update();
    benchmark::DoNotOptimize(filter->GetOutput()->GetNumberOfPoints());
  }
  set_counters(state, 20.0 * mesh.num_vertices());
}

void sizes(benchmark::internal::Benchmark* b) {
  b->Arg(10'000)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK(BM_BuildAdjacency)->Apply(sizes);
BENCHMARK(BM_UmbrellaPass)->Apply(sizes);
BENCHMARK(BM_Taubin20)->Apply(sizes);
BENCHMARK(BM_Taubin20WithAdjacency)->Apply(sizes);
BENCHMARK(BM_VtkWindowedSinc20)->Apply(sizes);

// Console output as usual, plus a closing table of ratios against VTK from the same run.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      if (r.run_type != Run::RT_Iteration) continue;
      const std::string name = r.benchmark_name();
      const auto slash = name.find('/');
      const std::string base = name.substr(0, slash);
      const std::string size = slash == std::string::npos ? "" : name.substr(slash + 1, name.find('/', slash + 1) - slash - 1);
      times_[size][base] = r.GetAdjustedRealTime();
    }
  }
  void Finalize() override {
    ConsoleReporter::Finalize();
    std::printf("\n%-10s %14s %14s %14s %12s %12s\n", "vertices", "taubin20 ms", "+adjacency ms", "vtk sinc20 ms",
                "ratio", "ratio+adj");
    for (const auto& [size, t] : times_) {
      auto get = [&](const char* k) { auto it = t.find(k); return it == t.end() ? NAN : it->second; };
      const double taubin = get("BM_Taubin20"), full = get("BM_Taubin20WithAdjacency"), vtk = get("BM_VtkWindowedSinc20");
      std::printf("%-10s %14.2f %14.2f %14.2f %12.3f %12.3f\n", size.c_str(), taubin, full, vtk, taubin / vtk, full / vtk);
    }
    std::printf("(ratio = ContourMesh time / VTK time, same mesh, same run; < 1 means faster than VTK)\n");
  }

 private:
  std::map<std::string, std::map<std::string, double>> times_;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
