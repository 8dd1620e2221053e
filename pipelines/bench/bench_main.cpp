// SPDX-License-Identifier: BSD-3-Clause
// contourmesh_bench: every stage of ContourMesh and its VTK counterparts at 10k, 100k, 1M and 4M
// vertices in one run, size by size, then the ratios between them and the speed targets of issue 6.
//
//   build/release/pipelines/bench/contourmesh_bench                       # everything (a few minutes)
//   build/release/pipelines/bench/contourmesh_bench --benchmark_filter=/1000000/
//   build/release/pipelines/bench/contourmesh_bench --benchmark_repetitions=5
//       --benchmark_filter='(default_method|vtk_windowed_sinc20)/1000000/'      # the speed target, medians
//
// With repetitions, the ratios and targets use each stage's median.
//
// Benchmarks are named stage/size/process_time[/manual_time]. Everything but default_method and
// crease_detection runs on one thread (VTK's SMP tools run on their sequential backend); those two count
// the CPU time of all their threads, so the ratios compare total work. See docs/benchmarks.md.
#include "bench_inputs.h"
#include "bench_stages.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

namespace {

using namespace contourmesh::bench;

struct Stage {
  const char* name;
  void (*function)(benchmark::State&);
  bool heavy;        // seconds at 1M vertices: run a fixed, small number of iterations at big sizes
  bool manual_time;  // the function reports its own per-iteration (CPU) time
};

const Stage kStages[] = {
    {"tiling", bm_tiling, true, false},
    {"adjacency", bm_adjacency, false, false},
    {"umbrella_pass", bm_umbrella_pass, false, false},
    {"taubin_iteration", bm_taubin_iteration, false, true},
    {"curvature", bm_curvature, true, false},
    {"feature_detection", bm_feature_detection, true, false},
    {"crease_detection", bm_crease_detection, true, false},
    {"adaptive_subdivision", bm_adaptive_subdivision, true, false},
    {"full_method", bm_full_method, true, false},
    {"default_method", bm_default_method, true, false},
    {"vtk_windowed_sinc20", bm_vtk_windowed_sinc20, true, false},
    {"vtk_smooth20", bm_vtk_smooth20, true, false},
    {"vtk_curvatures_mean", bm_vtk_curvatures_mean, true, false},
    {"vtk_curvatures_gaussian", bm_vtk_curvatures_gaussian, true, false},
};

void register_all() {
  for (const std::int64_t size : kSizes) {
    for (const Stage& s : kStages) {
      auto* b = benchmark::RegisterBenchmark(s.name, s.function)->Arg(size)->Unit(benchmark::kMillisecond);
      b->MeasureProcessCPUTime();
      if (s.manual_time) b->UseManualTime();
      // The whole run stays within a few minutes: tiling is the slowest stage (about 13 s at 1M).
      const bool slowest = std::string_view(s.name) == "tiling";
      if (s.heavy && (size >= 4'000'000 || (slowest && size >= 1'000'000))) b->Iterations(1);
      else if (s.heavy && size >= 1'000'000) b->Iterations(3);
    }
  }
}

// The console table as usual, then the ratios between stages measured in this run.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  explicit RatioReporter(OutputOptions options) : ConsoleReporter(options) {}

  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      // With --benchmark_repetitions the median of the repetitions replaces the last one (it is reported
      // after them), so the ratios and targets below compare medians.
      const bool median = r.run_type == Run::RT_Aggregate && r.aggregate_name == "median";
      if ((r.run_type != Run::RT_Iteration && !median) || r.error_occurred) continue;
      Result& out = results_[std::stoll(r.run_name.args)][r.run_name.function_name];
      // CPU time, ms for every stage (the machine is shared; every stage runs on one thread). A manual
      // time is already CPU time per iteration (bm_taubin_iteration).
      const bool manual = r.run_name.time_type.find("manual_time") != std::string::npos;
      out.ms = manual ? r.GetAdjustedRealTime() : r.GetAdjustedCPUTime();
      if (const auto it = r.counters.find("vertices_per_s"); it != r.counters.end()) out.rate = it->second;
      if (const auto it = r.counters.find("vertices"); it != r.counters.end()) out.vertices = it->second;
      if (const auto it = r.counters.find("peak_bytes_per_vertex"); it != r.counters.end()) out.peak = it->second;
    }
  }

  void Finalize() override {
    ConsoleReporter::Finalize();
    std::printf("\nRatios of times on the same meshes in this run (< 1: ContourMesh is faster)\n");
    std::printf("%-10s %-10s %12s %14s %14s %16s\n", "size", "vertices", "full/wsinc20", "taubin/vtksmth",
                "taubin/wsinc", "curv/vtkCurv");
    for (const auto& [size, stages] : results_) {
      auto ms = [&](const char* stage) {
        const auto it = stages.find(stage);
        return it == stages.end() ? NAN : it->second.ms;
      };
      double vertices = NAN;
      for (const auto& [name, r] : stages) {
        if (std::isfinite(r.vertices)) vertices = r.vertices;
      }
      std::printf("%-10lld %-10.0f %12.3f %14.3f %14.3f %16.3f\n", static_cast<long long>(size), vertices,
                  ms("full_method") / ms("vtk_windowed_sinc20"),
                  ms("taubin_iteration") / (ms("vtk_smooth20") / 20.0),
                  ms("taubin_iteration") / (ms("vtk_windowed_sinc20") / 20.0),
                  (ms("adjacency") + ms("curvature")) / (ms("vtk_curvatures_mean") + ms("vtk_curvatures_gaussian")));
    }
    std::printf(
        "full/wsinc20:   the full method (defaults, from a bare mesh) / vtkWindowedSincPolyDataFilter, 20 its,\n"
        "                3D Slicer's settings\n"
        "taubin/vtksmth: one Taubin iteration / one vtkSmoothPolyDataFilter iteration (its 20-iteration run / 20)\n"
        "taubin/wsinc:   one Taubin iteration / one windowed-sinc iteration (its 20-iteration run / 20)\n"
        "curv/vtkCurv:   adjacency + principal curvatures / vtkCurvatures mean + vtkCurvatures Gaussian\n");

    print_summary();
    std::printf("\nTargets (issue 6)\n");
    if (const auto it = results_.find(1'000'000); it != results_.end()) {
      const auto& st = it->second;
      if (st.count("default_method") && st.count("vtk_windowed_sinc20")) {
        const double ratio = st.at("default_method").ms / st.at("vtk_windowed_sinc20").ms;
        std::printf("  default smoothing (cross-slice) on the 1M mesh: %.2f x vtkWindowedSincPolyDataFilter 20 its, "
                    "CPU time of all its threads (target <= 2): %s\n",
                    ratio, ratio <= 2.0 ? "met" : "MISSED");
      }
      if (st.count("full_method") && st.count("vtk_windowed_sinc20")) {
        const double ratio = st.at("full_method").ms / st.at("vtk_windowed_sinc20").ms;
        std::printf("  full method on the 1M mesh: %.2f x vtkWindowedSincPolyDataFilter 20 its (target < 2): %s\n",
                    ratio, ratio < 2.0 ? "met" : "MISSED");
      }
    }
    for (const auto& [size, stages] : results_) {
      const auto it = stages.find("taubin_iteration");
      if (it == stages.end()) continue;
      std::printf("  Taubin iteration at %lld: %.3g vertex updates/s per core (target >= 5e7): %s\n",
                  static_cast<long long>(size), it->second.rate, it->second.rate >= 5e7 ? "met" : "MISSED");
    }
  }

 private:
  struct Result {
    double ms = NAN;
    double rate = NAN;
    double vertices = NAN;
    double peak = NAN;
  };

  // Stage x size as a Markdown table (docs/benchmarks.md): CPU time per run and vertices per second.
  void print_summary() const {
    std::printf("\nSummary: CPU time per run, vertices per second (Markdown)\n\n| stage |");
    for (const auto& [size, stages] : results_) std::printf(" %lld |", static_cast<long long>(size));
    std::printf("\n| --- |");
    for (std::size_t k = 0; k < results_.size(); ++k) std::printf(" --- |");
    std::printf("\n");
    for (const Stage& stage : kStages) {
      std::printf("| %s |", stage.name);
      for (const auto& [size, stages] : results_) {
        const auto it = stages.find(stage.name);
        if (it == stages.end()) std::printf(" |");
        else std::printf(" %s, %.3g/s |", format_ms(it->second.ms).c_str(), it->second.rate);
      }
      std::printf("\n");
    }
    for (const char* stage : {"full_method", "vtk_windowed_sinc20"}) {  // the stages that count their heap
      std::printf("| %s peak heap, bytes/vertex |", stage);
      for (const auto& [size, stages] : results_) {
        const auto it = stages.find(stage);
        if (it == stages.end()) std::printf(" |");
        else std::printf(" %.0f |", it->second.peak);
      }
      std::printf("\n");
    }
  }

  static std::string format_ms(double ms) {
    char buf[32];
    if (ms >= 1000.0) std::snprintf(buf, sizeof buf, "%.2f s", ms / 1000.0);
    else if (ms >= 10.0) std::snprintf(buf, sizeof buf, "%.0f ms", ms);
    else std::snprintf(buf, sizeof buf, "%.2f ms", ms);
    return buf;
  }

  std::map<std::int64_t, std::map<std::string, Result>> results_;
};

}  // namespace

int main(int argc, char** argv) {
  // Per-core comparison: ContourMesh is single-threaded, so VTK's SMP tools run sequentially too (read
  // when VTK first uses them; vtkSMPTools.h itself does not compile as C++20 in VTK 9.1).
  setenv("VTK_SMP_BACKEND_IN_USE", "Sequential", 0);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  register_all();
  RatioReporter reporter(isatty(STDOUT_FILENO) ? benchmark::ConsoleReporter::OO_ColorTabular
                                               : benchmark::ConsoleReporter::OO_Tabular);
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
