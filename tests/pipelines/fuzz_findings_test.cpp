// SPDX-License-Identifier: BSD-3-Clause
// What the fuzz targets found in the mesh readers (tests/fuzz, docs/robustness.md "Fuzzing"), each
// rebuilt by hand as a small file and fed through read_mesh: a clear InvalidInputError naming the
// file, where there used to be undefined behaviour, a hang or a crash. The fuzzers' own reproducers
// are replayed by the FuzzReplay.* tests (tests/fuzz/regressions).
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/vtk/vtk_convert.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/shapes.h>

#include <gtest/gtest.h>

#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "test_support.h"

namespace contourmesh {
namespace {

namespace fs = std::filesystem;

class FuzzFindings : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& bytes) {
    const fs::path p = tmp_.path() / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  }

  static std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

  // read_mesh must throw an InvalidInputError that names the file and contains `fragment`.
  static void expect_rejected(const fs::path& p, const std::string& fragment, const MeshReadOptions& options = {}) {
    try {
      (void)read_mesh(p, options);
      FAIL() << "no error for " << p;
    } catch (const InvalidInputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(p.string() + ": ", 0), 0u) << what;
      EXPECT_NE(what.find(fragment), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }

  // A small closed mesh as an appended, zlib-compressed VTP: base64-encoded as write_mesh writes it
  // (VTK's default), or raw.
  std::string compressed_vtp(bool raw = false) {
    ContourStackSpec spec;
    spec.curve = ridge_circle_curve(5.0, 1.0, 0.5);
    spec.slices = 3;
    spec.points_per_contour = 8;
    const Mesh mesh = make_contour_stack(spec);
    const fs::path p = tmp_.path() / "clean.vtp";
    if (!raw) {
      write_mesh(mesh, p);
    } else {
      vtkNew<vtkXMLPolyDataWriter> writer;
      writer->SetInputData(to_polydata(mesh));
      writer->SetFileName(p.c_str());
      writer->SetDataModeToAppended();
      writer->EncodeAppendedDataOff();
      writer->SetCompressorTypeToZLib();
      writer->SetHeaderTypeToUInt64();
      EXPECT_EQ(writer->Write(), 1);
    }
    return slurp(p);
  }

  static std::string base64(const std::string& bytes) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
      const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
      std::uint32_t v = 0;
      for (std::size_t k = 0; k < 3; ++k) v = (v << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
      out += table[(v >> 18) & 63];
      out += table[(v >> 12) & 63];
      out += n > 1 ? table[(v >> 6) & 63] : '=';
      out += n > 2 ? table[v & 63] : '=';
    }
    return out;
  }

  static std::string unbase64(const std::string& text) {
    std::string out;
    for (std::size_t g = 0; g + 4 <= text.size(); g += 4) {
      std::uint32_t v = 0;
      int pad = 0;
      for (int k = 0; k < 4; ++k) {
        const char c = text[g + k];
        const std::size_t at = std::string("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/").find(c);
        pad += c == '=';
        v = (v << 6) | (at == std::string::npos ? 0u : static_cast<std::uint32_t>(at));
      }
      for (int b = 0; b < 3 - pad; ++b) out += static_cast<char>((v >> (16 - 8 * b)) & 0xff);
    }
    return out;
  }

  // Sets word `index` of the compression header of the array at offset 0 (the first one written):
  // [blocks][block size][last block size][compressed size of each block], little endian.
  static std::string with_header_word(std::string vtp, std::size_t index, std::uint64_t value) {
    const std::size_t word = vtp.find("header_type=\"UInt64\"") != std::string::npos ? 8 : 4;
    const bool raw = vtp.find("encoding=\"raw\"") != std::string::npos;
    EXPECT_NE(vtp.find("offset=\"0\""), std::string::npos);
    const std::size_t start = vtp.find('_', vtp.find("<AppendedData")) + 1;
    auto put = [&](std::string& bytes) {
      for (std::size_t b = 0; b < word; ++b) bytes[index * word + b] = static_cast<char>((value >> (8 * b)) & 0xff);
    };
    if (raw) {
      std::string header = vtp.substr(start, 4 * word);
      put(header);
      vtp.replace(start, header.size(), header);
      return vtp;
    }
    // Base64: the header is encoded on its own (3 words plus one per block), padded.
    const std::string first = unbase64(vtp.substr(start, (3 * word + 2) / 3 * 4));
    std::uint64_t blocks = 0;
    for (std::size_t b = 0; b < word; ++b) blocks |= std::uint64_t{static_cast<unsigned char>(first[b])} << (8 * b);
    const std::size_t chars = ((3 + blocks) * word + 2) / 3 * 4;
    std::string header = unbase64(vtp.substr(start, chars));
    put(header);
    vtp.replace(start, chars, base64(header));
    return vtp;
  }

