// SPDX-License-Identifier: BSD-3-Clause
// The bad-input catalogue of docs/robustness.md, one test per entry: the contourmesh command run as a
// user runs it, on files written here. A rejected input exits 2 with one line on stderr naming the file
// and what is wrong, and leaves no output behind (an existing output untouched); a repaired input exits
// 0 with a warning.
// This part: volumes, DICOM series, outputs that cannot be written, and size limits.
// The support header first: it includes ITK, whose bundled Eigen must not follow the system one.
#include "bad_input_support.h"

#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/reconstruct/volume.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace contourmesh {
namespace {

using namespace bad_input_test;

// ----- Volumes ---------------------------------------------------------------------------------------

TEST_F(BadInput, VolumeWithOneSlice) {
  const fs::path out = dir_ / "out.vtp";
  const fs::path one = write_volume_file("one.mha", {16, 16, 1}, {1, 1, 1}, [](int i, int j, int) {
    return (i - 8) * (i - 8) + (j - 8) * (j - 8) < 25 ? 1000.0f : -1000.0f;
  });
  expect_rejected(run("reconstruct " + one.string() + " -o " + out.string()), {one.string(), "a single 2-D slice"});
  expect_rejected(run("run " + one.string() + " -o " + out.string()), {one.string(), "a single 2-D slice"});
  write_dicom_series(dir_ / "dicom1", "1.2.826.0.1.3680043.2.1125.71", 1);
  expect_rejected(run("reconstruct " + (dir_ / "dicom1").string() + " -o " + out.string()),
                  {"dicom1", "the DICOM series has 1 slice; a 3-D volume needs at least 2"});
  expect_nothing_written(out);
}

TEST_F(BadInput, AllAirAndAllBoneVolumes) {
  const fs::path out = dir_ / "out.vtp";
  const fs::path air = write_volume_file("air.mha", {12, 12, 4}, {1, 1, 1}, [](int, int, int) { return -1000.0f; });
  expect_rejected(run("reconstruct " + air.string() + " -o " + out.string()),
                  {air.string(), "no region at or above the threshold 300 in any of the 4 slices (all air"});
  const fs::path bone = write_volume_file("bone.mha", {12, 12, 4}, {1, 1, 1}, [](int, int, int) { return 1000.0f; });
  expect_rejected(run("reconstruct " + bone.string() + " -o " + out.string()),
                  {bone.string(), "every voxel is at or above the threshold 300 (all bone"});
  expect_rejected(run("run " + bone.string() + " -o " + out.string()), {bone.string(), "all bone"});
  // Bone in regions too small to keep: said so, not "all air".
  const fs::path specks = write_volume_file("specks.mha", {12, 12, 4}, {1, 1, 1}, [](int i, int j, int) {
    return i == 5 && j == 5 ? 1000.0f : -1000.0f;
  });
  expect_rejected(run("reconstruct " + specks.string() + " -o " + out.string()), {"4 regions were smaller"});
  expect_nothing_written(out);
}

TEST_F(BadInput, ExtremeSpacingRatiosStillGiveClosedMeshes) {
  // 0.01 x 0.01 x 50 mm: a needle 1.2 mm across and 150 mm long, triangles 5000 times longer than wide.
  const fs::path needle = write_volume_file("needle.mha", {150, 150, 3}, {0.01, 0.01, 50}, [](int i, int j, int) {
    return (i - 75) * (i - 75) + (j - 75) * (j - 75) < 60 * 60 ? 1000.0f : -1000.0f;
  });
  // 5 x 5 x 0.001 mm: a pancake 40 mm across, its pixels 5000 times wider than its slices are apart. (At 50 x
  // 50 x 0.01 mm the same ratio gave a disk 400 mm across, 317k vertices at the 1 mm contour sampling.)
  const fs::path pancake = write_volume_file("pancake.mha", {12, 12, 8}, {5, 5, 0.001}, [](int i, int j, int k) {
    return k > 1 && k < 6 && (i - 6) * (i - 6) + (j - 6) * (j - 6) < 16 ? 1000.0f : -1000.0f;
  });
  for (const fs::path& volume : {needle, pancake}) {
    const fs::path mesh = dir_ / (volume.stem().string() + ".vtp");
    CliRun r = run("reconstruct " + volume.string() + " -o " + mesh.string() + " --min-area 0.1 --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = json_of(r);
    EXPECT_TRUE(j["is_closed"].get<bool>()) << volume;
    EXPECT_TRUE(j["is_manifold"].get<bool>()) << volume;
    EXPECT_GT(j["volume"].get<double>(), 0.0) << volume;
    for (const std::string method : {"paper", "taubin"}) {
      const fs::path out = dir_ / (volume.stem().string() + "_" + method + ".ply");
      r = run("smooth " + mesh.string() + " -o " + out.string() + " --method " + method + " --json");
      ASSERT_EQ(r.code, 0) << volume << " " << method << ": " << r.err;
      EXPECT_TRUE(read_mesh(out).positions.allFinite()) << volume << " " << method;
      EXPECT_LT(std::abs(json_of(r)["volume_change_percent"].get<double>()), 5.0) << volume << " " << method;
    }
  }
}

TEST_F(BadInput, DicomDirectoryWithTwoSeries) {
  const fs::path one = dir_ / "one_series";
  write_dicom_series(one, "1.2.826.0.1.3680043.2.1125.81", 4);
  const fs::path out = dir_ / "out.vtp";
  const CliRun ok = run("reconstruct " + one.string() + " -o " + out.string() + " --json");
  ASSERT_EQ(ok.code, 0) << "the series alone is a readable volume: " << ok.err;
  fs::remove(out);
  const fs::path two = dir_ / "two_series";
  write_dicom_series(two, "1.2.826.0.1.3680043.2.1125.81", 4);
  write_dicom_series(two, "1.2.826.0.1.3680043.2.1125.82", 3);
  expect_rejected(run("reconstruct " + two.string() + " -o " + out.string()),
                  {two.string(), "holds 2 DICOM series", "1.2.826.0.1.3680043.2.1125.81",
                   "1.2.826.0.1.3680043.2.1125.82", "pick one with --series UID"});
  expect_rejected(run("run " + two.string() + " -o " + out.string()), {"holds 2 DICOM series"});
  expect_nothing_written(out);
  // --list-series names both; --series reads the one asked for (4 slices, not 3).
  const CliRun list = run("reconstruct " + two.string() + " --list-series");
  ASSERT_EQ(list.code, 0) << list.err;
  EXPECT_NE(list.out.find("1.2.826.0.1.3680043.2.1125.81"), std::string::npos) << list.out;
  EXPECT_NE(list.out.find("1.2.826.0.1.3680043.2.1125.82"), std::string::npos) << list.out;
  const nlohmann::json listed = json_of(run("reconstruct " + two.string() + " --list-series --json"));
  ASSERT_EQ(listed["series"].size(), 2u);
  EXPECT_EQ(listed["series"][1]["files"], 3);
  EXPECT_EQ(listed["series"][0]["modality"], "CT");
  const CliRun picked =
      run("reconstruct " + two.string() + " --series 1.2.826.0.1.3680043.2.1125.81 -o " + out.string() + " --json");
  ASSERT_EQ(picked.code, 0) << picked.err;
  EXPECT_EQ(json_of(picked)["slices"], 4);
  fs::remove(out);
  expect_rejected(run("reconstruct " + two.string() + " --series 1.2.3 -o " + out.string()),
                  {"no DICOM series 1.2.3 in the directory"});
  expect_nothing_written(out);
}

// ----- Outputs ---------------------------------------------------------------------------------------

TEST_F(BadInput, OutputPathsThatCannotBeWritten) {
  const std::string in = (dir_ / "stack.ply").string();
  const fs::path file = write_text("regular_file", "not a directory");
  const fs::path volume = write_volume_file("v.mha", {12, 12, 4}, {1, 1, 1}, [](int i, int j, int k) {
    return k > 0 && k < 3 && (i - 6) * (i - 6) + (j - 6) * (j - 6) < 16 ? 1000.0f : -1000.0f;
  });
  fs::create_directories(dir_ / "adir.ply");
  fs::create_directories(dir_ / "adir.mha");
  struct Case {
    std::string output;  // without extension
    std::string what;
  };
  const std::vector<Case> cases = {
      {(dir_ / "missing" / "out").string(), "directory '" + (dir_ / "missing").string() + "' does not exist"},
      {(file / "out").string(), "'" + file.string() + "' is not a directory"},
      {(dir_ / "adir").string(), "it is a directory"}};
  for (const Case& c : cases) {
    const std::string mesh_out = c.output + ".ply";
    expect_rejected(run("smooth " + in + " -o " + mesh_out + " --method none"), {mesh_out, c.what});
    expect_rejected(run("detect " + in + " -o " + mesh_out), {mesh_out, c.what});
    expect_rejected(run("reconstruct " + volume.string() + " -o " + mesh_out), {mesh_out, c.what});
    expect_rejected(run("phantom --shape femur -o " + c.output + ".mha"), {c.output + ".mha", c.what});
    // run creates a missing output directory (its default is out/femur.stl), the others fail alike.
    if (c.output.find("missing") == std::string::npos) {
      expect_rejected(run("run -o " + mesh_out + " --shape ridge-box --spacing 2,2,4"), {mesh_out, c.what});
    }
  }
  EXPECT_FALSE(fs::exists(dir_ / "missing"));
  EXPECT_TRUE(fs::is_empty(dir_ / "adir.ply"));
  // --labels-out that cannot be written: nothing is written, not even the main output.
  const fs::path out = dir_ / "out.ply";
  expect_rejected(run("smooth " + in + " -o " + out.string() + " --labels-out " + (file / "l.vtp").string()),
                  {"is not a directory"});
  expect_nothing_written(out);
  // A read-only directory; root writes anyway, so the check only means something for other users.
  const fs::path locked = dir_ / "locked";
  fs::create_directories(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
  if (::geteuid() != 0) {
    expect_rejected(run("smooth " + in + " -o " + (locked / "out.ply").string()), {"cannot write in", "ermission"});
    EXPECT_TRUE(fs::is_empty(locked));
  }
  fs::permissions(locked, fs::perms::owner_all);
}

TEST_F(BadInput, AFailedRunLeavesAnExistingOutputUntouched) {
  const fs::path out = write_text("precious.ply", "precious bytes");
  const fs::path labels = write_text("precious_labels.vtp", "precious labels");
  const fs::path nan = write_text("nan.obj", tetra_obj("v nan 0 0"));
  expect_rejected(run("smooth " + nan.string() + " -o " + out.string()), {"non-finite"});
  // Failing after the input was read, during the work (the paper's method: its adaptive mesh grows).
  const std::string in = (dir_ / "stack.ply").string();
  expect_rejected(run("smooth " + in + " -o " + out.string() + " --method paper --labels-out " + labels.string() +
                      " --max-vertices " + std::to_string(stack_.num_vertices())),
                  {"adaptive subdivision"});
  const fs::path air = write_volume_file("air.mha", {8, 8, 3}, {1, 1, 1}, [](int, int, int) { return -1000.0f; });
  expect_rejected(run("reconstruct " + air.string() + " -o " + out.string()), {"all air"});
  expect_rejected(run("run " + air.string() + " -o " + out.string()), {"all air"});
  EXPECT_EQ(test::read_bytes(out), "precious bytes");
  EXPECT_EQ(test::read_bytes(labels), "precious labels");
  for (const auto& e : fs::directory_iterator(dir_)) {
    EXPECT_NE(e.path().filename().string().front(), '.') << "stray temporary " << e.path();
  }
}

// ----- Size limits -----------------------------------------------------------------------------------

TEST_F(BadInput, MaxVerticesRefusesOversizedMeshesBeforeAllocating) {
  const std::string in = (dir_ / "stack.ply").string();
  const fs::path out = dir_ / "out.ply";
  const std::string n = std::to_string(stack_.num_vertices());
  // Reading: the PLY header's count is enough to refuse.
  expect_rejected(run("smooth " + in + " -o " + out.string() + " --max-vertices 100"),
                  {in, "the header announces " + n + " vertices, more than the limit of 100",
                   "raise it with --max-vertices"});
  write_mesh(stack_, dir_ / "stack.stl");
  expect_rejected(run("smooth " + (dir_ / "stack.stl").string() + " -o " + out.string() + " --max-vertices 100"),
                  {"more than the limit of 100 vertices", "raise it with --max-vertices"});
  // Producing: the adaptive mesh of the paper's method, then tiling.
  expect_rejected(run("smooth " + in + " -o " + out.string() + " --method paper --max-vertices " + n),
                  {in + ": adaptive subdivision level 1", "exceed the limit of " + n + " vertices"});
  EXPECT_EQ(run("smooth " + in + " -o " + out.string() + " --method taubin --max-vertices " + n).code, 0)
      << "the baselines produce no vertices";
  EXPECT_EQ(run("smooth " + in + " -o " + out.string() + " --max-vertices " + n).code, 0)
      << "neither does the default, cross-slice smoothing";
  fs::remove(out);
  const fs::path volume = write_volume_file("v.mha", {24, 24, 5}, {1, 1, 1}, [](int i, int j, int k) {
    return k > 0 && k < 4 && (i - 12) * (i - 12) + (j - 12) * (j - 12) < 64 ? 1000.0f : -1000.0f;
  });
  // The contour points are counted before they are resampled, so the limit stops the work there.
  expect_rejected(run("reconstruct " + volume.string() + " -o " + out.string() + " --max-vertices 50"),
                  {volume.string(), "contour resampling", "exceed the limit of 50 vertices"});
  expect_rejected(run("run " + volume.string() + " -o " + out.string() + " --max-vertices 50"),
                  {"contour resampling"});
  expect_nothing_written(out);
  // A volume header promising 170 TB of working memory: refused from the header, before any reading.
  const fs::path huge = write_text("huge.mha", "ObjectType = Image\nNDims = 3\nDimSize = 100000 100000 1000\n"
                                               "ElementType = MET_FLOAT\nElementDataFile = LOCAL\n");
  expect_rejected(run("reconstruct " + huge.string() + " -o " + out.string()),
                  {huge.string(), "100000 x 100000 x 1000 voxels: needs about 170000.0 GB of memory, more than the",
                   "available"});
  EXPECT_EQ(run("smooth " + in + " -o " + out.string() + " --max-vertices 0").code, 1) << "usage error";
  for (const std::string command : {"smooth", "detect", "reconstruct", "run"}) {
    EXPECT_NE(run(command + " --help").out.find("--max-vertices"), std::string::npos) << command;
  }
}

}  // namespace
}  // namespace contourmesh
