// SPDX-License-Identifier: BSD-3-Clause
// contourmesh_route_bench: the contour route against the voxel route, stage by stage, from the volume
// in memory to the mesh in memory, at one thread and at N threads, in one run (docs/benchmarks.md,
// "Contour route against voxel route").
//
//   build/release/pipelines/bench/contourmesh_route_bench --data ../shared/data        # both cases
//   build/release/pipelines/bench/contourmesh_route_bench --case skull --reps 7 --threads 2
//
// Contour route: what `contourmesh run` does after reading the volume: reconstruct() (segmentation,
// tiling, the component filter) and the default smoothing (smooth() with the default preset, the call
// `run` makes). Voxel route: what `contourmesh compare` runs as 3D Slicer's chain:
// threshold, islands and holes under the speck size removed, one voxel of padding,
// vtkDiscreteFlyingEdges3D, then vtkWindowedSincPolyDataFilter (20 iterations, pass band 0.01). The two
// routes alternate within each repetition, so both see the same load. Times are wall clock (threads);
// the process CPU time of each stage is printed too.
#include <contourmesh/vtk/vtk_image_convert.h>
#include <contourmesh/reconstruct/phantom.h>
#include <contourmesh/reconstruct/reconstruction.h>
#include <contourmesh/reconstruct/threads.h>
#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/smooth.h>

#include <vtkDiscreteFlyingEdges3D.h>
#include <vtkImageConnectivityFilter.h>
#include <vtkImageConstantPad.h>
#include <vtkImageData.h>
#include <vtkImageThreshold.h>
#include <vtkMultiThreader.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace contourmesh;

// ---- timing ------------------------------------------------------------------------------------

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Sample {
  double wall = 0.0;
  double cpu = 0.0;
};

