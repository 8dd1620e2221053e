// The bad-input catalogue of docs/robustness.md, one test per entry: the contourmesh command run as a
// user runs it, on files written here. A rejected input exits 2 with one line on stderr naming the file
// and what is wrong, and leaves no output behind (an existing output untouched); a repaired input exits
// 0 with a warning.
// ITK first: its writer headers pull in ITK's bundled Eigen, which must not follow the system one.
#include <itkGDCMImageIO.h>
#include <itkImageFileWriter.h>
#include <itkMetaDataObject.h>

#include <pipelines/mesh_io.h>
#include <pipelines/vtk_convert.h>
#include <reconstruct/volume.h>
#include <smooth/adjacency.h>
#include <smooth/shapes.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "test_support.h"

namespace contourmesh {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::expect_rejected;

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    stack_ = test::noisy_ridge_stack(8, 40, 2.0, 5);
    write_mesh(stack_, dir_ / "stack.ply");
  }

  CliRun run(const std::string& args) const { return test::run_cli(CONTOURMESH_CLI, args, dir_); }

  // No output and no temporary left in the directory: only the files the test wrote.
  void expect_nothing_written(const fs::path& output) const {
    EXPECT_FALSE(fs::exists(output)) << output;
    test::expect_no_temporaries(dir_);
  }

  fs::path write_text(const std::string& name, const std::string& text) const {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

  fs::path write_volume_file(const std::string& name, std::array<int, 3> n, const Eigen::Vector3d& spacing,
                             const std::function<float(int, int, int)>& hu) const {
    auto image = CtImage::New();
    CtImage::RegionType region;
    region.SetSize({{static_cast<itk::SizeValueType>(n[0]), static_cast<itk::SizeValueType>(n[1]),
                     static_cast<itk::SizeValueType>(n[2])}});
    image->SetRegions(region);
    image->SetSpacing(spacing.data());
    image->Allocate();
    for (int k = 0; k < n[2]; ++k) {
      for (int j = 0; j < n[1]; ++j) {
        for (int i = 0; i < n[0]; ++i) image->SetPixel({{i, j, k}}, hu(i, j, k));
      }
    }
    const fs::path p = dir_ / name;
    write_volume(image, p);
    return p;
  }

  // `slices` 2-D DICOM slices (16 x 16, 1 mm pixels, 2 mm apart) with a disk of bone, one series UID.
  void write_dicom_series(const fs::path& dir, const std::string& series_uid, int slices) const {
    using Slice = itk::Image<short, 2>;
    fs::create_directories(dir);
    for (int s = 0; s < slices; ++s) {
      auto slice = Slice::New();
      Slice::RegionType region;
      Slice::SizeType size;
      size.Fill(16);
      region.SetSize(size);
      slice->SetRegions(region);
      slice->Allocate();
      for (int y = 0; y < 16; ++y) {
        for (int x = 0; x < 16; ++x) slice->SetPixel({{x, y}}, (x - 8) * (x - 8) + (y - 8) * (y - 8) < 25 ? 1000 : -1000);
      }
      auto io = itk::GDCMImageIO::New();
      io->KeepOriginalUIDOn();
      itk::MetaDataDictionary& dict = io->GetMetaDataDictionary();
      itk::EncapsulateMetaData<std::string>(dict, "0008|0060", "CT");
      itk::EncapsulateMetaData<std::string>(dict, "0020|000d", "1.2.826.0.1.3680043.2.1125.7");
      itk::EncapsulateMetaData<std::string>(dict, "0020|000e", series_uid);
      itk::EncapsulateMetaData<std::string>(dict, "0008|0018", series_uid + "." + std::to_string(s + 1));
      itk::EncapsulateMetaData<std::string>(dict, "0020|0013", std::to_string(s + 1));
      itk::EncapsulateMetaData<std::string>(dict, "0020|0032", "0\\0\\" + std::to_string(2.0 * s));
      itk::EncapsulateMetaData<std::string>(dict, "0020|0037", "1\\0\\0\\0\\1\\0");
      itk::EncapsulateMetaData<std::string>(dict, "0028|0030", "1\\1");
      itk::EncapsulateMetaData<std::string>(dict, "0028|0004", "MONOCHROME2");
      auto writer = itk::ImageFileWriter<Slice>::New();
      writer->SetImageIO(io);
      writer->SetInput(slice);
      writer->UseInputMetaDataDictionaryOff();
      writer->SetFileName((dir / (series_uid + "_" + std::to_string(s) + ".dcm")).string());
      writer->Update();
    }
  }

  static nlohmann::json json_of(const CliRun& r) {
    try {
      return nlohmann::json::parse(r.out);
    } catch (const std::exception&) {
      ADD_FAILURE() << "no JSON on stdout: " << r.out << r.err;
      return nlohmann::json::object();
    }
  }

  test::ScopedTempDir tmp_{"contourmesh_bad_input"};
  const fs::path& dir_ = tmp_.path();
  Mesh stack_;
};

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void cut(const fs::path& p, std::size_t keep) {
  const std::string bytes = read_bytes(p);
  std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes.substr(0, keep);
}

