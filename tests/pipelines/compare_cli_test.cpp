// SPDX-License-Identifier: BSD-3-Clause
// `contourmesh compare` end to end: the files, renders (under xvfb-run when there is no display), regimes,
// seeds, variants, the summary and the Markdown page, exit codes and bad input.
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/reconstruct/phantom.h>
#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/shapes.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "compare_support.h"
#include "test_support.h"

namespace contourmesh {
namespace {

using namespace compare_test;
namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------------
// The CLI

TEST(CompareCli, OnePhantomWritesEveryFileAndRendersTheMeshes) {
  test::ScopedTempDir tmp("contourmesh_compare");
  const fs::path out = tmp.path() / "out" / "ridge";  // parents are created
  const CliRun r = run_cli("compare --phantom ridge-box " + std::string(kSmallPhantom) +
                               " --render-size 320x240 --color-levels 32 --out " + out.string() + " --json",
                           tmp.path(), true);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["comparisons"].size(), 1u);
  const auto& item = j["comparisons"][0];
  EXPECT_EQ(item["name"], "ridge-box");
  EXPECT_EQ(item["regime"], "ct100");
  ASSERT_TRUE(item["rendered"].get<bool>()) << item["render_note"];
  ASSERT_EQ(j["verdicts"].size(), 1u);
  EXPECT_EQ(j["verdicts"][0]["denoise"], "-") << "a CT regime";

  for (const char* file : {"metrics.csv", "metrics.json", "volume_curve.csv", "volume_curve.png", "report.html",
                           "labels_cross-slice.png", "detection_cross-slice.png", "labels_paper.png"}) {
    EXPECT_TRUE(fs::is_regular_file(out / file)) << file;
  }
  // No temporary files are left behind.
  for (const auto& entry : fs::directory_iterator(out)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  }

  const auto metrics = nlohmann::json::parse(read_text(out / "metrics.json"));
  std::vector<std::string> names;
  for (const auto& m : metrics["mean"]) {
    names.push_back(m["id"]);
    for (const char* key : {"rms_mm", "hausdorff_mm", "feature_rms_mm", "smooth_rms_mm"}) {
      EXPECT_TRUE(m[key].is_number() && std::isfinite(m[key].get<double>())) << m["id"] << " " << key;
    }
    EXPECT_TRUE(m["normal_error_degrees"].is_number());
    if (m["id"] == "none") {
      EXPECT_EQ(m["volume_change_percent"].get<double>(), 0.0);
    }
  }
  EXPECT_EQ(names, kMethods);
  EXPECT_EQ(metrics, item["metrics"]) << "--json prints the same metrics as metrics.json";

