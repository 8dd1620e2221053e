// SPDX-License-Identifier: BSD-3-Clause
// Diverging runs, inconsistent meshes, failed writes, signals and resource limits (docs/robustness.md):
// none may end with exit status 0 and a wrong or half-written file.
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/vtk/vtkContourFeatureSmoothingFilter.h>
#include <contourmesh/vtk/vtk_convert.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/metrics.h>

#include "cli_runner.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace contourmesh {
namespace {

namespace fs = std::filesystem;

class DamagedOutput : public ::testing::Test {
 protected:
  void SetUp() override {
    stack_ = test::noisy_ridge_stack(8, 40, 2.0, 5);
    write_mesh(stack_, input_);
  }
  test::CliRun run(const std::string& args, const std::string& prefix = "") const {
    return test::run_cli(CONTOURMESH_CLI, args, dir_, prefix);
  }
  fs::path write_text(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
  static nlohmann::json json_of(const test::CliRun& r) {
    try {
      return nlohmann::json::parse(r.out);
    } catch (const std::exception&) {
      ADD_FAILURE() << "no JSON on stdout: " << r.out << r.err;
      return nlohmann::json::object();
    }
  }

  test::ScopedTempDir tmp_{"contourmesh_damaged_output"};
  const fs::path& dir_ = tmp_.path();
  const fs::path input_ = dir_ / "stack.ply";
  Mesh stack_;
};

// ----- Non-finite and diverged results ----------------------------------------------------------------

TEST_F(DamagedOutput, AMillionIterationsIsADivergenceErrorNotANaNMesh) {
  const fs::path out = dir_ / "out.stl";
  for (const std::string method : {"paper", "taubin"}) {
    test::expect_rejected(run("smooth " + input_.string() + " -o " + out.string() + " --method " + method +
                              " --iterations 1000000 --json"),
                          {input_.string() + ": smoothing diverged at iteration"});
    EXPECT_FALSE(fs::exists(out)) << method;
  }
}

TEST_F(DamagedOutput, CoordinatesWhoseCubesOverflowAreRefused) {
  Mesh huge = stack_;
  huge.positions(0, 5) = 1e200;  // volumes and areas would be inf, then NaN
  write_mesh(huge, dir_ / "huge.ply");
  test::expect_rejected(run("smooth " + (dir_ / "huge.ply").string() + " -o " + (dir_ / "out.ply").string()),
                        {"huge.ply: vertex 5 has a coordinate beyond +-1e30"});
}

TEST_F(DamagedOutput, CoordinatesBeyondFloatRangeNeverReachAnStl) {
  Mesh big = stack_;
  big.positions(1, 7) = 1e39;  // above FLT_MAX: an STL would hold inf
  for (const MeshFormat format : {MeshFormat::StlBinary, MeshFormat::StlAscii}) {
    const fs::path out = dir_ / "big.stl";
    try {
      write_mesh(big, out, {format, {}, {}, {}});
      ADD_FAILURE() << "written";
    } catch (const InvalidInputError& e) {
      EXPECT_NE(std::string(e.what()).find("big.stl: vertex 7 has coordinate 1e+39, beyond the range of the 32-bit "
                                           "floats that STL stores"),
                std::string::npos)
          << e.what();
    }
    EXPECT_FALSE(fs::exists(out));
  }
  write_mesh(big, dir_ / "big.ply");  // PLY stores doubles
  test::expect_rejected(run("smooth " + (dir_ / "big.ply").string() + " -o " + (dir_ / "out.stl").string() +
                            " --method none"),
                        {"big.ply: vertex 7 has a coordinate beyond +-1e30"});
}

// ----- Inconsistent input meshes ----------------------------------------------------------------------

TEST_F(DamagedOutput, HalfTheTrianglesFlippedAreTurnedBackWithAWarning) {
  const test::CliRun clean = run("detect " + input_.string() + " -o " + (dir_ / "clean.ply").string() + " --json");
  ASSERT_EQ(clean.code, 0) << clean.err;
  Mesh flipped = stack_;
  for (std::size_t f = 0; f < flipped.triangles.size(); f += 2)
    std::swap(flipped.triangles[f][1], flipped.triangles[f][2]);
  write_mesh(flipped, dir_ / "flipped.ply");
  const test::CliRun r = run("smooth " + (dir_ / "flipped.ply").string() + " -o " + (dir_ / "out.ply").string() +
                             " --method none --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("flipped.ply: repaired: turned over"), std::string::npos) << r.err;
  EXPECT_NEAR(json_of(r)["volume_before"].get<double>(), enclosed_volume(stack_), 1e-9 * enclosed_volume(stack_));
  const test::CliRun d =
      run("detect " + (dir_ / "flipped.ply").string() + " -o " + (dir_ / "labels.ply").string() + " --json");
  ASSERT_EQ(d.code, 0) << d.err;
  EXPECT_EQ(json_of(d)["edge_vertices"], json_of(clean)["edge_vertices"]) << "the same features as the clean mesh";
}

TEST_F(DamagedOutput, IdsAllEqualAcrossManyPlanesAreRefusedOrRecoveredAlongTheGivenAxis) {
  Mesh same = stack_;
  std::fill(same.slice_ids.begin(), same.slice_ids.end(), 0);
  std::fill(same.contour_ids.begin(), same.contour_ids.end(), 0);
  write_mesh(same, dir_ / "same.ply");
  const std::string labels = (dir_ / "labels.ply").string();
  test::expect_rejected(run("detect " + (dir_ / "same.ply").string() + " -o " + labels),
                        {"same.ply: every vertex has slice id 0, but the vertices do not lie in one plane",
                         "give --slice-axis"});
  const test::CliRun r = run("detect " + (dir_ / "same.ply").string() + " -o " + labels + " --slice-axis z --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(json_of(r)["id_source"], "slice-planes");
  EXPECT_NE(r.err.find("recovered the ids from the slice planes along z"), std::string::npos) << r.err;
}

TEST_F(DamagedOutput, IdsOfMinusOneAndBelowAreNamedWithTheFile) {
  Mesh none = stack_;
  std::fill(none.slice_ids.begin(), none.slice_ids.end(), kNoId);
  std::fill(none.contour_ids.begin(), none.contour_ids.end(), kNoId);
  write_mesh(none, dir_ / "none.ply");
  // The paper's method falls back to curvature-only detection; the default, cross-slice smoothing,
  // cannot do without ids and says how to recover them.
  const test::CliRun r = run("smooth " + (dir_ / "none.ply").string() + " -o " + (dir_ / "out.ply").string() +
                             " --method paper --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("none.ply: every slice id is -1"), std::string::npos) << r.err;
  EXPECT_EQ(json_of(r)["id_source"], "none");
  test::expect_rejected(run("smooth " + (dir_ / "none.ply").string() + " -o " + (dir_ / "out.ply").string()),
                        {"none.ply: the mesh has no contour ids", "give --slice-axis"});
  Mesh below = stack_;
  below.slice_ids[9] = -2;
  write_mesh(below, dir_ / "below.ply");
  test::expect_rejected(run("smooth " + (dir_ / "below.ply").string() + " -o " + (dir_ / "out.ply").string()),
                        {"below.ply: vertex 9 has slice id -2", "ids are >= 0, or -1"});
}

// The CLI and vtkContourFeatureSmoothingFilter run one input policy: the same result on a dirty mesh.
TEST_F(DamagedOutput, TheCliAndTheVtkFilterAgreeOnADirtyMesh) {
  Mesh dirty = stack_;
  for (auto& s : dirty.slice_ids) s += s >= 4 ? 2 : 0;  // a gap in the slice ids
  dirty.slice_ids[3] = kNoId;                            // a vertex off the slices
  dirty.contour_ids[3] = kNoId;
  for (std::size_t f = 1; f < dirty.triangles.size(); f += 3) std::swap(dirty.triangles[f][1], dirty.triangles[f][2]);
  {  // a duplicated vertex: triangle 10 uses a copy of its first corner
    const Index copy = dirty.num_vertices();
    const Index v = dirty.triangles[10][0];
    dirty.positions.conservativeResize(3, copy + 1);
    dirty.positions.col(copy) = dirty.positions.col(v);
    dirty.slice_ids.push_back(dirty.slice_ids[v]);
    dirty.contour_ids.push_back(dirty.contour_ids[v]);
    dirty.triangles[10][0] = copy;
  }
  const fs::path in = dir_ / "dirty.vtp";
  const fs::path cli_out = dir_ / "cli.vtp";
  write_mesh(dirty, in);
  const test::CliRun r = run("smooth " + in.string() + " -o " + cli_out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("merged 1 coincident vertex"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("turned over"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("skip 2 unused values"), std::string::npos) << r.err;

  auto run_filter = [&](const fs::path& file, std::string& errors) {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(file.c_str());
    vtkNew<vtkContourFeatureSmoothingFilter> filter;
    filter->SetInputConnection(reader->GetOutputPort());
    vtkNew<vtkCallbackCommand> observer;
    observer->SetClientData(&errors);
    observer->SetCallback([](vtkObject*, unsigned long, void* client, void* data) {
      *static_cast<std::string*>(client) += static_cast<const char*>(data);
    });
    filter->AddObserver(vtkCommand::ErrorEvent, observer);
    filter->AddObserver(vtkCommand::WarningEvent, vtkNew<vtkCallbackCommand>());
    filter->Update();
    return from_polydata(filter->GetOutput());
  };
  std::string errors;
  const Mesh filtered = run_filter(in, errors);
  EXPECT_EQ(errors, "");
  const Mesh cli = read_mesh(cli_out);
  ASSERT_EQ(filtered.num_vertices(), cli.num_vertices());
  EXPECT_EQ(filtered.triangles, cli.triangles);
  EXPECT_LE((filtered.positions - cli.positions).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(filtered.slice_ids, cli.slice_ids);

  // Ids below -1: both refuse, with the same words.
  dirty.slice_ids[20] = -7;
  write_mesh(dirty, in);
  test::expect_rejected(run("smooth " + in.string() + " -o " + cli_out.string()),
                        {"dirty.vtp: vertex 20 has slice id -7"});
  errors.clear();
  EXPECT_EQ(run_filter(in, errors).num_vertices(), 0);
  EXPECT_NE(errors.find("input: vertex 20 has slice id -7"), std::string::npos) << "[" << errors << "]";
}

// ----- Writes -----------------------------------------------------------------------------------------

TEST_F(DamagedOutput, DevicesAndFifosAreNeverReplaced) {
  const fs::path fifo = dir_ / "fifo.stl";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  test::expect_rejected(run("smooth " + input_.string() + " -o " + fifo.string() + " --method none"),
                        {fifo.string() + ": cannot write: it is a FIFO, not a regular file"});
  EXPECT_TRUE(fs::is_fifo(fifo));
  // A character device, as /dev/null is (root may create one; else the FIFO above stands for both).
  const fs::path device = dir_ / "null.stl";
  if (::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) {
    test::expect_rejected(run("smooth " + input_.string() + " -o " + device.string() + " --method none"),
                          {"cannot write: it is a character device, not a regular file"});
    EXPECT_TRUE(fs::is_character_file(device));
  }
  test::expect_no_temporaries(dir_);
}

TEST_F(DamagedOutput, ASymlinkedOutputIsWrittenThrough) {
  fs::create_directories(dir_ / "real");
  const fs::path target = dir_ / "real" / "mesh.stl";
  std::ofstream(target) << "old";
  const fs::path link = dir_ / "link.stl";
  fs::create_symlink(target, link);
  const test::CliRun r = run("smooth " + input_.string() + " -o " + link.string() + " --method none");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(link)) << "the link stays a link";
  EXPECT_EQ(read_mesh(target).num_faces(), stack_.num_faces()) << "its target holds the mesh";
  // A dangling link: its target is created.
  const fs::path dangling = dir_ / "dangling.ply";
  fs::create_symlink(dir_ / "real" / "new.ply", dangling);
  ASSERT_EQ(run("smooth " + input_.string() + " -o " + dangling.string() + " --method none").code, 0);
  EXPECT_TRUE(fs::is_symlink(dangling));
  EXPECT_TRUE(fs::is_regular_file(dir_ / "real" / "new.ply"));
}

TEST_F(DamagedOutput, TheDataReachTheDiskBeforeTheRename) {
  if (std::system("command -v strace >/dev/null 2>&1") != 0) GTEST_SKIP() << "strace is not installed";
  const fs::path out = dir_ / "out.stl";
  const fs::path trace = dir_ / "trace.txt";
  const test::CliRun r = run(
      "smooth " + input_.string() + " -o " + out.string() + " --method none",
      // LeakSanitizer cannot run under ptrace (the asan build)
      "ASAN_OPTIONS=detect_leaks=0 strace -f -e trace=fsync,fdatasync,rename,renameat,renameat2 -o " + trace.string());
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(trace);
  bool synced = false, renamed_after_sync = false;
  for (std::string line; std::getline(in, line);) {
    if (line.find("fsync(") != std::string::npos || line.find("fdatasync(") != std::string::npos) synced = true;
    if (line.find("rename") != std::string::npos && line.find("out.stl") != std::string::npos) {
      renamed_after_sync = synced;
    }
  }
  EXPECT_TRUE(renamed_after_sync) << test::read_bytes(trace);
}

TEST_F(DamagedOutput, AFullDiskFailsEveryWriterAndKeepsTheOldFile) {
  // A file size limit of 4 blocks makes every write beyond it fail (EFBIG), as a full disk does.
  const std::string limit = "trap \"\" XFSZ; ulimit -f 4;";
  for (const std::string ext : {"stl", "obj", "ply", "vtp"}) {
    const fs::path out = write_text("precious." + ext, "precious");
    test::expect_rejected(run("smooth " + input_.string() + " -o " + out.string() + " --method none", limit),
                          {out.string() + ": cannot write"});
    EXPECT_EQ(test::read_bytes(out), "precious") << ext;
  }
  for (const std::string ext : {"mha", "nii", "nii.gz"}) {
    const fs::path out = write_text("precious." + ext, "precious");
    test::expect_rejected(run("phantom --shape ridge-box --spacing 1,1,2 -o " + out.string(), limit),
                          {out.string() + ": cannot write"});
    EXPECT_EQ(test::read_bytes(out), "precious") << ext;
  }
  test::expect_no_temporaries(dir_);
}

// Starts the CLI, waits until its smoothing stage runs, sends `signal`, returns the exit status.
int interrupted_exit_code(const std::vector<std::string>& args, const fs::path& err_file, int signal) {
  std::vector<char*> argv;
  const char* other = std::getenv("CONTOURMESH_TEST_CLI");
  const std::string cli = other != nullptr && *other != '\0' ? other : CONTOURMESH_CLI;
  std::vector<std::string> all = {cli};
  all.insert(all.end(), args.begin(), args.end());
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  if (posix_spawn(&pid, cli.c_str(), &actions, nullptr, argv.data(), environ) != 0) return -1;
  posix_spawn_file_actions_destroy(&actions);
  // "read done" is printed when the next stage starts.
  for (int k = 0; k < 200 && test::read_bytes(err_file).find("read ") == std::string::npos; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  ::kill(pid, signal);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
}

TEST_F(DamagedOutput, SigintAndSigtermCancelCleanlyWithTheirExitCodes) {
  const fs::path out = write_text("precious.stl", "precious");
  const fs::path err = dir_ / "interrupted.txt";
  // Laplacian smoothing converges: a hundred million iterations run until the signal.
  const std::vector<std::string> args = {"smooth", input_.string(), "-o", out.string(), "--method", "laplacian",
                                         "--iterations", "100000000"};
  EXPECT_EQ(interrupted_exit_code(args, err, SIGINT), 130) << test::read_bytes(err);
  EXPECT_NE(test::read_bytes(err).find("cancelled by SIGINT"), std::string::npos) << test::read_bytes(err);
  EXPECT_EQ(interrupted_exit_code(args, err, SIGTERM), 143) << test::read_bytes(err);
  EXPECT_EQ(test::read_bytes(out), "precious");
  fs::remove(err);
  test::expect_no_temporaries(dir_);
}

TEST_F(DamagedOutput, AnOutputNameOf249CharactersWorks) {
  const std::string name(245, 'n');
  const test::CliRun r =
      run("smooth " + input_.string() + " -o " + (dir_ / (name + ".stl")).string() + " --method none");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / (name + ".stl")));
  const test::CliRun p = run("phantom --shape ridge-box --spacing 2,2,3 -o " + (dir_ / (name + ".mha")).string());
  EXPECT_EQ(p.code, 0) << p.err;
  EXPECT_TRUE(fs::exists(dir_ / (name + ".mha")));
}

TEST_F(DamagedOutput, TwoOutputsNamingOneFileAreRefused) {
  const fs::path out = dir_ / "out.vtp";
  fs::create_symlink(out, dir_ / "alias.vtp");
  for (const std::string& labels : {out.string(), (dir_ / "." / "out.vtp").string(), (dir_ / "alias.vtp").string()}) {
    test::expect_rejected(run("smooth " + input_.string() + " -o " + out.string() + " --labels-out " + labels),
                          {"-o and --labels-out name the same file"});
  }
  test::expect_rejected(run("run --shape ridge-box --spacing 2,2,4 -o " + out.string() + " --labels-out " +
                            out.string()),
                        {"name the same file"});
  EXPECT_FALSE(fs::exists(out));
}

// ----- Resources ---------------------------------------------------------------------------------------

TEST_F(DamagedOutput, AContourSamplingBeyondTheLimitsIsRefusedBeforeResampling) {
  const fs::path volume = dir_ / "v.mha";
  ASSERT_EQ(run("phantom --shape ridge-box --spacing 2,2,4 -o " + volume.string()).code, 0);
  test::expect_rejected(run("reconstruct " + volume.string() + " -o " + (dir_ / "out.vtp").string() +
                            " --sampling 0.001 --max-vertices 100000"),
                        {"contour resampling at 0.001 mm", "exceed the limit of 100000 vertices",
                         "raise it with --max-vertices"});
  test::expect_rejected(run("reconstruct " + volume.string() + " -o " + (dir_ / "out.vtp").string() +
                            " --sampling 1e-6"),
                        {"contour resampling at 1e-06 mm"});
}

TEST_F(DamagedOutput, MoreThreadsThanItkCanRunAreRefused) {
  test::expect_rejected(run("smooth " + input_.string() + " -o " + (dir_ / "out.ply").string() + " --threads 100000"),
                        {"--threads 100000: more than the", "worker threads ITK can run"});
}

}  // namespace
}  // namespace contourmesh
