// SPDX-License-Identifier: BSD-3-Clause
#include "vtkCheckedXMLPolyDataReader.h"

#include <vtkDataArray.h>
#include <vtkDataCompressor.h>
#include <vtkObjectFactory.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkCheckedXMLPolyDataReader);

namespace {

// Cells a file may announce per allowed point (see MaximumNumberOfPoints).
constexpr vtkIdType kCellsPerPoint = 8;

bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }  // as vtkXMLParser::IsSpace

// Components a data array may have: far more than any mesh attribute needs (a tensor has 9).
constexpr long long kMaxComponents = 1024;

// The problem with the NumberOfComponents of the data arrays under `e` (PointData, CellData, Points or a
// cell array); empty when there is none. VTK reads the attribute into an int without checking it, then
// allocates and parses tuples x components values: 42949672963 components on 4 points kept it busy for
// minutes (found by fuzz_read_vtp).
std::string check_components(vtkXMLDataElement* e) {
  if (e == nullptr) return {};
  for (int k = 0; k < e->GetNumberOfNestedElements(); ++k) {
    vtkXMLDataElement* da = e->GetNestedElement(k);
    const char* value = da != nullptr ? da->GetAttribute("NumberOfComponents") : nullptr;
    if (value == nullptr) continue;
    char* end = nullptr;
    errno = 0;
    const long long n = std::strtoll(value, &end, 10);
    const bool integer = end != value && errno == 0 && std::all_of(end, end + std::strlen(end), is_space);
    if (!integer || n < 1 || n > kMaxComponents) {
      const char* name = da->GetAttribute("Name");
      return std::string("data array '") + (name != nullptr ? name : "") + "' of " + e->GetName() +
             " has NumberOfComponents=\"" + value + "\", not an integer in [1, " + std::to_string(kMaxComponents) +
             "]";
    }
  }
  return {};
}

// The bytes of one data block of a file, raw or base64 as vtkBase64InputStream decodes them: groups
// of four characters, a group with padding or another character ending the data.
class DataBytes {
 public:
  DataBytes(const char* file, std::int64_t start, bool base64)
      : in_(file, std::ios::binary), start_(start), base64_(base64) {
    in_.seekg(0, std::ios::end);
    size_ = in_ ? static_cast<std::int64_t>(in_.tellg()) : 0;
  }

  // An upper bound of the bytes from the start to the end of the file.
  [[nodiscard]] std::uint64_t available() const {
    if (start_ < 0 || start_ >= size_) return 0;
    const auto chars = static_cast<std::uint64_t>(size_ - start_);
    return base64_ ? chars / 4 * 3 : chars;
  }

  // Bytes [offset, offset + n); false when VTK could not read them either. Base64 is decoded from the
  // start as vtkBase64InputStream::Read does: a group with '=' gives fewer bytes and ends the data.
  bool read(std::uint64_t offset, std::uint64_t n, std::vector<unsigned char>& out) {
    out.clear();
    if (n > available() || offset > available() - n) return false;
    in_.clear();
    if (!base64_) {
      out.resize(n);
      in_.seekg(start_ + static_cast<std::int64_t>(offset));
      return static_cast<bool>(in_.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(n)));
    }
    const std::uint64_t end = offset + n;
    std::vector<char> chars((end + 2) / 3 * 4);
    in_.seekg(start_);
    if (!in_.read(chars.data(), static_cast<std::streamsize>(chars.size()))) return false;
    std::vector<unsigned char> decoded;
    decoded.reserve(chars.size() / 4 * 3);
    for (std::size_t g = 0; g < chars.size() && decoded.size() < end; g += 4) {
      unsigned word = 0;
      for (int c = 0; c < 4; ++c) {
        const int v = sextet(chars[g + c]);
        if (v < 0) return false;
        word = (word << 6) | static_cast<unsigned>(v);
      }
      const int count = chars[g + 2] == '=' ? 1 : chars[g + 3] == '=' ? 2 : 3;
      for (int b = 0; b < count; ++b) decoded.push_back(static_cast<unsigned char>(word >> (8 * (2 - b))));
      if (count < 3) break;
    }
    if (decoded.size() < end) return false;
    out.assign(decoded.begin() + static_cast<std::ptrdiff_t>(offset),
               decoded.begin() + static_cast<std::ptrdiff_t>(end));
    return true;
  }

 private:
  static int sextet(char c) {  // as vtkBase64Utilities: '=' decodes as 0 (it shortens its group)
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    if (c == '=') return 0;
    return -1;
  }

  std::ifstream in_;
  std::int64_t start_;
  bool base64_;
  std::int64_t size_ = 0;
};