  const std::string html = read_text(out / "report.html");
  for (const std::string& m : kMethods) {
    const std::string png = "render_" + m + ".png";
    EXPECT_NE(html.find("src=\"" + png + "\""), std::string::npos) << png;
    const PngStats s = png_stats(out / png);
    EXPECT_EQ(s.width, 320) << png;
    EXPECT_EQ(s.height, 240) << png;
    EXPECT_GT(s.variance, 50.0) << png << " is blank";
    EXPECT_GT(s.foreground, 0.10) << png << " shows no mesh";
  }
  for (const char* png : {"labels_cross-slice.png", "detection_cross-slice.png", "volume_curve.png"}) {
    const PngStats s = png_stats(out / png);
    EXPECT_GT(s.variance, 50.0) << png;
    EXPECT_GT(s.foreground, 0.02) << png;
  }
  EXPECT_NE(html.find("volume_curve.png"), std::string::npos);
  EXPECT_NE(html.find("metrics.csv"), std::string::npos);
}

// Two regimes, two seeds, a few methods and a variant: one directory per regime, means over the seeds,
// the summary with the verdicts, and the Markdown page.
TEST(CompareCli, RegimesSeedsVariantsAndTheSummary) {
  test::ScopedTempDir tmp("contourmesh_compare");
  const fs::path out = tmp.path() / "out";
  const fs::path md = tmp.path() / "results.md";
  const CliRun r = run_cli(
      "compare --phantom ridge-box --spacing 2,2,4 --regimes ct20,contour0.4 --seeds 1-2 --methods "
      "none,cross-slice,voxel-windowed-sinc --variant along-off:stages=across-only --no-render "
      "--no-curves --out " +
          out.string() + " --markdown " + md.string() + " --json",
      tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["comparisons"].size(), 2u);
  for (const auto& item : j["comparisons"]) {
    const fs::path dir = item["directory"].get<std::string>();
    EXPECT_EQ(dir.parent_path(), out);
    EXPECT_EQ(dir.filename(), item["regime"].get<std::string>());
    const auto& m = item["metrics"];
    EXPECT_EQ(m["seeds"], nlohmann::json::array({1, 2}));
    ASSERT_EQ(m["runs"].size(), 2u);
    ASSERT_EQ(m["mean"].size(), 4u);
    EXPECT_EQ(m["mean"][3]["id"], "along-off");
    EXPECT_TRUE(m["mean"][3]["variant"].get<bool>());
    const double a = m["runs"][0]["methods"][1]["accuracy"]["all"]["rms"],
                 b = m["runs"][1]["methods"][1]["accuracy"]["all"]["rms"];
    EXPECT_NEAR(m["mean"][1]["rms_mm"].get<double>(), 0.5 * (a + b), 1e-12);
    EXPECT_EQ(m["mean"][1]["runs"], 2);
  }
  for (const char* file : {"summary.csv", "summary.json", "report.html"}) EXPECT_TRUE(fs::exists(out / file)) << file;
  const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary["series"].size(), 2u);
  EXPECT_EQ(summary["verdicts"].size(), 2u);
  EXPECT_FALSE(summary["verdicts"][0]["do_no_harm"].is_null());
  EXPECT_TRUE(summary["verdicts"][1]["beat_voxel_route"].is_null()) << "contour noise: bar 2 does not apply";
  const std::string page = read_text(md);
  for (const char* text : {"## Verdicts of the default", "## ct20", "## contour0.4", "## Feature labels", "along-off",
                           "the mean over the noise seeds 1, 2"}) {
    EXPECT_NE(page.find(text), std::string::npos) << text;
  }
  EXPECT_NE(r.out.find("\"verdicts\""), std::string::npos);
  // Every row of the verdict table has its six cells: a '|' inside a cell ("|dV|") is escaped.
  std::istringstream lines(page);
  int rows = 0;
  for (std::string line; std::getline(lines, line);) {
    const bool verdict_row =
        (line.rfind("| ct20 | ridge-box |", 0) == 0 || line.rfind("| contour0.4 | ridge-box |", 0) == 0) &&
        line.find("RMS ") != std::string::npos;
    if (!verdict_row) continue;
    int bars = 0;
    for (std::size_t i = 0; i < line.size(); ++i) bars += line[i] == '|' && (i == 0 || line[i - 1] != '\\');
    EXPECT_EQ(bars, 7) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 2);
}

TEST(CompareCli, WithoutADisplayTheRendersAreSkippedAndSaidSo) {
  test::ScopedTempDir tmp("contourmesh_compare");
  const fs::path out = tmp.path() / "out";
  const CliRun r = run_cli("compare --phantom ridge-box " + std::string(kSmallPhantom) +
                               " --methods none,cross-slice --no-curves --out " + out.string(),
                           tmp.path(), false, "env -u DISPLAY");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("no renders"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out / "render_cross-slice.png"));
  EXPECT_TRUE(fs::is_regular_file(out / "volume_curve.png")) << "the plot needs no display";
  EXPECT_NE(read_text(out / "report.html").find("xvfb-run"), std::string::npos);
}

