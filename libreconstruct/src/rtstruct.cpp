// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/rtstruct.h"

#include <contourmesh/smooth/errors.h>

#include <Eigen/Geometry>

#include <gdcmDataElement.h>
#include <gdcmDataSet.h>
#include <gdcmItem.h>
#include <gdcmReader.h>
#include <gdcmSequenceOfItems.h>
#include <gdcmTag.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <new>
#include <set>
#include <sstream>

namespace contourmesh {

namespace {

constexpr const char* kRtStructureSetStorage = "1.2.840.10008.5.1.4.1.1.481.3";

const gdcm::Tag kSpecificCharacterSet(0x0008, 0x0005);
const gdcm::Tag kSopClassUid(0x0008, 0x0016);
const gdcm::Tag kModality(0x0008, 0x0060);
const gdcm::Tag kStructureSetLabel(0x3006, 0x0002);
const gdcm::Tag kStructureSetName(0x3006, 0x0004);
const gdcm::Tag kStructureSetRoiSequence(0x3006, 0x0020);
const gdcm::Tag kRoiNumber(0x3006, 0x0022);
const gdcm::Tag kReferencedFrameOfReferenceUid(0x3006, 0x0024);
const gdcm::Tag kRoiName(0x3006, 0x0026);
const gdcm::Tag kRoiDisplayColor(0x3006, 0x002A);
const gdcm::Tag kRoiGenerationAlgorithm(0x3006, 0x0036);
const gdcm::Tag kRoiContourSequence(0x3006, 0x0039);
const gdcm::Tag kContourSequence(0x3006, 0x0040);
const gdcm::Tag kContourGeometricType(0x3006, 0x0042);
const gdcm::Tag kNumberOfContourPoints(0x3006, 0x0046);
const gdcm::Tag kContourData(0x3006, 0x0050);
const gdcm::Tag kRtRoiObservationsSequence(0x3006, 0x0080);
const gdcm::Tag kReferencedRoiNumber(0x3006, 0x0084);
const gdcm::Tag kRtRoiInterpretedType(0x3006, 0x00A4);

enum class Charset { Ascii, Latin1, Utf8 };

// The raw bytes of an element's value ("" when absent or empty).
std::string raw_value(const gdcm::DataSet& ds, const gdcm::Tag& tag) {
  if (!ds.FindDataElement(tag)) return {};
  const gdcm::DataElement& de = ds.GetDataElement(tag);
  const gdcm::ByteValue* bv = de.GetByteValue();
  if (bv == nullptr || bv->GetPointer() == nullptr) return {};
  return {bv->GetPointer(), bv->GetLength()};
}

std::string trim(std::string s) {
  const auto blank = [](unsigned char c) { return c == ' ' || c == '\0' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && blank(static_cast<unsigned char>(s.back()))) s.pop_back();
  std::size_t start = 0;
  while (start < s.size() && blank(static_cast<unsigned char>(s[start]))) ++start;
  return s.substr(start);
}

bool valid_utf8(const std::string& s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    const std::size_t extra = c < 0x80 ? 0 : (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xE ? 2 : (c >> 3) == 0x1E ? 3 : 4;
    if (extra == 4 || i + extra >= s.size() + (extra == 0 ? 1 : 0)) return false;
    for (std::size_t k = 1; k <= extra; ++k) {
      if ((static_cast<unsigned char>(s[i + k]) >> 6) != 0x2) return false;
    }
    i += extra + 1;
  }
  return true;
}

// A text value in UTF-8, whatever the file's character set.
std::string text_value(const gdcm::DataSet& ds, const gdcm::Tag& tag, Charset charset) {
  std::string s = trim(raw_value(ds, tag));
  if (charset == Charset::Utf8 && valid_utf8(s)) return s;
  std::string out;
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x80) {
      out += ch;
    } else if (charset == Charset::Latin1) {
      out += static_cast<char>(0xC0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else {
      out += '?';
    }
  }
  return out;
}

// Backslash-separated numbers of a DS or IS value (none for an empty value). Returns false if one is
// not a finite number.
bool parse_numbers(const std::string& text, std::vector<double>& out) {
  out.clear();
  if (trim(text).empty()) return true;
  std::size_t start = 0;
  while (true) {
    std::size_t end = text.find('\\', start);
    if (end == std::string::npos) end = text.size();
    std::size_t a = start, b = end;
    while (a < b && (text[a] == ' ' || text[a] == '\0')) ++a;
    while (b > a && (text[b - 1] == ' ' || text[b - 1] == '\0')) --b;
    if (a < b && text[a] == '+') ++a;  // from_chars does not take the '+' DICOM allows
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(text.data() + a, text.data() + b, v);
    if (a == b || ec != std::errc() || ptr != text.data() + b || !std::isfinite(v)) return false;
    out.push_back(v);
    if (end == text.size()) return true;
    start = end + 1;
  }
}

std::optional<int> int_value(const gdcm::DataSet& ds, const gdcm::Tag& tag) {
  std::vector<double> v;
  if (!parse_numbers(raw_value(ds, tag), v) || v.size() != 1 || v[0] != std::floor(v[0]) || std::abs(v[0]) > 2e9) {
    return std::nullopt;
  }
  return static_cast<int>(v[0]);
}

// The items of a sequence element (none when absent).
gdcm::SmartPointer<gdcm::SequenceOfItems> sequence(const gdcm::DataSet& ds, const gdcm::Tag& tag) {
  if (!ds.FindDataElement(tag)) return nullptr;
  return ds.GetDataElement(tag).GetValueAsSQ();
}

RtContourType contour_type(const std::string& s) {
  if (s == "CLOSED_PLANAR") return RtContourType::ClosedPlanar;
  if (s == "CLOSEDPLANAR_XOR") return RtContourType::ClosedPlanarXor;
  if (s == "OPEN_PLANAR") return RtContourType::OpenPlanar;
  if (s == "OPEN_NONPLANAR") return RtContourType::OpenNonplanar;
  if (s == "POINT") return RtContourType::Point;
  return RtContourType::Unknown;
}

bool is_closed(RtContourType t) { return t == RtContourType::ClosedPlanar || t == RtContourType::ClosedPlanarXor; }

std::string quoted(const std::filesystem::path& p) { return p.string(); }

// The contours of one ROI Contour item. Unreadable Contour Data sets `error` (the ROI cannot be used;
// the others can).
std::vector<RtContour> read_contours(const gdcm::DataSet& item, const std::filesystem::path& file,
                                     const std::string& roi_label, std::vector<std::string>& warnings,
                                     std::string& error) {
  std::vector<RtContour> out;
  const auto contours = sequence(item, kContourSequence);
  if (!contours) return out;
  std::vector<double> values;
  std::size_t count_mismatch = 0;
  for (std::size_t k = 1; k <= contours->GetNumberOfItems(); ++k) {
    const gdcm::DataSet& c = contours->GetItem(k).GetNestedDataSet();
    RtContour contour;
    contour.type_name = trim(raw_value(c, kContourGeometricType));
    contour.type = contour_type(contour.type_name);
    if (!parse_numbers(raw_value(c, kContourData), values) || values.size() % 3 != 0) {
      if (error.empty()) {
        error = roi_label + ", contour " + std::to_string(k) +
                ": Contour Data (3006,0050) is not a list of x\\y\\z numbers";
      }
      values.clear();
    }
    contour.points.reserve(values.size() / 3);
    for (std::size_t i = 0; i + 2 < values.size(); i += 3)
      contour.points.emplace_back(values[i], values[i + 1], values[i + 2]);
    const auto declared = int_value(c, kNumberOfContourPoints);
    if (declared && *declared != static_cast<int>(contour.points.size())) ++count_mismatch;
    out.push_back(std::move(contour));
  }
  if (count_mismatch > 0) {
    warnings.push_back(quoted(file) + ": " + roi_label + ": " + std::to_string(count_mismatch) + " contour" +
                       (count_mismatch == 1 ? "'s" : "s'") +
                       " Number of Contour Points (3006,0046) disagrees with the Contour Data; the data is used");
  }
  return out;
}

// Mean position of each closed contour along the contours' common normal.
std::vector<double> closed_contour_positions(const RtRoi& roi) {
  std::vector<const RtContour*> closed;
  for (const RtContour& c : roi.contours) {
    if (is_closed(c.type) && c.points.size() >= 3) closed.push_back(&c);
  }
  Eigen::Vector3d largest = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> areas;
  for (const RtContour* c : closed) {
    Eigen::Vector3d a = Eigen::Vector3d::Zero();
    for (std::size_t i = 1; i + 1 < c->points.size(); ++i) {
      a += (c->points[i] - c->points[0]).cross(c->points[i + 1] - c->points[0]);
    }
    areas.push_back(a);
    if (a.norm() > largest.norm()) largest = a;
  }
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& a : areas) axis += a.dot(largest) < 0.0 ? -a : a;
  if (!(axis.norm() > 0.0)) axis = Eigen::Vector3d::UnitZ();
  axis.normalize();
  std::vector<double> w;
  for (const RtContour* c : closed) {
    double sum = 0.0;
    for (const Eigen::Vector3d& p : c->points) sum += p.dot(axis);
    w.push_back(sum / static_cast<double>(c->points.size()));
  }
  return w;
}

}  // namespace