std::uint64_t word_at(const std::vector<unsigned char>& bytes, std::size_t index, std::size_t word, bool big_endian) {
  std::uint64_t v = 0;
  for (std::size_t k = 0; k < word; ++k) {
    const std::size_t b = big_endian ? k : word - 1 - k;
    v = (v << 8) | bytes[index * word + b];
  }
  return v;
}

// Where VTK starts reading after the start tag at `tag` (its '>' then white space), as
// vtkXMLDataParser::SeekInlineDataPosition and FindAppendedDataPosition do; -1 if the file ends first.
std::int64_t data_start(const char* file, std::int64_t tag, bool skip_underscore) {
  std::ifstream in(file, std::ios::binary);
  in.seekg(tag);
  char c = 0;
  while (in.get(c) && c != '>') {
  }
  while (in.get(c) && is_space(c)) {
  }
  if (!in) return -1;
  const auto at = static_cast<std::int64_t>(in.tellg());
  return skip_underscore && c == '_' ? at : at - 1;
}

}  // namespace

int vtkCheckedXMLPolyDataReader::ReadXMLInformation() {
  this->AnnouncedPoints = 0;
  this->AnnouncedCells = 0;
  this->LimitError.clear();
  return this->Superclass::ReadXMLInformation();
}

int vtkCheckedXMLPolyDataReader::ReadPiece(vtkXMLDataElement* ePiece) {
  if (!this->Superclass::ReadPiece(ePiece)) return 0;
  // The counts as the base class read them (it has checked they are present).
  vtkIdType points = 0;
  ePiece->GetScalarAttribute("NumberOfPoints", points);
  vtkIdType cells = 0;
  for (const char* kind : {"NumberOfVerts", "NumberOfLines", "NumberOfStrips", "NumberOfPolys"}) {
    vtkIdType n = 0;
    ePiece->GetScalarAttribute(kind, n);
    if (n < 0) {
      vtkErrorMacro(<< "the piece announces " << n << " for " << kind);
      return 0;
    }
    cells = n > VTK_ID_MAX - cells ? VTK_ID_MAX : cells + n;
  }
  if (points < 0) {
    vtkErrorMacro(<< "the piece announces " << points << " points");
    return 0;
  }
  for (const char* kind : {"PointData", "CellData", "Points", "Verts", "Lines", "Strips", "Polys"}) {
    const std::string problem = check_components(ePiece->FindNestedElementWithName(kind));
    if (!problem.empty()) {
      vtkErrorMacro(<< problem);
      return 0;
    }
  }
  // VTK refuses points with other than 3 components too, but leaks its array iterator on the way.
  if (vtkXMLDataElement* ePoints = ePiece->FindNestedElementWithName("Points");
      ePoints != nullptr && ePoints->GetNumberOfNestedElements() > 0) {
    int components = 1;
    ePoints->GetNestedElement(0)->GetScalarAttribute("NumberOfComponents", components);
    if (components != 3) {
      vtkErrorMacro(<< "the points have " << components << " components, not 3");
      return 0;
    }
  }
  this->AnnouncedPoints = points > VTK_ID_MAX - this->AnnouncedPoints ? VTK_ID_MAX : this->AnnouncedPoints + points;
  this->AnnouncedCells = cells > VTK_ID_MAX - this->AnnouncedCells ? VTK_ID_MAX : this->AnnouncedCells + cells;
  const vtkIdType max_cells = this->MaximumNumberOfPoints > VTK_ID_MAX / kCellsPerPoint
                                  ? VTK_ID_MAX
                                  : kCellsPerPoint * this->MaximumNumberOfPoints;
  if (this->AnnouncedPoints > this->MaximumNumberOfPoints) {
    this->LimitError = "VTP: the header announces " + std::to_string(this->AnnouncedPoints) +
                       " points, more than the limit of " + std::to_string(this->MaximumNumberOfPoints);
  } else if (this->AnnouncedCells > max_cells) {
    this->LimitError = "VTP: the header announces " + std::to_string(this->AnnouncedCells) + " cells, more than " +
                       std::to_string(kCellsPerPoint) + " per vertex of the limit of " +
                       std::to_string(this->MaximumNumberOfPoints) + " vertices";
  }
  if (!this->LimitError.empty()) {
    vtkErrorMacro(<< this->LimitError);
    return 0;
  }
  return 1;
}

