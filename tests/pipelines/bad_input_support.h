// SPDX-License-Identifier: BSD-3-Clause
// Shared by the bad-input tests (the catalogue of docs/robustness.md): the BadInput fixture, which runs the
// contourmesh command on files written to a scratch folder, and small writers of damaged mesh files.
#pragma once

// ITK first: its writer headers pull in ITK's bundled Eigen, which must not follow the system one.
#include <itkGDCMImageIO.h>
#include <itkImageFileWriter.h>
#include <itkMetaDataObject.h>

#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/mesh.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "cli_runner.h"
#include "reconstruct/partial_volume.h"
#include "test_support.h"

namespace contourmesh::bad_input_test {

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
    const auto image = test::pixel_volume(n, spacing, hu);
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
        for (int x = 0; x < 16; ++x)
          slice->SetPixel({{x, y}}, (x - 8) * (x - 8) + (y - 8) * (y - 8) < 25 ? 1000 : -1000);
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

inline void cut(const fs::path& p, std::size_t keep) {
  const std::string bytes = test::read_bytes(p);
  std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes.substr(0, keep);
}

// A small closed mesh as text: a tetrahedron in OBJ, with `vertex2` as the text of vertex 2's line.
inline std::string tetra_obj(const std::string& vertex2 = "v 0 1 0", const std::string& last_face = "f 2 3 4") {
  return "# tetrahedron\nv 0 0 0\nv 1 0 0\n" + vertex2 + "\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n" + last_face + "\n";
}

inline std::string tetra_ascii_ply(const std::string& vertex2 = "0 1 0", const std::string& last_face = "3 1 2 3") {
  return "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n" +
         vertex2 + "\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n" + last_face + "\n";
}

// Replaces every occurrence of `from`'s bytes (or text) in a file by `to`'s.
inline void patch(const fs::path& p, const std::string& from, const std::string& to) {
  std::string bytes = test::read_bytes(p);
  for (auto at = bytes.find(from); at != std::string::npos; at = bytes.find(from, at + to.size())) {
    bytes.replace(at, from.size(), to);
  }
  std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
}

template <typename T>
inline std::string bytes_of(T value) {
  std::string b(sizeof(T), '\0');
  std::memcpy(b.data(), &value, sizeof(T));
  return b;
}

}  // namespace contourmesh::bad_input_test
