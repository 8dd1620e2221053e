// SPDX-License-Identifier: BSD-3-Clause
#include "detail/dicom_series.h"

#include <contourmesh/smooth/errors.h>

#include <gdcmAttribute.h>
#include <gdcmImage.h>
#include <gdcmImageReader.h>
#include <gdcmReader.h>
#include <itkGDCMImageIO.h>
#include <itkGDCMSeriesFileNames.h>
#include <itkImageSeriesReader.h>

// After ITK: its IO headers bring ITK's own Eigen, which must come before the system one.
#include <contourmesh/smooth/limits.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>

namespace contourmesh::detail {

namespace fs = std::filesystem;

namespace {

const gdcm::Tag kPixelData(0x7fe0, 0x0010);

using Vec3 = std::array<double, 3>;

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3 minus(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

std::string number(double x) {
  std::ostringstream s;
  s << std::setprecision(4) << x;
  return s.str();
}

std::string vec(const Vec3& v) { return "(" + number(v[0]) + ", " + number(v[1]) + ", " + number(v[2]) + ")"; }

struct SliceHeader {
  fs::path file;
  Vec3 position{}, row{}, column{};
  unsigned rows = 0, columns = 0;
  double row_spacing = 0.0, column_spacing = 0.0;  // Pixel Spacing: between rows, between columns
  double w = 0.0;                                   // position along the series' slice normal
};

// The numbers of a DS (decimal string) element: "a\b\c". Empty when absent or malformed.
std::vector<double> decimals(const gdcm::DataSet& ds, const gdcm::Tag& tag) {
  if (!ds.FindDataElement(tag)) return {};
  const gdcm::DataElement& de = ds.GetDataElement(tag);
  const gdcm::ByteValue* bv = de.GetByteValue();
  if (bv == nullptr) return {};
  std::string text(bv->GetPointer(), bv->GetLength());
  std::vector<double> out;
  std::istringstream parts(text);
  for (std::string part; std::getline(parts, part, '\\');) {
    char* end = nullptr;
    const double v = std::strtod(part.c_str(), &end);
    while (end != nullptr && *end != '\0' && std::isspace(static_cast<unsigned char>(*end))) ++end;
    if (end == part.c_str() || (end != nullptr && *end != '\0') || !std::isfinite(v)) return {};
    out.push_back(v);
  }
  return out;
}

template <std::uint16_t Group, std::uint16_t Element>
unsigned unsigned_short(const gdcm::DataSet& ds, unsigned fallback) {
  if (!ds.FindDataElement(gdcm::Tag(Group, Element)) || ds.GetDataElement(gdcm::Tag(Group, Element)).IsEmpty()) {
    return fallback;
  }
  gdcm::Attribute<Group, Element> a;
  a.SetFromDataSet(ds);
  return static_cast<unsigned>(a.GetValue());
}

std::string text_of(const gdcm::DataSet& ds, const gdcm::Tag& tag) {
  if (!ds.FindDataElement(tag)) return {};
  const gdcm::ByteValue* bv = ds.GetDataElement(tag).GetByteValue();
  if (bv == nullptr) return {};
  std::string text(bv->GetPointer(), bv->GetLength());
  while (!text.empty() && (text.back() == ' ' || text.back() == '\0')) text.pop_back();
  return text;
}

bool has_dicom_magic(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  char magic[4] = {};
  in.seekg(128);
  return in.read(magic, 4) && std::string(magic, 4) == "DICM";
}

// Reads everything up to the pixel data (whose value is skipped) and checks that the file holds it.
SliceHeader read_slice_header(const fs::path& file, const std::string& shown) {
  const std::string where = shown + ": " + file.filename().string();
  gdcm::Reader reader;
  reader.SetFileName(file.c_str());
  if (!reader.ReadUpToTag(kPixelData, {kPixelData})) {
    throw InvalidInputError(where + ": cannot be decoded as DICOM (truncated or corrupt file?)");
  }
  const gdcm::DataSet& ds = reader.GetFile().GetDataSet();
  SliceHeader h;
  h.file = file;
  const std::vector<double> position = decimals(ds, gdcm::Tag(0x0020, 0x0032));
  const std::vector<double> orientation = decimals(ds, gdcm::Tag(0x0020, 0x0037));
  const std::vector<double> spacing = decimals(ds, gdcm::Tag(0x0028, 0x0030));
  if (position.size() != 3) throw InvalidInputError(where + ": no valid Image Position (Patient) (0020,0032)");
  if (orientation.size() != 6) throw InvalidInputError(where + ": no valid Image Orientation (Patient) (0020,0037)");
  if (spacing.size() != 2 || !(spacing[0] > 0.0) || !(spacing[1] > 0.0)) {
    throw InvalidInputError(where + ": no valid Pixel Spacing (0028,0030): two numbers > 0 are needed");
  }
  h.position = {position[0], position[1], position[2]};
  h.row = {orientation[0], orientation[1], orientation[2]};
  h.column = {orientation[3], orientation[4], orientation[5]};
  h.row_spacing = spacing[0];
  h.column_spacing = spacing[1];
  if (std::abs(norm(h.row) - 1.0) > 1e-3 || std::abs(norm(h.column) - 1.0) > 1e-3 ||
      std::abs(dot(h.row, h.column)) > 1e-3) {
    throw InvalidInputError(where + ": its Image Orientation (Patient) " + vec(h.row) + ", " + vec(h.column) +
                            " is not two orthogonal unit vectors");
  }
  h.rows = unsigned_short<0x0028, 0x0010>(ds, 0);
  h.columns = unsigned_short<0x0028, 0x0011>(ds, 0);
  if (h.rows == 0 || h.columns == 0) throw InvalidInputError(where + ": no image size (Rows, Columns)");
  const std::string frames = text_of(ds, gdcm::Tag(0x0028, 0x0008));
  if (!frames.empty() && std::atoi(frames.c_str()) > 1) {
    throw InvalidInputError(where + ": a multi-frame image (" + frames + " frames); only series of single-frame "
                                    "images are supported");
  }
  const gdcm::TransferSyntax& syntax = reader.GetFile().GetHeader().GetDataSetTransferSyntax();
  if (!syntax.IsEncapsulated()) {
    const std::uint64_t samples = unsigned_short<0x0028, 0x0002>(ds, 1);
    const std::uint64_t bits = unsigned_short<0x0028, 0x0100>(ds, 16);
    const std::uint64_t expected = std::uint64_t{h.rows} * h.columns * samples * ((bits + 7) / 8);
    // The reader stopped where the pixel data's value starts (it skips the value): the rest of the file.
    const std::size_t start = reader.GetStreamCurrentPosition();
    std::error_code ec;
    const std::uint64_t size = fs::file_size(file, ec);
    const std::uint64_t held = !ec && start != static_cast<std::size_t>(-1) && size > start ? size - start : 0;
    if (held < expected) {
      throw InvalidInputError(where + ": its pixel data are cut: " + std::to_string(held) + " of the " +
                              std::to_string(expected) + " bytes of a " + std::to_string(h.columns) + " x " +
                              std::to_string(h.rows) + " image (truncated file?)");
    }
  } else {
    // Compressed: only decoding tells.
    gdcm::ImageReader image_reader;
    image_reader.SetFileName(file.c_str());
    std::vector<char> buffer;
    bool ok = image_reader.Read();
    if (ok) {
      const gdcm::Image& image = image_reader.GetImage();
      buffer.resize(image.GetBufferLength());
      ok = image.GetBuffer(buffer.data());
    }
    if (!ok) throw InvalidInputError(where + ": its compressed pixel data cannot be decoded (corrupt or truncated?)");
  }
  return h;
}

// Linear interpolation of the slices at positions `w` (sorted) onto `count` slices from w.front() to
// w.back().
CtImage::Pointer resample_slices(const CtImage& stacked, const std::vector<double>& w, std::size_t count) {
  const auto size = stacked.GetLargestPossibleRegion().GetSize();
  const std::size_t plane = size[0] * size[1];
  auto out = CtImage::New();
  CtImage::RegionType region;
  region.SetSize({{size[0], size[1], static_cast<itk::SizeValueType>(count)}});
  out->SetRegions(region);
  out->Allocate();
  const float* in = stacked.GetBufferPointer();
  float* to = out->GetBufferPointer();
  const double step = (w.back() - w.front()) / static_cast<double>(count - 1);
  std::size_t k = 0;
  for (std::size_t j = 0; j < count; ++j) {
    const double t = j + 1 == count ? w.back() : w.front() + step * static_cast<double>(j);
    while (k + 2 < w.size() && w[k + 1] <= t) ++k;
    const double a = std::clamp((t - w[k]) / (w[k + 1] - w[k]), 0.0, 1.0);
    const float* lo = in + k * plane;
    const float* hi = in + (k + 1) * plane;
    for (std::size_t p = 0; p < plane; ++p) {
      to[j * plane + p] = static_cast<float>((1.0 - a) * lo[p] + a * hi[p]);
    }
  }
  return out;
}

}  // namespace

namespace {

// The files of the one series in `directory`; a DICOM file the scan left out did not decode, and a
// slice would silently be missing: an error.
std::vector<std::string> series_files(const fs::path& directory, const std::string& shown,
                                      const std::string& series_uid) {
  auto names = itk::GDCMSeriesFileNames::New();
  names->SetUseSeriesDetails(false);  // group by Series Instance UID only, so the UIDs listed are real
  names->SetDirectory(directory.string());
  std::vector<std::string> uids;
  try {
    uids = names->GetSeriesUIDs();
  } catch (const itk::ExceptionObject& e) {
    throw InvalidInputError(shown + ": cannot scan the directory for DICOM files: " + e.GetDescription());
  }
  if (uids.empty()) throw InvalidInputError(shown + ": a directory without a DICOM series");
  std::string list;
  for (const std::string& uid : uids) list += (list.empty() ? "" : ", ") + uid;
  if (series_uid.empty() && uids.size() > 1) {
    throw InvalidInputError(shown + ": the directory holds " + std::to_string(uids.size()) + " DICOM series (" + list +
                            "); pick one with --series UID (--list-series describes them)");
  }
  if (!series_uid.empty() && std::find(uids.begin(), uids.end(), series_uid) == uids.end()) {
    throw InvalidInputError(shown + ": no DICOM series " + series_uid + " in the directory (it holds " + list + ")");
  }
  const std::string chosen = series_uid.empty() ? uids.front() : series_uid;
  std::vector<std::string> files = names->GetFileNames(chosen);
  const std::set<fs::path> listed(files.begin(), files.end());
  std::vector<fs::path> others;
  for (const auto& entry : fs::directory_iterator(directory)) {
    if (entry.is_regular_file() && !listed.count(entry.path()) && has_dicom_magic(entry.path())) {
      others.push_back(entry.path());
    }
  }
  std::sort(others.begin(), others.end());
  for (const fs::path& file : others) {
    gdcm::Reader reader;
    reader.SetFileName(file.c_str());
    if (!reader.ReadUpToTag(kPixelData, {kPixelData})) {
      throw InvalidInputError(shown + ": " + file.filename().string() +
                              ": cannot be decoded as DICOM (truncated or corrupt file?)");
    }
    if (text_of(reader.GetFile().GetDataSet(), gdcm::Tag(0x0020, 0x000e)) == chosen) {
      throw InvalidInputError(shown + ": " + file.filename().string() +
                              ": belongs to the series but could not be placed in it (no position?)");
    }
  }
  if (files.size() < 2) {
    throw InvalidInputError(shown + ": the DICOM series has " + std::to_string(files.size()) +
                            " slice; a 3-D volume needs at least 2");
  }
  return files;
}

// One image size, pixel spacing and orientation.
void check_headers_agree(const std::vector<SliceHeader>& slices, const std::string& shown) {
  const SliceHeader& first = slices.front();
  for (const SliceHeader& s : slices) {
    const std::string pair = s.file.filename().string() + " and " + first.file.filename().string();
    if (s.rows != first.rows || s.columns != first.columns) {
      throw InvalidInputError(shown + ": " + s.file.filename().string() + " is " + std::to_string(s.columns) + " x " +
                              std::to_string(s.rows) + " pixels but " + first.file.filename().string() + " is " +
                              std::to_string(first.columns) + " x " + std::to_string(first.rows) +
                              ": the images of a series must have one size");
    }
    if (std::abs(s.row_spacing - first.row_spacing) > 1e-4 * first.row_spacing ||
        std::abs(s.column_spacing - first.column_spacing) > 1e-4 * first.column_spacing) {
      throw InvalidInputError(shown + ": " + pair + " have different pixel spacings (" + number(s.row_spacing) + " x " +
                              number(s.column_spacing) + " and " + number(first.row_spacing) + " x " +
                              number(first.column_spacing) + " mm)");
    }
    if (norm(minus(s.row, first.row)) > 1e-4 || norm(minus(s.column, first.column)) > 1e-4) {
      throw InvalidInputError(shown + ": " + pair + " have different orientations (rows along " + vec(s.row) + " and " +
                              vec(first.row) + ", columns along " + vec(s.column) + " and " + vec(first.column) + ")");
    }
  }
}

// How the slices lie along the normal, once sorted.
struct SlicePlacement {
  Vec3 normal{};
  double typical_gap = 0.0;  // the median distance between neighbours
  std::string uneven;        // empty when evenly spaced, else what is uneven
};

// Sorts the slices along the normal and checks that they lie on one line, at distinct positions;
// reports whether they are evenly spaced.
SlicePlacement place_slices(std::vector<SliceHeader>& slices, const std::string& shown) {
  SlicePlacement out;
  const SliceHeader& first = slices.front();
  const Vec3 normal = cross(first.row, first.column);
  const double length = norm(normal);
  out.normal = {normal[0] / length, normal[1] / length, normal[2] / length};
  for (SliceHeader& s : slices) s.w = dot(s.position, out.normal);
  std::stable_sort(slices.begin(), slices.end(), [](const SliceHeader& a, const SliceHeader& b) { return a.w < b.w; });
  const double pixel = std::min(first.row_spacing, first.column_spacing);
  for (const SliceHeader& s : slices) {
    const Vec3 d = minus(s.position, slices.front().position);
    const double along = dot(d, out.normal);
    const Vec3 across = {d[0] - along * out.normal[0], d[1] - along * out.normal[1], d[2] - along * out.normal[2]};
    if (norm(across) > 0.01 * pixel + 1e-4) {
      throw InvalidInputError(shown + ": " + s.file.filename().string() + " lies " + number(norm(across)) +
                              " mm sideways of the line through " + slices.front().file.filename().string() +
                              " along the slice normal: the slices are sheared (a gantry tilt?); resample the "
                              "series onto an orthogonal grid first");
    }
  }
  std::vector<double> gaps;
  for (std::size_t k = 0; k + 1 < slices.size(); ++k) gaps.push_back(slices[k + 1].w - slices[k].w);
  std::vector<double> sorted = gaps;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  out.typical_gap = sorted[sorted.size() / 2];
  std::size_t widest = 0;
  for (std::size_t k = 0; k < gaps.size(); ++k) {
    if (gaps[k] < std::max(1e-4, 0.01 * out.typical_gap)) {
      throw InvalidInputError(shown + ": " + slices[k].file.filename().string() + " and " +
                              slices[k + 1].file.filename().string() + " lie at the same position (" +
                              number(slices[k].w) + " mm along the slice normal): a duplicated slice");
    }
    if (std::abs(gaps[k] - out.typical_gap) > std::abs(gaps[widest] - out.typical_gap)) widest = k;
  }
  if (std::abs(gaps[widest] - out.typical_gap) > std::max(1e-3, 0.01 * out.typical_gap)) {
    out.uneven = "uneven slice spacing: " + slices[widest].file.filename().string() + " and " +
                 slices[widest + 1].file.filename().string() + " are " + number(gaps[widest]) +
                 " mm apart, most slices " + number(out.typical_gap) + " mm" +
                 (gaps[widest] > 1.5 * out.typical_gap ? " (a missing slice?)" : "");
  }
  return out;
}

CtImage::Pointer read_pixels(const std::vector<SliceHeader>& slices, const std::string& shown) {
  std::vector<std::string> ordered;
  for (const SliceHeader& s : slices) ordered.push_back(s.file.string());
  auto reader = itk::ImageSeriesReader<CtImage>::New();
  reader->SetImageIO(itk::GDCMImageIO::New());
  reader->SetFileNames(ordered);
  try {
    reader->Update();
  } catch (const itk::ExceptionObject& e) {
    std::string text = e.GetDescription();
    if (const auto nl = text.find('\n'); nl != std::string::npos) text.resize(nl);
    throw InvalidInputError(shown + ": cannot read the DICOM series: " + text);
  }
  CtImage::Pointer image = reader->GetOutput();
  image->DisconnectPipeline();
  return image;
}

}  // namespace

CtImage::Pointer read_dicom_series(const fs::path& directory, const std::string& shown, const std::string& series_uid,
                                   UnevenSlices uneven, std::vector<std::string>& warnings) {
  std::vector<SliceHeader> slices;
  for (const std::string& file : series_files(directory, shown, series_uid)) {
    slices.push_back(read_slice_header(file, shown));
  }
  check_headers_agree(slices, shown);
  const SlicePlacement placement = place_slices(slices, shown);
  if (!placement.uneven.empty() && uneven == UnevenSlices::Refuse) {
    throw InvalidInputError(shown + ": " + placement.uneven +
                            "; refused, as stacking them would misplace slices (allow uneven slices to resample "
                            "them onto an even grid)");
  }
  CtImage::Pointer image = read_pixels(slices, shown);
  std::vector<double> w;
  for (const SliceHeader& s : slices) w.push_back(s.w);
  double slice_spacing = (w.back() - w.front()) / static_cast<double>(w.size() - 1);
  if (!placement.uneven.empty()) {
    const auto count = static_cast<std::size_t>(std::llround((w.back() - w.front()) / placement.typical_gap)) + 1;
    const auto size = image->GetLargestPossibleRegion().GetSize();
    const double voxels = static_cast<double>(size[0]) * static_cast<double>(size[1]) * static_cast<double>(count);
    try {
      check_allocation("resampling " + std::to_string(count) + " slices", 0.0, voxels * kVolumeBytesPerVoxel,
                       ResourceLimits{});
    } catch (const LimitError&) {
      rethrow_with_context(shown);
    }
    image = resample_slices(*image, w, count);
    slice_spacing = (w.back() - w.front()) / static_cast<double>(count - 1);
    warnings.push_back(shown + ": " + placement.uneven + ": resampled the " + std::to_string(w.size()) +
                       " slices onto " + std::to_string(count) + " slices " + number(slice_spacing) +
                       " mm apart, interpolating linearly along the slice normal");
  }
  // The geometry from the checked headers.
  const SliceHeader& first = slices.front();
  CtImage::SpacingType spacing;
  spacing[0] = first.column_spacing;
  spacing[1] = first.row_spacing;
  spacing[2] = slice_spacing;
  CtImage::PointType origin;
  CtImage::DirectionType direction;
  for (int r = 0; r < 3; ++r) {
    origin[r] = first.position[r];
    direction[r][0] = first.row[r];
    direction[r][1] = first.column[r];
    direction[r][2] = placement.normal[r];
  }
  image->SetSpacing(spacing);
  image->SetOrigin(origin);
  image->SetDirection(direction);
  return image;
}

}  // namespace contourmesh::detail
