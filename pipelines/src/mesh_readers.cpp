// SPDX-License-Identifier: BSD-3-Clause
#include "mesh_readers.h"

#include <contourmesh/smooth/errors.h>

#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace contourmesh::detail {

namespace {

// Printable, bounded excerpt of file text for messages.
std::string quote(std::string_view text) {
  std::string out;
  for (char c : text.substr(0, 40)) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  if (text.size() > 40) out += "...";
  return "'" + out + "'";
}

std::string vertex_limit_message(Index max_vertices) {
  return "more than the limit of " + std::to_string(max_vertices) + " vertices";
}

// Merges bit-identical float corners (with -0 == +0) into shared vertices.
class CornerMerger {
 public:
  explicit CornerMerger(Index max_vertices) : max_vertices_(max_vertices) {}

  Index add(const std::array<float, 3>& p) {
    Key key{};
    for (int k = 0; k < 3; ++k) key[k] = std::bit_cast<std::uint32_t>(p[k] == 0.0f ? 0.0f : p[k]);
    const auto [it, inserted] = index_.try_emplace(key, static_cast<Index>(xyz_.size() / 3));
    if (inserted) {
      if (it->second >= max_vertices_) throw LimitError("the STL has " + vertex_limit_message(max_vertices_));
      for (int k = 0; k < 3; ++k) xyz_.push_back(p[k]);
    }
    return it->second;
  }

  Mesh finish(std::vector<Triangle> triangles) {
    Mesh mesh;
    const auto n = static_cast<Index>(xyz_.size() / 3);
    mesh.positions.resize(3, n);
    for (Index i = 0; i < n; ++i) {
      for (int k = 0; k < 3; ++k) mesh.positions(k, i) = xyz_[3 * static_cast<std::size_t>(i) + k];
    }
    mesh.triangles = std::move(triangles);
    return mesh;
  }

 private:
  using Key = std::array<std::uint32_t, 3>;
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = 1469598103934665603ull;
      for (std::uint32_t v : k) h = (h ^ v) * 1099511628211ull;
      return static_cast<std::size_t>(h ^ (h >> 29));
    }
  };
  Index max_vertices_;
  std::unordered_map<Key, Index, KeyHash> index_;
  std::vector<float> xyz_;
};

std::string format_point(const std::array<float, 3>& p) {
  std::ostringstream out;
  out << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return out.str();
}

float read_le_float(const char* at) {
  std::uint32_t bits = 0;
  for (int b = 3; b >= 0; --b) bits = (bits << 8) | static_cast<unsigned char>(at[b]);
  return std::bit_cast<float>(bits);
}

Mesh read_binary_stl(const std::string& bytes, Index max_vertices) {
  const std::size_t size = bytes.size();
  if (size < 84) {
    throw InvalidInputError("truncated binary STL: " + std::to_string(size) +
                            " bytes, less than the 84-byte header");
  }
  std::uint32_t count = 0;
  for (int b = 3; b >= 0; --b) count = (count << 8) | static_cast<unsigned char>(bytes[80 + b]);
  const std::size_t whole = (size - 84) / 50;
  const std::size_t rest = (size - 84) % 50;
  if (count > whole) {
    throw InvalidInputError("truncated or corrupt binary STL: the header announces " + std::to_string(count) +
                            " triangles (" + std::to_string(84 + 50 * static_cast<std::uint64_t>(count)) +
                            " bytes) but the file has " + std::to_string(size) + " bytes, " + std::to_string(whole) +
                            " whole triangles");
  }
  if (rest != 0) {
    throw InvalidInputError("not a valid binary STL: " + std::to_string(size) +
                            " bytes is not 84 + 50 x triangles (truncated, trailing data, or not an STL file)");
  }
  // A count of zero or below the data is common (exporters that never fill it in): read all.
  const std::size_t triangles = whole;
  CornerMerger merger(max_vertices);
  std::vector<Triangle> tris;
  tris.reserve(triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    const char* facet = bytes.data() + 84 + 50 * t + 12;  // skip the normal
    Triangle tri{};
    for (int c = 0; c < 3; ++c) {
      const std::array<float, 3> p = {read_le_float(facet + 12 * c), read_le_float(facet + 12 * c + 4),
                                      read_le_float(facet + 12 * c + 8)};
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
        throw InvalidInputError("triangle " + std::to_string(t) + ", corner " + std::to_string(c) +
                                " has a non-finite coordinate " + format_point(p));
      }
      tri[c] = merger.add(p);
    }
    tris.push_back(tri);
  }
  return merger.finish(std::move(tris));
}

