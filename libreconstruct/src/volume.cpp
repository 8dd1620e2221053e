// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/volume.h"

#include "detail/captured_output.h"
#include "detail/image_io.h"
#include "detail/dicom_series.h"
#include "detail/volume_file_checks.h"

#include <contourmesh/smooth/atomic_file.h>
#include <contourmesh/smooth/errors.h>

#include <itkGDCMImageIO.h>
#include <itkGDCMImageIOFactory.h>
#include <itkImageFileReader.h>
#include <itkImageFileWriter.h>
#include <itkImageIOFactory.h>
#include <itkGDCMSeriesFileNames.h>
#include <itkMetaDataObject.h>
#include <itkMetaImageIO.h>
#include <itkMetaImageIOFactory.h>
#include <itkNiftiImageIO.h>
#include <itkNiftiImageIOFactory.h>
#include <itkNrrdImageIO.h>
#include <itkNrrdImageIOFactory.h>

// After ITK: its IO headers bring ITK's own Eigen, which must come before the system one.
#include <contourmesh/smooth/limits.h>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>
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

// The IO factories are registered once, so that reading does not depend on UseITK.cmake's generated
// registration code (the label-map reader shares them).
void register_io_factories() { detail::register_image_io_factories(); }

// ITK's description of an exception, on one line (its first meaningful line).
std::string describe(const itk::ExceptionObject& e) {
  std::string text = detail::first_line(e.GetDescription());
  const std::string prefix = "ITK ERROR: ";
  if (text.rfind(prefix, 0) == 0) text = detail::first_line(text.substr(prefix.size()));
  return text.empty() ? std::string("unknown ITK error") : text;
}

// The first line of what the libraries printed, for context: " (MetaIO: ...)", or nothing.
std::string library_said(detail::CapturedOutput& captured) {
  const std::string line = detail::first_line(captured.text());
  return line.empty() ? std::string() : " (" + line + ")";
}

void check_volume(const CtImage& image, const std::string& name) {
  const auto size = image.GetLargestPossibleRegion().GetSize();
  if (size[0] == 0 || size[1] == 0 || size[2] == 0) {
    throw InvalidInputError(name + ": empty volume (" + std::to_string(size[0]) + " x " + std::to_string(size[1]) +
                            " x " + std::to_string(size[2]) + " voxels)");
  }
  if (size[2] == 1) {
    throw InvalidInputError(name + ": a single 2-D slice (" + std::to_string(size[0]) + " x " +
                            std::to_string(size[1]) + "), not a 3-D volume");
  }
}

std::string format3(const double* v) {
  std::ostringstream s;
  s << v[0] << ", " << v[1] << ", " << v[2];
  return s.str();
}

// Spacing, origin and direction (columns = the voxel axes) as a header gives them.
void check_geometry(const double spacing[3], const double origin[3], const double direction[3][3],
                    const std::string& name) {
  for (int d = 0; d < 3; ++d) {
    if (!std::isfinite(spacing[d]) || !(spacing[d] > 0.0)) {
      throw InvalidInputError(name + ": the voxel spacing (" + format3(spacing) +
                              ") must be finite and > 0 along every axis");
    }
  }
  if (!std::isfinite(origin[0]) || !std::isfinite(origin[1]) || !std::isfinite(origin[2])) {
    throw InvalidInputError(name + ": the origin (" + format3(origin) + ") is not finite");
  }
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m(r, c) = direction[r][c];
  }
  if (!m.allFinite()) throw InvalidInputError(name + ": the direction matrix is not finite");
  if (std::abs(m.determinant()) < 1e-6 * std::max(1.0, m.cwiseAbs().maxCoeff())) {
    throw InvalidInputError(name + ": the direction matrix is singular (its axes do not span 3-D space): the voxel "
                                   "grid has no 3-D geometry");
  }
  for (int a = 0; a < 3; ++a) {
    if (std::abs(m.col(a).norm() - 1.0) > 1e-3) {
      std::ostringstream msg;
      msg << name << ": the direction matrix is not orthonormal: axis " << a + 1 << " has length " << m.col(a).norm()
          << ", not 1";
      throw InvalidInputError(msg.str());
    }
    for (int b = a + 1; b < 3; ++b) {
      const double cosine = m.col(a).dot(m.col(b)) / (m.col(a).norm() * m.col(b).norm());
      if (std::abs(cosine) > 1e-3) {
        std::ostringstream msg;
        msg.precision(3);
        msg << name << ": the direction matrix is sheared: voxel axes " << a + 1 << " and " << b + 1 << " meet at "
            << std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / 3.14159265358979
            << " degrees, not 90 (a gantry tilt?); the segmentation assumes orthogonal axes and would misplace every "
               "slice: resample the volume onto an orthogonal grid first";
        throw InvalidInputError(msg.str());
      }
    }
  }
}

