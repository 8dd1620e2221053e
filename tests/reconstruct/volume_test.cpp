// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/volume.h"

#include <contourmesh/smooth/errors.h>

#include <itkGDCMImageIO.h>
#include <itkImageFileWriter.h>
#include <itkMetaDataObject.h>
#include <itkMetaImageIO.h>
#include <itkMinimumMaximumImageCalculator.h>

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace contourmesh {
namespace {

namespace fs = std::filesystem;

const fs::path kSharedData = CONTOURMESH_SHARED_DATA;

// A fresh scratch directory per test, removed afterwards.
class VolumeIo : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("contourmesh_volume_" + std::to_string(::getpid()) + "_" + std::string(info->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

CtImage::Pointer make_image(unsigned nx, unsigned ny, unsigned nz) {
  auto image = CtImage::New();
  CtImage::RegionType region;
  CtImage::SizeType size;
  size[0] = nx;
  size[1] = ny;
  size[2] = nz;
  region.SetSize(size);
  image->SetRegions(region);
  CtImage::SpacingType spacing;
  spacing[0] = 0.7;
  spacing[1] = 0.8;
  spacing[2] = 2.0;
  image->SetSpacing(spacing);
  CtImage::PointType origin;
  origin[0] = -10.5;
  origin[1] = 3.25;
  origin[2] = 7.0;
  image->SetOrigin(origin);
  image->Allocate();
  float* data = image->GetBufferPointer();
  for (std::size_t i = 0; i < image->GetLargestPossibleRegion().GetNumberOfPixels(); ++i) {
    data[i] = -1000.0f + 1.25f * static_cast<float>(i) + 0.125f * static_cast<float>(i % 7);
  }
  return image;
}

std::string message_of(const fs::path& path) {
  try {
    (void)read_volume(path);
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "(no error)";
}

void expect_read_error(const fs::path& path, const std::string& expected_part) {
  const std::string message = message_of(path);
  EXPECT_EQ(message.rfind(path.string(), 0), 0u) << "message does not start with the path: " << message;
  EXPECT_NE(message.find(expected_part), std::string::npos) << message;
}

TEST_F(VolumeIo, RoundTripKeepsGeometryAndValues) {
  const CtImage::Pointer original = make_image(7, 6, 5);
  for (const char* name : {"vol.mha", "vol.nrrd", "vol.nii.gz", "vol.nii"}) {
    SCOPED_TRACE(name);
    const fs::path path = dir_ / name;
    write_volume(original, path);
    ASSERT_TRUE(fs::exists(path));
    const CtImage::Pointer back = read_volume(path);
    EXPECT_EQ(back->GetLargestPossibleRegion().GetSize(), original->GetLargestPossibleRegion().GetSize());
    for (unsigned a = 0; a < 3; ++a) {
      EXPECT_NEAR(back->GetSpacing()[a], original->GetSpacing()[a], 1e-5);
      EXPECT_NEAR(back->GetOrigin()[a], original->GetOrigin()[a], 1e-4);
    }
    const std::size_t n = original->GetLargestPossibleRegion().GetNumberOfPixels();
    const std::vector<float> a(original->GetBufferPointer(), original->GetBufferPointer() + n);
    const std::vector<float> b(back->GetBufferPointer(), back->GetBufferPointer() + n);
    EXPECT_EQ(a, b);
  }
  // Nothing but the four outputs is left behind (no temporaries).
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir_)) {
    ++files;
    EXPECT_NE(entry.path().filename().string().front(), '.') << entry.path();
  }
  EXPECT_EQ(files, 4u);
}

TEST_F(VolumeIo, WriteOverwritesAtomicallyAndRejectsBadPaths) {
  const fs::path path = dir_ / "v.mha";
  write_volume(make_image(4, 4, 3), path);
  write_volume(make_image(5, 4, 3), path);
  EXPECT_EQ(read_volume(path)->GetLargestPossibleRegion().GetSize()[0], 5u);

  EXPECT_THROW(write_volume(make_image(4, 4, 3), dir_ / "v.png"), InvalidInputError);
  EXPECT_THROW(write_volume(make_image(4, 4, 3), dir_ / "missing" / "v.mha"), InvalidInputError);
  EXPECT_THROW(write_volume(nullptr, dir_ / "w.mha"), InvalidInputError);
  EXPECT_FALSE(fs::exists(dir_ / "v.png"));
  EXPECT_FALSE(fs::exists(dir_ / "w.mha"));
}

TEST_F(VolumeIo, ReadErrorsNameThePath) {
  expect_read_error(dir_ / "missing.mha", "no such file");

  const fs::path empty = dir_ / "empty.mha";
  std::ofstream(empty).close();
  expect_read_error(empty, "empty");

  const fs::path garbage = dir_ / "garbage.mha";
  {
    std::ofstream out(garbage, std::ios::binary);
    std::mt19937 rng(3);
    for (int i = 0; i < 4096; ++i) out.put(static_cast<char>(rng() & 0xff));
  }
  expect_read_error(garbage, "not a readable image");

  // A 2-D image written by ITK.
  using Slice = itk::Image<float, 2>;
  auto slice = Slice::New();
  Slice::RegionType region;
  Slice::SizeType size;
  size.Fill(8);
  region.SetSize(size);
  slice->SetRegions(region);
  slice->Allocate();
  slice->FillBuffer(1.0f);
  const fs::path flat = dir_ / "slice.mha";
  auto writer = itk::ImageFileWriter<Slice>::New();
  writer->SetImageIO(itk::MetaImageIO::New());
  writer->SetInput(slice);
  writer->SetFileName(flat.string());
  writer->Update();
  expect_read_error(flat, "2-D");

  // A 3-D file with a single slice is not a volume either.
  const fs::path thin = dir_ / "thin.nrrd";
  write_volume(make_image(6, 6, 1), thin);
  expect_read_error(thin, "single 2-D slice");

  const fs::path empty_dir = dir_ / "no_dicom";
  fs::create_directories(empty_dir);
  std::ofstream(empty_dir / "notes.txt") << "not a DICOM file\n";
  expect_read_error(empty_dir, "without a DICOM series");
}

// Writes a small DICOM series (2-D slices) with the given series UID into `dir`.
void write_dicom_series(const fs::path& dir, const std::string& series_uid, int slices, int first_instance) {
  using Slice = itk::Image<short, 2>;
  for (int s = 0; s < slices; ++s) {
    auto slice = Slice::New();
    Slice::RegionType region;
    Slice::SizeType size;
    size.Fill(8);
    region.SetSize(size);
    slice->SetRegions(region);
    slice->Allocate();
    slice->FillBuffer(static_cast<short>(100 * s));
    auto io = itk::GDCMImageIO::New();
    io->KeepOriginalUIDOn();
    itk::MetaDataDictionary& dict = io->GetMetaDataDictionary();
    itk::EncapsulateMetaData<std::string>(dict, "0008|0060", "CT");
    itk::EncapsulateMetaData<std::string>(dict, "0020|000d", "1.2.826.0.1.3680043.2.1125.1");
    itk::EncapsulateMetaData<std::string>(dict, "0020|000e", series_uid);
    itk::EncapsulateMetaData<std::string>(dict, "0008|0018", series_uid + "." + std::to_string(s + 1));
    itk::EncapsulateMetaData<std::string>(dict, "0020|0013", std::to_string(first_instance + s));
    itk::EncapsulateMetaData<std::string>(dict, "0020|0032", "0\\0\\" + std::to_string(3.0 * s));
    itk::EncapsulateMetaData<std::string>(dict, "0020|0037", "1\\0\\0\\0\\1\\0");
    itk::EncapsulateMetaData<std::string>(dict, "0018|0050", "1.0");
    auto writer = itk::ImageFileWriter<Slice>::New();
    writer->SetImageIO(io);
    writer->SetInput(slice);
    writer->UseInputMetaDataDictionaryOff();
    writer->SetFileName((dir / (series_uid + "_" + std::to_string(s) + ".dcm")).string());
    writer->Update();
  }
}

TEST_F(VolumeIo, DicomDirectories) {
  const fs::path one = dir_ / "one";
  fs::create_directories(one);
  write_dicom_series(one, "1.2.826.0.1.3680043.2.1125.11", 4, 1);
  const CtImage::Pointer image = read_volume(one);
  EXPECT_EQ(image->GetLargestPossibleRegion().GetSize()[2], 4u);
  EXPECT_NEAR(image->GetSpacing()[2], 3.0, 1e-3);  // from the positions, not SliceThickness (1.0)

  const fs::path two = dir_ / "two";
  fs::create_directories(two);
  write_dicom_series(two, "1.2.826.0.1.3680043.2.1125.21", 3, 1);
  write_dicom_series(two, "1.2.826.0.1.3680043.2.1125.22", 3, 1);
  const std::string message = message_of(two);
  EXPECT_EQ(message.rfind(two.string(), 0), 0u) << message;
  EXPECT_NE(message.find("2 DICOM series"), std::string::npos) << message;
  EXPECT_NE(message.find("1.2.826.0.1.3680043.2.1125.21"), std::string::npos) << message;
  EXPECT_NE(message.find("1.2.826.0.1.3680043.2.1125.22"), std::string::npos) << message;
}

// ----- The shared real data ----------------------------------------------------------------------------

std::pair<float, float> min_max(const CtImage::Pointer& image) {
  auto calculator = itk::MinimumMaximumImageCalculator<CtImage>::New();
  calculator->SetImage(image);
  calculator->Compute();
  return {calculator->GetMinimum(), calculator->GetMaximum()};
}

#define REQUIRE_SHARED(path) \
  if (!fs::exists(path)) GTEST_SKIP() << "shared data not found: " << (path)

TEST(SharedData, HeadsqQuarterMetaImage) {
  const fs::path path = kSharedData / "headsq_quarter" / "headsq_quarter.mhd";
  REQUIRE_SHARED(path);
  const CtImage::Pointer image = read_volume(path);
  const auto size = image->GetLargestPossibleRegion().GetSize();
  EXPECT_EQ(size[0], 64u);
  EXPECT_EQ(size[1], 64u);
  EXPECT_EQ(size[2], 93u);
  EXPECT_NEAR(image->GetSpacing()[0], 3.2, 1e-6);
  EXPECT_NEAR(image->GetSpacing()[1], 3.2, 1e-6);
  EXPECT_NEAR(image->GetSpacing()[2], 1.5, 1e-6);
  const auto [lo, hi] = min_max(image);
  EXPECT_GE(lo, 0.0f);
  EXPECT_GT(hi, 1150.0f);  // bone, in raw units
}

TEST(SharedData, TotalSegmentatorNifti) {
  const fs::path path = kSharedData / "totalsegmentator_ct" / "example_ct_sm.nii.gz";
  REQUIRE_SHARED(path);
  const CtImage::Pointer image = read_volume(path);
  EXPECT_EQ(image->GetLargestPossibleRegion().GetSize()[2], 30u);
  for (unsigned a = 0; a < 3; ++a) EXPECT_NEAR(image->GetSpacing()[a], 3.0, 1e-3);
  const auto [lo, hi] = min_max(image);
  EXPECT_GE(lo, -1100.0f);
  EXPECT_LE(lo, -990.0f);
  EXPECT_GT(hi, 300.0f);
}

TEST(SharedData, DicomSeriesSpacingFromImagePosition) {
  const fs::path path = kSharedData / "dicom_series_headneck";
  REQUIRE_SHARED(path);
  const CtImage::Pointer image = read_volume(path);
  const auto size = image->GetLargestPossibleRegion().GetSize();
  EXPECT_EQ(size[0], 512u);
  EXPECT_EQ(size[1], 512u);
  EXPECT_EQ(size[2], 48u);
  EXPECT_NEAR(image->GetSpacing()[0], 0.977, 0.001);
  EXPECT_NEAR(image->GetSpacing()[2], 1.2, 1e-3);  // the SliceThickness tag says 1.5
  const auto [lo, hi] = min_max(image);
  EXPECT_LT(lo, -900.0f);  // air, in HU after the rescale
  EXPECT_GT(hi, 300.0f);   // bone
}

TEST(SharedData, SingleDicomSliceIsNotAVolume) {
  const fs::path path = kSharedData / "rtstruct_breast" / "ct.0.dcm";
  REQUIRE_SHARED(path);
  expect_read_error(path, "slice");
}

}  // namespace
}  // namespace contourmesh
