// SPDX-License-Identifier: BSD-3-Clause
// Damaged volumes and DICOM series (docs/robustness.md): each used to give a plausible mesh of the wrong
// shape with exit status 0. Now each is refused with exit 2 and one line naming the file and the
// problem (or, on request, repaired with a warning). The files are made by tests/damaged_inputs.h.
#include "cli_runner.h"
#include "damaged_inputs.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace contourmesh {
namespace {

namespace fs = std::filesystem;

class DamagedVolume : public ::testing::Test {
 protected:
  test::CliRun run(const std::string& args, const std::string& prefix = "") const {
    return test::run_cli(CONTOURMESH_CLI, args, dir_, prefix);
  }
  // Refused by `reconstruct` and by `run`, naming the file; nothing written.
  void expect_refused(const fs::path& input, const std::vector<std::string>& fragments,
                      const std::string& options = "", bool also_run = true) const {
    std::vector<std::string> all = fragments;
    all.push_back(input.string() + ": ");
    test::expect_rejected(run("reconstruct " + input.string() + " -o " + out_.string() + " " + options), all);
    if (also_run) test::expect_rejected(run("run " + input.string() + " -o " + out_.string() + " " + options), all);
    EXPECT_FALSE(fs::exists(out_));
    test::expect_no_temporaries(dir_);
  }
  fs::path volume(const std::string& name, bool compressed = false) const {
    const fs::path p = dir_ / name;
    test::write_raw_volume(*test::small_volume(), p, compressed);
    return p;
  }
  nlohmann::json reconstruct_json(const fs::path& input, const std::string& options = "") const {
    const test::CliRun r = run("reconstruct " + input.string() + " -o " + out_.string() + " --json " + options);
    EXPECT_EQ(r.code, 0) << r.err;
    fs::remove(out_);
    return r.code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json::object();
  }