CtImage::Pointer read_image_file(const fs::path& path, const std::string& name, detail::CapturedOutput& captured) {
  std::error_code ec;
  if (fs::file_size(path, ec) == 0 && !ec) throw InvalidInputError(name + ": empty file, not an image");
  itk::ImageIOBase::Pointer io = itk::ImageIOFactory::CreateImageIO(path.c_str(), itk::IOFileModeEnum::ReadMode);
  if (!io) {
    detail::check_volume_file(path, name);  // a header cut short is named as such
    throw InvalidInputError(name +
                            ": not a readable image (unknown format or corrupt file; expected .mha/.mhd, "
                            ".nrrd/.nhdr, .nii/.nii.gz or a DICOM series directory)");
  }
  io->SetFileName(path.string());
  try {
    io->ReadImageInformation();
  } catch (const itk::ExceptionObject& e) {
    detail::check_volume_file(path, name);  // names a malformed field, where ITK's reason is often vague
    throw InvalidInputError(name + ": cannot read the image header: " + describe(e) + library_said(captured));
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
    double spacing[3], origin[3], direction[3][3];
    for (unsigned c = 0; c < 3; ++c) {
      spacing[c] = io->GetSpacing(c);
      origin[c] = io->GetOrigin(c);
      const std::vector<double> axis = io->GetDirection(c);
      for (unsigned r = 0; r < 3; ++r) direction[r][c] = r < axis.size() ? axis[r] : 0.0;
    }
    check_geometry(spacing, origin, direction, name);
  }
  {
    const double voxels = static_cast<double>(io->GetDimensions(0)) * static_cast<double>(io->GetDimensions(1)) *
                          static_cast<double>(io->GetDimensions(2));
    try {
      check_allocation(std::to_string(io->GetDimensions(0)) + " x " + std::to_string(io->GetDimensions(1)) + " x " +
                           std::to_string(io->GetDimensions(2)) + " voxels",
                       0.0, voxels * kVolumeBytesPerVoxel, ResourceLimits{});
    } catch (const LimitError&) {
      rethrow_with_context(name);
    }
  }
  // What the header promises, checked before ITK reads the data (it reads short data without complaint).
  detail::check_volume_file(path, name);
  auto reader = itk::ImageFileReader<CtImage>::New();
  reader->SetImageIO(io);
  reader->SetFileName(path.string());
  try {
    reader->Update();
  } catch (const itk::ExceptionObject& e) {
    throw InvalidInputError(name + ": cannot read the image: " + describe(e) + library_said(captured));
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
  std::vector<std::string> warnings;
  CtImage::Pointer image;
  {
    detail::CapturedOutput captured(options.library_messages == LibraryMessages::Capture);
    if (fs::is_directory(status)) {
      // ITK's own remarks on a series (its uniformity warning) are superseded by the checks made here.
      image = detail::read_dicom_series(path, name, options.series_uid, options.uneven_slices, warnings);
    } else {
      image = read_image_file(path, name, captured);
      if (const std::string said = detail::first_line(captured.text()); !said.empty()) {
        warnings.push_back(name + ": the image library said: " + said);
      }
    }
  }
  check_volume(*image, name);
  check_volume_geometry(*image, name);
  check_voxel_values(*image, name, options.non_finite, options.on_warning);
  if (options.on_warning) {
    for (const std::string& w : warnings) options.on_warning(w);
  }
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

void check_volume_geometry(const CtImage& image, const std::string& name) {
  double spacing[3], origin[3], direction[3][3];
  for (int c = 0; c < 3; ++c) {
    spacing[c] = image.GetSpacing()[c];
    origin[c] = image.GetOrigin()[c];
    for (int r = 0; r < 3; ++r) direction[r][c] = image.GetDirection()[r][c];
  }
  check_geometry(spacing, origin, direction, name);
}

void check_voxel_values(CtImage& image, const std::string& name, NonFiniteVoxels policy,
                        const std::function<void(const std::string&)>& on_warning) {
  const auto size = image.GetLargestPossibleRegion().GetSize();
  float* v = image.GetBufferPointer();
  const std::size_t n = image.GetLargestPossibleRegion().GetNumberOfPixels();
  std::size_t bad = 0, first = n;
  float lowest = std::numeric_limits<float>::infinity();
  for (std::size_t k = 0; k < n; ++k) {
    if (std::isfinite(v[k])) {
      lowest = std::min(lowest, v[k]);
    } else {
      if (bad++ == 0) first = k;
    }
  }
  if (bad == 0) return;
  const std::size_t plane = size[0] * size[1];
  std::ostringstream at;
  at << "(" << first % size[0] << ", " << (first / size[0]) % size[1] << ", " << first / plane << ")";
  const std::string where = at.str();
  const std::string count = std::to_string(bad) + " of its " + std::to_string(n) + " voxels are NaN or infinite";
  if (bad == n) throw InvalidInputError(name + ": every voxel is NaN or infinite: there is no image to segment");
  if (policy == NonFiniteVoxels::Refuse) {
    throw InvalidInputError(name + ": " + count + " (the first at voxel " + where +
                            "); refused, as they would silently drop out of the segmentation (treat non-finite "
                            "voxels as air to read them as the lowest value)");
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(v[k])) v[k] = lowest;
  }
  if (on_warning) {
    std::ostringstream msg;
    msg << name << ": " << count << " (the first at voxel " << where << "): read them as air, " << lowest
        << ", the lowest value of the volume";
    on_warning(msg.str());
  }
}

void write_volume(const CtImage* image, const fs::path& path, const ProgressCallback& progress) {
  register_io_factories();
  const std::string name = path.string();
  if (image == nullptr) throw InvalidInputError(name + ": no image to write");
  const std::string extension = volume_extension(path);
  if (extension.empty()) {
    throw InvalidInputError(name + ": unsupported volume extension; use .mha, .nrrd, .nii or .nii.gz");
  }
  const auto size = image->GetLargestPossibleRegion().GetSize();
  if (size[0] == 0 || size[1] == 0 || size[2] == 0) throw InvalidInputError(name + ": cannot write an empty volume");
  write_atomically(
      path,
      [&](const fs::path& tmp) {
        // The temporary keeps the caller's extension; every ImageIO is chosen here, from the lower-case one.
        detail::CapturedOutput captured(true);
        auto writer = itk::ImageFileWriter<CtImage>::New();
        writer->SetImageIO(writer_io(extension));
        writer->SetInput(image);
        writer->SetFileName(tmp.string());
        try {
          writer->Update();
        } catch (const itk::ExceptionObject& e) {
          throw InvalidInputError(name + ": cannot write: " + describe(e) + library_said(captured));
        }
        // ITK's writers do not check their writes (a full disk gave a short file and success).
        try {
          detail::check_volume_file(tmp, name);
        } catch (const InvalidInputError& e) {
          std::string what = e.what();
          what = what.substr(std::min(what.size(), name.size() + 2));
          throw InvalidInputError(name + ": cannot write: the written file is incomplete (disk full or a file size "
                                         "limit?): " + what + library_said(captured));
        }
      },
      progress);
}

}  // namespace contourmesh
