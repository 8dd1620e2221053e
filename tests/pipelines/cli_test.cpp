// SPDX-License-Identifier: BSD-3-Clause
// Runs the contourmesh executable as a user would and checks exit codes, JSON and outputs.
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/shapes.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <cmath>
#include <map>
#include <vector>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "cli_runner.h"
#include "test_support.h"

namespace contourmesh {
namespace {

namespace fs = std::filesystem;

using test::CliRun;

using test::run_cli;

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    input_ = dir_ / "in.vtp";
    write_mesh(test::noisy_ridge_stack(10, 60, 3.0, 2), input_);
  }
  test::ScopedTempDir tmp_{"contourmesh_cli"};
  const fs::path& dir_ = tmp_.path();
  fs::path input_;
};

TEST_F(Cli, SmoothEveryMethodWithJson) {
  for (const std::string method : {"none", "laplacian", "taubin", "mcf", "mindist", "paper", "cross-slice"}) {
    const fs::path out = dir_ / ("out_" + method + ".ply");
    const CliRun r =
        run_cli("smooth " + input_.string() + " -o " + out.string() + " --method " + method + " --json", dir_);
    ASSERT_EQ(r.code, 0) << method << ": " << r.err;
    const auto j = nlohmann::json::parse(r.out);
    for (const char* key : {"method", "iterations", "vertices", "faces", "volume_before", "volume_after", "seconds"}) {
      EXPECT_TRUE(j.contains(key)) << key;
    }
    EXPECT_EQ(j["method"], method);
    EXPECT_FALSE(j.contains("preset")) << "--method names no preset";
    // The library's default counts; none and cross-slice run no iterations.
    EXPECT_EQ(j["iterations"], method == "paper" ? 40 : (method == "none" || method == "cross-slice" ? 0 : 20));
    if (method == "paper") {
      for (const char* key : {"edge_vertices", "corner_vertices", "noise_vertices", "subdivided_vertices",
                              "adaptive_vertices", "seconds_detect", "seconds_subdivide", "seconds_smooth"}) {
        EXPECT_TRUE(j.contains(key)) << key;
      }
      EXPECT_EQ(j["id_source"], "file");
    }
    if (method == "cross-slice") {
      for (const char* key : {"edge_vertices", "corner_vertices", "noise_vertices", "profiles", "seconds_detect"}) {
        EXPECT_TRUE(j.contains(key)) << key;
      }
      EXPECT_GT(j["profiles"].get<int>(), 0);
    }
    EXPECT_EQ(j["vertices"], 600 + 120);  // 10 contours of 60, and two end-cap copies
    const Mesh result = read_mesh(out);
    EXPECT_TRUE(result.has_contour_ids()) << "PLY output keeps the contour ids";
    if (method == "none") {
      EXPECT_EQ(j["volume_before"], j["volume_after"]);
    }
    if (method == "laplacian") {
      EXPECT_LT(j["volume_after"].get<double>(), 0.97 * j["volume_before"].get<double>());
    }
  }
}

