// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/vtk/atomic_file.h>
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/shapes.h>

#include <gtest/gtest.h>

#include <vtkDataArray.h>
#include <vtkType.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "test_support.h"

namespace contourmesh {
namespace {

namespace fs = std::filesystem;

class MeshIo : public ::testing::Test {
 protected:
  static Mesh stack_with_ids() {
    Mesh m = test::noisy_ridge_stack(5, 30, 2.0, 9);
    for (std::size_t i = 0; i < m.contour_ids.size(); ++i) m.contour_ids[i] = static_cast<int>(i % 3);
    return m;
  }

  static void write_bytes(const fs::path& p, const std::string& bytes) {
    std::ofstream(p, std::ios::binary) << bytes;
  }

  // Files in the test directory other than `keep`.
  [[nodiscard]] std::vector<std::string> stray_files(const fs::path& keep = {}) const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir_)) {
      if (e.path() != keep) out.push_back(e.path().filename().string());
    }
    return out;
  }

  test::ScopedTempDir tmp_{"contourmesh_io"};
  const fs::path& dir_ = tmp_.path();
};

TEST_F(MeshIo, RoundTripKeepsPositionsConnectivityAndIds) {
  const Mesh m = stack_with_ids();
  struct Case {
    const char* file;
    double tolerance;  // STL stores floats
    bool ids;
  };
  for (const Case c : {Case{"m.ply", 0.0, true}, Case{"m.vtp", 0.0, true}, Case{"m.obj", 1e-5, false},
                       Case{"m.stl", 1e-5, false}}) {
    const fs::path p = dir_ / c.file;
    write_mesh(m, p);
    const Mesh r = read_mesh(p);
    ASSERT_EQ(r.num_vertices(), m.num_vertices()) << c.file;  // STL corners are merged back
    ASSERT_EQ(r.num_faces(), m.num_faces()) << c.file;
    EXPECT_EQ(r.has_contour_ids(), c.ids) << c.file;
    if (c.ids) {
      EXPECT_EQ(r.slice_ids, m.slice_ids) << c.file;
      EXPECT_EQ(r.contour_ids, m.contour_ids) << c.file;
      EXPECT_EQ(r.positions, m.positions) << c.file;
      EXPECT_EQ(r.triangles, m.triangles) << c.file;
    } else {
      // Vertex order may change (STL merging): compare each triangle's corners geometrically.
      double worst = 0.0;
      for (Index f = 0; f < m.num_faces(); ++f) {
        for (int k = 0; k < 3; ++k) {
          worst = std::max(worst, (r.positions.col(r.triangles[f][k]) - m.positions.col(m.triangles[f][k])).norm());
        }
      }
      EXPECT_LE(worst, c.tolerance * 20.0) << c.file;
    }
  }
  EXPECT_EQ(stray_files().size(), 4u);  // no temporaries left behind
}

TEST_F(MeshIo, AsciiStlAndExplicitFormat) {
  const Mesh m = make_icosphere(2);
  const fs::path p = dir_ / "ascii.stl";
  write_mesh(m, p, {MeshFormat::StlAscii, {}, {}, {}});
  std::ifstream in(p);
  std::string first;
  in >> first;
  EXPECT_EQ(first, "solid");
  EXPECT_EQ(read_mesh(p).num_faces(), m.num_faces());
  // A .dat file written as PLY by explicit format, read back the same way.
  const fs::path q = dir_ / "mesh.dat";
  write_mesh(m, q, {MeshFormat::Ply, {}, {}, {}});
  EXPECT_EQ(read_mesh(q, {MeshFormat::Ply, {}}).num_vertices(), m.num_vertices());
}

TEST_F(MeshIo, CustomIdArrayNames) {
  const Mesh m = stack_with_ids();
  const ContourIdArrayNames names{"Slice", "Which"};
  for (const char* file : {"n.vtp", "n.ply"}) {
    write_mesh(m, dir_ / file, {MeshFormat::Auto, names, {}, {}});
    EXPECT_FALSE(read_mesh(dir_ / file).has_contour_ids()) << file;
    EXPECT_EQ(read_mesh(dir_ / file, {MeshFormat::Auto, names}).slice_ids, m.slice_ids) << file;
  }
}

