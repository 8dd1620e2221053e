// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/vtk/ply_io.h"

#include <contourmesh/smooth/errors.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace contourmesh {

namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

PlyType parse_type(const std::string& name) {
  if (name == "char" || name == "int8") return PlyType::Int8;
  if (name == "uchar" || name == "uint8") return PlyType::UInt8;
  if (name == "short" || name == "int16") return PlyType::Int16;
  if (name == "ushort" || name == "uint16") return PlyType::UInt16;
  if (name == "int" || name == "int32") return PlyType::Int32;
  if (name == "uint" || name == "uint32") return PlyType::UInt32;
  if (name == "float" || name == "float32") return PlyType::Float32;
  if (name == "double" || name == "float64") return PlyType::Float64;
  throw InvalidInputError("PLY header: unknown property type '" + name + "'");
}

int type_size(PlyType t) {
  switch (t) {
    case PlyType::Int8: case PlyType::UInt8: return 1;
    case PlyType::Int16: case PlyType::UInt16: return 2;
    case PlyType::Int32: case PlyType::UInt32: case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 0;
}

struct Property {
  std::string name;
  PlyType type = PlyType::Float32;
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

enum class Encoding { Ascii, BinaryLE, BinaryBE };

class ValueReader {
 public:
  ValueReader(std::istream& in, Encoding enc) : in_(in), enc_(enc) {}

  // Reads one value of type t; false at end of data.
  bool read(PlyType t, double& value) {
    if (enc_ == Encoding::Ascii) {
      if (!(in_ >> token_)) return false;
      char* end = nullptr;
      value = std::strtod(token_.c_str(), &end);
      if (end == token_.c_str() || *end != '\0') throw InvalidInputError("PLY data: '" + token_ + "' is not a number");
      return true;
    }
    unsigned char buf[8];
    const int size = type_size(t);
    if (!in_.read(reinterpret_cast<char*>(buf), size)) return false;
    const bool swap = (enc_ == Encoding::BinaryBE) == (std::endian::native == std::endian::little);
    if (swap) {
      for (int a = 0, b = size - 1; a < b; ++a, --b) std::swap(buf[a], buf[b]);
    }
    switch (t) {
      case PlyType::Int8: { std::int8_t v; std::memcpy(&v, buf, 1); value = v; break; }
      case PlyType::UInt8: value = buf[0]; break;
      case PlyType::Int16: { std::int16_t v; std::memcpy(&v, buf, 2); value = v; break; }
      case PlyType::UInt16: { std::uint16_t v; std::memcpy(&v, buf, 2); value = v; break; }
      case PlyType::Int32: { std::int32_t v; std::memcpy(&v, buf, 4); value = v; break; }
      case PlyType::UInt32: { std::uint32_t v; std::memcpy(&v, buf, 4); value = v; break; }
      case PlyType::Float32: { float v; std::memcpy(&v, buf, 4); value = v; break; }
      case PlyType::Float64: { double v; std::memcpy(&v, buf, 8); value = v; break; }
    }
    return true;
  }

 private:
  std::istream& in_;
  Encoding enc_;
  std::string token_;
};

std::string element_at(const Element& e, std::uint64_t k) {
  return "element '" + e.name + "' #" + std::to_string(k);
}

// A contour id read as a double (any property type, or ASCII text): must be a 32-bit integer, since
// converting anything else to int is undefined.
std::int32_t to_id(double value, const std::string& name, std::uint64_t vertex) {
  if (!(value >= std::numeric_limits<std::int32_t>::min() && value <= std::numeric_limits<std::int32_t>::max()) ||
      value != std::floor(value)) {
    std::ostringstream msg;
    msg << "PLY: vertex " << vertex << " has " << name << " = " << value << ", not a 32-bit integer";
    throw InvalidInputError(msg.str());
  }
  return static_cast<std::int32_t>(value);
}

}  // namespace

Mesh read_ply(std::istream& in, const ContourIdArrayNames& arrays, Index max_vertices) {
  std::string line;
  if (!std::getline(in, line) || line.substr(0, 3) != "ply") throw InvalidInputError("not a PLY file (no 'ply' magic)");
  Encoding enc = Encoding::Ascii;
  bool have_format = false;
  std::vector<Element> elements;
  bool header_done = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key.empty() || key == "comment" || key == "obj_info") continue;
    if (key == "end_header") {
      header_done = true;
      break;
    }
    if (key == "format") {
      std::string f;
      words >> f;
      if (f == "ascii") enc = Encoding::Ascii;
      else if (f == "binary_little_endian") enc = Encoding::BinaryLE;
      else if (f == "binary_big_endian") enc = Encoding::BinaryBE;
      else throw InvalidInputError("PLY header: unknown format '" + f + "'");
      have_format = true;
    } else if (key == "element") {
      Element e;
      long long count = -1;
      words >> e.name >> count;
      if (e.name.empty() || count < 0) throw InvalidInputError("PLY header: malformed line '" + line + "'");
      e.count = static_cast<std::uint64_t>(count);
      elements.push_back(std::move(e));
    } else if (key == "property") {
      if (elements.empty()) throw InvalidInputError("PLY header: property before any element");
      Property p;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type >> p.name;
        p.is_list = true;
        p.count_type = parse_type(count_type);
        p.type = parse_type(item_type);
      } else {
        p.type = parse_type(type);
        words >> p.name;
      }
      if (p.name.empty()) throw InvalidInputError("PLY header: malformed line '" + line + "'");
      elements.back().properties.push_back(p);
    } else {
      throw InvalidInputError("PLY header: unexpected line '" + line + "'");
    }
  }
  if (!header_done) throw InvalidInputError("PLY header: no end_header line (truncated file?)");
  if (!have_format) throw InvalidInputError("PLY header: no format line");

  Mesh mesh;
  std::vector<double> xyz;
  std::vector<std::int32_t> slice, contour;
  bool have_vertices = false;
  std::vector<std::uint64_t> face_of;  // the face element each triangle came from
  ValueReader reader(in, enc);
  std::vector<double> row;
  for (const Element& e : elements) {
    const bool is_vertex = e.name == "vertex";
    const bool is_face = e.name == "face";
    int ix = -1, iy = -1, iz = -1, islice = -1, icontour = -1, iface = -1;
    for (int p = 0; p < static_cast<int>(e.properties.size()); ++p) {
      const std::string& n = e.properties[p].name;
      if (is_vertex && !e.properties[p].is_list) {
        if (n == "x") ix = p;
        if (n == "y") iy = p;
        if (n == "z") iz = p;
        if (n == arrays.slice) islice = p;
        if (n == arrays.contour) icontour = p;
      }
      if (is_face && e.properties[p].is_list && (n == "vertex_indices" || n == "vertex_index")) iface = p;
    }
    if (is_vertex) {
      if (ix < 0 || iy < 0 || iz < 0) throw InvalidInputError("PLY: vertex element lacks x, y or z");
      // A second one would number its vertices after the first's, with or without ids: nobody writes that.
      if (have_vertices) throw InvalidInputError("PLY: more than one vertex element");
      have_vertices = true;
      if (e.count > static_cast<std::uint64_t>(max_vertices)) {
        throw LimitError("PLY: the header announces " + std::to_string(e.count) + " vertices, more than the limit of " +
                         std::to_string(max_vertices));
      }
    }
    if (is_face && iface < 0) throw InvalidInputError("PLY: face element has no vertex_indices list");
    const bool ids = is_vertex && islice >= 0 && icontour >= 0;
    std::vector<Index> corners;
    // An element without properties has no data, whatever its count (which may be 2^63: no loop).
    const std::uint64_t rows = e.properties.empty() ? 0 : e.count;
    for (std::uint64_t k = 0; k < rows; ++k) {
      row.assign(e.properties.size(), 0.0);
      for (int p = 0; p < static_cast<int>(e.properties.size()); ++p) {
        const Property& prop = e.properties[p];
        if (!prop.is_list) {
          if (!reader.read(prop.type, row[p])) throw InvalidInputError("PLY: data ends inside " + element_at(e, k));
          continue;
        }
        double count = 0;
        if (!reader.read(prop.count_type, count)) throw InvalidInputError("PLY: data ends inside " + element_at(e, k));
        if (!(count >= 0 && count <= 1e6) || count != std::floor(count)) {  // NaN included
          throw InvalidInputError("PLY: bad list length " + std::to_string(count) + " in " + element_at(e, k));
        }
        if (p == iface) corners.clear();
        for (long long c = 0; c < static_cast<long long>(count); ++c) {
          double v = 0;
          if (!reader.read(prop.type, v)) throw InvalidInputError("PLY: data ends inside " + element_at(e, k));
          if (p == iface) corners.push_back(static_cast<Index>(std::max(-1.0, std::min(v, 2147483647.0))));
        }
      }
      if (is_vertex) {
        if (!std::isfinite(row[ix]) || !std::isfinite(row[iy]) || !std::isfinite(row[iz])) {
          std::ostringstream msg;
          msg << "PLY: vertex " << k << " has a non-finite coordinate (" << row[ix] << ", " << row[iy] << ", "
              << row[iz] << ")";
          throw InvalidInputError(msg.str());
        }
        xyz.push_back(row[ix]);
        xyz.push_back(row[iy]);
        xyz.push_back(row[iz]);
        if (ids) {
          slice.push_back(to_id(row[islice], arrays.slice, k));
          contour.push_back(to_id(row[icontour], arrays.contour, k));
        }
      } else if (is_face && corners.size() >= 3) {
        for (std::size_t c = 1; c + 1 < corners.size(); ++c) {
          mesh.triangles.push_back({corners[0], corners[c], corners[c + 1]});
          face_of.push_back(k);
        }
      }
    }
  }
  if (!have_vertices) throw InvalidInputError("PLY: no vertex element");
  const auto n = static_cast<Index>(xyz.size() / 3);
  mesh.positions = Eigen::Map<const Eigen::Matrix3Xd>(xyz.data(), 3, n);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (Index v : mesh.triangles[f]) {
      if (v < 0 || v >= n) {
        throw InvalidInputError("PLY: triangle " + std::to_string(f) + " (face " + std::to_string(face_of[f]) +
                                ") references vertex " + std::to_string(v) + " but the file has " +
                                std::to_string(n) + " vertices");
      }
    }
  }
  mesh.slice_ids = std::move(slice);
  mesh.contour_ids = std::move(contour);
  return mesh;
}