TEST(CompareCli, VolumeWithAndWithoutAReferenceSurface) {
  test::ScopedTempDir tmp("contourmesh_compare");
  const fs::path volume = tmp.path() / "scan.nrrd";
  PhantomVolumeOptions v;
  v.spacing = {1.5, 1.5, 3.0};
  write_volume(render_phantom(make_phantom(PhantomShape::RidgeBox), v), volume);
  const fs::path reference = tmp.path() / "reference.stl";
  write_mesh(make_icosphere(3, 20.0), reference);

  CliRun r = run_cli("compare " + volume.string() + " --truth " + reference.string() +
                         " --threshold 520 --methods none,taubin --no-render --no-curves --out " +
                         (tmp.path() / "with").string() + " --json",
                     tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  auto m = nlohmann::json::parse(r.out)["comparisons"][0]["metrics"];
  EXPECT_EQ(m["truth"], "reference-surface");
  EXPECT_TRUE(m["mean"][0]["rms_mm"].is_number());
  EXPECT_TRUE(m["mean"][0]["normal_error_degrees"].is_null());
  EXPECT_EQ(m["regime"]["name"], "input");
  // --off-slice reaches the reconstruction: the unsmoothed mesh's distance to the reference changes.
  const double image_rms = m["mean"][0]["rms_mm"].get<double>();
  r = run_cli("compare " + volume.string() + " --truth " + reference.string() +
                  " --threshold 520 --off-slice tiled --methods none --no-render --no-curves --out " +
                  (tmp.path() / "tiled").string() + " --json",
              tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(nlohmann::json::parse(r.out)["comparisons"][0]["metrics"]["mean"][0]["rms_mm"].get<double>(), image_rms);

  r = run_cli("compare " + volume.string() + " --threshold 520 --methods none,taubin --no-render --no-curves --out " +
                  (tmp.path() / "without").string() + " --json",
              tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  m = nlohmann::json::parse(r.out)["comparisons"][0]["metrics"];
  EXPECT_EQ(m["truth"], "none");
  EXPECT_TRUE(m["runs"][0]["methods"][0]["accuracy"].is_null());
  EXPECT_NE(read_text(tmp.path() / "without" / "report.html").find("no distance"), std::string::npos);
}

TEST(CompareCli, BadInputExitsWithTwoAndAClearMessage) {
  test::ScopedTempDir tmp("contourmesh_compare");
  const std::string out = " --out " + (tmp.path() / "out").string();
  CliRun r = run_cli("compare --phantom tibia" + out, tmp.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("tibia"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("femur"), std::string::npos) << "lists the valid names: " << r.err;

  const fs::path missing = tmp.path() / "no_such_scan.nrrd";
  r = run_cli("compare " + missing.string() + out, tmp.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("no_such_scan.nrrd"), std::string::npos) << r.err;

  // A regular file where the output directory should be, and a directory that cannot be created.
  const fs::path file = tmp.path() / "a_file";
  std::ofstream(file) << "x";
  r = run_cli("compare --phantom ridge-box --out " + file.string(), tmp.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("a_file"), std::string::npos) << r.err;
  r = run_cli("compare --phantom ridge-box --out " + (file / "sub").string(), tmp.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("a_file"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_regular_file(file));

  // The truth surface is checked before the volume is reconstructed.
  const fs::path volume = tmp.path() / "scan.nrrd";
  PhantomVolumeOptions v;
  v.spacing = {2.0, 2.0, 4.0};
  write_volume(render_phantom(make_phantom(PhantomShape::RidgeBox), v), volume);
  r = run_cli("compare " + volume.string() + " --truth " + (tmp.path() / "missing.stl").string() + out, tmp.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("missing.stl"), std::string::npos) << r.err;

  // Options checked before any work.
  for (const auto& [option, fragment] : std::vector<std::pair<std::string, std::string>>{
           {"--render-size 10x10", "--render-size"},
           {"--color-levels 1", "--color-levels"},
           {"--regimes ct20,mri", "mri"},
           {"--seeds 3-1", "--seeds"},
           {"--methods none,slicer", "slicer"},
           {"--variant x:colour=red", "colour"},
           {"--render-methods cross-slice,foo", "foo"},
           {"--iterations 0", "--iterations"},
           {"--off-slice sideways", "--off-slice"}}) {
    r = run_cli("compare --phantom ridge-box " + option + out, tmp.path());
    EXPECT_EQ(r.code, 2) << option;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << option << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(tmp.path() / "out" / "report.html"));
}

TEST(CompareCli, ConflictingOptionsAreUsageErrors) {
  test::ScopedTempDir tmp("contourmesh_compare");
  const std::string out = " --out " + (tmp.path() / "out").string();
  EXPECT_EQ(run_cli("compare --phantom femur in.nrrd" + out, tmp.path()).code, 1);
  EXPECT_EQ(run_cli("compare --phantom femur --truth ref.stl" + out, tmp.path()).code, 1);
  EXPECT_EQ(run_cli("compare --phantom femur --regimes ct20 --noise 60" + out, tmp.path()).code, 1);
  EXPECT_EQ(run_cli("compare --phantom femur --seeds 1-3 --seed 2" + out, tmp.path()).code, 1);
  EXPECT_EQ(run_cli("compare --phantom femur", tmp.path()).code, 1) << "--out is required";
  EXPECT_FALSE(fs::exists(tmp.path() / "out"));
}

}  // namespace
}  // namespace contourmesh
