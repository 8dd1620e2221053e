// SPDX-License-Identifier: BSD-3-Clause
#include "detail/volume_file_checks.h"

#include <contourmesh/smooth/errors.h>

#include <itk_zlib.h>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

namespace contourmesh::detail {

namespace fs = std::filesystem;

namespace {

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string trim(const std::string& text) {
  std::size_t a = 0, b = text.size();
  while (a < b && std::isspace(static_cast<unsigned char>(text[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(text[b - 1]))) --b;
  return text.substr(a, b - a);
}

std::string describe_bytes(std::uint64_t n) { return std::to_string(n) + " byte" + (n == 1 ? "" : "s"); }

// What a header promises: the voxel grid, the bytes of one voxel, and where the data are.
struct Promise {
  std::vector<std::uint64_t> sizes;
  std::uint64_t voxel_bytes = 0;  // 0: unknown type, the size is not checked
  [[nodiscard]] std::uint64_t bytes() const {
    std::uint64_t n = voxel_bytes;
    for (std::uint64_t s : sizes) n *= s;
    return n;
  }
  [[nodiscard]] std::string grid() const {
    std::string g;
    for (std::size_t k = 0; k < sizes.size(); ++k) g += (k ? " x " : "") + std::to_string(sizes[k]);
    return g;
  }
};

[[noreturn]] void fail(const std::string& shown, const std::string& what) {
  throw InvalidInputError(shown + ": " + what);
}

void check_length(const std::string& shown, const Promise& p, std::uint64_t available, const std::string& where) {
  if (p.voxel_bytes == 0 || available >= p.bytes()) return;
  fail(shown, "the header promises " + p.grid() + " voxels of " + describe_bytes(p.voxel_bytes) + " (" +
                  describe_bytes(p.bytes()) + ") but " + where + " holds " + describe_bytes(available) +
                  " (truncated file?)");
}

// Inflates a zlib or gzip stream (detected from its header; gzip members may follow one another) from
// `in`, at most `limit` compressed bytes, and returns the number of bytes it decompresses to. A corrupt
// stream, or one that ends before its end marker, is an error naming `what`.
std::uint64_t inflated_size(std::istream& in, std::uint64_t limit, const std::string& shown, const std::string& what) {
  z_stream z{};
  if (inflateInit2(&z, 15 + 32) != Z_OK) fail(shown, "cannot start zlib");
  std::vector<unsigned char> input(1 << 16), output(1 << 16);
  std::uint64_t total = 0, consumed = 0;
  auto refill = [&]() {
    if (z.avail_in > 0) return true;
    const std::uint64_t want = std::min<std::uint64_t>(input.size(), limit - consumed);
    if (want == 0) return false;
    in.read(reinterpret_cast<char*>(input.data()), static_cast<std::streamsize>(want));
    const auto got = static_cast<std::uint64_t>(in.gcount());
    consumed += got;
    z.next_in = input.data();
    z.avail_in = static_cast<uInt>(got);
    return got > 0;
  };
  auto error = [&](const std::string& text) {
    inflateEnd(&z);
    fail(shown, what + text);
  };
  for (;;) {  // one compressed stream (gzip member) per pass
    int status = Z_OK;
    while (status != Z_STREAM_END) {
      if (!refill()) {
        error(" stop in the middle of their compressed stream, after " + describe_bytes(total) +
              " of decompressed data (truncated file?)");
      }
      z.next_out = output.data();
      z.avail_out = static_cast<uInt>(output.size());
      const uInt before = z.avail_in;
      status = inflate(&z, Z_NO_FLUSH);
      const std::size_t produced = output.size() - z.avail_out;
      total += produced;
      if (status == Z_STREAM_END || (status == Z_OK && (produced > 0 || z.avail_in < before))) continue;
      error(std::string(" are corrupt (zlib: ") + (z.msg != nullptr ? z.msg : "no progress") + ") after " +
            describe_bytes(total) + " of decompressed data");
    }
    if (!refill()) break;  // the end of the data
    if (z.avail_in < 2 || z.next_in[0] != 0x1f || z.next_in[1] != 0x8b) break;  // trailing bytes, not a member
    inflateReset(&z);
  }
  inflateEnd(&z);
  return total;
}

std::uint64_t file_size(const fs::path& path, const std::string& shown) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec) fail(shown, "cannot read '" + path.string() + "': " + ec.message());
  return size;
}

// ----- MetaImage ----------------------------------------------------------------------------------

std::uint64_t metaio_type_size(const std::string& type) {
  static const std::map<std::string, std::uint64_t> sizes = {
      {"MET_CHAR", 1},  {"MET_UCHAR", 1},  {"MET_SHORT", 2},     {"MET_USHORT", 2},     {"MET_INT", 4},
      {"MET_UINT", 4},  {"MET_FLOAT", 4},  {"MET_DOUBLE", 8},    {"MET_LONG_LONG", 8},  {"MET_ULONG_LONG", 8}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;  // MET_LONG and the rest: platform-dependent, unchecked
}

void check_metaimage(const fs::path& path, const std::string& shown) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(shown, "cannot open for reading");
  std::map<std::string, std::string> fields;
  std::string line;
  bool data_line = false;
  for (int lines = 0; lines < 200 && std::getline(in, line); ++lines) {
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = trim(line.substr(0, eq));
    fields[key] = trim(line.substr(eq + 1));
    if (key == "ElementDataFile") {
      data_line = true;
      break;
    }
  }
  if (!data_line) {
    if (fields.count("ObjectType") || fields.count("NDims")) {
      fail(shown, "the MetaImage header does not end (no ElementDataFile line: truncated file?)");
    }
    return;  // not a MetaImage: ITK decides what it is
  }
  const std::uint64_t data_start = static_cast<std::uint64_t>(in.tellg());
  // MetaIO reports a malformed number as a missing field ("DimSize required"): say what is wrong.
  for (const char* key : {"ElementSpacing", "ElementSize", "Offset", "Origin", "Position", "TransformMatrix",
                          "Rotation", "Orientation"}) {
    if (!fields.count(key)) continue;
    std::istringstream values(fields[key]);
    for (std::string word; values >> word;) {
      char* end = nullptr;
      const double v = std::strtod(word.c_str(), &end);
      const bool spacing = std::string(key) == "ElementSpacing" || std::string(key) == "ElementSize";
      if (end == word.c_str() || *end != '\0' || !std::isfinite(v) || (spacing && !(v > 0.0))) {
        fail(shown, std::string("the header's ") + key + " '" + fields[key] + "' is not a list of " +
                        (spacing ? "numbers > 0" : "finite numbers"));
      }
    }
  }
  Promise p;
  {
    std::istringstream dims(fields["DimSize"]);
    for (std::uint64_t d = 0; dims >> d;) p.sizes.push_back(d);
    if (p.sizes.empty()) return;
  }
  p.voxel_bytes = metaio_type_size(fields["ElementType"]);
  if (fields.count("ElementNumberOfChannels")) {
    const long channels = std::atol(fields["ElementNumberOfChannels"].c_str());
    if (channels > 1) p.voxel_bytes *= static_cast<std::uint64_t>(channels);
  }
  const std::string file = fields["ElementDataFile"];
  const bool compressed = lower(fields["CompressedData"]) == "true";
  fs::path data = path;
  std::uint64_t offset = data_start;
  if (file != "LOCAL") {
    if (file == "LIST" || file.find('%') != std::string::npos || file.find(' ') != std::string::npos) return;
    data = fs::path(file).is_absolute() ? fs::path(file) : path.parent_path() / file;
    if (!fs::exists(data)) fail(shown, "its data file '" + data.string() + "' does not exist");
    offset = 0;
    if (fields.count("HeaderSize")) {
      const long long header = std::atoll(fields["HeaderSize"].c_str());
      if (header > 0) offset = static_cast<std::uint64_t>(header);
      if (header < 0) return;  // data at the end of the file: nothing to compare
    }
  }
  const std::uint64_t size = file_size(data, shown);
  const std::uint64_t available = size > offset ? size - offset : 0;
  const std::string where = data == path ? "the file" : "its data file '" + data.filename().string() + "'";
  if (!compressed) {
    check_length(shown, p, available, where);
    return;
  }
  std::uint64_t limit = available;
  if (fields.count("CompressedDataSize")) {
    const long long announced = std::atoll(fields["CompressedDataSize"].c_str());
    if (announced > 0 && static_cast<std::uint64_t>(announced) > available) {
      fail(shown, "the header announces " + describe_bytes(static_cast<std::uint64_t>(announced)) +
                      " of compressed data but " + where + " holds " + describe_bytes(available) +
                      " (truncated file?)");
    }
    if (announced > 0) limit = static_cast<std::uint64_t>(announced);
  }
  std::ifstream stream(data, std::ios::binary);
  stream.seekg(static_cast<std::streamoff>(offset));
  const std::uint64_t inflated = inflated_size(stream, limit, shown, "the compressed voxel data");
  check_length(shown, p, inflated, "the compressed data decompress to what");
}

// ----- NIfTI --------------------------------------------------------------------------------------

template <typename T>
T get(const std::vector<unsigned char>& b, std::size_t at, bool swap) {
  std::array<unsigned char, sizeof(T)> bytes{};
  std::memcpy(bytes.data(), b.data() + at, sizeof(T));
  if (swap) std::reverse(bytes.begin(), bytes.end());
  return std::bit_cast<T>(bytes);
}

// Reads `n` bytes of the (possibly gzipped) file into `out`; returns how many it got.
std::size_t read_start(const fs::path& path, bool gz, std::size_t n, std::vector<unsigned char>& out) {
  out.assign(n, 0);
  if (!gz) {
    std::ifstream in(path, std::ios::binary);
    in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(n));
    return static_cast<std::size_t>(in.gcount());
  }
  gzFile f = gzopen(path.c_str(), "rb");
  if (f == nullptr) return 0;
  const int got = gzread(f, out.data(), static_cast<unsigned>(n));
  gzclose(f);
  return got > 0 ? static_cast<std::size_t>(got) : 0;
}

void check_sform(const std::string& shown, const Eigen::Matrix3d& m) {
  for (int c = 0; c < 3; ++c) {
    if (!(m.col(c).norm() > 0.0) || !m.col(c).allFinite()) {
      fail(shown, "the NIfTI sform matrix is singular (axis " + std::to_string(c + 1) +
                      " is zero or not finite): the voxel grid has no 3-D geometry");
    }
  }
  const Eigen::Matrix3d unit = m.colwise().normalized();
  if (std::abs(unit.determinant()) < 1e-6) {
    fail(shown, "the NIfTI sform matrix is singular (its axes do not span 3-D space)");
  }
  for (int a = 0; a < 3; ++a) {
    for (int b = a + 1; b < 3; ++b) {
      const double cosine = unit.col(a).dot(unit.col(b));
      if (std::abs(cosine) > 1e-3) {
        std::ostringstream msg;
        msg.precision(3);
        msg << "the NIfTI sform matrix is sheared: voxel axes " << a + 1 << " and " << b + 1 << " meet at "
            << std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / 3.14159265358979
            << " degrees, not 90 (a gantry tilt?); "
            << "ITK would make them orthogonal and misplace every slice: resample the volume onto an orthogonal grid "
               "first";
        fail(shown, msg.str());
      }
    }
  }
}

void check_nifti(const fs::path& path, const std::string& shown, bool gz) {
  std::vector<unsigned char> h;
  const std::size_t got = read_start(path, gz, 540, h);
  if (got < 348) {
    fail(shown, "shorter than a NIfTI header: " + describe_bytes(got) + (gz ? " after decompression" : "") +
                    " (truncated file?)");
  }
  const auto le = get<std::int32_t>(h, 0, false);
  const auto be = get<std::int32_t>(h, 0, true);
  bool swap = false;
  int version = 0;
  if (le == 348 || le == 540) {
    version = le == 348 ? 1 : 2;
  } else if (be == 348 || be == 540) {
    version = be == 348 ? 1 : 2;
    swap = true;
  } else {
    return;  // not NIfTI: ITK decides what it is
  }
  if (version == 2 && got < 540) fail(shown, "shorter than a NIfTI-2 header (truncated file?)");
  Promise p;
  std::uint64_t offset = 0;
  int sform_code = 0;
  Eigen::Matrix3d sform;
  if (version == 1) {
    const auto ndim = get<std::int16_t>(h, 40, swap);
    if (ndim < 1 || ndim > 7) return;
    for (int d = 1; d <= ndim; ++d)
      p.sizes.push_back(static_cast<std::uint64_t>(std::max<std::int16_t>(get<std::int16_t>(h, 40 + 2 * d, swap), 1)));
    const auto bitpix = get<std::int16_t>(h, 72, swap);
    p.voxel_bytes = bitpix > 0 && bitpix % 8 == 0 ? static_cast<std::uint64_t>(bitpix / 8) : 0;
    const auto vox_offset = get<float>(h, 108, swap);
    offset = vox_offset > 0.0f && std::isfinite(vox_offset) ? static_cast<std::uint64_t>(vox_offset) : 352;
    sform_code = get<std::int16_t>(h, 254, swap);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) sform(r, c) = get<float>(h, 280 + 16 * r + 4 * c, swap);
    }
  } else {
    const auto ndim = get<std::int64_t>(h, 16, swap);
    if (ndim < 1 || ndim > 7) return;
    for (int d = 1; d <= ndim; ++d) {
      p.sizes.push_back(static_cast<std::uint64_t>(std::max<std::int64_t>(get<std::int64_t>(h, 16 + 8 * d, swap), 1)));
    }
    const auto bitpix = get<std::int16_t>(h, 14, swap);
    p.voxel_bytes = bitpix > 0 && bitpix % 8 == 0 ? static_cast<std::uint64_t>(bitpix / 8) : 0;
    offset = static_cast<std::uint64_t>(std::max<std::int64_t>(get<std::int64_t>(h, 168, swap), 0));
    sform_code = get<std::int32_t>(h, 348, swap);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) sform(r, c) = get<double>(h, 400 + 32 * r + 8 * c, swap);
    }
  }
  // Only a single-file NIfTI carries its data here; a header of a .hdr/.img pair has none.
  const std::string magic(reinterpret_cast<const char*>(h.data()) + (version == 1 ? 344 : 4), 3);
  if (magic != "n+1" && magic != "n+2") return;
  if (sform_code > 0) check_sform(shown, sform);
  std::uint64_t total = 0;
  if (gz) {
    std::ifstream in(path, std::ios::binary);
    total = inflated_size(in, file_size(path, shown), shown, "the gzip-compressed data");
  } else {
    total = file_size(path, shown);
  }
  const std::uint64_t available = total > offset ? total - offset : 0;
  check_length(shown, p, available, gz ? "the decompressed file" : "the file");
}