const char* to_string(RtContourType type) {
  switch (type) {
    case RtContourType::ClosedPlanar: return "CLOSED_PLANAR";
    case RtContourType::ClosedPlanarXor: return "CLOSEDPLANAR_XOR";
    case RtContourType::OpenPlanar: return "OPEN_PLANAR";
    case RtContourType::OpenNonplanar: return "OPEN_NONPLANAR";
    case RtContourType::Point: return "POINT";
    case RtContourType::Unknown: break;
  }
  return "unknown";
}

std::string RtRoi::label() const { return "ROI " + std::to_string(number) + " '" + name + "'"; }

std::size_t RtRoi::closed_contours() const {
  return static_cast<std::size_t>(
      std::count_if(contours.begin(), contours.end(), [](const RtContour& c) { return is_closed(c.type); }));
}

std::size_t RtRoi::slices(double tolerance) const {
  std::vector<double> w = closed_contour_positions(*this);
  std::sort(w.begin(), w.end());
  std::size_t n = 0;
  double first = 0.0;
  for (const double x : w) {
    if (n == 0 || x - first > tolerance) {
      ++n;
      first = x;
    }
  }
  return n;
}

std::size_t RtRoi::points() const {
  std::size_t n = 0;
  for (const RtContour& c : contours) n += c.points.size();
  return n;
}