  test::ScopedTempDir tmp_{"contourmesh_fuzz_findings"};
};

const std::string kTetraVertices = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
const std::string kTetraFaces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

// Found by fuzz_read_ply: an id property of 1e300 was converted to int (undefined behaviour).
TEST_F(FuzzFindings, PlyContourIdsMustBe32BitIntegers) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property double ContourId\nproperty double ContourIndex\nelement face 4\n"
      "property list uchar int vertex_indices\nend_header\n";
  const std::string faces = kTetraFaces;
  const fs::path huge = write("huge.ply", head + "0 0 0 0 0\n1 0 0 0 0\n0 1 0 0 0\n0 0 1 1 1e300\n" + faces);
  expect_rejected(huge, "vertex 3 has ContourIndex = 1e+300, not a 32-bit integer");
  const fs::path nan = write("nan.ply", head + "0 0 0 nan 0\n1 0 0 0 0\n0 1 0 0 0\n0 0 1 1 0\n" + faces);
  expect_rejected(nan, "vertex 0 has ContourId = nan");
  const fs::path half = write("half.ply", head + "0 0 0 0 0\n1 0 0 0.5 0\n0 1 0 0 0\n0 0 1 1 0\n" + faces);
  expect_rejected(half, "vertex 1 has ContourId = 0.5");
  const fs::path fine = write("fine.ply", head + "0 0 0 0 0\n1 0 0 0 0\n0 1 0 0 0\n0 0 1 -1 -1\n" + faces);
  const Mesh m = read_mesh(fine);
  EXPECT_EQ(m.slice_ids, (std::vector<std::int32_t>{0, 0, 0, -1}));
}

// An ASCII list length "nan" was converted to long long before being checked.
TEST_F(FuzzFindings, PlyListLengthThatIsNotANumberIsRejected) {
  const fs::path p = write("nanlist.ply",
                           "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                           "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n" +
                               kTetraVertices + "nan 0 1 2\n");
  expect_rejected(p, "bad list length");
}