// Splits text into lines, keeping 1-based line numbers.
class LineReader {
 public:
  explicit LineReader(const std::string& text) : text_(text) {}
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    const std::size_t end = text_.find('\n', pos_);
    const std::size_t stop = end == std::string::npos ? text_.size() : end;
    line = std::string_view(text_).substr(pos_, stop - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = end == std::string::npos ? text_.size() : end + 1;
    ++number_;
    return true;
  }
  [[nodiscard]] std::size_t number() const { return number_; }

 private:
  const std::string& text_;
  std::size_t pos_ = 0;
  std::size_t number_ = 0;
};

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

std::string lower(std::string_view word) {
  std::string out(word);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Parses a whole word as a number; false when it is not one.
bool parse_number(std::string_view word, double& value) {
  const std::string text(word);
  char* end = nullptr;
  errno = 0;
  value = std::strtod(text.c_str(), &end);
  return end != text.c_str() && *end == '\0';
}

std::string at_line(std::size_t line) { return "line " + std::to_string(line) + ": "; }

Mesh read_ascii_stl(const std::string& text, Index max_vertices) {
  enum class State { Solid, Facet, Loop, Vertex, EndLoop, EndFacet };
  const char* expected[] = {"solid", "facet", "outer loop", "vertex", "endloop", "endfacet"};
  State state = State::Solid;
  bool any_solid = false;
  int corner = 0;
  Triangle tri{};
  std::vector<Triangle> tris;
  CornerMerger merger(max_vertices);
  LineReader lines(text);
  std::string_view line;
  while (lines.next(line)) {
    const auto words = split(line);
    if (words.empty()) continue;
    const std::string key = lower(words[0]);
    const std::string where = at_line(lines.number());
    auto unexpected = [&]() {
      return InvalidInputError(where + "expected '" + expected[static_cast<int>(state)] + "', found " + quote(line));
    };
    switch (state) {
      case State::Solid:
        if (key != "solid") throw unexpected();
        any_solid = true;
        state = State::Facet;
        break;
      case State::Facet:
        if (key == "endsolid") state = State::Solid;
        else if (key == "facet") state = State::Loop;
        else if (key != "color") throw unexpected();
        break;
      case State::Loop:
        if (key != "outer") throw unexpected();
        state = State::Vertex;
        break;
      case State::Vertex: {
        if (key != "vertex") throw unexpected();
        if (words.size() < 4) throw InvalidInputError(where + "a vertex needs three coordinates: " + quote(line));
        std::array<float, 3> p{};
        for (int k = 0; k < 3; ++k) {
          double v = 0.0;
          if (!parse_number(words[1 + k], v)) throw InvalidInputError(where + quote(words[1 + k]) + " is not a number");
          if (!std::isfinite(v) || !std::isfinite(static_cast<float>(v))) {
            throw InvalidInputError(where + "triangle " + std::to_string(tris.size()) + ", corner " +
                                    std::to_string(corner) + " has a non-finite coordinate " + quote(words[1 + k]));
          }
          p[k] = static_cast<float>(v);
        }
        tri[corner++] = merger.add(p);
        if (corner == 3) {
          tris.push_back(tri);
          corner = 0;
          state = State::EndLoop;
        }
        break;
      }
      case State::EndLoop:
        if (key != "endloop") throw unexpected();
        state = State::EndFacet;
        break;
      case State::EndFacet:
        if (key != "endfacet") throw unexpected();
        state = State::Facet;
        break;
    }
  }
  if (!any_solid) throw InvalidInputError("an ASCII STL without a 'solid' line");
  if (state != State::Solid) {
    throw InvalidInputError("the ASCII STL ends inside a solid after line " + std::to_string(lines.number()) +
                            ", while expecting '" + expected[static_cast<int>(state)] +
                            (state == State::Facet ? "' or 'endsolid'" : "'") + " (truncated file?)");
  }
  return merger.finish(std::move(tris));
}

bool starts_with_solid(const std::string& bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && i < 256 && std::isspace(static_cast<unsigned char>(bytes[i]))) ++i;
  return bytes.size() - i >= 5 && lower(std::string_view(bytes).substr(i, 5)) == "solid";
}

}  // namespace