namespace {

template <typename T>
void put(std::ostream& out, T value) {
  unsigned char buf[sizeof(T)];
  std::memcpy(buf, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) {
    for (std::size_t a = 0, b = sizeof(T) - 1; a < b; ++a, --b) std::swap(buf[a], buf[b]);
  }
  out.write(reinterpret_cast<const char*>(buf), sizeof(T));
}

}  // namespace

void write_ply(std::ostream& out, const Mesh& mesh, const ContourIdArrayNames& arrays,
               const std::vector<PointScalars>& extra) {
  const bool ids = mesh.has_contour_ids();
  for (const PointScalars& scalars : extra) {
    if (scalars.values.size() != static_cast<std::size_t>(mesh.num_vertices())) {
      throw InvalidInputError("point array '" + scalars.name + "' has " + std::to_string(scalars.values.size()) +
                              " values for " + std::to_string(mesh.num_vertices()) + " vertices");
    }
  }
  out << "ply\nformat binary_little_endian 1.0\ncomment written by ContourMesh\ncomment " << kCoordinateSystemTag
      << "\n";
  out << "element vertex " << mesh.num_vertices() << "\n";
  out << "property double x\nproperty double y\nproperty double z\n";
  if (ids) out << "property int " << arrays.slice << "\nproperty int " << arrays.contour << "\n";
  for (const PointScalars& scalars : extra) {
    out << "property " << (scalars.type == ScalarType::Int32 ? "int " : "double ") << scalars.name << "\n";
  }
  out << "element face " << mesh.num_faces() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    put(out, mesh.positions(0, i));
    put(out, mesh.positions(1, i));
    put(out, mesh.positions(2, i));
    if (ids) {
      put(out, mesh.slice_ids[i]);
      put(out, mesh.contour_ids[i]);
    }
    for (const PointScalars& scalars : extra) {
      if (scalars.type == ScalarType::Int32) put(out, static_cast<std::int32_t>(scalars.values[i]));
      else put(out, scalars.values[i]);
    }
  }
  for (const Triangle& t : mesh.triangles) {
    put<std::uint8_t>(out, 3);
    for (Index v : t) put<std::int32_t>(out, v);
  }
}

}  // namespace contourmesh