bool is_rt_structure_set(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return false;
  try {
    gdcm::Reader reader;
    reader.SetFileName(file.string().c_str());
    // Modality (0008,0060) comes after the SOP Class UID: reading up to it reads both.
    if (!reader.ReadUpToTag(gdcm::Tag(0x0008, 0x0061))) return false;
    const gdcm::DataSet& ds = reader.GetFile().GetDataSet();
    return trim(raw_value(ds, kSopClassUid)) == kRtStructureSetStorage || trim(raw_value(ds, kModality)) == "RTSTRUCT";
  } catch (const std::exception&) {
    return false;
  }
}

namespace {

RtStructureSet read_structure_set(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw InvalidInputError(quoted(file) + ": no such file");
  if (!std::filesystem::is_regular_file(file, ec)) throw InvalidInputError(quoted(file) + ": not a regular file");
  gdcm::Reader reader;
  reader.SetFileName(file.string().c_str());
  if (!reader.Read()) throw InvalidInputError(quoted(file) + ": not a readable DICOM file (truncated or corrupt?)");
  const gdcm::DataSet& ds = reader.GetFile().GetDataSet();
  const std::string sop = trim(raw_value(ds, kSopClassUid));
  const std::string modality = trim(raw_value(ds, kModality));
  if (sop != kRtStructureSetStorage && modality != "RTSTRUCT") {
    throw InvalidInputError(quoted(file) + ": a DICOM file but not an RT Structure Set (modality '" + modality +
                            "', SOP class " + (sop.empty() ? "none" : sop) + ")");
  }
  const std::string charset_text = trim(raw_value(ds, kSpecificCharacterSet));
  const Charset charset = charset_text.find("ISO_IR 192") != std::string::npos   ? Charset::Utf8
                          : charset_text.find("ISO_IR 100") != std::string::npos ? Charset::Latin1
                                                                                 : Charset::Ascii;
  RtStructureSet set;
  set.file = file;
  set.label = text_value(ds, kStructureSetLabel, charset);
  set.name = text_value(ds, kStructureSetName, charset);

  const auto rois = sequence(ds, kStructureSetRoiSequence);
  if (!rois) throw InvalidInputError(quoted(file) + ": no Structure Set ROI Sequence (3006,0020): not a structure set");
  std::map<int, std::size_t> by_number;
  for (std::size_t k = 1; k <= rois->GetNumberOfItems(); ++k) {
    const gdcm::DataSet& item = rois->GetItem(k).GetNestedDataSet();
    RtRoi roi;
    const auto number = int_value(item, kRoiNumber);
    if (!number) {
      set.warnings.push_back(quoted(file) + ": item " + std::to_string(k) +
                             " of the Structure Set ROI Sequence has no valid ROI Number: skipped");
      continue;
    }
    roi.number = *number;
    roi.name = text_value(item, kRoiName, charset);
    roi.generation_algorithm = text_value(item, kRoiGenerationAlgorithm, charset);
    if (set.frame_of_reference.empty()) set.frame_of_reference = trim(raw_value(item, kReferencedFrameOfReferenceUid));
    if (by_number.count(roi.number) != 0) {
      set.warnings.push_back(quoted(file) + ": ROI number " + std::to_string(roi.number) +
                             " is declared twice; the second, '" + roi.name + "', is ignored");
      continue;
    }
    by_number[roi.number] = set.rois.size();
    set.rois.push_back(std::move(roi));
  }

  if (const auto contours = sequence(ds, kRoiContourSequence)) {
    for (std::size_t k = 1; k <= contours->GetNumberOfItems(); ++k) {
      const gdcm::DataSet& item = contours->GetItem(k).GetNestedDataSet();
      const auto ref = int_value(item, kReferencedRoiNumber);
      if (!ref || by_number.count(*ref) == 0) {
        set.warnings.push_back(quoted(file) + ": item " + std::to_string(k) +
                               " of the ROI Contour Sequence refers to " +
                               (ref ? "ROI number " + std::to_string(*ref) + ", which is not declared" : "no ROI") +
                               ": skipped");
        continue;
      }
      RtRoi& roi = set.rois[by_number[*ref]];
      std::vector<double> rgb;
      if (parse_numbers(raw_value(item, kRoiDisplayColor), rgb) && rgb.size() == 3 &&
          std::all_of(rgb.begin(), rgb.end(), [](double v) { return v >= 0.0 && v <= 255.0 && v == std::floor(v); })) {
        roi.color = std::array<int, 3>{static_cast<int>(rgb[0]), static_cast<int>(rgb[1]), static_cast<int>(rgb[2])};
      }
      std::vector<RtContour> more = read_contours(item, file, roi.label(), set.warnings, roi.error);
      roi.contours.insert(roi.contours.end(), std::make_move_iterator(more.begin()),
                          std::make_move_iterator(more.end()));
    }
  }
  if (const auto observations = sequence(ds, kRtRoiObservationsSequence)) {
    for (std::size_t k = 1; k <= observations->GetNumberOfItems(); ++k) {
      const gdcm::DataSet& item = observations->GetItem(k).GetNestedDataSet();
      const auto ref = int_value(item, kReferencedRoiNumber);
      if (ref && by_number.count(*ref) != 0) {
        set.rois[by_number[*ref]].interpreted_type = text_value(item, kRtRoiInterpretedType, charset);
      }
    }
  }
  return set;
}

}  // namespace