// A small closed mesh as text: a tetrahedron in OBJ, with `vertex2` as the text of vertex 2's line.
std::string tetra_obj(const std::string& vertex2 = "v 0 1 0", const std::string& last_face = "f 2 3 4") {
  return "# tetrahedron\nv 0 0 0\nv 1 0 0\n" + vertex2 + "\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n" + last_face + "\n";
}

std::string tetra_ascii_ply(const std::string& vertex2 = "0 1 0", const std::string& last_face = "3 1 2 3") {
  return "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n" +
         vertex2 + "\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n" + last_face + "\n";
}

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
  cut(ascii, read_bytes(ascii).find('\n', read_bytes(ascii).size() / 2) + 1);  // after a whole line
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
  cut(ply, read_bytes(ply).size() * 6 / 10);
  expect_rejected(run("smooth " + ply.string() + " -o " + out.string()), {ply.string(), "PLY: data ends inside element"});
  const fs::path ascii = write_text("cut_ascii.ply", tetra_ascii_ply().substr(0, tetra_ascii_ply().size() - 12));
  expect_rejected(run("smooth " + ascii.string() + " -o " + out.string()),
                  {ascii.string(), "PLY: data ends inside element 'face'"});
  const fs::path vtp = dir_ / "cut.vtp";
  write_mesh(stack_, vtp);
  cut(vtp, read_bytes(vtp).size() * 6 / 10);
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

// Replaces every occurrence of `from`'s bytes (or text) in a file by `to`'s.
void patch(const fs::path& p, const std::string& from, const std::string& to) {
  std::string bytes = read_bytes(p);
  for (auto at = bytes.find(from); at != std::string::npos; at = bytes.find(from, at + to.size())) {
    bytes.replace(at, from.size(), to);
  }
  std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
}

template <typename T>
std::string bytes_of(T value) {
  std::string b(sizeof(T), '\0');
  std::memcpy(b.data(), &value, sizeof(T));
  return b;
}

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
  expect_rejected(run("detect " + obj_inf.string() + " -o " + out.string()), {"vertex 3 has a non-finite coordinate '-inf'"});
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

// ----- Meshes that are repaired or smoothed as they are --------------------------------------------------

TEST_F(BadInput, ZeroAreaAndDuplicateTrianglesAreRepairedWithAWarning) {
  Mesh m = stack_;
  const Index n = m.num_vertices();
  const Triangle t = m.triangles[20];
  m.triangles.push_back(m.triangles[3]);        // duplicate
  m.triangles.push_back({t[2], t[1], t[0]});    // duplicate, reversed
  m.triangles.push_back({t[0], t[0], t[1]});    // a repeated vertex: zero area by construction
  m.positions.conservativeResize(3, n + 1);     // a sliver: three distinct vertices on one line
  m.positions.col(n) = 0.5 * (m.positions.col(t[0]) + m.positions.col(t[1]));
  m.slice_ids.push_back(kNoId);
  m.contour_ids.push_back(kNoId);
  m.triangles.push_back({t[0], n, t[1]});
  write_mesh(m, dir_ / "dirty.ply");
  for (const std::string method : {"taubin", "paper"}) {
    const fs::path out = dir_ / ("clean_" + method + ".ply");
    const CliRun r = run("smooth " + (dir_ / "dirty.ply").string() + " -o " + out.string() + " --method " + method +
                         " --json");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("repaired: dropped 1 triangle with a repeated vertex and 2 duplicate triangles"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("degenerate triangle " + std::to_string(stack_.num_faces()) + " (zero area)"),
              std::string::npos)
        << "the sliver is kept, and reported: " << r.err;
    EXPECT_EQ(json_of(r)["faces"], stack_.num_faces() + 1);
    const Mesh result = read_mesh(out);
    EXPECT_EQ(result.num_faces(), stack_.num_faces() + 1);
    EXPECT_TRUE(result.positions.allFinite()) << method;
  }
}