// ----- NRRD ---------------------------------------------------------------------------------------

std::uint64_t nrrd_type_size(const std::string& type) {
  static const std::map<std::string, std::uint64_t> sizes = {
      {"signed char", 1}, {"int8", 1}, {"int8_t", 1}, {"uchar", 1}, {"unsigned char", 1}, {"uint8", 1},
      {"uint8_t", 1}, {"short", 2}, {"short int", 2}, {"signed short", 2}, {"signed short int", 2}, {"int16", 2},
      {"int16_t", 2}, {"ushort", 2}, {"unsigned short", 2}, {"unsigned short int", 2}, {"uint16", 2},
      {"uint16_t", 2}, {"int", 4}, {"signed int", 4}, {"int32", 4}, {"int32_t", 4}, {"uint", 4},
      {"unsigned int", 4}, {"uint32", 4}, {"uint32_t", 4}, {"longlong", 8}, {"long long", 8},
      {"long long int", 8}, {"signed long long", 8}, {"signed long long int", 8}, {"int64", 8}, {"int64_t", 8},
      {"ulonglong", 8}, {"unsigned long long", 8}, {"unsigned long long int", 8}, {"uint64", 8}, {"uint64_t", 8},
      {"float", 4}, {"double", 8}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

void check_nrrd(const fs::path& path, const std::string& shown) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  if (!std::getline(in, line) || line.rfind("NRRD", 0) != 0) return;
  std::map<std::string, std::string> fields;
  bool blank = false;
  for (int lines = 0; lines < 500 && std::getline(in, line); ++lines) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) {
      blank = true;
      break;
    }
    if (line[0] == '#') continue;
    const auto colon = line.find(": ");
    if (colon == std::string::npos) continue;  // "key:=value" pairs and the like
    fields[lower(trim(line.substr(0, colon)))] = trim(line.substr(colon + 2));
  }
  Promise p;
  {
    std::istringstream sizes(fields["sizes"]);
    for (std::uint64_t s = 0; sizes >> s;) p.sizes.push_back(s);
    if (p.sizes.empty()) return;
  }
  p.voxel_bytes = nrrd_type_size(lower(fields["type"]));
  if (fields.count("byte skip") || fields.count("byteskip") || fields.count("line skip") || fields.count("lineskip"))
    return;
  const std::string encoding = lower(fields["encoding"]);
  const bool gzip = encoding == "gzip" || encoding == "gz";
  if (encoding != "raw" && !gzip) return;
  fs::path data = path;
  std::uint64_t offset = 0;
  std::string file = fields.count("data file") ? fields["data file"] : fields["datafile"];
  if (!file.empty()) {
    if (file.find(' ') != std::string::npos || file.find('%') != std::string::npos || file == "LIST") return;
    data = fs::path(file).is_absolute() ? fs::path(file) : path.parent_path() / file;
    if (!fs::exists(data)) fail(shown, "its data file '" + data.string() + "' does not exist");
  } else {
    if (!blank) fail(shown, "the NRRD header does not end (no blank line before the data; truncated file?)");
    offset = static_cast<std::uint64_t>(in.tellg());
  }
  const std::uint64_t size = file_size(data, shown);
  const std::uint64_t available = size > offset ? size - offset : 0;
  const std::string where = data == path ? "the file" : "its data file '" + data.filename().string() + "'";
  if (!gzip) {
    check_length(shown, p, available, where);
    return;
  }
  std::ifstream stream(data, std::ios::binary);
  stream.seekg(static_cast<std::streamoff>(offset));
  check_length(shown, p, inflated_size(stream, available, shown, "the compressed voxel data"),
               "the compressed data decompress to what");
}

}  // namespace

void check_volume_file(const fs::path& path, const std::string& shown) {
  const std::string name = lower(path.filename().string());
  if (ends_with(name, ".mha") || ends_with(name, ".mhd")) {
    check_metaimage(path, shown);
  } else if (ends_with(name, ".nii.gz")) {
    check_nifti(path, shown, true);
  } else if (ends_with(name, ".nii")) {
    check_nifti(path, shown, false);
  } else if (ends_with(name, ".nrrd") || ends_with(name, ".nhdr")) {
    check_nrrd(path, shown);
  }
}

}  // namespace contourmesh::detail
