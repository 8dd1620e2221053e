#include "reconstruct/volume.h"

#include "detail/image_io.h"

#include <smooth/errors.h>

#include <itkGDCMImageIO.h>
#include <itkGDCMImageIOFactory.h>
#include <itkGDCMSeriesFileNames.h>
#include <itkImageFileReader.h>
#include <itkImageFileWriter.h>
#include <itkImageIOFactory.h>
#include <itkImageSeriesReader.h>
#include <itkMetaDataObject.h>
#include <itkMetaImageIO.h>
#include <itkMetaImageIOFactory.h>
#include <itkNiftiImageIO.h>
#include <itkNiftiImageIOFactory.h>
#include <itkNrrdImageIO.h>
#include <itkNrrdImageIOFactory.h>

// After ITK: its IO headers bring ITK's own Eigen, which must come before the system one.
#include <smooth/limits.h>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <mutex>
#include <random>
#include <string>
#include <system_error>
#include <vector>

namespace contourmesh {

namespace detail {

void register_image_io_factories() {
  static std::once_flag once;
  std::call_once(once, [] {
    itk::MetaImageIOFactory::RegisterOneFactory();
    itk::NrrdImageIOFactory::RegisterOneFactory();
    itk::NiftiImageIOFactory::RegisterOneFactory();
    itk::GDCMImageIOFactory::RegisterOneFactory();
  });
}

}  // namespace detail

namespace fs = std::filesystem;

namespace {

void register_io_factories() { detail::register_image_io_factories(); }

std::string describe(const itk::ExceptionObject& e) {
  std::string text = e.GetDescription();
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  return text.empty() ? std::string("unknown ITK error") : text;
}

void check_volume(const CtImage& image, const fs::path& path) {
  const auto size = image.GetLargestPossibleRegion().GetSize();
  if (size[0] == 0 || size[1] == 0 || size[2] == 0) {
    throw InvalidInputError(path.string() + ": empty volume (" + std::to_string(size[0]) + " x " +
                            std::to_string(size[1]) + " x " + std::to_string(size[2]) + " voxels)");
  }
  if (size[2] == 1) {
    throw InvalidInputError(path.string() + ": a single 2-D slice (" + std::to_string(size[0]) + " x " +
                            std::to_string(size[1]) + "), not a 3-D volume");
  }
}

CtImage::Pointer read_image_file(const fs::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (fs::file_size(path, ec) == 0 && !ec) throw InvalidInputError(name + ": empty file, not an image");
  itk::ImageIOBase::Pointer io = itk::ImageIOFactory::CreateImageIO(name.c_str(), itk::IOFileModeEnum::ReadMode);
  if (!io) {
    throw InvalidInputError(name +
                            ": not a readable image (unknown format or corrupt file; expected .mha/.mhd, "
                            ".nrrd/.nhdr, .nii/.nii.gz or a DICOM series directory)");
  }
  io->SetFileName(name);
  try {
    io->ReadImageInformation();
  } catch (const itk::ExceptionObject& e) {
    throw InvalidInputError(name + ": cannot read the image header: " + describe(e));
  }
  const unsigned dimensions = io->GetNumberOfDimensions();
  if (dimensions < 3) {
    throw InvalidInputError(name + ": a " + std::to_string(dimensions) + "-D image (a single slice), not a 3-D volume");
  }
  for (unsigned d = 3; d < dimensions; ++d) {
    if (io->GetDimensions(d) > 1) {
      throw InvalidInputError(name + ": a " + std::to_string(dimensions) + "-D image; only 3-D volumes are supported");
    }
  }
  for (unsigned d = 0; d < 3; ++d) {
    if (io->GetDimensions(d) == 0) throw InvalidInputError(name + ": empty volume (an axis of size 0)");
  }
  if (io->GetDimensions(2) == 1) {
    throw InvalidInputError(name + ": a single 2-D slice (" + std::to_string(io->GetDimensions(0)) + " x " +
                            std::to_string(io->GetDimensions(1)) + "), not a 3-D volume");
  }
  {
    const double voxels = static_cast<double>(io->GetDimensions(0)) * static_cast<double>(io->GetDimensions(1)) *
                          static_cast<double>(io->GetDimensions(2));
    try {
      check_allocation(std::to_string(io->GetDimensions(0)) + " x " + std::to_string(io->GetDimensions(1)) + " x " +
                           std::to_string(io->GetDimensions(2)) + " voxels",
                       0.0, voxels * kVolumeBytesPerVoxel, ResourceLimits{});
    } catch (const LimitError& e) {
      throw LimitError(name + ": " + e.what());
    }
  }
  auto reader = itk::ImageFileReader<CtImage>::New();
  reader->SetImageIO(io);
  reader->SetFileName(name);
  try {
    reader->Update();
  } catch (const itk::ExceptionObject& e) {
    throw InvalidInputError(name + ": cannot read the image: " + describe(e));
  }
  CtImage::Pointer image = reader->GetOutput();
  image->DisconnectPipeline();
  return image;
}

CtImage::Pointer read_dicom_directory(const fs::path& path, const std::string& series_uid) {
  const std::string name = path.string();
  auto names = itk::GDCMSeriesFileNames::New();
  names->SetUseSeriesDetails(false);  // group by Series Instance UID only, so the UIDs listed are real
  names->SetDirectory(name);
  std::vector<std::string> uids;
  try {
    uids = names->GetSeriesUIDs();
  } catch (const itk::ExceptionObject& e) {
    throw InvalidInputError(name + ": cannot scan the directory for DICOM files: " + describe(e));
  }
  if (uids.empty()) throw InvalidInputError(name + ": a directory without a DICOM series");
  std::string list;
  for (const std::string& uid : uids) list += (list.empty() ? "" : ", ") + uid;
  if (series_uid.empty() && uids.size() > 1) {
    throw InvalidInputError(name + ": the directory holds " + std::to_string(uids.size()) + " DICOM series (" + list +
                            "); pick one with --series UID (--list-series describes them)");
  }
  if (!series_uid.empty() && std::find(uids.begin(), uids.end(), series_uid) == uids.end()) {
    throw InvalidInputError(name + ": no DICOM series " + series_uid + " in the directory (it holds " + list + ")");
  }
  // GDCMSeriesFileNames sorts the files along the slice normal by Image Position (Patient); the series
  // reader then takes the slice spacing from those positions, not from SliceThickness.
  const std::vector<std::string> files = names->GetFileNames(series_uid.empty() ? uids.front() : series_uid);
  if (files.size() < 2) {
    throw InvalidInputError(name + ": the DICOM series has " + std::to_string(files.size()) +
                            " slice; a 3-D volume needs at least 2");
  }
  auto reader = itk::ImageSeriesReader<CtImage>::New();
  reader->SetImageIO(itk::GDCMImageIO::New());
  reader->SetFileNames(files);
  try {
    reader->Update();
  } catch (const itk::ExceptionObject& e) {
    throw InvalidInputError(name + ": cannot read the DICOM series: " + describe(e));
  }
  CtImage::Pointer image = reader->GetOutput();
  image->DisconnectPipeline();
  return image;
}

// ".nii.gz" counts as one extension; returns the lower-case extension, or an empty string.
std::string volume_extension(const fs::path& path) {
  std::string file = path.filename().string();
  std::transform(file.begin(), file.end(), file.begin(), [](unsigned char c) { return std::tolower(c); });
  for (const char* ext : {".nii.gz", ".mha", ".nrrd", ".nii"}) {
    const std::string e = ext;
    if (file.size() > e.size() && file.compare(file.size() - e.size(), e.size(), e) == 0) return e;
  }
  return {};
}

fs::path temporary_sibling(const fs::path& path, const std::string& extension) {
  const std::string file = path.filename().string();
  const std::string stem = file.substr(0, file.size() - extension.size());
  std::random_device rd;
  const std::string tag = std::to_string(::getpid()) + "-" + std::to_string(rd() % 1000000u);
  // The lower-case extension, which every ImageIO recognises; the rename restores the caller's spelling.
  return path.parent_path() / ("." + stem + ".tmp-" + tag + extension);
}

itk::ImageIOBase::Pointer writer_io(const std::string& extension) {
  if (extension == ".mha") return itk::MetaImageIO::New().GetPointer();
  if (extension == ".nrrd") return itk::NrrdImageIO::New().GetPointer();
  return itk::NiftiImageIO::New().GetPointer();
}

}  // namespace

CtImage::Pointer read_volume(const fs::path& path, const VolumeReadOptions& options) {
  register_io_factories();
  const std::string name = path.string();
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw InvalidInputError(name + ": no such file or directory");
  if (!options.series_uid.empty() && !fs::is_directory(status)) {
    throw InvalidInputError(name + ": a DICOM series UID applies to a directory of DICOM files, not to a file");
  }
  CtImage::Pointer image =
      fs::is_directory(status) ? read_dicom_directory(path, options.series_uid) : read_image_file(path);
  check_volume(*image, path);
  return image;
}

std::vector<DicomSeries> list_dicom_series(const fs::path& directory) {
  register_io_factories();
  const std::string name = directory.string();
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) throw InvalidInputError(name + ": not a directory");
  auto names = itk::GDCMSeriesFileNames::New();
  names->SetUseSeriesDetails(false);  // as read_volume: one entry per Series Instance UID
  names->SetDirectory(name);
  std::vector<std::string> uids;
  try {
    uids = names->GetSeriesUIDs();
  } catch (const itk::ExceptionObject& e) {
    throw InvalidInputError(name + ": cannot scan the directory for DICOM files: " + describe(e));
  }
  std::vector<DicomSeries> series;
  for (const std::string& uid : uids) {
    DicomSeries s;
    s.uid = uid;
    const std::vector<std::string> files = names->GetFileNames(uid);
    s.files = files.size();
    if (!files.empty()) {
      auto io = itk::GDCMImageIO::New();
      io->SetFileName(files.front());
      try {
        io->ReadImageInformation();
        const auto tag = [&](const char* key) {
          std::string value;
          itk::ExposeMetaData<std::string>(io->GetMetaDataDictionary(), key, value);
          while (!value.empty() && (std::isspace(static_cast<unsigned char>(value.back())) || value.back() == '\0')) {
            value.pop_back();
          }
          return value;
        };
        s.number = tag("0020|0011");
        s.modality = tag("0008|0060");
        s.description = tag("0008|103e");
      } catch (const itk::ExceptionObject&) {
        // The listing still names the series; reading it reports the problem.
      }
    }
    series.push_back(std::move(s));
  }
  return series;
}