// An element without properties and a count of 2^63 - 1 made the reader loop for ever over nothing.
TEST_F(FuzzFindings, PlyElementWithoutPropertiesIsSkippedWhateverItsCount) {
  const fs::path p = write("empty_element.ply",
                           "ply\nformat binary_little_endian 1.0\nelement nothing 9223372036854775807\n"
                           "element vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n");
  const auto start = std::chrono::steady_clock::now();
  expect_rejected(p, "no triangles");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

// Two vertex elements gave a mesh whose id arrays did not match its vertices.
TEST_F(FuzzFindings, PlyWithTwoVertexElementsIsRejected) {
  const std::string vertex = "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n";
  const fs::path p = write("two_vertex.ply", "ply\nformat ascii 1.0\n" + vertex + "property int ContourId\n" +
                                                 "property int ContourIndex\n" + vertex +
                                                 "end_header\n0 0 0 0 0\n1 0 0 0 0\n0 1 0 0 0\n0 0 1 1 0\n" +
                                                 kTetraVertices);
  expect_rejected(p, "more than one vertex element");
}

// Found by fuzz_read_vtp: VTK 9.1 trusts the compression header of appended data. A huge block count
// made it allocate for the count (bad_alloc or std::length_error escaping read_mesh), a block size of
// 0 made it divide by zero (SIGFPE, the process died), a block count of 0 with a last-block size made
// it allocate that size, and a huge compressed size made it allocate that.
TEST_F(FuzzFindings, VtpCompressionHeadersAreCheckedBeforeVtkTrustsThem) {
  for (const bool raw : {false, true}) {
    const std::string clean = compressed_vtp(raw);
    ASSERT_NE(clean.find("vtkZLibDataCompressor"), std::string::npos);
    const std::string kind = raw ? "raw_" : "base64_";
    EXPECT_GT(read_mesh(write(kind + "clean.vtp", clean)).num_faces(), 0);
    EXPECT_GT(read_mesh(write(kind + "rewritten.vtp", with_header_word(clean, 0, 1))).num_faces(), 0)
        << "the test's header rewriting keeps a valid file valid";

    expect_rejected(write(kind + "blocks.vtp", with_header_word(clean, 0, std::uint64_t{1} << 28)),
                    "blocks, more than the file could hold");
    expect_rejected(write(kind + "zero_block_size.vtp", with_header_word(clean, 1, 0)), "block size of 0");
    expect_rejected(write(kind + "no_blocks.vtp", with_header_word(with_header_word(clean, 0, 0), 2, 1000000)),
                    "no blocks but a last block of 1000000 bytes");
    expect_rejected(write(kind + "last.vtp", with_header_word(clean, 2, 1u << 30)), "is larger than the block size");
    expect_rejected(write(kind + "compressed.vtp", with_header_word(clean, 3, 1u << 30)),
                    "compressed bytes, more than the file holds");
  }
}

// The same checks apply to inline base64 data, decoded as VTK decodes it.
TEST_F(FuzzFindings, VtpInlineBinaryCompressionHeaderIsChecked) {
  // Headers (UInt32 words: blocks, block size, last block size, compressed sizes) encoded alone, as
  // VTK writes them, followed by some data.
  auto words = [](std::initializer_list<std::uint32_t> w) {
    std::string out;
    for (std::uint32_t v : w) {
      for (int b = 0; b < 4; ++b) out += static_cast<char>((v >> (8 * b)) & 0xff);
    }
    return out;
  };
  auto vtp = [&](const std::string& header) {
    return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt32\" compressor=\"vtkZLibDataCompressor\">\n<PolyData>\n"
           "<Piece NumberOfPoints=\"4\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
           "NumberOfPolys=\"1\">\n"
           "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">\n" +
           base64(header) +
           "AAAAAAAAAAAAAAAA\n</DataArray></Points>\n"
           "<Polys><DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray>"
           "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">3</DataArray></Polys>\n"
           "</Piece>\n</PolyData>\n</VTKFile>\n";
  };
  expect_rejected(write("inline_zero.vtp", vtp(words({1, 0, 48, 12}))), "block size of 0");
  expect_rejected(write("inline_blocks.vtp", vtp(words({4000000, 48, 48, 12}))), "more than the file could hold");
}

// VTK leaked its array iterator on points with other than 3 components; now refused before it reads.
TEST_F(FuzzFindings, VtpPointsNeedThreeComponents) {
  std::string vtp = compressed_vtp();
  const std::size_t points = vtp.find("NumberOfComponents=\"3\"");
  ASSERT_NE(points, std::string::npos);
  vtp[points + 20] = '6';
  expect_rejected(write("six.vtp", vtp), "the points have 6 components, not 3");
}

// VTK read a data array's NumberOfComponents into an int unchecked and then parsed tuples x components
// values: 42949672963 components on a point-data array of 4 points kept it busy for minutes (found by
// fuzz_read_vtp). Now refused before it reads.
TEST_F(FuzzFindings, VtpDataArrayWithAHugeComponentCountIsRefusedAtOnce) {
  const std::string vtp =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      "<PolyData><Piece NumberOfPoints=\"3\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
      "NumberOfPolys=\"1\">\n<PointData><DataArray type=\"Float64\" Name=\"weights\" "
      "NumberOfComponents=\"42949672963\" format=\"ascii\">0 0 1</DataArray></PointData>\n"
      "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0"
      "</DataArray></Points>\n"
      "<Polys><DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray>"
      "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">3</DataArray></Polys>\n"
      "</Piece>\n</PolyData>\n</VTKFile>\n";
  expect_rejected(write("components.vtp", vtp), "data array 'weights' of PointData has "
                                                "NumberOfComponents=\"42949672963\", not an integer in [1, 1024]");
  std::string zero = vtp;
  zero.replace(zero.find("42949672963"), 11, "0");
  expect_rejected(write("zero_components.vtp", zero), "has NumberOfComponents=\"0\"");
}

// VTK leaked an array's iterator when the file ended before a compressed array's header (found by
// fuzz_read_vtp: the appended data cut off after its start tag, and in the middle of a header).
TEST_F(FuzzFindings, VtpDataEndingBeforeACompressionHeaderIsReportedWithoutALeak) {
  const std::string vtp = compressed_vtp();
  const std::size_t data = vtp.find('_', vtp.find("<AppendedData"));
  ASSERT_NE(data, std::string::npos);
  expect_rejected(write("no_data.vtp", vtp.substr(0, data)), "ends before its compression header (truncated file?)");
  expect_rejected(write("short_header.vtp", vtp.substr(0, data + 1 + 5)),
                  "ends before its compression header (truncated file?)");
}

// With the AppendedData element's name damaged, VTK read a compressed array's header from the start of the
// file as base64 text and allocated 7 GB for the block sizes it announced (found by fuzz_read_vtp).
TEST_F(FuzzFindings, VtpOffsetsWithoutAppendedDataAreRejected) {
  std::string vtp = compressed_vtp();
  const std::size_t at = vtp.find("<AppendedData");
  ASSERT_NE(at, std::string::npos);
  vtp.replace(at, 13, "<AppendedDatacndo");
  expect_rejected(write("no_appended.vtp", vtp), "has an offset but the file has no AppendedData (corrupt file)");
}

// The points a file announces are checked against the vertex limit before VTK allocates for them.
TEST_F(FuzzFindings, VtpAnnouncedPointsAreLimitedBeforeVtkAllocates) {
  std::string vtp = compressed_vtp();
  const std::size_t at = vtp.find("NumberOfPoints=\"");
  ASSERT_NE(at, std::string::npos);
  const std::size_t end = vtp.find('"', at + 16);
  vtp.replace(at + 16, end - at - 16, "4000000000000");
  const fs::path p = write("many_points.vtp", vtp);
  EXPECT_THROW((void)read_mesh(p), LimitError);
  expect_rejected(p, "announces 4000000000000 points, more than the limit of 50000000");
}

// VTK sizes the connectivity from the last cell offset before reading it: 2^53 made it allocate 64 PB
// (found by fuzz_read_vtp once the compression headers were checked).
TEST_F(FuzzFindings, VtpCellOffsetsMustFitTheFile) {
  auto vtp = [](const std::string& offsets) {
    return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
           "<PolyData>\n<Piece NumberOfPoints=\"4\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
           "NumberOfPolys=\"4\">\n<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
           "0 0 0 1 0 0 0 1 0 0 0 1</DataArray></Points>\n<Polys><DataArray type=\"Int64\" Name=\"connectivity\" "
           "format=\"ascii\">0 2 1 0 1 3 0 3 2 1 2 3</DataArray><DataArray type=\"Int64\" Name=\"offsets\" "
           "format=\"ascii\">" + offsets + "</DataArray></Polys>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  };
  EXPECT_EQ(read_mesh(write("fine.vtp", vtp("3 6 9 12"))).num_faces(), 4);
  expect_rejected(write("huge.vtp", vtp("3 6 9 9007199254741004")),
                  "cell offset 3 is 9.0072e+15, more connectivity entries than the file can hold");
  expect_rejected(write("decreasing.vtp", vtp("3 6 2 12")), "cell offset 2 is 2, below the previous one");
}

// A ContourId array of doubles holding 1e300 was converted to int (undefined behaviour).
TEST_F(FuzzFindings, VtpContourIdsMustBe32BitIntegers) {
  const std::string vtp =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\">\n<PolyData>\n"
      "<Piece NumberOfPoints=\"4\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"4\">\n"
      "<PointData><DataArray type=\"Float64\" Name=\"ContourId\" format=\"ascii\">0 0 0 1e300</DataArray></PointData>\n"
      "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0 0 0 "
      "1</DataArray></Points>\n"
      "<Polys><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 2 1 0 1 3 0 3 2 1 2 3</DataArray>"
      "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">3 6 9 12</DataArray></Polys>\n"
      "</Piece>\n</PolyData>\n</VTKFile>\n";
  expect_rejected(write("huge_ids.vtp", vtp), "point 3 has ContourId = 1e+300, not a 32-bit integer");
}

}  // namespace
}  // namespace contourmesh