int vtkCheckedXMLPolyDataReader::ReadArrayValues(vtkXMLDataElement* da, vtkIdType arrayIndex, vtkAbstractArray* array,
                                                 vtkIdType startIndex, vtkIdType numValues, FieldType fieldType) {
  if (this->XMLParser != nullptr && this->XMLParser->GetCompressor() != nullptr) {
    const std::string problem = this->CheckCompressionHeader(da);
    if (!problem.empty()) {
      vtkErrorMacro(<< problem);
      return 0;
    }
  }
  if (!this->Superclass::ReadArrayValues(da, arrayIndex, array, startIndex, numValues, fieldType)) return 0;
  // A cell array's offsets: VTK sizes the connectivity array from the last one before reading it.
  const char* name = da->GetAttribute("Name");
  vtkDataArray* values = vtkDataArray::SafeDownCast(array);
  if (name != nullptr && std::strcmp(name, "offsets") == 0 && values != nullptr && this->GetFileName() != nullptr) {
    std::error_code ec;
    const auto file_size = static_cast<double>(std::filesystem::file_size(this->GetFileName(), ec));
    // Every connectivity entry takes at least a byte of the file, or 1/4096 of one when compressed
    // (about 1/1032 for zlib), plus one 64 MiB block a compressed header may announce on any data.
    const double most = 4096.0 * file_size + static_cast<double>(std::uint64_t{64} << 20);
    // The values read are array values [arrayIndex, arrayIndex + numValues) (VTK 9 puts a 0 first and
    // reads the file's offsets from index 1); startIndex is where they start in the file's data.
    double previous = 0.0;
    const vtkIdType end = std::min<vtkIdType>(arrayIndex + numValues, values->GetNumberOfTuples());
    for (vtkIdType i = std::max<vtkIdType>(arrayIndex, 0); i < end; ++i) {
      const double offset = values->GetComponent(i, 0);
      if (!(offset >= previous) || offset > most) {
        vtkErrorMacro(<< "cell offset " << startIndex + (i - arrayIndex) << " is " << offset
                      << (offset > most ? ", more connectivity entries than the file can hold"
                                        : ", below the previous one")
                      << " (corrupt file)");
        return 0;
      }
      previous = offset;
    }
  }
  return 1;
}