TEST_F(BadInput, CoincidentVerticesOfATriangleSoupAreMerged) {
  // Each triangle with its own three vertices: without merging, smoothing would shrink every one alone.
  const Mesh sphere = make_icosphere(2);
  Mesh soup;
  soup.positions.resize(3, 3 * sphere.num_faces());
  for (Index f = 0; f < sphere.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) soup.positions.col(3 * f + k) = sphere.positions.col(sphere.triangles[f][k]);
    soup.triangles.push_back({3 * f, 3 * f + 1, 3 * f + 2});
  }
  write_mesh(soup, dir_ / "soup.ply");
  const CliRun r = run("smooth " + (dir_ / "soup.ply").string() + " -o " + (dir_ / "out.ply").string() +
                       " --method taubin --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("merged " + std::to_string(soup.num_vertices() - sphere.num_vertices()) + " coincident vertices"),
            std::string::npos)
      << r.err;
  const auto j = json_of(r);
  EXPECT_EQ(j["vertices"], sphere.num_vertices());
  EXPECT_TRUE(j["is_closed"].get<bool>());
}

TEST_F(BadInput, NonManifoldEdgesAndVerticesAreSmoothedWithAWarning) {
  Mesh m = stack_;
  const Index n = m.num_vertices();
  const Triangle t = m.triangles[30];
  m.positions.conservativeResize(3, n + 3);
  m.positions.col(n) = m.positions.col(t[0]) + Eigen::Vector3d(4, 4, 0.3);   // a fin on edge (t0, t1)
  m.positions.col(n + 1) = m.positions.col(t[2]) + Eigen::Vector3d(5, 0, 0.2);  // a flap at vertex t2
  m.positions.col(n + 2) = m.positions.col(t[2]) + Eigen::Vector3d(5, 1, -0.2);
  m.triangles.push_back({t[0], t[1], n});
  m.triangles.push_back({t[2], n + 1, n + 2});
  for (int k = 0; k < 3; ++k) {
    m.slice_ids.push_back(kNoId);
    m.contour_ids.push_back(kNoId);
  }
  write_mesh(m, dir_ / "nonmanifold.vtp");
  for (const std::string method : {"paper", "taubin", "laplacian", "mcf", "mindist"}) {
    const fs::path out = dir_ / ("out_" + method + ".vtp");
    const CliRun r = run("smooth " + (dir_ / "nonmanifold.vtp").string() + " -o " + out.string() + " --method " + method);
    ASSERT_EQ(r.code, 0) << method << ": " << r.err;
    EXPECT_NE(r.err.find("topology problems left as they are, first: non-manifold edge between vertices"),
              std::string::npos)
        << r.err;
    EXPECT_TRUE(read_mesh(out).positions.allFinite()) << method;
  }
  const CliRun d = run("detect " + (dir_ / "nonmanifold.vtp").string() + " -o " + (dir_ / "labels.vtp").string());
  EXPECT_EQ(d.code, 0) << d.err;
}

TEST_F(BadInput, OpenMeshesAreSmoothedWithTheirBoundaryFixed) {
  // The stack without its caps: an open tube.
  Mesh tube = stack_;
  std::erase_if(tube.triangles, [&](const Triangle& t) {
    return tube.slice_ids[t[0]] == kNoId || tube.slice_ids[t[1]] == kNoId || tube.slice_ids[t[2]] == kNoId;
  });
  write_mesh(tube, dir_ / "tube.ply");
  const MeshAdjacency adjacency = build_adjacency(tube);
  ASSERT_FALSE(adjacency.is_closed());
  for (const std::string method : {"paper", "taubin"}) {
    const fs::path out = dir_ / ("tube_" + method + ".ply");
    const CliRun r = run("smooth " + (dir_ / "tube.ply").string() + " -o " + out.string() + " --method " + method +
                         " --json");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_FALSE(json_of(r)["is_closed"].get<bool>());
    const Mesh result = read_mesh(out);
    ASSERT_EQ(result.num_vertices(), tube.num_vertices());
    double boundary_moved = 0.0, interior_moved = 0.0;
    for (Index i = 0; i < tube.num_vertices(); ++i) {
      const double d = (result.positions.col(i) - tube.positions.col(i)).norm();
      double& worst = adjacency.is_boundary[i] ? boundary_moved : interior_moved;
      worst = std::max(worst, d);
    }
    EXPECT_EQ(boundary_moved, 0.0) << method << ": --boundary fixed is the default";
    EXPECT_GT(interior_moved, 0.0) << method;
  }
}