// Wall and process CPU seconds of `body`.
Sample measure(const std::function<void()>& body) {
  const auto w0 = std::chrono::steady_clock::now();
  const double c0 = cpu_seconds();
  body();
  return {std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count(), cpu_seconds() - c0};
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// Samples per stage name, in the order stages were first recorded.
class StageTimes {
 public:
  void add(const std::string& stage, Sample s) {
    if (std::find(order_.begin(), order_.end(), stage) == order_.end()) order_.push_back(stage);
    wall_[stage].push_back(s.wall);
    cpu_[stage].push_back(s.cpu);
  }
  [[nodiscard]] double wall(const std::string& stage) const { return median(at(wall_, stage)); }
  [[nodiscard]] double cpu(const std::string& stage) const { return median(at(cpu_, stage)); }
  [[nodiscard]] const std::vector<std::string>& stages() const { return order_; }

 private:
  static std::vector<double> at(const std::map<std::string, std::vector<double>>& m, const std::string& k) {
    const auto it = m.find(k);
    return it == m.end() ? std::vector<double>{} : it->second;
  }
  std::vector<std::string> order_;
  std::map<std::string, std::vector<double>> wall_, cpu_;
};

// ---- the two routes --------------------------------------------------------------------------------

struct Case {
  std::string name;
  CtImage::Pointer image;
  double threshold = 0.0;
};

// The contour route of `contourmesh run`: reconstruct() with the CLI's options for this input, then
// the default smoothing. Records segment, tile, "checks + component filter" (the rest of
// reconstruct()), smooth, and the route's total.
std::size_t contour_route(const Case& c, StageTimes& times) {
  ReconstructionOptions ro;
  ro.segmentation.threshold = c.threshold;
  Reconstruction rec;
  const Sample whole = measure([&] { rec = reconstruct(*c.image, ro); });
  // reconstruct() times its own stages (wall clock); their CPU time is not known separately.
  times.add("segment", {rec.report.seconds_segment, NAN});
  times.add("tile", {rec.report.seconds_tile, NAN});
  times.add("checks + components",
            {std::max(0.0, whole.wall - rec.report.seconds_segment - rec.report.seconds_tile), NAN});
  times.add("reconstruct() in all", whole);
  // Segmentation once more on its own, for its process CPU time (how many cores it kept busy).
  const Sample alone = measure([&] { (void)segment_contours(*c.image, ro.segmentation); });
  times.add("segment_contours() alone", alone);
  SmoothResult smoothed;
  const MethodConfig config = preset(Preset::Default);
  const Sample smoothing = measure([&] { smoothed = smooth(rec.mesh, config.method, config.options); });
  times.add("smooth (default)", smoothing);
  times.add("contour total", {whole.wall + smoothing.wall, whole.cpu + smoothing.cpu});
  return static_cast<std::size_t>(smoothed.mesh.num_vertices());
}

// Keeps the 6-connected regions of value 1 with at least `min_voxels` voxels, as 1; the rest becomes 0.
void keep_large_regions(vtkImageConnectivityFilter* filter, vtkIdType min_voxels) {
  filter->SetScalarRange(1.0, 1.0);
  filter->SetExtractionModeToAllRegions();
  filter->SetSizeRange(min_voxels, std::numeric_limits<vtkIdType>::max());
  filter->SetLabelModeToConstantValue();
  filter->SetLabelConstantValue(1);
  filter->SetLabelScalarTypeToUnsignedChar();
  filter->GenerateRegionExtentsOff();
}

void binary_threshold(vtkImageThreshold* filter, double lower, bool invert) {
  if (invert) filter->ThresholdByLower(lower);
  else filter->ThresholdByUpper(lower);
  filter->SetInValue(1);
  filter->SetOutValue(0);
  filter->ReplaceInOn();
  filter->ReplaceOutOn();
  filter->SetOutputScalarTypeToUnsignedChar();
}

// The voxel route as `contourmesh compare` runs it (voxel_route in pipelines/src/comparison.cpp: keep
// the two in step): threshold, islands and holes under the contour route's speck size (4 voxels)
// removed, padding, flying edges, windowed sinc. With `clean_up` false, the bare chain (threshold,
// padding, flying edges, windowed sinc: 3D Slicer's closed surface without the Islands effect), stage
// names prefixed "bare ". The image is already in VTK form (the harness also converts it outside the
// timed region). Returns the vertices of the smoothed surface.
std::size_t voxel_route(vtkImageData* image, const int extent[6], double threshold, bool clean_up, StageTimes& times) {
  const std::string prefix = clean_up ? "" : "bare ";
  const auto min_speck_voxels = static_cast<vtkIdType>(std::ceil(ReconstructionOptions{}.min_component_voxels));
  vtkNew<vtkImageThreshold> above;
  vtkNew<vtkImageConnectivityFilter> islands;
  vtkNew<vtkImageThreshold> background;
  vtkNew<vtkImageConnectivityFilter> large_background;
  vtkNew<vtkImageThreshold> filled;
  vtkNew<vtkImageConstantPad> pad;
  const Sample binary = measure([&] {
    above->SetInputData(image);
    binary_threshold(above, threshold, false);
    vtkAlgorithm* last = above;
    if (clean_up) {
      islands->SetInputConnection(above->GetOutputPort());
      keep_large_regions(islands, min_speck_voxels);
      background->SetInputConnection(islands->GetOutputPort());
      binary_threshold(background, 0.5, true);
      large_background->SetInputConnection(background->GetOutputPort());
      keep_large_regions(large_background, min_speck_voxels);
      filled->SetInputConnection(large_background->GetOutputPort());
      binary_threshold(filled, 0.5, true);
      last = filled;
    }
    pad->SetInputConnection(last->GetOutputPort());
    pad->SetOutputWholeExtent(extent[0] - 1, extent[1] + 1, extent[2] - 1, extent[3] + 1, extent[4] - 1, extent[5] + 1);
    pad->SetConstant(0);
    pad->Update();
  });
  times.add(prefix + (clean_up ? "threshold + islands/holes" : "threshold"), binary);
  vtkNew<vtkDiscreteFlyingEdges3D> surface;
  const Sample fe = measure([&] {
    surface->SetInputConnection(pad->GetOutputPort());
    surface->SetValue(0, 1.0);
    surface->ComputeNormalsOff();
    surface->ComputeGradientsOff();
    surface->ComputeScalarsOff();
    surface->Update();
  });
  times.add(prefix + "flying edges", fe);
  vtkNew<vtkWindowedSincPolyDataFilter> sinc;
  const Sample smooth = measure([&] {
    sinc->SetInputData(surface->GetOutput());
    sinc->SetNumberOfIterations(20);
    sinc->SetPassBand(0.01);
    sinc->NormalizeCoordinatesOn();
    sinc->BoundarySmoothingOff();
    sinc->FeatureEdgeSmoothingOff();
    sinc->NonManifoldSmoothingOn();
    sinc->Update();
  });
  times.add(prefix + "windowed sinc 20", smooth);
  times.add(prefix + "voxel total", {binary.wall + fe.wall + smooth.wall, binary.cpu + fe.cpu + smooth.cpu});
  return static_cast<std::size_t>(sinc->GetOutput()->GetNumberOfPoints());
}

// ---- the run ---------------------------------------------------------------------------------------

struct Args {
  std::filesystem::path data = "../shared/data";
  std::string which = "all";
  int reps = 5;
  int threads = 0;  // N: every core
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--data") a.data = value();
    else if (arg == "--case") a.which = value();
    else if (arg == "--reps") a.reps = std::stoi(value());
    else if (arg == "--threads") a.threads = std::stoi(value());
    else if (arg == "--help" || arg == "-h") {
      std::printf("usage: contourmesh_route_bench [--data DIR] [--case headneck|skull|all] [--reps N] [--threads N]\n");
      std::exit(0);
    } else {
      throw std::invalid_argument("unknown argument " + arg);
    }
  }
  if (a.reps < 1) throw std::invalid_argument("--reps must be >= 1");
  if (a.threads < 0) throw std::invalid_argument("--threads must be >= 0");
  if (a.which != "all" && a.which != "headneck" && a.which != "skull") {
    throw std::invalid_argument("--case must be headneck, skull or all");
  }
  return a;
}