RtStructureSet read_rt_structure_set(const std::filesystem::path& file) {
  try {
    return read_structure_set(file);
  } catch (const InvalidInputError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    // GDCM reports some malformed sequences by throwing.
    throw InvalidInputError(quoted(file) + ": malformed RT Structure Set (" + e.what() + ")");
  }
}

const RtRoi& find_roi(const RtStructureSet& set, const std::string& selector) {
  const std::string wanted = trim(selector);
  for (const RtRoi& roi : set.rois) {
    if (roi.name == wanted) return roi;
  }
  const auto lower = [](std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  const RtRoi* match = nullptr;
  std::size_t matches = 0;
  for (const RtRoi& roi : set.rois) {
    if (lower(roi.name) == lower(wanted)) {
      match = &roi;
      ++matches;
    }
  }
  if (matches == 1) return *match;
  std::vector<double> number;
  if (matches == 0 && parse_numbers(wanted, number) && number.size() == 1) {
    for (const RtRoi& roi : set.rois) {
      if (roi.number == number[0]) return roi;
    }
  }
  std::ostringstream msg;
  msg << quoted(set.file) << ": " << (matches > 1 ? "several ROIs are named '" : "no ROI named '") << wanted
      << "'; the ROIs are:";
  for (std::size_t i = 0; i < set.rois.size(); ++i) msg << (i ? ", " : " ") << "'" << set.rois[i].name << "'";
  if (set.rois.empty()) msg << " none";
  throw InvalidInputError(msg.str());
}

RoiStack roi_contour_stack(const RtRoi& roi, const PlanarStackOptions& options) {
  const std::string what = roi.label();
  if (!roi.error.empty()) throw InvalidInputError(roi.error);
  if (roi.contours.empty()) throw InvalidInputError(what + " has no contours: there is nothing to reconstruct");
  std::vector<PlanarContour> closed;
  std::map<std::string, std::vector<std::size_t>> skipped;  // type name -> contour numbers
  for (std::size_t k = 0; k < roi.contours.size(); ++k) {
    const RtContour& c = roi.contours[k];
    if (!is_closed(c.type)) {
      skipped[c.type_name.empty() ? "no geometric type" : c.type_name].push_back(k + 1);
      continue;
    }
    closed.push_back({c.points, "contour " + std::to_string(k + 1), std::nullopt});
  }
  std::string skipped_text;
  std::size_t skipped_count = 0;
  for (const auto& [type, numbers] : skipped) {
    std::ostringstream s;
    s << (skipped_text.empty() ? "" : "; ") << numbers.size() << " " << type << " (contour"
      << (numbers.size() == 1 ? " " : "s ");
    for (std::size_t i = 0; i < numbers.size() && i < 8; ++i) s << (i ? ", " : "") << numbers[i];
    if (numbers.size() > 8) s << ", ...";
    s << ")";
    skipped_text += s.str();
    skipped_count += numbers.size();
  }
  if (closed.empty()) {
    throw InvalidInputError(what + " has no closed planar contour, only " + skipped_text +
                            ": a surface needs CLOSED_PLANAR contours");
  }
  RoiStack out;
  out.planar = build_contour_stack(closed, what, options);
  // build_contour_stack numbers contours within `closed`; map sources back to the ROI's contour order.
  std::vector<std::size_t> index;
  for (std::size_t k = 0; k < roi.contours.size(); ++k) {
    if (is_closed(roi.contours[k].type)) index.push_back(k);
  }
  for (auto& slice : out.planar.report.source) {
    for (std::size_t& s : slice) s = index[s];
  }
  out.skipped_contours = skipped_count;
  if (skipped_count > 0) {
    out.planar.report.warnings.insert(
        out.planar.report.warnings.begin(),
        what + ": skipped " + skipped_text + ": only closed planar contours bound a volume");
  }
  return out;
}

std::optional<double> structure_set_slice_spacing(const RtStructureSet& set) {
  std::vector<double> w;
  for (const RtRoi& roi : set.rois) {
    const std::vector<double> more = closed_contour_positions(roi);
    w.insert(w.end(), more.begin(), more.end());
  }
  std::sort(w.begin(), w.end());
  std::vector<double> planes;
  for (const double x : w) {
    if (planes.empty() || x - planes.back() > 0.1) planes.push_back(x);
  }
  if (planes.size() < 2) return std::nullopt;
  std::vector<double> gaps;
  for (std::size_t i = 1; i < planes.size(); ++i) gaps.push_back(planes[i] - planes[i - 1]);
  std::nth_element(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2), gaps.end());
  return gaps[gaps.size() / 2];
}