// (The paper's detection: it has a fallback without ids; cross-slice smoothing, the default, needs them.)
TEST_F(BadInput, MissingContourIdsFallBackWithAWarning) {
  write_mesh(stack_, dir_ / "plain.stl");
  CliRun r = run("detect " + (dir_ / "plain.stl").string() + " -o " + (dir_ / "l.vtp").string() + " --method paper --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(json_of(r)["mode"], "curvature-only");
  EXPECT_NE(r.err.find("has no contour ids"), std::string::npos) << r.err;
  r = run("detect " + (dir_ / "plain.stl").string() + " -o " + (dir_ / "l.vtp").string() + " --slice-axis z --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(json_of(r)["id_source"], "slice-planes");
  r = run("detect " + (dir_ / "plain.stl").string() + " -o " + (dir_ / "l.vtp").string() + " --slice-axis x");
  expect_rejected(r, {"plain.stl", "do not lie on planes normal to the slice axis x"});
  // The default, cross-slice smoothing, refuses a mesh without ids, naming the way out.
  r = run("smooth " + (dir_ / "plain.stl").string() + " -o " + (dir_ / "o.stl").string());
  expect_rejected(r, {"plain.stl", "cross-slice smoothing needs contour ids", "--slice-axis"});
  r = run("smooth " + (dir_ / "plain.stl").string() + " -o " + (dir_ / "o.stl").string() + " --slice-axis z");
  EXPECT_EQ(r.code, 0) << r.err;
}

TEST_F(BadInput, InconsistentContourIdsAreCorrected) {
  auto detect = [&](const Mesh& m, const std::string& name) {
    write_mesh(m, dir_ / name);
    return run("detect " + (dir_ / name).string() + " -o " + (dir_ / "labels.ply").string() + " --method paper --json");
  };
  const CliRun clean = detect(stack_, "clean.ply");
  ASSERT_EQ(clean.code, 0) << clean.err;
  const auto truth = json_of(clean);
  EXPECT_EQ(truth["id_source"], "file");
  auto expect_same_labels = [&](const CliRun& r, const std::string& source, const std::string& warning) {
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = json_of(r);
    EXPECT_EQ(j["id_source"], source);
    EXPECT_EQ(j["edge_vertices"], truth["edge_vertices"]);
    EXPECT_EQ(j["noise_vertices"], truth["noise_vertices"]);
    EXPECT_NE(r.err.find(warning), std::string::npos) << r.err;
  };
  // Ids that jump by 2: slice 4 onwards numbered from 5.
  Mesh gap = stack_;
  for (auto& s : gap.slice_ids) s += s >= 4 ? 1 : 0;
  expect_same_labels(detect(gap, "gap.ply"), "file", "the slice ids skip 1 unused value: renumbered them");
  // A vertex of slice 4 labelled slice 5: a same-slice edge between two slice planes.
  Index v = 0;
  while (stack_.slice_ids[v] != 4) ++v;
  Mesh wrong = stack_;
  wrong.slice_ids[v] = 5;
  expect_same_labels(detect(wrong, "wrong.ply"), "file-repaired", "inconsistent contour ids (");
  // Nonsense ids: negative (refused: -1 is the only legal negative id), and far beyond the others.
  Mesh negative = stack_;
  negative.slice_ids[v] = -7;
  expect_rejected(detect(negative, "negative.ply"),
                  {"negative.ply: vertex " + std::to_string(v) + " has slice id -7", "ids are >= 0, or -1"});
  Mesh huge = stack_;
  huge.slice_ids[v] = 1'000'000;
  expect_same_labels(detect(huge, "huge.ply"), "file-repaired", "corrected them from the slice planes");
  // Off the planes (noise across the slices too): nothing to recover from, curvature-only detection.
  Mesh off_planes = stack_;
  add_noise(off_planes, {0.05, 3, NoiseDirection::Isotropic});
  off_planes.slice_ids[v] = 6;
  const CliRun r = detect(off_planes, "off_planes.ply");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(json_of(r)["mode"], "curvature-only");
  EXPECT_NE(r.err.find("no slice planes to recover them from"), std::string::npos) << r.err;
}

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
  // 50 x 50 x 0.01 mm: a pancake.
  const fs::path pancake = write_volume_file("pancake.mha", {12, 12, 8}, {50, 50, 0.01}, [](int i, int j, int k) {
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
  EXPECT_EQ(read_bytes(out), "precious bytes");
  EXPECT_EQ(read_bytes(labels), "precious labels");
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
