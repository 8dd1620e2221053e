// SPDX-License-Identifier: BSD-3-Clause
#include "damaged_inputs.h"

#include <gdcmAttribute.h>
#include <gdcmReader.h>
#include <gdcmWriter.h>
#include <itkImageFileWriter.h>
#include <itkMetaImageIO.h>
#include <itkNiftiImageIO.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace contourmesh::test {

CtImage::Pointer small_volume() {
  auto image = CtImage::New();
  CtImage::RegionType region;
  region.SetSize({{28, 24, 12}});
  image->SetRegions(region);
  const double spacing[3] = {1.0, 1.0, 2.0};
  image->SetSpacing(spacing);
  image->Allocate();
  for (int k = 0; k < 12; ++k) {
    for (int j = 0; j < 24; ++j) {
      for (int i = 0; i < 28; ++i) {
        const bool bone = i >= 6 && i < 22 && j >= 5 && j < 19 && k >= 2 && k < 10;
        image->SetPixel({{i, j, k}}, bone ? 1000.0f : 40.0f);
      }
    }
  }
  return image;
}

void write_raw_volume(const CtImage& image, const fs::path& path, bool compressed) {
  auto writer = itk::ImageFileWriter<CtImage>::New();
  const std::string name = path.filename().string();
  if (name.find(".nii") != std::string::npos) {
    writer->SetImageIO(itk::NiftiImageIO::New());
  } else {
    writer->SetImageIO(itk::MetaImageIO::New());
  }
  writer->SetInput(&image);
  writer->SetFileName(path.string());
  writer->SetUseCompression(compressed);
  writer->Update();
}

namespace {

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void dump(const fs::path& path, const std::string& bytes) {
  fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::add);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

}  // namespace

void cut_file(const fs::path& path, std::uintmax_t keep) { dump(path, slurp(path).substr(0, keep)); }

void cut_file_fraction(const fs::path& path, double fraction) {
  cut_file(path, static_cast<std::uintmax_t>(static_cast<double>(fs::file_size(path)) * fraction));
}

bool replace_in_file(const fs::path& path, const std::string& from, const std::string& to) {
  std::string bytes = slurp(path);
  const auto at = bytes.find(from);
  if (at == std::string::npos) return false;
  bytes.replace(at, from.size(), to);
  dump(path, bytes);
  return true;
}

void patch_floats(const fs::path& path, std::size_t offset, const std::vector<float>& values) {
  std::string bytes = slurp(path);
  std::memcpy(bytes.data() + offset, values.data(), values.size() * sizeof(float));  // little-endian host
  dump(path, bytes);
}

void set_mha_voxels(const fs::path& path, std::size_t first, std::size_t count, float value) {
  std::string bytes = slurp(path);
  const std::string marker = "ElementDataFile = LOCAL\n";
  const auto data = bytes.find(marker);
  if (data == std::string::npos) throw std::runtime_error(path.string() + ": not a LOCAL MetaImage");
  for (std::size_t k = first; k < first + count; ++k) {
    std::memcpy(bytes.data() + data + marker.size() + 4 * k, &value, sizeof value);
  }
  dump(path, bytes);
}

fs::path headneck_series() { return fs::path(CONTOURMESH_SHARED_DATA) / "dicom_series_headneck"; }

std::vector<fs::path> copy_headneck_slices(const fs::path& dir, int first, int count) {
  std::vector<fs::path> all;
  for (const auto& e : fs::directory_iterator(headneck_series())) {
    if (e.path().extension() == ".dcm") all.push_back(e.path());
  }
  std::sort(all.begin(), all.end());
  fs::create_directories(dir);
  std::vector<fs::path> copies;
  for (int k = first; k < first + count && k < static_cast<int>(all.size()); ++k) {
    const fs::path to = dir / all[k].filename();
    fs::copy_file(all[k], to, fs::copy_options::overwrite_existing);
    fs::permissions(to, fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::add);
    copies.push_back(to);
  }
  return copies;
}

namespace {

void rewrite_dicom(const fs::path& file, const gdcm::DataElement& element) {
  gdcm::Reader reader;
  reader.SetFileName(file.c_str());
  if (!reader.Read()) throw std::runtime_error(file.string() + ": cannot read as DICOM");
  reader.GetFile().GetDataSet().Replace(element);
  gdcm::Writer writer;
  writer.SetFile(reader.GetFile());
  writer.SetFileName(file.c_str());
  if (!writer.Write()) throw std::runtime_error(file.string() + ": cannot write DICOM");
}

}  // namespace

void set_dicom_text(const fs::path& file, std::uint16_t group, std::uint16_t element, const std::string& value) {
  gdcm::DataElement de(gdcm::Tag(group, element));
  de.SetVR(gdcm::VR::DS);
  std::string padded = value;
  if (padded.size() % 2 != 0) padded += ' ';
  de.SetByteValue(padded.data(), static_cast<gdcm::VL::Type>(padded.size()));
  rewrite_dicom(file, de);
}

void set_dicom_us(const fs::path& file, std::uint16_t group, std::uint16_t element, std::uint16_t value) {
  gdcm::DataElement de(gdcm::Tag(group, element));
  de.SetVR(gdcm::VR::US);
  de.SetByteValue(reinterpret_cast<const char*>(&value), 2);  // little-endian host and file
  rewrite_dicom(file, de);
}

std::string dicom_text(const fs::path& file, std::uint16_t group, std::uint16_t element) {
  gdcm::Reader reader;
  reader.SetFileName(file.c_str());
  if (!reader.Read()) throw std::runtime_error(file.string() + ": cannot read as DICOM");
  const gdcm::ByteValue* bv = reader.GetFile().GetDataSet().GetDataElement(gdcm::Tag(group, element)).GetByteValue();
  if (bv == nullptr) return {};
  std::string text(bv->GetPointer(), bv->GetLength());
  while (!text.empty() && (text.back() == ' ' || text.back() == '\0')) text.pop_back();
  return text;
}

}  // namespace contourmesh::test