std::vector<Case> load_cases(const Args& a) {
  std::vector<Case> cases;
  if (a.which == "all" || a.which == "headneck") {
    cases.push_back({"dicom_series_headneck, 300 HU", read_volume(a.data / "dicom_series_headneck"), 300.0});
  }
  if (a.which == "all" || a.which == "skull") {
    // `contourmesh run --shape skull --spacing 0.4,0.4,1`: default noise 20 HU, blur 0.5 mm, and the
    // phantom threshold halfway between soft tissue and bone.
    PhantomVolumeOptions vo;
    vo.spacing = {0.4, 0.4, 1.0};
    vo.noise = 20.0;
    vo.blur = 0.5;
    cases.push_back({"skull phantom 0.4 x 0.4 x 1 mm, 520 HU", render_phantom(make_phantom(PhantomShape::Skull), vo),
                     0.5 * (vo.bone_hu + vo.tissue_hu)});
  }
  return cases;
}

struct Run {
  StageTimes times;
  std::size_t contour_vertices = 0, voxel_vertices = 0, bare_vertices = 0;
};

// One repetition of the three routes under a cap of `threads` threads (TBB, ITK, and VTK's SMP tools
// and vtkMultiThreader).
void repetition(const Case& c, vtkImageData* image, const int extent[6], int threads, Run& run) {
  const ThreadLimit limit(threads);
  vtkMultiThreader::SetGlobalMaximumNumberOfThreads(threads);
  run.contour_vertices = contour_route(c, run.times);
  run.voxel_vertices = voxel_route(image, extent, c.threshold, true, run.times);
  run.bare_vertices = voxel_route(image, extent, c.threshold, false, run.times);
  vtkMultiThreader::SetGlobalMaximumNumberOfThreads(0);
}

// `reps` repetitions at 1 thread and at n threads, alternating, so that a change in the machine's
// load affects both alike; one warm-up repetition of each is not recorded.
std::pair<Run, Run> run_case(const Case& c, vtkImageData* image, const int extent[6], int n, int reps) {
  Run one, many, warmup;
  repetition(c, image, extent, 1, warmup);
  repetition(c, image, extent, n, warmup);
  for (int r = 0; r < reps; ++r) {
    repetition(c, image, extent, 1, one);
    repetition(c, image, extent, n, many);
  }
  return {one, many};
}