std::string vtkCheckedXMLPolyDataReader::CheckCompressionHeader(vtkXMLDataElement* da) {
  const char* file = this->GetFileName();
  vtkXMLDataElement* root = this->XMLParser->GetRootElement();
  if (file == nullptr || root == nullptr) return {};
  // Where the data are, decided as vtkXMLDataReader does: appended when there is an offset attribute,
  // else inline, binary when format="binary" (ASCII data have no compression header).
  std::int64_t start = -1;
  bool base64 = true;
  const char* name = da->GetAttribute("Name");
  const std::string where = std::string("compressed data array '") + (name != nullptr ? name : "") + "': ";
  // VTK reports a missing or short compression header too, but leaks the array's iterator on the way
  // (found by fuzz_read_vtp): say it first.
  const std::string truncated = where + "the file ends before its compression header (truncated file?)";
  if (da->GetAttribute("offset") != nullptr) {
    vtkTypeInt64 offset = 0;
    da->GetScalarAttribute("offset", offset);
    vtkXMLDataElement* appended = root->FindNestedElementWithName("AppendedData");
    // Without the element VTK reads the array from the file's start as base64 text, and took a header word
    // of that text for 1.8 billion blocks (found by fuzz_read_vtp: the element's name cut short).
    if (appended == nullptr) {
      return where + "the data array has an offset but the file has no AppendedData (corrupt file)";
    }
    const char* encoding = appended->GetAttribute("encoding");
    base64 = !(encoding != nullptr && std::strcmp(encoding, "raw") == 0);
    const std::int64_t position = data_start(file, appended->GetXMLByteIndex(), true);
    if (position < 0) return truncated;
    if (offset < -position || offset > std::numeric_limits<std::int64_t>::max() - position) return {};
    start = position + offset;
  } else {
    const char* format = da->GetAttribute("format");
    if (format == nullptr || std::strcmp(format, "binary") != 0) return {};
    start = data_start(file, da->GetXMLByteIndex(), false);
  }
  if (start < 0) return {};

  const char* header_type = root->GetAttribute("header_type");
  const std::size_t word = header_type != nullptr && std::strcmp(header_type, "UInt64") == 0 ? 8 : 4;
  const char* byte_order = root->GetAttribute("byte_order");
  const bool big_endian = byte_order != nullptr && std::strcmp(byte_order, "BigEndian") == 0;

  DataBytes data(file, start, base64);
  std::vector<unsigned char> head;
  if (!data.read(0, 3 * word, head)) return truncated;
  const std::uint64_t blocks = word_at(head, 0, word, big_endian);
  const std::uint64_t block_size = word_at(head, 1, word, big_endian);
  const std::uint64_t last_size = word_at(head, 2, word, big_endian);
  const std::uint64_t after_header = data.available() - 3 * word;
  if (blocks > after_header / word) {
    return where + "the header announces " + std::to_string(blocks) +
           " blocks, more than the file could hold (corrupt file)";
  }
  if (blocks == 0) {
    // VTK then takes the data size as 0 - block size + last block size and reads that.
    if (last_size == 0) return {};
    return where + "the header announces no blocks but a last block of " + std::to_string(last_size) +
           " bytes (corrupt file)";
  }
  if (block_size == 0) return where + "the header gives a block size of 0 (corrupt file)";
  if (last_size > block_size) {
    return where + "the last block (" + std::to_string(last_size) + " bytes) is larger than the block size (" +
           std::to_string(block_size) + " bytes) (corrupt file)";
  }
  std::vector<unsigned char> sizes;
  if (!data.read(3 * word, blocks * word, sizes)) return {};
  const std::uint64_t data_bytes = after_header - blocks * word;
  std::uint64_t largest = 0;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const std::uint64_t size = word_at(sizes, static_cast<std::size_t>(b), word, big_endian);
    if (size > data_bytes) {
      return where + "block " + std::to_string(b) + " announces " + std::to_string(size) +
             " compressed bytes, more than the file holds (truncated or corrupt file)";
    }
    largest = std::max(largest, size);
  }
  // VTK allocates a whole block before decompressing into it. zlib expands at most about 1032:1 and
  // LZ4 255:1, and VTK writes 32 KiB blocks: a block beyond both bounds is a corrupt size, not data.
  constexpr std::uint64_t kRoomyBlock = std::uint64_t{64} << 20;
  constexpr std::uint64_t kMaxRatio = 4096;
  if (block_size > kRoomyBlock && block_size / kMaxRatio > largest) {
    return where + "the header gives a block size of " + std::to_string(block_size) + " bytes for at most " +
           std::to_string(largest) + " compressed bytes (corrupt file)";
  }
  return {};
}