Mesh read_stl(const std::string& bytes, Index max_vertices) {
  bool binary = !starts_with_solid(bytes);
  if (!binary && bytes.size() >= 84) {
    // Binary files may start with "solid" too; their size then matches the header's count.
    std::uint32_t count = 0;
    for (int b = 3; b >= 0; --b) count = (count << 8) | static_cast<unsigned char>(bytes[80 + b]);
    binary = bytes.size() == 84 + 50 * static_cast<std::uint64_t>(count);
  }
  return binary ? read_binary_stl(bytes, max_vertices) : read_ascii_stl(bytes, max_vertices);
}

Mesh read_obj(const std::string& text, Index max_vertices) {
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos) {
    throw InvalidInputError("binary data (a NUL byte at offset " + std::to_string(nul) + "): not a text OBJ file");
  }
  std::vector<double> xyz;
  struct Face {
    std::vector<long long> corners;  // 0-based, unchecked
    std::size_t line;
  };
  std::vector<Face> faces;
  LineReader lines(text);
  std::string_view line;
  while (lines.next(line)) {
    const auto words = split(line);
    if (words.empty() || words[0].front() == '#') continue;
    const std::string where = at_line(lines.number());
    if (words[0] == "v") {
      if (words.size() < 4) throw InvalidInputError(where + "a vertex needs three coordinates: " + quote(line));
      const std::size_t vertex = xyz.size() / 3 + 1;
      if (vertex > static_cast<std::size_t>(max_vertices)) {
        throw LimitError("the OBJ has " + vertex_limit_message(max_vertices));
      }
      for (int k = 1; k <= 3; ++k) {
        double v = 0.0;
        if (!parse_number(words[k], v)) throw InvalidInputError(where + quote(words[k]) + " is not a number");
        if (!std::isfinite(v)) {
          throw InvalidInputError(where + "vertex " + std::to_string(vertex) + " has a non-finite coordinate " +
                                  quote(words[k]));
        }
        xyz.push_back(v);
      }
    } else if (words[0] == "f") {
      if (words.size() < 4) throw InvalidInputError(where + "a face needs at least three corners: " + quote(line));
      Face face{{}, lines.number()};
      const auto vertices = static_cast<long long>(xyz.size() / 3);
      for (std::size_t k = 1; k < words.size(); ++k) {
        const std::string_view corner = words[k].substr(0, words[k].find('/'));
        const std::string number(corner);
        char* end = nullptr;
        const long long index = std::strtoll(number.c_str(), &end, 10);
        if (number.empty() || *end != '\0') {
          throw InvalidInputError(where + "face corner " + quote(words[k]) + " does not start with a vertex index");
        }
        if (index == 0) throw InvalidInputError(where + "vertex index 0 (OBJ indices start at 1)");
        face.corners.push_back(index > 0 ? index - 1 : vertices + index);  // negative: relative to the end
      }
      faces.push_back(std::move(face));
    }
  }
  Mesh mesh;
  const auto n = static_cast<Index>(xyz.size() / 3);
  mesh.positions = Eigen::Map<const Eigen::Matrix3Xd>(xyz.data(), 3, n);
  for (const Face& face : faces) {
    for (long long c : face.corners) {
      if (c < 0 || c >= n) {
        throw InvalidInputError(at_line(face.line) + "triangle " + std::to_string(mesh.triangles.size()) +
                                " references vertex " + std::to_string(c + 1) + " but the file has " +
                                std::to_string(n) + " vertices");
      }
    }
    for (std::size_t c = 1; c + 1 < face.corners.size(); ++c) {
      mesh.triangles.push_back({static_cast<Index>(face.corners[0]), static_cast<Index>(face.corners[c]),
                                static_cast<Index>(face.corners[c + 1])});
    }
  }
  return mesh;
}

}  // namespace contourmesh::detail