std::string ms(double seconds) {
  if (std::isnan(seconds)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, seconds >= 10.0 ? "%.1f s" : "%.0f ms", seconds >= 10.0 ? seconds : 1000.0 * seconds);
  return buf;
}

void report(const Case& c, const Run& one, const Run& many, int n, int reps) {
  const StageTimes& a = one.times;
  const StageTimes& b = many.times;
  std::printf("\n## %s\n\n", c.name.c_str());
  const auto size = c.image->GetLargestPossibleRegion().GetSize();
  std::printf("Volume %lu x %lu x %lu. Smoothed meshes: contour route %zu vertices, voxel route %zu (bare %zu). "
              "Medians of %d repetitions, wall clock, process CPU time in brackets (- : not measured "
              "separately).\n\n",
              static_cast<unsigned long>(size[0]), static_cast<unsigned long>(size[1]),
              static_cast<unsigned long>(size[2]), one.contour_vertices, one.voxel_vertices, one.bare_vertices, reps);
  std::printf("| stage | 1 thread | %d threads | speed-up |\n| --- | --- | --- | --- |\n", n);
  for (const std::string& s : a.stages()) {
    std::printf("| %s | %s (%s) | %s (%s) | %.2f |\n", s.c_str(), ms(a.wall(s)).c_str(), ms(a.cpu(s)).c_str(),
                ms(b.wall(s)).c_str(), ms(b.cpu(s)).c_str(), a.wall(s) / b.wall(s));
  }
  struct Ratios {
    double tiled, whole, tiled_bare, whole_bare;
  };
  auto ratios = [](const StageTimes& t) {
    const double tiled = t.wall("segment") + t.wall("tile");
    return Ratios{tiled / (t.wall("threshold + islands/holes") + t.wall("flying edges")),
                  t.wall("contour total") / t.wall("voxel total"),
                  tiled / (t.wall("bare threshold") + t.wall("bare flying edges")),
                  t.wall("contour total") / t.wall("bare voxel total")};
  };
  const Ratios ra = ratios(a), rb = ratios(b);
  std::printf("\n| ratio | 1 thread | %d threads | target |\n| --- | --- | --- | --- |\n", n);
  std::printf("| (segment + tile) / (threshold + islands/holes + flying edges) | %.2f | %.2f | <= 2 |\n", ra.tiled,
              rb.tiled);
  std::printf("| contour route / voxel route, both smoothed | %.2f | %.2f | <= 2.5 |\n", ra.whole, rb.whole);
  std::printf("| (segment + tile) / bare (threshold + flying edges) | %.2f | %.2f | <= 2 |\n", ra.tiled_bare,
              rb.tiled_bare);
  std::printf("| contour route / bare voxel route, both smoothed | %.2f | %.2f | <= 2.5 |\n", ra.whole_bare,
              rb.whole_bare);
  std::printf("\nProcess CPU time at 1 thread (the work, whatever the machine's load): contour route / voxel "
              "route %.2f, / bare voxel route %.2f.\n",
              a.cpu("contour total") / a.cpu("voxel total"), a.cpu("contour total") / a.cpu("bare voxel total"));
  std::printf("Tiling: %.0f%% of the contour route at 1 thread, %.0f%% at %d threads.\n",
              100.0 * a.wall("tile") / a.wall("contour total"), 100.0 * b.wall("tile") / b.wall("contour total"), n);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args args = parse(argc, argv);
    const int n = args.threads > 0 ? args.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    std::printf("# Contour route against voxel route: 1 thread and %d threads (%u cores)\n", n,
                std::thread::hardware_concurrency());
    for (const Case& c : load_cases(args)) {
      // Index space scaled by the spacing, origin 0, as the harness runs flying edges.
      vtkSmartPointer<vtkImageData> image = to_image_data(c.image.GetPointer());
      image->SetOrigin(0.0, 0.0, 0.0);
      image->SetDirectionMatrix(1, 0, 0, 0, 1, 0, 0, 0, 1);
      int extent[6];
      image->GetExtent(extent);
      const auto [one, many] = run_case(c, image, extent, n, args.reps);
      report(c, one, many, n, args.reps);
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "contourmesh_route_bench: error: %s\n", e.what());
    return 2;
  }
  return 0;
}