  test::ScopedTempDir tmp_{"contourmesh_damaged_volume"};
  const fs::path& dir_ = tmp_.path();
  const fs::path out_ = dir_ / "out.vtp";
};

TEST_F(DamagedVolume, ANiftiGzCutPartwayIsRefused) {
  const fs::path whole = volume("whole.nii.gz");
  EXPECT_GT(reconstruct_json(whole)["volume"].get<double>(), 0.0) << "the intact file reads";
  const fs::path cut = volume("cut.nii.gz");
  test::cut_file_fraction(cut, 0.6);
  expect_refused(cut, {"the gzip-compressed data stop in the middle of their compressed stream", "truncated file?"});
}

TEST_F(DamagedVolume, ANiftiCutInItsDataOrItsHeaderIsRefused) {
  const fs::path data = volume("data.nii");
  test::cut_file_fraction(data, 0.7);
  expect_refused(data, {"the header promises 28 x 24 x 12 voxels of 4 bytes (32256 bytes) but the file holds",
                        "(truncated file?)"});
  const fs::path header = volume("header.nii");
  test::cut_file(header, 200);
  expect_refused(header, {"shorter than a NIfTI header"});
}

TEST_F(DamagedVolume, AMetaImageShorterThanDimSizeIsRefused) {
  const fs::path p = volume("short.mha");
  test::cut_file_fraction(p, 0.7);
  expect_refused(p, {"the header promises 28 x 24 x 12 voxels of 4 bytes (32256 bytes) but the file holds"});
}

TEST_F(DamagedVolume, AMetaImageWithACutOrCorruptZlibStreamIsRefused) {
  const fs::path whole = volume("whole.mha", true);
  EXPECT_GT(reconstruct_json(whole)["volume"].get<double>(), 0.0) << "the intact compressed file reads";
  const fs::path cut = volume("cut.mha", true);
  test::cut_file_fraction(cut, 0.8);
  expect_refused(cut, {"compressed data", "(truncated file?)"});
  // The stream's middle overwritten: zlib finds it corrupt.
  const fs::path corrupt = volume("corrupt.mha", true);
  const std::string bytes = test::read_bytes(corrupt);
  const std::size_t data = bytes.find("ElementDataFile = LOCAL\n") + 24;
  ASSERT_TRUE(test::replace_in_file(corrupt, bytes.substr(data + 20, 16), std::string(16, '\xff')));
  expect_refused(corrupt, {"the compressed voxel data are corrupt (zlib: "});
}

TEST_F(DamagedVolume, ZeroNegativeAndNonFiniteSpacingsAreRefused) {
  for (const std::string spacing : {"1 0 2", "1 -1 2", "1 nan 2", "1 inf 2"}) {
    const fs::path p = volume("spacing.mha");
    ASSERT_TRUE(test::replace_in_file(p, "ElementSpacing = 1 1 2", "ElementSpacing = " + spacing));
    const test::CliRun r = run("reconstruct " + p.string() + " -o " + out_.string());
    test::expect_rejected(r, {p.string() + ": "});
    EXPECT_TRUE(r.err.find("spacing") != std::string::npos || r.err.find("ElementSpacing") != std::string::npos)
        << spacing << ": " << r.err;
  }
}

TEST_F(DamagedVolume, AShearedDirectionIsRefusedNotOrthogonalised) {
  // A gantry tilt: the slice axis leans 17.5 degrees towards y.
  const fs::path mha = volume("sheared.mha");
  ASSERT_TRUE(test::replace_in_file(mha, "TransformMatrix = 1 0 0 0 1 0 0 0 1",
                                    "TransformMatrix = 1 0 0 0 1 0 0 0.3 0.953939"));
  expect_refused(mha, {"the direction matrix is sheared: voxel axes 2 and 3 meet at 72.5 degrees, not 90",
                       "resample the volume onto an orthogonal grid first"});
  // NIfTI: ITK turned a sheared sform into an orthogonal one without a word.
  const fs::path nii = volume("sheared.nii");
  test::patch_floats(nii, 280, {-1.0f, 0.0f, 0.9f});  // srow_x: the slice axis gains an x component
  expect_refused(nii, {"the NIfTI sform matrix is sheared: voxel axes 1 and 3 meet at"});
}

TEST_F(DamagedVolume, ASingularDirectionIsOneLine) {
  const fs::path p = volume("singular.mha");
  ASSERT_TRUE(test::replace_in_file(p, "TransformMatrix = 1 0 0 0 1 0 0 0 1", "TransformMatrix = 1 0 0 0 1 0 0 1 0"));
  expect_refused(p, {"the direction matrix is singular (its axes do not span 3-D space)"});
}

TEST_F(DamagedVolume, NonFiniteVoxelsAreRefusedUnlessReadAsAir) {
  const double clean = reconstruct_json(volume("clean.mha"))["volume"].get<double>();
  const fs::path p = volume("nan.mha");
  // 37 NaN voxels in the bone, from voxel (10, 8, 5) on.
  test::set_mha_voxels(p, 10 + 28 * (8 + 24 * 5), 37, std::numeric_limits<float>::quiet_NaN());
  expect_refused(p, {"37 of its 8064 voxels are NaN or infinite (the first at voxel (10, 8, 5))",
                     "give --non-finite-as-air"});
  const test::CliRun r = run("reconstruct " + p.string() + " -o " + out_.string() + " --non-finite-as-air --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: " + p.string() + ": 37 of its 8064 voxels are NaN or infinite"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("read them as air, 40"), std::string::npos) << r.err;
  EXPECT_LT(nlohmann::json::parse(r.out)["volume"].get<double>(), clean) << "the NaN voxels became air";
  fs::remove(out_);
  // Every voxel NaN: Otsu has nothing to work on, and that is bad input, not an internal error.
  const fs::path all = volume("all_nan.mha");
  test::set_mha_voxels(all, 0, 28 * 24 * 12, std::numeric_limits<float>::quiet_NaN());
  expect_refused(all, {"NaN or infinite"}, "--otsu", false);
  expect_refused(all, {"every voxel is NaN or infinite"}, "--otsu --non-finite-as-air", false);
}

// ----- DICOM series -------------------------------------------------------------------------------

class DamagedDicom : public DamagedVolume {
 protected:
  void SetUp() override {
    if (!fs::is_directory(test::headneck_series())) GTEST_SKIP() << "no " << test::headneck_series();
    slices_ = test::copy_headneck_slices(series_, 20, 5);
  }
  fs::path series_ = dir_ / "series";
  std::vector<fs::path> slices_;
};

TEST_F(DamagedDicom, TheIntactSeriesReads) {
  const auto j = reconstruct_json(series_);
  EXPECT_EQ(j["size"], nlohmann::json::array({512, 512, 5}));
  EXPECT_NEAR(j["spacing"][2].get<double>(), 1.2, 1e-9);
}

TEST_F(DamagedDicom, ADuplicatedSlicePositionIsRefused) {
  test::set_dicom_text(slices_[3], 0x0020, 0x0032, test::dicom_text(slices_[2], 0x0020, 0x0032));
  expect_refused(series_, {slices_[2].filename().string(), slices_[3].filename().string(),
                           "lie at the same position", "a duplicated slice"});
}

TEST_F(DamagedDicom, AFileCutInTheMiddleOfTheSeriesIsRefused) {
  test::cut_file_fraction(slices_[2], 0.5);
  expect_refused(series_, {slices_[2].filename().string() + ": its pixel data are cut", "of the 524288 bytes"});
}

TEST_F(DamagedDicom, AFileThatDoesNotDecodeIsRefused) {
  test::cut_file(slices_[2], 1000);  // inside the header: the series scan leaves it out
  expect_refused(series_, {slices_[2].filename().string() + ": cannot be decoded as DICOM"});
}

TEST_F(DamagedDicom, AMissingSliceIsRefusedOrResampledOnRequest) {
  fs::remove(slices_[2]);
  expect_refused(series_, {"uneven slice spacing", "2.4 mm apart, most slices 1.2 mm (a missing slice?)",
                           "give --allow-uneven-slices"});
  const test::CliRun r =
      run("reconstruct " + series_.string() + " -o " + out_.string() + " --allow-uneven-slices --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("resampled the 4 slices onto 5 slices 1.2 mm apart"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["size"], nlohmann::json::array({512, 512, 5}));
  EXPECT_NEAR(j["spacing"][2].get<double>(), 1.2, 1e-9);
  // ITK's own warning about the gap stays off the terminal, unless --verbose.
  EXPECT_EQ(r.err.find("Non uniform sampling"), std::string::npos) << r.err;
  const test::CliRun verbose =
      run("reconstruct " + series_.string() + " -o " + out_.string() + " --allow-uneven-slices --verbose");
  EXPECT_EQ(verbose.code, 0) << verbose.err;
  EXPECT_NE(verbose.err.find("Non uniform sampling"), std::string::npos)
      << "--verbose shows ITK's text: " << verbose.err;
}

TEST_F(DamagedDicom, MismatchedSizesAndOrientationsAreRefused) {
  test::set_dicom_us(slices_[1], 0x0028, 0x0010, 256);  // Rows
  expect_refused(series_, {slices_[1].filename().string() + " is 512 x 256 pixels but", "one size"});
  slices_ = test::copy_headneck_slices(series_, 20, 5);
  test::set_dicom_text(slices_[3], 0x0020, 0x0037, "1\\0\\0\\0\\0.980581\\0.196116");
  expect_refused(series_, {slices_[3].filename().string(), "have different orientations"});
}

TEST_F(DamagedDicom, ASeriesDriftingSidewaysIsRefused) {
  // A gantry tilt shifts each slice sideways: stacked straight, the volume is sheared.
  for (std::size_t k = 0; k < slices_.size(); ++k) {
    std::string position = test::dicom_text(slices_[k], 0x0020, 0x0032);
    const double y = std::stod(position.substr(position.find('\\') + 1));
    const std::string x = position.substr(0, position.find('\\'));
    const std::string z = position.substr(position.rfind('\\') + 1);
    test::set_dicom_text(slices_[k], 0x0020, 0x0032, x + "\\" + std::to_string(y + 0.4 * k) + "\\" + z);
  }
  expect_refused(series_, {"mm sideways of the line through", "the slices are sheared (a gantry tilt?)"});
}

}  // namespace
}  // namespace contourmesh