TEST_F(MeshIo, ExtraPointArraysGoToVtpAndPlyOnly) {
  const Mesh m = stack_with_ids();
  MeshWriteOptions o;
  PointScalars labels{"FeatureLabel", {}, ScalarType::Int32};
  PointScalars curvature{"KappaMax", {}, ScalarType::Float64};
  for (Index i = 0; i < m.num_vertices(); ++i) {
    labels.values.push_back(i % 4);
    curvature.values.push_back(0.5 * i);
  }
  o.point_scalars = {labels, curvature};
  write_mesh(m, dir_ / "labels.vtp", o);
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((dir_ / "labels.vtp").c_str());
  reader->Update();
  vtkDataArray* l = reader->GetOutput()->GetPointData()->GetArray("FeatureLabel");
  vtkDataArray* k = reader->GetOutput()->GetPointData()->GetArray("KappaMax");
  ASSERT_NE(l, nullptr);
  ASSERT_NE(k, nullptr);
  EXPECT_EQ(l->GetDataType(), VTK_INT);
  EXPECT_EQ(l->GetComponent(7, 0), 3.0);
  EXPECT_EQ(k->GetComponent(7, 0), 3.5);
  write_mesh(m, dir_ / "labels.ply", o);
  std::ifstream ply(dir_ / "labels.ply", std::ios::binary);
  std::string header((std::istreambuf_iterator<char>(ply)), {});
  EXPECT_NE(header.find("property int FeatureLabel"), std::string::npos);
  EXPECT_EQ(read_mesh(dir_ / "labels.ply").slice_ids, m.slice_ids);  // extra properties are skipped
  EXPECT_THROW(write_mesh(m, dir_ / "labels.stl", o), InvalidInputError);
  o.point_scalars[0].values.pop_back();
  EXPECT_THROW(write_mesh(m, dir_ / "short.vtp", o), InvalidInputError);
  EXPECT_FALSE(fs::exists(dir_ / "short.vtp"));
}

TEST_F(MeshIo, AsciiPlyWithQuadsAndExtraElements) {
  write_bytes(dir_ / "quad.ply",
              "ply\nformat ascii 1.0\ncomment hand written\nelement vertex 4\nproperty float x\nproperty float y\n"
              "property float z\nproperty uchar red\nelement face 1\nproperty list uchar int vertex_indices\n"
              "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
              "0 0 0 1\n1 0 0 2\n1 1 0 3\n0 1 0 4\n4 0 1 2 3\n0 1\n");
  const Mesh m = read_mesh(dir_ / "quad.ply");
  EXPECT_EQ(m.num_vertices(), 4);
  ASSERT_EQ(m.num_faces(), 2);
  EXPECT_EQ(m.triangles[1], (Triangle{0, 2, 3}));
}

std::string le_float(float v) {
  std::string out(4, '\0');
  std::uint32_t bits = 0;
  std::memcpy(&bits, &v, 4);
  for (int b = 0; b < 4; ++b) out[b] = static_cast<char>((bits >> (8 * b)) & 0xff);
  return out;
}

// A binary STL of the given triangles; the header text and the triangle count are the caller's.
std::string binary_stl(const std::string& header, std::uint32_t count, const std::vector<std::array<float, 9>>& tris) {
  std::string out = header;
  out.resize(80, ' ');
  for (int b = 0; b < 4; ++b) out += static_cast<char>((count >> (8 * b)) & 0xff);
  for (const auto& t : tris) {
    for (int k = 0; k < 3; ++k) out += le_float(0.0f);
    for (float v : t) out += le_float(v);
    out += std::string(2, '\0');
  }
  return out;
}

TEST_F(MeshIo, StlVariantsWrittenByOtherTools) {
  const std::vector<std::array<float, 9>> tet = {{0, 0, 0, 0, 1, 0, 1, 0, 0}, {0, 0, 0, 1, 0, 0, 0, 0, 1},
                                                 {0, 0, 0, 0, 0, 1, 0, 1, 0}, {1, 0, 0, 0, 1, 0, -0.0f, 0, 1}};
  // Binary whose header starts with "solid" (many exporters do this): told apart by its size.
  write_bytes(dir_ / "solid_header.stl", binary_stl("solid exported by some CAD tool", 4, tet));
  Mesh m = read_mesh(dir_ / "solid_header.stl");
  EXPECT_EQ(m.num_vertices(), 4) << "corners merged, -0 and 0 alike";
  EXPECT_EQ(m.num_faces(), 4);
  // A triangle count left at zero: all the triangles the file holds are read (as VTK does).
  write_bytes(dir_ / "count0.stl", binary_stl("", 0, tet));
  EXPECT_EQ(read_mesh(dir_ / "count0.stl").num_faces(), 4);
  // ASCII with two solids, blank lines, CRLF and upper case.
  write_bytes(dir_ / "two.stl",
              "solid a\r\n  FACET NORMAL 0 0 1\r\n OUTER LOOP\r\n VERTEX 0 0 0\r\n vertex 1 0 0\r\n vertex 0 1 0\r\n"
              " endloop\r\n endfacet\r\nendsolid a\r\n\r\nsolid b\nfacet normal 0 0 1\nouter loop\nvertex 1 0 0\n"
              "vertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid b\n");
  m = read_mesh(dir_ / "two.stl");
  EXPECT_EQ(m.num_vertices(), 4);
  ASSERT_EQ(m.num_faces(), 2);
  EXPECT_EQ(m.triangles[1][0], m.triangles[0][1]) << "shared corner across solids";
}

