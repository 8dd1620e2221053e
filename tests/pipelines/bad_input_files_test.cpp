// SPDX-License-Identifier: BSD-3-Clause
// The bad-input catalogue of docs/robustness.md, one test per entry: the contourmesh command run as a
// user runs it, on files written here. A rejected input exits 2 with one line on stderr naming the file
// and what is wrong, and leaves no output behind (an existing output untouched); a repaired input exits
// 0 with a warning.
// This part: mesh files that cannot be read, or read but hold invalid data.
// The support header first: it includes ITK, whose bundled Eigen must not follow the system one.
#include "bad_input_support.h"

#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/vtk/vtk_convert.h>

#include <gtest/gtest.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace contourmesh {
namespace {

using namespace bad_input_test;

// ----- Files that cannot be read ---------------------------------------------------------------------

TEST_F(BadInput, EmptyFile) {
  const fs::path out = dir_ / "out.stl";
  for (const std::string ext : {"stl", "ply", "vtp", "obj"}) {
    const fs::path in = write_text("empty." + ext, "");
    expect_rejected(run("smooth " + in.string() + " -o " + out.string()), {in.string(), "file is empty"});
  }
  const fs::path volume = write_text("empty.mha", "");
  expect_rejected(run("reconstruct " + volume.string() + " -o " + (dir_ / "out.vtp").string()),
                  {volume.string(), "empty file"});
  expect_nothing_written(out);
  expect_nothing_written(dir_ / "out.vtp");
}

TEST_F(BadInput, TruncatedStlBinaryAndAscii) {
  const fs::path out = dir_ / "out.ply";
  const fs::path binary = dir_ / "cut.stl";
  write_mesh(stack_, binary);
  ASSERT_EQ(run("smooth " + binary.string() + " -o " + out.string() + " --method none").code, 0) << "intact file";
  fs::remove(out);
  cut(binary, 84 + 50 * 10 + 20);  // inside triangle 10
  expect_rejected(run("smooth " + binary.string() + " -o " + out.string()),
                  {binary.string(), "truncated or corrupt binary STL", "the file has 604 bytes, 10 whole triangles"});
  cut(binary, 84 + 50 * 10);  // on a triangle boundary: only the header's count tells
  expect_rejected(run("smooth " + binary.string() + " -o " + out.string()), {binary.string(), "10 whole triangles"});

  const fs::path ascii = dir_ / "cut_ascii.stl";
  write_mesh(stack_, ascii, {MeshFormat::StlAscii, {}, {}, {}});
  cut(ascii, test::read_bytes(ascii).find('\n', test::read_bytes(ascii).size() / 2) + 1);  // after a whole line
  expect_rejected(run("smooth " + ascii.string() + " -o " + out.string()),
                  {ascii.string(), "the ASCII STL ends inside a solid", "truncated file?"});
  // A malformed line is named by its number.
  const fs::path typo = write_text("typo.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                               "vertex 0 1 zero\nendloop\nendfacet\nendsolid t\n");
  expect_rejected(run("smooth " + typo.string() + " -o " + out.string()), {"line 6: 'zero' is not a number"});
  expect_nothing_written(out);
}

TEST_F(BadInput, TruncatedPlyAndVtp) {
  const fs::path out = dir_ / "out.stl";
  const fs::path ply = dir_ / "cut.ply";
  write_mesh(stack_, ply);
  cut(ply, test::read_bytes(ply).size() * 6 / 10);
  expect_rejected(run("smooth " + ply.string() + " -o " + out.string()),
                  {ply.string(), "PLY: data ends inside element"});
  const fs::path ascii = write_text("cut_ascii.ply", tetra_ascii_ply().substr(0, tetra_ascii_ply().size() - 12));
  expect_rejected(run("smooth " + ascii.string() + " -o " + out.string()),
                  {ascii.string(), "PLY: data ends inside element 'face'"});
  const fs::path vtp = dir_ / "cut.vtp";
  write_mesh(stack_, vtp);
  cut(vtp, test::read_bytes(vtp).size() * 6 / 10);
  expect_rejected(run("smooth " + vtp.string() + " -o " + out.string()), {vtp.string(), "cannot read"});
  expect_nothing_written(out);
}

TEST_F(BadInput, RandomBytesWithAMeshExtension) {
  std::mt19937 rng(7);
  std::string noise(4096, '\0');
  for (char& c : noise) c = static_cast<char>(rng());
  const fs::path out = dir_ / "out.ply";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"stl", "binary STL"}, {"ply", "not a PLY file"}, {"vtp", "cannot read"}, {"obj", "not a text OBJ file"}};
  for (const auto& [ext, what] : cases) {
    const fs::path in = write_text("noise." + ext, noise);
    const CliRun r = run("smooth " + in.string() + " -o " + out.string());
    expect_rejected(r, {in.string(), what});
    for (const char c : r.err) EXPECT_TRUE(c == '\n' || std::isprint(static_cast<unsigned char>(c))) << ext;
  }
  expect_nothing_written(out);
}

