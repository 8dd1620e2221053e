// SPDX-License-Identifier: BSD-3-Clause
// The contour route of the contourmesh executable: `contours`, `reconstruct` and `run` on RT Structure
// Sets and contour files, --roi all, --contours-out, and what they refuse.
#include <contourmesh/vtk/contour_stack_io.h>
#include <contourmesh/vtk/mesh_io.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "cli_runner.h"
#include "reconstruct/rtstruct_writer.h"
#include "test_support.h"

namespace contourmesh {
namespace {

namespace fs = std::filesystem;

const fs::path kBreast = fs::path(CONTOURMESH_SHARED_DATA) / "rtstruct_breast" / "rtss.dcm";

using test::CliRun;

using test::run_cli;

// The path quoted for the shell.
std::string q(const fs::path& p) { return test::shell_quote(p.string()); }

class ContoursCli : public ::testing::Test {
 protected:
  // A structure set of two cylinders, an empty ROI and a non-planar one.
  fs::path small_set() {
    const fs::path path = dir_ / "small.dcm";
    std::vector<test::TestRoi> rois;
    for (const auto& [number, name, r] : {std::tuple{1, "GTV 1", 8.0}, std::tuple{2, "Cord/Canal", 5.0}}) {
      test::TestRoi roi = test::roi_of(number, name);
      for (int k = 0; k < 5; ++k)
        roi.contours.push_back(test::contour_of("CLOSED_PLANAR", test::ellipse(20.0 * number, 0, r, r, 3.0 * k)));
      rois.push_back(roi);
    }
    rois.push_back(test::roi_of(3, "Empty"));
    test::TestRoi bent = test::roi_of(4, "Bent");
    for (int k = 0; k < 3; ++k)
      bent.contours.push_back(test::contour_of("CLOSED_PLANAR", test::ellipse(-30, 0, 5, 5, 3.0 * k)));
    bent.contours[1].points[3].z() += 2.0;
    rois.push_back(bent);
    test::write_rtstruct(path, rois);
    return path;
  }
  // GTEST_SKIP only leaves the function it is in: call as `if (!have_breast()) GTEST_SKIP() << ...`.
  static bool have_breast() { return fs::exists(kBreast); }
  test::ScopedTempDir tmp_{"contourmesh_contours_cli"};
  const fs::path& dir_ = tmp_.path();
};

TEST_F(ContoursCli, ListsTheRoisOfAStructureSet) {
  if (!have_breast()) GTEST_SKIP() << "no " << kBreast;
  const CliRun r = run_cli("contours " + q(kBreast) + " --list", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("Lt Lung"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(no contours)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("3.00 mm apart"), std::string::npos) << r.out;
  const CliRun j = run_cli("contours " + q(kBreast) + " --json", dir_);
  ASSERT_EQ(j.code, 0) << j.err;
  const auto doc = nlohmann::json::parse(j.out);
  ASSERT_EQ(doc["rois"].size(), 10u);
  EXPECT_EQ(doc["rois"][0]["name"], "BODY");
  EXPECT_EQ(doc["rois"][0]["contours"], 141);
  EXPECT_EQ(doc["rois"][0]["slices"], 98);
  EXPECT_EQ(doc["rois"][0]["color"], nlohmann::json({154, 155, 100}));
  EXPECT_EQ(doc["rois"][1]["contours"], 0);
  EXPECT_EQ(doc["rois"][5]["slices"], 80);
}

TEST_F(ContoursCli, ReconstructsAnRoiWithIdsAndReportsTheChecks) {
  if (!have_breast()) GTEST_SKIP() << "no " << kBreast;
  const fs::path out = dir_ / "heart.vtp";
  const CliRun r = run_cli("reconstruct " + q(kBreast) + " --roi heart -o " + q(out) + " --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["roi"]["name"], "Heart");
  EXPECT_EQ(j["roi"]["number"], 5);
  EXPECT_EQ(j["contours"], 33);
  EXPECT_TRUE(j["is_closed"].get<bool>());
  EXPECT_TRUE(j["is_manifold"].get<bool>());
  EXPECT_LT(std::abs(j["volume_difference_percent"].get<double>()), 5.0);
  EXPECT_LT(j["contour_deviation_max"].get<double>(), 0.1);
  const Mesh m = read_mesh(out);
  EXPECT_TRUE(m.has_contour_ids());
  EXPECT_EQ(m.num_vertices(), j["vertices"].get<int>());
}

TEST_F(ContoursCli, AnRoiWithoutContoursIsAClearErrorAndWritesNothing) {
  if (!have_breast()) GTEST_SKIP() << "no " << kBreast;
  const fs::path out = dir_ / "areola.vtp";
  const CliRun r = run_cli("reconstruct " + q(kBreast) + " --roi Areola -o " + q(out), dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("ROI 2 'Areola' has no contours"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("rtss.dcm"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(ContoursCli, UsageErrorsExitOne) {
  if (!have_breast()) GTEST_SKIP() << "no " << kBreast;
  CliRun r = run_cli("reconstruct " + q(kBreast) + " -o " + q(dir_ / "x.vtp"), dir_);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--roi"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'Tumor Bed Block'"), std::string::npos) << r.err;
  r = run_cli("reconstruct " + q(kBreast) + " --roi Heart --threshold 200 -o " + q(dir_ / "x.vtp"), dir_);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--threshold applies to CT volumes"), std::string::npos) << r.err;
  r = run_cli("reconstruct " + q(kBreast) + " --roi Nope -o " + q(dir_ / "x.vtp"), dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("no ROI named 'Nope'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.vtp"));
}

TEST_F(ContoursCli, RoiAllWritesOneMeshPerRoiNamedAfterIt) {
  const fs::path set = small_set();
  const fs::path out = dir_ / "meshes";
  const CliRun r = run_cli("reconstruct " + q(set) + " --roi all -o " + q(out) + " --json", dir_);
  EXPECT_EQ(r.code, 2) << "the non-planar ROI fails: " << r.err;
  EXPECT_TRUE(fs::exists(out / "GTV_1.vtp"));
  EXPECT_TRUE(fs::exists(out / "Cord_Canal.vtp"));
  EXPECT_FALSE(fs::exists(out / "Bent.vtp"));
  EXPECT_NE(r.err.find("ROI 3 'Empty' has no contours: skipped"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("ROI 4 'Bent'"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["rois"].size(), 3u);
  EXPECT_EQ(j["rois"][0]["status"], "ok");
  EXPECT_EQ(j["rois"][2]["status"], "failed");
  EXPECT_EQ(j["failed"], 1);
  EXPECT_EQ(j["skipped"].size(), 1u);
  // A file name is not a place for several meshes.
  const CliRun file = run_cli("reconstruct " + q(set) + " --roi all -o " + q(dir_ / "one.vtp"), dir_);
  EXPECT_EQ(file.code, 1);
  EXPECT_NE(file.err.find("{roi}"), std::string::npos) << file.err;
  // A pattern with {roi}, and another format.
  const CliRun p = run_cli("reconstruct " + q(set) + " --roi all -o " + q(dir_ / "m_{roi}.ply") + " --quiet", dir_);
  EXPECT_TRUE(fs::exists(dir_ / "m_GTV_1.ply"));
  EXPECT_TRUE(fs::exists(dir_ / "m_Cord_Canal.ply"));
}

TEST_F(ContoursCli, RunSmoothsAnRoiAndReportsTheInPlaneDeviation) {
  const fs::path set = small_set();
  const fs::path out = dir_ / "gtv.stl";
  const CliRun r = run_cli("run " + q(set) + " --roi 'GTV 1' -o " + q(out) + " --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["method"], "cross-slice");  // the default preset, as for a CT volume
  EXPECT_EQ(j["preset"], "default");
  EXPECT_TRUE(j["is_closed"].get<bool>());
  for (const char* key : {"contour_deviation_before_mean", "contour_deviation_before_max",
                          "contour_deviation_after_mean", "contour_deviation_after_max", "slicewise_volume",
                          "volume_before", "volume_after", "seconds_tile", "seconds_smooth"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_LT(j["contour_deviation_before_max"].get<double>(), 0.1);
  EXPECT_GT(j["contour_deviation_after_mean"].get<double>(), 0.0);
  EXPECT_TRUE(fs::exists(out));
  // --roi all without -o writes out/<ROI>.stl in the working directory: here, with -o a directory.
  const CliRun all = run_cli("run " + q(set) + " --roi all -o " + q(dir_ / "smoothed") + " --quiet", dir_);
  EXPECT_EQ(all.code, 2);
  EXPECT_TRUE(fs::exists(dir_ / "smoothed" / "GTV_1.stl"));
  EXPECT_TRUE(fs::exists(dir_ / "smoothed" / "Cord_Canal.stl"));
}

TEST_F(ContoursCli, RunKeepsTheVolumeOfAThinDrawnStructure) {
  // A thin ellipse drifting along its long axis, 7 mm per 3 mm slice (the breast set's Scar is like this):
  // most of its surface lies between the slices, on intermediate contours that carry no image noise.
  // Fitted freely to filtered normals they round its ends inwards (-1.4 % of the volume); run keeps it.
  nlohmann::json slices = nlohmann::json::array();
  for (int k = 0; k < 6; ++k) {
    nlohmann::json points = nlohmann::json::array();
    for (int i = 0; i < 32; ++i) {
      const double t = 2.0 * std::numbers::pi * i / 32.0;
      points.push_back({2.5 * std::cos(t), 7.0 * k + 7.0 * std::sin(t)});
    }
    slices.push_back({{"w", 3.0 * k}, {"contours", {{{"points", points}}}}});
  }
  const fs::path json = dir_ / "drift.json";
  std::ofstream(json) << nlohmann::json{{"format", "contourmesh-contours"}, {"version", 1}, {"slices", slices}};
  const CliRun r = run_cli("run " + q(json) + " -o " + q(dir_ / "drift.vtp") + " --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_LT(std::abs(j["volume_change_percent"].get<double>()), 0.5) << r.out;
  // --off-slice-volume free: the fit stands, and the structure shrinks.
  const CliRun free =
      run_cli("run " + q(json) + " -o " + q(dir_ / "free.vtp") + " --json --off-slice-volume free", dir_);
  ASSERT_EQ(free.code, 0) << free.err;
  EXPECT_LT(nlohmann::json::parse(free.out)["volume_change_percent"].get<double>(), -0.5) << free.out;
  const CliRun taubin =
      run_cli("run " + q(json) + " -o " + q(dir_ / "t.vtp") + " --method taubin --off-slice-volume free", dir_);
  EXPECT_EQ(taubin.code, 2);
  EXPECT_NE(taubin.err.find("--off-slice-volume does not apply to taubin"), std::string::npos) << taubin.err;
  EXPECT_FALSE(fs::exists(dir_ / "t.vtp"));
}

TEST_F(ContoursCli, ContourFilesRoundTripThroughContoursAndReconstruct) {
  const fs::path set = small_set();
  const fs::path json = dir_ / "gtv.json";
  CliRun r = run_cli("contours " + q(set) + " --roi 1 -o " + q(json), dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const ContourStackFile file = read_contour_stack(json);
  EXPECT_EQ(file.name, "GTV 1");
  EXPECT_EQ(file.stack.slices.size(), 5u);
  r = run_cli("contours " + q(json) + " --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["contours"], 5);
  const CliRun a = run_cli("reconstruct " + q(set) + " --roi 1 -o " + q(dir_ / "a.vtp") + " --json", dir_);
  const CliRun b = run_cli("reconstruct " + q(json) + " -o " + q(dir_ / "b.vtp") + " --json", dir_);
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(a.out)["volume"].get<double>(),
                   nlohmann::json::parse(b.out)["volume"].get<double>());
}

TEST_F(ContoursCli, AHandWrittenContourFile) {
  const fs::path json = dir_ / "hand.json";
  std::ofstream(json) << R"({"format": "contourmesh-contours", "version": 1,
    "slices": [
      {"w": 0, "contours": [{"points": [[0, 0], [20, 0], [20, 10], [0, 10]]}]},
      {"w": 2.5, "contours": [{"points": [[0, 0], [0, 10], [20, 10], [20, 0]]},
                              {"points": [[5, 3], [8, 3], [8, 6], [5, 6]]}]},
      {"w": 5, "contours": [{"points": [[1, 1], [19, 1], [19, 9], [1, 9]]}]}
    ]})";
  const CliRun r = run_cli("reconstruct " + q(json) + " -o " + q(dir_ / "hand.vtp") + " --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["hole_contours"], 1);
  EXPECT_TRUE(j["is_closed"].get<bool>() && j["is_manifold"].get<bool>());
  EXPECT_LT(std::abs(j["volume_difference_percent"].get<double>()), 5.0);
}

TEST_F(ContoursCli, OneSliceNeedsASlabThickness) {
  const fs::path json = dir_ / "one.json";
  std::ofstream(json) << R"({"format": "contourmesh-contours", "version": 1,
    "slices": [{"w": 4, "contours": [{"points": [[0, 0], [10, 0], [10, 10], [0, 10]]}]}]})";
  CliRun r = run_cli("reconstruct " + q(json) + " -o " + q(dir_ / "one.vtp"), dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("one slice"), std::string::npos) << r.err;
  r = run_cli("reconstruct " + q(json) + " -o " + q(dir_ / "one.vtp") + " --slab-thickness 3 --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NEAR(nlohmann::json::parse(r.out)["volume"].get<double>(), 300.0, 1e-6);
}

TEST_F(ContoursCli, MalformedContourFilesNameTheLocation) {
  const fs::path json = dir_ / "bad.json";
  std::ofstream(json) << R"({"format": "contourmesh-contours", "version": 1,
    "slices": [{"w": 0, "contours": [{"points": [[0, 0], [10, "x"], [10, 10]]}]}]})";
  CliRun r = run_cli("reconstruct " + q(json) + " -o " + q(dir_ / "bad.vtp"), dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("slices[0].contours[0].points[1]"), std::string::npos) << r.err;
  std::ofstream(json) << "{ not json";
  r = run_cli("reconstruct " + q(json) + " -o " + q(dir_ / "bad.vtp"), dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("not valid JSON"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "bad.vtp"));
}

TEST_F(ContoursCli, ContoursOutWritesWhatTheImageRouteFound) {
  const fs::path volume = dir_ / "box.nii.gz";
  ASSERT_EQ(run_cli("phantom --shape ridge-box -o " + q(volume) + " --quiet", dir_).code, 0);
  const fs::path contours = dir_ / "found.json";
  const CliRun r = run_cli("reconstruct " + q(volume) + " --threshold 520 -o " + q(dir_ / "box.vtp") +
                               " --contours-out " + q(contours) + " --json",
                           dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const ContourStackFile file = read_contour_stack(contours);
  EXPECT_EQ(file.stack.slices.size(), j["slices"].get<std::size_t>());
  EXPECT_EQ(file.stack.num_contours(), j["contours"].get<std::size_t>());
  // Tiled again as contours, they give about the same solid.
  const CliRun again =
      run_cli("reconstruct " + q(contours) + " --sampling 0 -o " + q(dir_ / "again.vtp") + " --json", dir_);
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_NEAR(nlohmann::json::parse(again.out)["volume"].get<double>() / j["volume"].get<double>(), 1.0, 0.01);
  EXPECT_LT(nlohmann::json::parse(again.out)["contour_deviation_max"].get<double>(), 1e-6);
}

}  // namespace
}  // namespace contourmesh