void write_volume(const CtImage* image, const fs::path& path) {
  register_io_factories();
  const std::string name = path.string();
  if (image == nullptr) throw InvalidInputError(name + ": no image to write");
  const std::string extension = volume_extension(path);
  if (extension.empty()) {
    throw InvalidInputError(name + ": unsupported volume extension; use .mha, .nrrd, .nii or .nii.gz");
  }
  const auto size = image->GetLargestPossibleRegion().GetSize();
  if (size[0] == 0 || size[1] == 0 || size[2] == 0) throw InvalidInputError(name + ": cannot write an empty volume");
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code ec;
  if (!fs::exists(dir, ec)) {
    throw InvalidInputError(name + ": cannot write: directory '" + dir.string() + "' does not exist");
  }
  if (!fs::is_directory(dir, ec)) {
    throw InvalidInputError(name + ": cannot write: '" + dir.string() + "' is not a directory");
  }
  if (fs::is_directory(path, ec)) throw InvalidInputError(name + ": cannot write: it is a directory");

  const fs::path tmp = temporary_sibling(path, extension);
  try {
    auto writer = itk::ImageFileWriter<CtImage>::New();
    writer->SetImageIO(writer_io(extension));
    writer->SetInput(image);
    writer->SetFileName(tmp.string());
    try {
      writer->Update();
    } catch (const itk::ExceptionObject& e) {
      throw InvalidInputError(name + ": cannot write: " + describe(e));
    }
    if (!fs::exists(tmp, ec)) throw InvalidInputError(name + ": cannot write: no output was produced");
    fs::rename(tmp, path, ec);
    if (ec) throw InvalidInputError(name + ": cannot write: " + ec.message());
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
}

}  // namespace contourmesh