TEST_F(MeshIo, ObjFacesWithTextureAndNormalIndicesRelativeIndicesAndPolygons) {
  write_bytes(dir_ / "quad.obj",
              "# comment\nmtllib x.mtl\no square\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5 0.5 0.5\nv 0 1 0\n"
              "vt 0 0\nvn 0 0 1\ns off\nusemtl m\nf 1/1/1 2/1/1 3/1/1 4/1/1\nv 0 0 1\nf -5//1 -4//1 -1//1\nl 1 2\n");
  const Mesh m = read_mesh(dir_ / "quad.obj");
  ASSERT_EQ(m.num_vertices(), 5);
  ASSERT_EQ(m.num_faces(), 3);
  EXPECT_EQ(m.triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(m.triangles[1], (Triangle{0, 2, 3}));
  EXPECT_EQ(m.triangles[2], (Triangle{0, 1, 4}));
  EXPECT_EQ(m.positions.col(4), Eigen::Vector3d(0, 0, 1));
}

void expect_error(const fs::path& p, const std::string& fragment) {
  try {
    (void)read_mesh(p);
    FAIL() << "no error for " << p;
  } catch (const InvalidInputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(p.string()), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

TEST_F(MeshIo, BadInputsGiveClearErrorsNamingTheFile) {
  expect_error(dir_ / "missing.stl", "no such file");
  write_bytes(dir_ / "empty.stl", "");
  expect_error(dir_ / "empty.stl", "empty");
  write_bytes(dir_ / "mesh.xyz", "hello");
  expect_error(dir_ / "mesh.xyz", "unknown mesh extension");
  std::mt19937 rng(1);
  std::string noise(4096, '\0');
  for (char& ch : noise) ch = static_cast<char>(rng());
  write_bytes(dir_ / "noise.vtp", noise);
  expect_error(dir_ / "noise.vtp", "cannot read");
  write_bytes(dir_ / "noise.ply", noise);
  expect_error(dir_ / "noise.ply", "not a PLY file");
  write_bytes(dir_ / "cut.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 100\nproperty double x\n"
                                "property double y\nproperty double z\nend_header\n0123456789");
  expect_error(dir_ / "cut.ply", "data ends inside element 'vertex'");
  write_bytes(dir_ / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  expect_error(dir_ / "points.obj", "no triangles");
  write_bytes(dir_ / "badindex.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                     "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                     "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  expect_error(dir_ / "badindex.ply", "references vertex 7");
  expect_error(dir_, "is a directory");
}

TEST_F(MeshIo, FailedWriteLeavesNothingAndKeepsAnExistingFile) {
  const Mesh m = make_icosphere(1);
  EXPECT_THROW(write_mesh(m, dir_ / "no" / "such" / "dir.stl"), InvalidInputError);
  EXPECT_TRUE(stray_files().empty());

  const fs::path existing = dir_ / "keep.stl";
  write_bytes(existing, "precious");
  EXPECT_THROW(write_atomically(existing, [](const fs::path& tmp) {
                 std::ofstream(tmp) << "half";
                 throw InvalidInputError("simulated failure half way");
               }),
               InvalidInputError);
  std::ifstream in(existing);
  std::string content;
  in >> content;
  EXPECT_EQ(content, "precious");
  EXPECT_EQ(stray_files(existing).size(), 0u);
}

TEST_F(MeshIo, FormatNames) {
  EXPECT_EQ(parse_mesh_format("stl-ascii"), MeshFormat::StlAscii);
  EXPECT_THROW((void)parse_mesh_format("3mf"), InvalidInputError);
  EXPECT_EQ(format_from_extension("A.STL"), MeshFormat::StlBinary);
  EXPECT_TRUE(format_keeps_contour_ids(MeshFormat::Vtp));
  EXPECT_FALSE(format_keeps_contour_ids(MeshFormat::StlBinary));
}

}  // namespace
}  // namespace contourmesh
