// SPDX-License-Identifier: BSD-3-Clause
#include "mesh_writers.h"

#include "contourmesh/vtk/mesh_io.h"

#include <contourmesh/smooth/errors.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <system_error>

namespace contourmesh::detail {

namespace {

// A FILE* whose every write is checked; the error names what the system said.
class CheckedFile {
 public:
  explicit CheckedFile(const std::filesystem::path& path) : file_(std::fopen(path.c_str(), "wb")) {
    if (file_ == nullptr) fail(errno);
    buffer_.reserve(kFlushAt + 256);
  }
  ~CheckedFile() {
    if (file_ != nullptr) std::fclose(file_);
  }
  CheckedFile(const CheckedFile&) = delete;
  CheckedFile& operator=(const CheckedFile&) = delete;

  void put(std::string_view bytes) {
    buffer_.append(bytes);
    if (buffer_.size() >= kFlushAt) flush();
  }
  void put_number(double value) { put_chars(value); }
  void put_number(float value) { put_chars(value); }
  void put_number(long long value) { put_chars(value); }
  template <typename T>
  void put_binary(T value) {
    std::array<char, sizeof(T)> bytes{};
    std::memcpy(bytes.data(), &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) std::reverse(bytes.begin(), bytes.end());
    put(std::string_view(bytes.data(), bytes.size()));
  }

  // Writes what is buffered and closes the file; a failure of either throws.
  void close() {
    flush();
    std::FILE* f = file_;
    file_ = nullptr;
    if (std::fclose(f) != 0) fail(errno);
  }

 private:
  static constexpr std::size_t kFlushAt = 1 << 16;

  template <typename T>
  void put_chars(T value) {
    char text[64];
    const auto [end, ec] = std::to_chars(text, text + sizeof text, value);
    put(std::string_view(text, ec == std::errc{} ? static_cast<std::size_t>(end - text) : 0));
  }
  void flush() {
    if (buffer_.empty()) return;
    if (std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size()) fail(errno);
    buffer_.clear();
  }
  [[noreturn]] static void fail(int error) {
    throw InvalidInputError("cannot write: " + std::generic_category().message(error) + " (disk full?)");
  }

  std::FILE* file_;
  std::string buffer_;
};

std::array<float, 3> as_float(const Mesh& mesh, Index v) {
  std::array<float, 3> p{};
  for (int k = 0; k < 3; ++k) {
    const double x = mesh.positions(k, v);
    if (!(std::abs(x) <= static_cast<double>(std::numeric_limits<float>::max()))) {
      std::ostringstream msg;
      msg << "vertex " << v << " has coordinate " << x << ", beyond the range of the 32-bit floats that STL stores (+-"
          << std::numeric_limits<float>::max() << "): write .ply or .vtp, which store doubles";
      throw InvalidInputError(msg.str());
    }
    p[k] = static_cast<float>(x);
  }
  return p;
}

std::array<float, 3> facet_normal(const std::array<std::array<float, 3>, 3>& c) {
  const Eigen::Vector3d a(c[0][0], c[0][1], c[0][2]), b(c[1][0], c[1][1], c[1][2]), d(c[2][0], c[2][1], c[2][2]);
  Eigen::Vector3d n = (b - a).cross(d - a);
  const double length = n.norm();
  n = length > 0.0 && std::isfinite(length) ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
  return {static_cast<float>(n.x()), static_cast<float>(n.y()), static_cast<float>(n.z())};
}

}  // namespace

void write_stl(const std::filesystem::path& file, const Mesh& mesh, bool binary) {
  // Every coordinate is checked before the file is touched.
  std::vector<std::array<float, 3>> points(static_cast<std::size_t>(mesh.num_vertices()));
  for (Index v = 0; v < mesh.num_vertices(); ++v) points[v] = as_float(mesh, v);
  if (binary && mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidInputError("too many triangles for binary STL's 32-bit count");
  }
  CheckedFile out(file);
  if (binary) {
    std::string header = kStlHeader;  // carries SPACE=LPS, which 3D Slicer reads
    header.resize(80, ' ');
    out.put(header);
    out.put_binary(static_cast<std::uint32_t>(mesh.triangles.size()));
  } else {
    out.put(std::string("solid ") + kStlHeader + "\n");
  }
  for (const Triangle& t : mesh.triangles) {
    const std::array<std::array<float, 3>, 3> c = {points[t[0]], points[t[1]], points[t[2]]};
    const std::array<float, 3> n = facet_normal(c);
    if (binary) {
      for (float x : n) out.put_binary(x);
      for (const auto& p : c) {
        for (float x : p) out.put_binary(x);
      }
      out.put_binary(std::uint16_t{0});
      continue;
    }
    out.put(" facet normal ");
    for (int k = 0; k < 3; ++k) {
      out.put_number(n[k]);
      out.put(k < 2 ? " " : "\n  outer loop\n");
    }
    for (const auto& p : c) {
      out.put("   vertex ");
      for (int k = 0; k < 3; ++k) {
        out.put_number(p[k]);
        out.put(k < 2 ? " " : "\n");
      }
    }
    out.put("  endloop\n endfacet\n");
  }
  if (!binary) out.put(std::string("endsolid ") + kStlHeader + "\n");
  out.close();
}

void write_obj(const std::filesystem::path& file, const Mesh& mesh) {
  CheckedFile out(file);
  out.put("# written by ContourMesh\n");
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    out.put("v ");
    for (int k = 0; k < 3; ++k) {
      out.put_number(mesh.positions(k, v));
      out.put(k < 2 ? " " : "\n");
    }
  }
  for (const Triangle& t : mesh.triangles) {
    out.put("f ");
    for (int k = 0; k < 3; ++k) {
      out.put_number(static_cast<long long>(t[k]) + 1);
      out.put(k < 2 ? " " : "\n");
    }
  }
  out.close();
}

}  // namespace contourmesh::detail