TEST_F(Cli, PaperMethodWritesLabelsAndTheAdaptiveMesh) {
  const fs::path out = dir_ / "adaptive.vtp";
  const fs::path labels = dir_ / "labels.vtp";
  CliRun r = run_cli("smooth " + input_.string() + " -o " + out.string() +
                         " --method paper --keep-adaptive --labels-out " + labels.string() + " --max-levels 2 --json",
                     dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(read_mesh(out).num_vertices(), j["adaptive_vertices"].get<int>());
  EXPECT_EQ(read_mesh(labels).num_vertices(), j["vertices"].get<int>());
  // detect gives the same labels as the paper method's detection.
  const fs::path detected = dir_ / "detected.ply";
  r = run_cli("detect " + input_.string() + " -o " + detected.string() + " --method paper --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto d = nlohmann::json::parse(r.out);
  EXPECT_EQ(d["edge_vertices"], j["edge_vertices"]);
  EXPECT_EQ(d["noise_vertices"], j["noise_vertices"]);
  EXPECT_EQ(d["mode"], "contour-continuity");
  // Labels cannot go to STL; a mesh without ids falls back to curvature-only detection, with a warning.
  EXPECT_EQ(run_cli("detect " + input_.string() + " -o " + (dir_ / "l.stl").string(), dir_).code, 2);
  const fs::path stl = dir_ / "plain.stl";
  ASSERT_EQ(run_cli("smooth " + input_.string() + " -o " + stl.string() + " --method none", dir_).code, 0);
  r = run_cli("detect " + stl.string() + " -o " + (dir_ / "l.vtp").string() + " --method paper --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["mode"], "curvature-only");
  EXPECT_NE(r.err.find("no contour ids"), std::string::npos) << r.err;
  // ... or recovers the ids from the slice planes when told the axis.
  r = run_cli("detect " + stl.string() + " -o " + (dir_ / "l.vtp").string() + " --slice-axis z --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["id_source"], "slice-planes");
  EXPECT_EQ(nlohmann::json::parse(r.out)["mode"], "creases") << "the default's labels: creases of its result";
  // detect's labels are those smooth writes with --labels-out, for the default too.
  const fs::path smoothed_labels = dir_ / "smoothed_labels.ply";
  r = run_cli("smooth " + input_.string() + " -o " + (dir_ / "s.ply").string() + " --labels-out " +
                  smoothed_labels.string() + " --json",
              dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto sj = nlohmann::json::parse(r.out);
  r = run_cli("detect " + input_.string() + " -o " + detected.string() + " --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto dj = nlohmann::json::parse(r.out);
  EXPECT_EQ(dj["edge_vertices"], sj["edge_vertices"]);
  EXPECT_EQ(dj["corner_vertices"], sj["corner_vertices"]);
}

// Without --method the default preset runs (cross-slice smoothing); --preset xu2006 is the paper's method
// with its literal settings; --method and --preset exclude each other; options that the selected method
// has no use for are errors.
TEST_F(Cli, SmoothPresetsAndTheDefault) {
  const fs::path out = dir_ / "out.ply";
  CliRun r = run_cli("smooth " + input_.string() + " -o " + out.string() + " --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["method"], "cross-slice");
  EXPECT_EQ(j["preset"], "default");
  const Mesh by_default = read_mesh(out);
  r = run_cli("smooth " + input_.string() + " -o " + out.string() + " --method cross-slice --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_mesh(out).positions, by_default.positions);

  r = run_cli("smooth " + input_.string() + " -o " + out.string() + " --preset xu2006 --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["method"], "paper");
  EXPECT_EQ(j["preset"], "xu2006");
  EXPECT_EQ(j["iterations"], 40);
  EXPECT_EQ(j["lambda"], 0.6307);

  EXPECT_EQ(
      run_cli("smooth " + input_.string() + " -o " + out.string() + " --preset xu2006 --method taubin", dir_).code, 1);
  for (const std::string& bad : {std::string("--preset slicer"), std::string("--method bilateral"),
                                 std::string("--lambda 0.5"), std::string("--max-levels 2"), std::string("--gamma 0.3"),
                                 std::string("--iterations 5"), std::string("--method taubin --max-levels 2")}) {
    r = run_cli("smooth " + input_.string() + " -o " + (dir_ / "never.ply").string() + " " + bad, dir_);
    EXPECT_EQ(r.code, 2) << bad << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "never.ply")) << bad;
  }
  // Labels from cross-slice smoothing; none from a baseline.
  const fs::path labels = dir_ / "labels.vtp";
  r = run_cli("smooth " + input_.string() + " -o " + out.string() + " --labels-out " + labels.string(), dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_mesh(labels).num_vertices(), by_default.num_vertices());
  r = run_cli("smooth " + input_.string() + " -o " + out.string() + " --method mcf --labels-out " + labels.string(),
              dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--labels-out needs a method that labels features"), std::string::npos) << r.err;
}

// `smooth --preset xu2006` on the golden mesh gives the golden labels and positions
// (tests/data/xu2006/README.md), through the file formats and the CLI.
TEST_F(Cli, PresetXu2006MatchesTheGolden) {
  const fs::path data = fs::path(CONTOURMESH_TEST_DATA) / "xu2006";
  const fs::path out = dir_ / "xu2006.ply", labels = dir_ / "xu2006_labels.vtp";
  const CliRun r = run_cli("smooth " + (data / "input.ply").string() + " -o " + out.string() + " --preset xu2006" +
                               " --labels-out " + labels.string() + " --json",
                           dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream expected(data / "expected.txt");
  std::string header;
  std::getline(expected, header);
  std::vector<int> want_labels;
  std::vector<double> want;
  int label = 0;
  double x = 0, y = 0, z = 0;
  while (expected >> label >> x >> y >> z) {
    want_labels.push_back(label);
    want.insert(want.end(), {x, y, z});
  }
  const Mesh result = read_mesh(out);
  ASSERT_EQ(static_cast<std::size_t>(result.num_vertices()), want_labels.size());
  double worst = 0.0;
  for (Index i = 0; i < result.num_vertices(); ++i) {
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(result.positions(c, i) - want[3 * i + c]));
  }
  EXPECT_LE(worst, 1e-9);
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(labels.c_str());
  reader->Update();
  vtkDataArray* array = reader->GetOutput()->GetPointData()->GetArray("FeatureLabel");
  ASSERT_NE(array, nullptr);
  ASSERT_EQ(static_cast<std::size_t>(array->GetNumberOfTuples()), want_labels.size());
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i) {
    ASSERT_EQ(static_cast<int>(array->GetComponent(i, 0)), want_labels[static_cast<std::size_t>(i)]) << "vertex " << i;
  }
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["edge_vertices"], 26);
  EXPECT_EQ(j["noise_vertices"], 103);
  EXPECT_EQ(j["iterations"], 40);
}

TEST_F(Cli, SmoothHonoursParameters) {
  const fs::path out = dir_ / "o.stl";
  const CliRun r = run_cli("smooth " + input_.string() + " -o " + out.string() +
                            " --method taubin --iterations 3 --lambda 0.5 --mu -0.53 --json",
                        dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["iterations"], 3);
  EXPECT_EQ(j["lambda"], 0.5);
  EXPECT_EQ(j["mu"], -0.53);
  EXPECT_TRUE(fs::exists(out));
}

TEST_F(Cli, BadInputExitsTwoNamingTheFileAndWritesNothing) {
  const fs::path out = dir_ / "never.stl";
  CliRun r = run_cli("smooth " + (dir_ / "absent.vtp").string() + " -o " + out.string(), dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("absent.vtp"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));

  std::ofstream(dir_ / "nan.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                     "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                     "end_header\n0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n";
  r = run_cli("smooth " + (dir_ / "nan.ply").string() + " -o " + out.string(), dir_);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("non-finite"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));

  r = run_cli("smooth " + input_.string() + " -o " + (dir_ / "missing_dir" / "x.stl").string(), dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("does not exist"), std::string::npos) << r.err;

  // (--method taubin: the default, cross-slice smoothing, has no step factor.)
  r = run_cli("smooth " + input_.string() + " -o " + out.string() + " --method taubin --lambda 3", dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("lambda"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, UsageErrorsExitOne) {
  EXPECT_EQ(run_cli("smooth", dir_).code, 1);
  EXPECT_EQ(run_cli("frobnicate", dir_).code, 1);
  EXPECT_EQ(run_cli("smooth " + input_.string() + " -o x.stl --iterations many", dir_).code, 1);
  const CliRun help = run_cli("smooth --help", dir_);
  EXPECT_EQ(help.code, 0);
  for (const char* option : {"--method", "--preset", "--iterations", "--lambda", "--mu", "--beta", "--json", "--output",
                             "--gamma", "--delta", "--max-levels", "--keep-adaptive", "--labels-out", "--slice-axis"}) {
    EXPECT_NE(help.out.find(option), std::string::npos) << option;
  }
}

TEST_F(Cli, PhantomThenReconstructGivesAClosedMeshWithIds) {
  const fs::path volume = dir_ / "branch.nrrd";
  CliRun r = run_cli("phantom --shape branch -o " + volume.string() + " --spacing 0.8,0.8,2 --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["shape"], "branch");
  const fs::path mesh = dir_ / "branch.vtp";
  r = run_cli("reconstruct " + volume.string() + " -o " + mesh.string() + " --threshold 520 --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  for (const char* key : {"slices", "contours", "vertices", "faces", "components", "is_closed", "is_manifold",
                          "euler_characteristic", "volume", "seconds"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_TRUE(j["is_closed"].get<bool>());
  EXPECT_TRUE(j["is_manifold"].get<bool>());
  EXPECT_EQ(j["components"], 1);
  EXPECT_EQ(j["euler_characteristic"], 2);
  EXPECT_GE(j["branchings"].get<int>(), 1);
  const Mesh m = read_mesh(mesh);
  EXPECT_TRUE(m.has_contour_ids());
  EXPECT_EQ(m.num_vertices(), j["vertices"].get<int>());
}

// The tiling options reach the tiler on the volume route and on the contour route, and bad values are
// refused with exit code 2 naming the option.
TEST_F(Cli, TilingOptionsReachTheTilerOnBothRoutes) {
  const fs::path volume = dir_ / "branch.nrrd", contours = dir_ / "branch.json";
  ASSERT_EQ(run_cli("phantom --shape branch -o " + volume.string() + " --spacing 1,1,2.5 -q", dir_).code, 0);
  auto vertices = [&](const fs::path& input, const std::string& options) {
    const CliRun r =
        run_cli("reconstruct " + input.string() + " -o " + (dir_ / "out.vtp").string() + " --json " + options, dir_);
    EXPECT_EQ(r.code, 0) << options << ": " << r.err;
    return r.code == 0 ? nlohmann::json::parse(r.out)["vertices"].get<long>() : -1L;
  };
  const long interpolated = vertices(volume, "--threshold 520 --contours-out " + contours.string());
  EXPECT_NE(vertices(volume, "--threshold 520 --band-refinement none"), interpolated);
  EXPECT_NE(vertices(volume, "--threshold 520 --cap-refinement ear-clipping"), interpolated);
  const long drawn = vertices(contours, "");
  EXPECT_NE(vertices(contours, "--branching mid-plane"), drawn);
  EXPECT_NE(vertices(contours, "--max-band-aspect 1"), drawn);
  for (const std::string bad : {"--band-refinement some", "--max-band-aspect 0", "--interpolation-grid 2",
                                "--min-overlap-of-larger 1", "--cap-refinement none"}) {
    const CliRun r = run_cli("reconstruct " + volume.string() + " -o " + (dir_ / "bad.vtp").string() + " " + bad, dir_);
    EXPECT_EQ(r.code, 2) << bad;
    EXPECT_NE(r.err.find(bad.substr(0, bad.find(' '))), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad.vtp"));
  }
}

// --single-slice applies to volumes: the diploe phantom's cavities that one slice alone sees are hollow
// slabs by default and left out with `drop`; a bad value exits 2 naming the option, writing nothing.
TEST_F(Cli, SingleSliceReachesTheVolumeRoute) {
  const fs::path volume = dir_ / "diploe.nrrd";
  ASSERT_EQ(run_cli("phantom --shape skull-diploe -o " + volume.string() + " -q", dir_).code, 0);
  auto report = [&](const std::string& options) {
    const CliRun r = run_cli(
        "reconstruct " + volume.string() + " --threshold 520 -o " + (dir_ / "out.vtp").string() + " --json " + options,
        dir_);
    EXPECT_EQ(r.code, 0) << options << ": " << r.err;
    return r.code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json{};
  };
  const auto kept = report(""), dropped = report("--single-slice drop");
  ASSERT_FALSE(kept.is_null() || dropped.is_null());
  EXPECT_GT(kept["single_slice_cavities"].get<int>(), 50);
  EXPECT_EQ(dropped["single_slice_cavities"].get<int>(), 0);
  // Dropped, every contour of one slice is either a hole filled or left out (with the holes inside it).
  EXPECT_EQ(dropped["single_slice_filled"].get<int>() + dropped["single_slice_left_out"].get<int>(),
            dropped["dropped_contours"].get<int>());
  EXPECT_EQ(kept["dropped_contours"], dropped["dropped_contours"]);
  EXPECT_GT(kept["components"].get<int>(), dropped["components"].get<int>() + 50);
  const CliRun bad =
      run_cli("reconstruct " + volume.string() + " -o " + (dir_ / "bad.vtp").string() + " --single-slice keep", dir_);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--single-slice"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ / "bad.vtp"));
}

// --contour-noise reaches the volume on phantom and run, is range-checked (exit 2), and is refused
// next to an input volume (exit 1), which it could not change.
TEST_F(Cli, ContourNoiseOption) {
  const fs::path clean = dir_ / "clean.mha", noisy = dir_ / "noisy.mha";
  const std::string common = " --shape ridge-box --spacing 1.5,1.5,3 --noise 0 --blur 0 --json";
  ASSERT_EQ(run_cli("phantom -o " + clean.string() + common, dir_).code, 0);
  const CliRun r = run_cli("phantom -o " + noisy.string() + common + " --contour-noise 0.5", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["contour_noise"], 0.5);
  std::ifstream a(clean, std::ios::binary), b(noisy, std::ios::binary);
  const std::string bytes_a((std::istreambuf_iterator<char>(a)), {}), bytes_b((std::istreambuf_iterator<char>(b)), {});
  EXPECT_NE(bytes_a, bytes_b);
  for (const char* bad : {"-0.1", "11", "nan"}) {
    const CliRun e = run_cli("phantom -o " + noisy.string() + common + " --contour-noise " + bad, dir_);
    EXPECT_EQ(e.code, 2) << bad;
    EXPECT_NE(e.err.find("--contour-noise"), std::string::npos) << e.err;
  }
  const CliRun run = run_cli("run -o " + (dir_ / "box.stl").string() +
                                 " --shape ridge-box --spacing 1.5,1.5,3 --contour-noise 0.4 --method none",
                             dir_);
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_NE(run.out.find("0.4 mm contour noise"), std::string::npos) << run.out;
  EXPECT_EQ(run_cli("run " + clean.string() + " -o x.stl --contour-noise 0.4", dir_).code, 1);
  EXPECT_EQ(run_cli("compare " + clean.string() + " --out cmp --contour-noise 0.4", dir_).code, 1);
}

TEST_F(Cli, ReconstructRejectsBadVolumesWithExitTwo) {
  std::ofstream(dir_ / "junk.mha") << "this is not an image";
  const fs::path out = dir_ / "out.vtp";
  CliRun r = run_cli("reconstruct " + (dir_ / "junk.mha").string() + " -o " + out.string(), dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("junk.mha"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  // A volume with nothing above the threshold.
  const fs::path air = dir_ / "cube.mha";
  ASSERT_EQ(run_cli("phantom --shape ridge-box -o " + air.string() + " --spacing 2,2,4", dir_).code, 0);
  r = run_cli("reconstruct " + air.string() + " -o " + out.string() + " --threshold 5000", dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("no region at or above the threshold 5000"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  r = run_cli("phantom --shape banana -o " + air.string(), dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("banana"), std::string::npos) << r.err;
}

TEST_F(Cli, RunWithNoInputIsTheWholePipelineOnAPhantom) {
  const fs::path out = dir_ / "femur.stl";
  const CliRun r = run_cli("run -o " + out.string() + " --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["is_closed"].get<bool>());
  EXPECT_TRUE(j["is_manifold"].get<bool>());
  EXPECT_EQ(j["components"], 1);
  // The default preset: cross-slice smoothing (it detects, but does not subdivide).
  EXPECT_EQ(j["method"], "cross-slice");
  EXPECT_EQ(j["preset"], "default");
  EXPECT_GT(j["edge_vertices"].get<int>(), 0);
  EXPECT_LT(std::abs(j["volume_change_percent"].get<double>()), 3.0);
  EXPECT_LT(j["rms_distance_after"].get<double>(), 0.5) << "mm from the analytic femur";
  // Measured over the surfaces, as compare does: the default does no harm to the distance (the
  // do-no-harm bar, 1.05 x + 0.01 mm) and lowers the normal error.
  const double before = j["surface_rms_before"].get<double>();
  EXPECT_GT(before, 0.0);
  EXPECT_LE(j["surface_rms_after"].get<double>(), 1.05 * before + 0.01);
  EXPECT_LT(j["normal_error_degrees_after"].get<double>(), j["normal_error_degrees_before"].get<double>());
  EXPECT_TRUE(std::isfinite(j["surface_feature_rms_after"].get<double>()));
  for (const char* key : {"seconds_segment", "seconds_tile", "seconds_detect", "seconds_smooth"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  const Mesh m = read_mesh(out);
  EXPECT_EQ(m.num_vertices(), j["vertices"].get<int>());
  EXPECT_TRUE(build_adjacency(m).is_closed());
  const CliRun human = run_cli("run -o " + out.string() + " --shape ridge-box --method taubin", dir_);
  EXPECT_EQ(human.code, 0) << human.err;
  EXPECT_NE(human.out.find("wrote"), std::string::npos);
  EXPECT_NE(human.out.find("accuracy"), std::string::npos);
}

TEST_F(Cli, RunOnARealScan) {
  const fs::path scan = fs::path(CONTOURMESH_SHARED_DATA) / "totalsegmentator_ct" / "example_ct_sm.nii.gz";
  if (!fs::exists(scan)) GTEST_SKIP() << "no " << scan;
  const fs::path out = dir_ / "pelvis.stl";
  const CliRun r = run_cli("run " + scan.string() + " -o " + out.string() + " --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["is_closed"].get<bool>());
  EXPECT_TRUE(j["is_manifold"].get<bool>());
  EXPECT_FALSE(j.contains("rms_distance_after"));  // no truth for a real scan
  // 3 mm pixels: contours sampled at the pixel spacing lost a third of the volume under smoothing.
  EXPECT_LT(std::abs(j["volume_change_percent"].get<double>()), 10.0);
  EXPECT_TRUE(fs::exists(out));
}

// run: --format overrides the extension, --labels-out writes the detection on the reconstructed mesh.
TEST_F(Cli, RunFormatOverrideAndLabelsOut) {
  const fs::path out = dir_ / "ridge.mesh";
  const fs::path labels = dir_ / "labels.vtp";
  const CliRun r = run_cli("run --shape ridge-box --spacing 1.4,1.4,3 --format ply -o " + out.string() +
                               " --labels-out " + labels.string() + " --json",
                           dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  std::ifstream in(out, std::ios::binary);
  std::string magic(3, '\0');
  in.read(magic.data(), 3);
  EXPECT_EQ(magic, "ply") << "--format ply wins over the unknown extension";
  const Mesh m = read_mesh(labels);
  EXPECT_TRUE(m.has_contour_ids());
  EXPECT_EQ(j["labels_out"].get<std::string>(), labels.string());
  EXPECT_GT(j["edge_vertices"].get<int>(), 0);

  // --labels-out with a baseline method is a usage problem, caught before any work or output.
  const fs::path out2 = dir_ / "taubin.stl";
  const CliRun bad = run_cli("run --method taubin -o " + out2.string() + " --labels-out " + labels.string(), dir_);
  EXPECT_EQ(bad.code, 2) << bad.err;
  EXPECT_NE(bad.err.find("--labels-out needs a method that labels features"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(out2));
}

// run --creases restore: the ridge box's creases restored on a refined mesh, closer to the truth in the
// feature region than without; the labels stay one per reconstructed vertex; other methods refuse it.
TEST_F(Cli, RunCreasesRestoreRefinesAndSharpensTheRidgeBox) {
  const auto run = [&](const std::string& extra, const fs::path& out, const fs::path& labels) {
    const CliRun r = run_cli(
        "run --shape ridge-box -o " + out.string() + " --labels-out " + labels.string() + " --json " + extra, dir_);
    EXPECT_EQ(r.code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const auto plain = run("", dir_ / "plain.vtp", dir_ / "plain_labels.vtp");
  const auto restored = run("--creases restore", dir_ / "restored.vtp", dir_ / "restored_labels.vtp");
  EXPECT_GT(restored["vertices"].get<int>(), plain["vertices"].get<int>());
  EXPECT_EQ(read_mesh(dir_ / "restored.vtp").num_vertices(), restored["vertices"].get<int>());
  EXPECT_EQ(read_mesh(dir_ / "restored_labels.vtp").num_vertices(),
            read_mesh(dir_ / "plain_labels.vtp").num_vertices());
  EXPECT_TRUE(restored["is_closed"].get<bool>());
  EXPECT_TRUE(restored["is_manifold"].get<bool>());
  EXPECT_LT(restored["surface_feature_rms_after"].get<double>(),
            0.9 * plain["surface_feature_rms_after"].get<double>());
  const fs::path out = dir_ / "refused.stl";
  EXPECT_EQ(run_cli("run --method taubin --creases restore -o " + out.string(), dir_).code, 2);
  EXPECT_EQ(run_cli("run --creases sharp -o " + out.string(), dir_).code, 2);
  EXPECT_FALSE(fs::exists(out));
}

// Off a terminal (here stderr is a file) progress is one line per finished stage; --quiet silences it
// and the summary; --threads is validated.
TEST_F(Cli, ProgressIsOneLinePerStageOffATerminalAndQuietSilencesIt) {
  const fs::path out = dir_ / "femur.stl";
  const std::string coarse = " --spacing 1.4,1.4,3 -o " + out.string();
  const CliRun r = run_cli("run" + coarse, dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  // The default method, cross-slice smoothing, has no subdivision stage.
  for (const char* stage : {"phantom", "segment", "tile", "detect", "smooth", "write"}) {
    EXPECT_NE(r.err.find(std::string("contourmesh run: ") + stage), std::string::npos) << stage << " in\n" << r.err;
  }
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << "no bar redraws off a terminal";
  EXPECT_NE(r.out.find("wrote"), std::string::npos);

  const CliRun quiet = run_cli("run --quiet --threads 1" + coarse, dir_);
  ASSERT_EQ(quiet.code, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
  EXPECT_EQ(quiet.out, "");
  EXPECT_TRUE(fs::exists(out));

  const CliRun bad = run_cli("run --threads -2" + coarse, dir_);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--threads"), std::string::npos) << bad.err;
}

// Every subcommand's --help lists each of its options, and --version names the program.
TEST_F(Cli, HelpListsEveryOptionOfEverySubcommand) {
  const std::map<std::string, std::vector<std::string>> options = {
      {"phantom", {"--shape", "--spacing", "--noise", "--blur", "--seed", "--json"}},
      {"reconstruct",
       {"--threshold", "--otsu", "--end-caps", "--branching", "--band-refinement", "--full-dp-limit",
        "--min-overlap-of-larger", "--keep", "--fill-holes", "--json", "--quiet", "--threads", "--roi",
        "--contours-out", "--sampling", "--slab-thickness", "--align", "--single-slice"}},
      {"contours", {"--list", "--roi", "--output", "--json", "--planarity-tolerance"}},
      {"detect",
       {"--method", "--preset", "--gamma", "--delta", "--measure", "--in-slice", "--prefilter", "--window",
        "--corner-spread", "--slice-axis", "--json"}},
      {"smooth",
       {"--method", "--preset", "--iterations", "--gamma", "--delta", "--max-levels", "--keep-adaptive", "--labels-out",
        "--in-slice", "--creases", "--json", "--quiet", "--threads"}},
      {"run",
       {"--shape", "--noise", "--method", "--preset", "--iterations", "--threshold", "--end-caps", "--branching",
        "--max-band-aspect", "--interpolation-grid", "--in-slice", "--measure", "--json", "--quiet", "--threads",
        "--roi", "--sampling", "--slab-thickness", "--creases"}},
  };
  for (const auto& [command, names] : options) {
    const CliRun r = run_cli(command + " --help", dir_);
    EXPECT_EQ(r.code, 0) << command;
    for (const std::string& name : names) EXPECT_NE(r.out.find(name), std::string::npos) << command << " " << name;
  }
  const CliRun v = run_cli("--version", dir_);
  EXPECT_EQ(v.code, 0);
  EXPECT_NE(v.out.find("contourmesh "), std::string::npos) << v.out;
}

}  // namespace
}  // namespace contourmesh
