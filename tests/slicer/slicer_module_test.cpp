// SPDX-License-Identifier: BSD-3-Clause
// The 3D Slicer CLI module run as Slicer runs it, and the LPS tag of written meshes.
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/reconstruct/phantom.h>
#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/smooth.h>
#include <contourmesh/smooth/topology.h>

#include "cli_runner.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <regex>
#include <string>

namespace contourmesh {
namespace {

namespace fs = std::filesystem;

test::CliRun run(const std::string& args, const fs::path& dir) {
  return test::run_program(CONTOURMESH_SLICER_MODULE, args, dir);
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

class SlicerModule : public ::testing::Test {
 protected:
  void SetUp() override {
    PhantomVolumeOptions o;
    o.spacing = {1.0, 1.0, 2.0};
    write_volume(render_phantom(make_phantom(PhantomShape::RidgeBox), o), dir_ / "box.nrrd");
  }
  test::ScopedTempDir tmp_{"contourmesh_slicer"};
  const fs::path& dir_ = tmp_.path();
};

// Slicer passes the flags of the description, then the input image and the output model by index.
TEST_F(SlicerModule, RunsAsSlicerCallsItAndReportsProgress) {
  const fs::path model = dir_ / "model.stl";
  const test::CliRun r =
      run("--threshold 520 --method paper --iterations 10 --threads 1 " + (dir_ / "box.nrrd").string() + " " +
              model.string(),
          dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("<filter-start><filter-name>ContourMesh Surface</filter-name>", 0), 0u) << r.out;
  const std::regex progress("<filter-progress>([0-9.e-]+)</filter-progress>");
  double last = -1.0;
  int count = 0;
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), progress); it != std::sregex_iterator(); ++it) {
    const double f = std::stod((*it)[1]);
    EXPECT_GE(f, last);
    EXPECT_LE(f, 1.0);
    last = f;
    ++count;
  }
  EXPECT_GT(count, 5);
  EXPECT_EQ(last, 1.0);
  EXPECT_NE(r.out.find("<filter-end>"), std::string::npos);
  EXPECT_NE(read_file(model).substr(0, 80).find("SPACE=LPS"), std::string::npos);
  const Mesh mesh = read_mesh(model);
  EXPECT_TRUE(summarize_topology(mesh).closed);
}

// The module's default method, as Slicer shows it, is the library's default preset's (the command line's).
TEST_F(SlicerModule, DefaultMethodIsTheLibrarysDefault) {
  const test::CliRun r = run("--xml", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, std::regex("<name>method</name>[\\s\\S]*?<default>([^<]*)</default>")))
      << r.out;
  EXPECT_EQ(m[1].str(), to_string(preset(Preset::Default).method));
  // And it runs: the iteration count Slicer always passes is ignored by a method that has none.
  const fs::path model = dir_ / "default.ply";
  const test::CliRun d =
      run("--threshold 520 --iterations 10 " + (dir_ / "box.nrrd").string() + " " + model.string(), dir_);
  ASSERT_EQ(d.code, 0) << d.err;
  EXPECT_TRUE(summarize_topology(read_mesh(model)).closed);
}

// --creases restore refines the model around the box's ridge; Slicer passes --creases with every method,
// so "none" goes with any, and "restore" with another method than cross-slice is refused before the work.
TEST_F(SlicerModule, CreasesRestoreRefinesTheModelAndNeedsCrossSlice) {
  const test::CliRun xml = run("--xml", dir_);
  ASSERT_EQ(xml.code, 0) << xml.err;
  EXPECT_NE(xml.out.find("<name>creases</name>"), std::string::npos);
  const fs::path plain = dir_ / "plain.ply", restored = dir_ / "restored.ply";
  const std::string box = (dir_ / "box.nrrd").string();
  ASSERT_EQ(run("--threshold 520 --creases none " + box + " " + plain.string(), dir_).code, 0);
  const test::CliRun r = run("--threshold 520 --creases restore " + box + " " + restored.string(), dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const Mesh a = read_mesh(plain), b = read_mesh(restored);
  EXPECT_GT(b.num_vertices(), a.num_vertices());
  EXPECT_TRUE(summarize_topology(b).closed);
  const fs::path taubin = dir_ / "taubin.ply";
  EXPECT_EQ(run("--threshold 520 --method taubin --creases none " + box + " " + taubin.string(), dir_).code, 0);
  const fs::path refused = dir_ / "refused.ply";
  const test::CliRun bad =
      run("--threshold 520 --method taubin --creases restore " + box + " " + refused.string(), dir_);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--creases restore needs the cross-slice method"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(refused));
}

TEST_F(SlicerModule, BadInputIsOneLineAndExitTwoWithNothingWritten) {
  const fs::path model = dir_ / "model.stl";
  const test::CliRun r = run("--threshold 5000 " + (dir_ / "box.nrrd").string() + " " + model.string(), dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("box.nrrd: no region at or above the threshold 5000"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(model));
}

TEST(MeshFiles, StlAndPlyCarryTheLpsTagAsSlicerReadsIt) {
  test::ScopedTempDir tmp("contourmesh_lps");
  Mesh mesh;
  mesh.positions = Eigen::Matrix3Xd::Identity(3, 3);
  mesh.triangles = {{0, 1, 2}};
  for (const char* name : {"m.stl", "m.ply"}) write_mesh(mesh, tmp.path() / name);
  MeshWriteOptions ascii;
  ascii.format = MeshFormat::StlAscii;
  write_mesh(mesh, tmp.path() / "a.stl", ascii);
  EXPECT_NE(read_file(tmp.path() / "m.stl").substr(0, 80).find("SPACE=LPS"), std::string::npos);
  EXPECT_EQ(read_file(tmp.path() / "a.stl").rfind("solid ContourMesh output. SPACE=LPS", 0), 0u);
  const std::string ply = read_file(tmp.path() / "m.ply");
  EXPECT_NE(ply.substr(0, ply.find("end_header")).find("\ncomment SPACE=LPS\n"), std::string::npos);
  EXPECT_EQ(read_mesh(tmp.path() / "m.stl").num_faces(), 1);  // still read back
}

}  // namespace
}  // namespace contourmesh