// ----- Files that read but hold invalid data -----------------------------------------------------------

TEST_F(BadInput, NonFiniteCoordinatesInEveryFormat) {
  const fs::path out = dir_ / "out.ply";
  // The writers refuse NaN, so the broken files are written with a sentinel coordinate that is then
  // patched to NaN in the bytes (the VTP uncompressed, so that its bytes can be found).
  constexpr double kSentinel = 1234.5;
  Mesh bad = stack_;
  bad.positions(1, 5) = kSentinel;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  write_mesh(bad, dir_ / "nan.stl");
  patch(dir_ / "nan.stl", bytes_of(static_cast<float>(kSentinel)), bytes_of(static_cast<float>(nan)));
  write_mesh(bad, dir_ / "nan_ascii.stl", {MeshFormat::StlAscii, {}, {}, {}});
  patch(dir_ / "nan_ascii.stl", "1234.5", "nan");
  write_mesh(bad, dir_ / "nan.ply");
  patch(dir_ / "nan.ply", bytes_of(kSentinel), bytes_of(nan));
  {
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetInputData(to_polydata(bad, {}, {}));
    writer->SetFileName((dir_ / "nan.vtp").c_str());
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();
    writer->SetCompressorTypeToNone();
    ASSERT_EQ(writer->Write(), 1);
    patch(dir_ / "nan.vtp", bytes_of(kSentinel), bytes_of(nan));
  }
  for (const auto& [file, what] : std::vector<std::pair<std::string, std::string>>{
           {"nan.stl", "has a non-finite coordinate ("},
           {"nan_ascii.stl", "has a non-finite coordinate 'nan'"},
           {"nan.ply", "vertex 5 has a non-finite coordinate ("},
           {"nan.vtp", "vertex 5 has a non-finite coordinate ("}}) {
    expect_rejected(run("smooth " + (dir_ / file).string() + " -o " + out.string()), {file, what});
  }
  // vtkOBJReader reads "nan" as 0; ours refuses it, and infinities, naming the line.
  const fs::path obj_nan = write_text("nan.obj", tetra_obj("v 0 nan 0"));
  expect_rejected(run("smooth " + obj_nan.string() + " -o " + out.string()),
                  {obj_nan.string(), "line 4: vertex 3 has a non-finite coordinate 'nan'"});
  const fs::path obj_inf = write_text("inf.obj", tetra_obj("v 0 -inf 0"));
  expect_rejected(run("detect " + obj_inf.string() + " -o " + out.string()),
                  {"vertex 3 has a non-finite coordinate '-inf'"});
  const fs::path ply_inf = write_text("inf.ply", tetra_ascii_ply("0 1e999 0"));
  expect_rejected(run("smooth " + ply_inf.string() + " -o " + out.string()), {"vertex 2 has a non-finite coordinate"});
  expect_nothing_written(out);
}

TEST_F(BadInput, TriangleIndicesOutOfRange) {
  const fs::path out = dir_ / "out.ply";
  const fs::path obj = write_text("index.obj", tetra_obj("v 0 1 0", "f 2 3 9001"));
  expect_rejected(run("smooth " + obj.string() + " -o " + out.string()),
                  {obj.string(), "line 9: triangle 3 references vertex 9001 but the file has 4 vertices"});
  const fs::path zero = write_text("zero.obj", tetra_obj("v 0 1 0", "f 0 1 2"));
  expect_rejected(run("smooth " + zero.string() + " -o " + out.string()), {"vertex index 0 (OBJ indices start at 1)"});
  const fs::path ply = write_text("index.ply", tetra_ascii_ply("0 1 0", "3 1 2 9001"));
  expect_rejected(run("smooth " + ply.string() + " -o " + out.string()),
                  {ply.string(), "triangle 3 (face 3) references vertex 9001 but the file has 4 vertices"});
  Mesh bad = stack_;
  bad.triangles[12][1] = 9001;
  write_mesh(bad, dir_ / "index.vtp");
  expect_rejected(run("detect " + (dir_ / "index.vtp").string() + " -o " + out.string()),
                  {"index.vtp", "polygon 12 references point 9001 but the file has " +
                                    std::to_string(stack_.num_vertices()) + " points"});
  expect_nothing_written(out);
}

}  // namespace
}  // namespace contourmesh