std::string roi_file_stem(const RtRoi& roi) {
  std::string out;
  bool gap = false;
  for (const char ch : roi.name) {
    const auto c = static_cast<unsigned char>(ch);
    if (std::isalnum(c) != 0 && c < 0x80) {
      if (gap && !out.empty()) out += '_';
      gap = false;
      out += ch;
    } else if (c == '.' || c == '-' || c == '_') {
      if (gap && !out.empty()) out += '_';
      gap = false;
      out += ch;
    } else {
      gap = true;
    }
  }
  while (!out.empty() && (out.front() == '_' || out.front() == '.')) out.erase(out.begin());
  while (!out.empty() && (out.back() == '_' || out.back() == '.')) out.pop_back();
  if (out.empty()) out = "roi" + std::to_string(roi.number);
  return out;
}

std::vector<std::string> roi_file_stems(const RtStructureSet& set) {
  std::vector<std::string> stems;
  std::map<std::string, int> seen;
  const auto lower = [](std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  for (const RtRoi& roi : set.rois) {
    stems.push_back(roi_file_stem(roi));
    ++seen[lower(stems.back())];
  }
  for (std::size_t i = 0; i < stems.size(); ++i) {
    if (seen[lower(stems[i])] > 1) {
      stems[i].push_back('_');  // (appending "_" + number trips a false -Wrestrict of gcc 12)
      stems[i].append(std::to_string(set.rois[i].number));
    }
  }
  return stems;
}

}  // namespace contourmesh
