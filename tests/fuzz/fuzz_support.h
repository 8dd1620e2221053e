// SPDX-License-Identifier: BSD-3-Clause
// Helpers shared by the fuzz targets (tests/fuzz, docs/robustness.md): a reader that turns fuzz bytes
// into bounded numbers, the failure report, a scratch file for the file readers, and the mesh checks
// every target applies to what the library returns.
#pragma once

#include <contourmesh/smooth/mesh.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <string_view>
#include <unistd.h>
#include <utility>

namespace contourmesh::fuzz {

/// A broken promise of the library (not a rejected input): printed, then abort() so that libFuzzer
/// (or the replay test) reports the input.
[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "contourmesh fuzz: contract violated: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

/// CONTOURMESH_FUZZ_VERBOSE=1 makes the targets say what they did with each input (to check seeds).
inline bool verbose() {
  static const bool on = std::getenv("CONTOURMESH_FUZZ_VERBOSE") != nullptr;
  return on;
}

/// Consumes fuzz bytes from the front. Past the end every read returns its lowest value, so short
/// inputs decode to small, simple cases.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  [[nodiscard]] bool empty() const { return pos_ >= size_; }
  [[nodiscard]] std::size_t remaining() const { return empty() ? 0 : size_ - pos_; }

  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  bool flag() { return (byte() & 1) != 0; }

  /// An integer in [lo, hi] (one byte, two when the range needs them).
  int integer(int lo, int hi) {
    if (hi <= lo) return lo;
    const auto span = static_cast<std::uint32_t>(hi - lo) + 1;
    std::uint32_t v = byte();
    if (span > 256) v = (v << 8) | byte();
    return lo + static_cast<int>(v % span);
  }

  /// A number in [0, 1] (two bytes).
  double unit() {
    const std::uint32_t v = (static_cast<std::uint32_t>(byte()) << 8) | byte();
    return v / 65535.0;
  }
  /// A number in [lo, hi].
  double real(double lo, double hi) { return lo + (hi - lo) * unit(); }
  /// A number in [-1, 1] that is exactly 0 past the end.
  double symmetric() { return empty() ? 0.0 : 2.0 * unit() - 1.0; }

  /// Points with coordinates in [lo, hi], read x first (never several reads in one argument list or
  /// parenthesised initialiser: their order is unspecified, and gcc and clang must decode alike).
  Eigen::Vector2d vec2(double lo, double hi) {
    const double x = real(lo, hi);
    const double y = real(lo, hi);
    return {x, y};
  }
  Eigen::Vector3d vec3(double lo, double hi) {
    const double x = real(lo, hi);
    const double y = real(lo, hi);
    const double z = real(lo, hi);
    return {x, y, z};
  }
  /// A vector with coordinates in [-1, 1], zero past the end.
  Eigen::Vector3d symmetric3() {
    const double x = symmetric();
    const double y = symmetric();
    const double z = symmetric();
    return {x, y, z};
  }

  /// Eight bytes as a double bit pattern: any value, NaN and infinities included.
  double raw_double() {
    std::uint64_t bits = 0;
    for (int k = 0; k < 8; ++k) bits = (bits << 8) | byte();
    double v = 0.0;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

/// A file in /dev/shm (memory, when the machine has it) or the temporary directory, named after this
/// process so parallel fuzz jobs do not share it, removed at exit. One per extension.
inline const std::filesystem::path& scratch_file(const std::string& extension) {
  struct Files {
    std::map<std::string, std::filesystem::path> paths;
    ~Files() {
      std::error_code ec;
      for (const auto& [ext, path] : paths) std::filesystem::remove(path, ec);
    }
  };
  static Files files;
  auto [it, inserted] = files.paths.try_emplace(extension);
  if (inserted) {
    std::error_code ec;
    std::filesystem::path dir = "/dev/shm";
    if (!std::filesystem::is_directory(dir, ec) || access(dir.c_str(), W_OK) != 0) {
      dir = std::filesystem::temp_directory_path();
    }
    it->second = dir / ("contourmesh_fuzz_" + std::to_string(getpid()) + extension);
  }
  return it->second;
}

inline void write_file(const std::filesystem::path& path, const std::uint8_t* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) fail("cannot write the scratch file " + path.string());
}

/// What every mesh the library hands back must satisfy: finite coordinates, triangle indices in range,
/// id arrays either absent or one entry per vertex.
inline void check_mesh_is_sane(const Mesh& mesh, std::string_view context) {
  const Index n = mesh.num_vertices();
  for (Index i = 0; i < n; ++i) {
    if (!mesh.positions.col(i).allFinite())
      fail(std::string(context) + ": vertex " + std::to_string(i) + " is not finite");
  }
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (Index v : mesh.triangles[f]) {
      if (v < 0 || v >= n) {
        fail(std::string(context) + ": triangle " + std::to_string(f) + " references vertex " + std::to_string(v) +
             " of " + std::to_string(n));
      }
    }
  }
  const bool no_ids = mesh.slice_ids.empty() && mesh.contour_ids.empty();
  if (!no_ids && !mesh.has_contour_ids()) fail(std::string(context) + ": id arrays of the wrong size");
}

/// A message of a typed exception: one line (the CLI prints it as one), not empty.
inline void check_message_is_one_line(std::string_view what, std::string_view context) {
  if (what.empty()) fail(std::string(context) + ": empty error message");
  if (what.find('\n') != std::string_view::npos) {
    fail(std::string(context) + ": error message spans several lines: " + std::string(what));
  }
}

}  // namespace contourmesh::fuzz
