// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/vtk/contour_stack_io.h"

#include "contourmesh/vtk/atomic_file.h"

#include <contourmesh/smooth/errors.h>

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

namespace contourmesh {

namespace {

using json = nlohmann::json;

constexpr const char* kFormat = "contourmesh-contours";

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InvalidInputError(file_ + ": " + (where.empty() ? "" : where + ": ") + what);
  }

  double number(const json& j, const std::string& where) const {
    if (!j.is_number()) fail(where, "expected a number, got " + std::string(j.type_name()));
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(where, "not a finite number");
    return v;
  }

  Eigen::Vector3d vector3(const json& j, const std::string& where) const {
    if (!j.is_array() || j.size() != 3) fail(where, "expected an array of 3 numbers");
    return {number(j[0], where + "[0]"), number(j[1], where + "[1]"), number(j[2], where + "[2]")};
  }

  const json& member(const json& object, const char* key, const std::string& where) const {
    const auto it = object.find(key);
    if (it == object.end()) fail(where, std::string("missing \"") + key + "\"");
    return *it;
  }

 private:
  std::string file_;
};

std::string number_text(double v) { return json(v).dump(); }

}  // namespace

bool is_contour_stack_path(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".json";
}

ContourStackFile read_contour_stack(const std::filesystem::path& path) {
  const std::string name = path.string();
  const Reader r(name);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) r.fail("", "no such file");
  if (std::filesystem::is_directory(path, ec)) r.fail("", "is a directory, not a contour file");
  std::ifstream in(path, std::ios::binary);
  if (!in) r.fail("", "cannot be opened");
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::parse_error& e) {
    r.fail("", std::string("not valid JSON (") + e.what() + ")");
  }
  if (!doc.is_object()) r.fail("", "expected a JSON object with \"format\": \"" + std::string(kFormat) + "\"");
  const json& format = r.member(doc, "format", "");
  if (!format.is_string() || format.get<std::string>() != kFormat) {
    r.fail("format", std::string("expected \"") + kFormat + "\"");
  }
  const json& version = r.member(doc, "version", "");
  if (!version.is_number_integer() || version.get<long long>() != 1) {
    r.fail("version", "this reader knows version 1, got " + version.dump());
  }
  ContourStackFile out;
  if (const auto it = doc.find("name"); it != doc.end()) {
    if (!it->is_string()) r.fail("name", "expected a string");
    out.name = it->get<std::string>();
  }
  if (const auto it = doc.find("color"); it != doc.end()) {
    if (!it->is_array() || it->size() != 3) r.fail("color", "expected [r, g, b] with values 0-255");
    std::array<int, 3> rgb{};
    for (std::size_t k = 0; k < 3; ++k) {
      const double v = r.number((*it)[k], "color[" + std::to_string(k) + "]");
      if (v < 0.0 || v > 255.0 || v != std::floor(v)) r.fail("color", "expected [r, g, b] with integers 0-255");
      rgb[k] = static_cast<int>(v);
    }
    out.color = rgb;
  }
  ContourStack& stack = out.stack;
  if (const auto it = doc.find("frame"); it != doc.end()) {
    if (!it->is_object()) r.fail("frame", "expected an object with origin, axis_u, axis_v, axis_w");
    const json& f = *it;
    stack.origin = r.vector3(r.member(f, "origin", "frame"), "frame.origin");
    stack.axis_u = r.vector3(r.member(f, "axis_u", "frame"), "frame.axis_u");
    stack.axis_v = r.vector3(r.member(f, "axis_v", "frame"), "frame.axis_v");
    stack.axis_w = r.vector3(r.member(f, "axis_w", "frame"), "frame.axis_w");
    constexpr double kTol = 1e-6;
    const bool unit = std::abs(stack.axis_u.norm() - 1.0) < kTol && std::abs(stack.axis_v.norm() - 1.0) < kTol &&
                      std::abs(stack.axis_w.norm() - 1.0) < kTol;
    const bool orthogonal = std::abs(stack.axis_u.dot(stack.axis_v)) < kTol &&
                            std::abs(stack.axis_u.dot(stack.axis_w)) < kTol &&
                            std::abs(stack.axis_v.dot(stack.axis_w)) < kTol;
    if (!unit || !orthogonal) r.fail("frame", "axis_u, axis_v and axis_w must be orthonormal");
    if (stack.axis_u.cross(stack.axis_v).dot(stack.axis_w) < 0.0) {
      r.fail("frame", "axis_u x axis_v must equal axis_w (a right-handed frame)");
    }
  }
  const json& slices = r.member(doc, "slices", "");
  if (!slices.is_array()) r.fail("slices", "expected an array");
  for (std::size_t s = 0; s < slices.size(); ++s) {
    const std::string ws = "slices[" + std::to_string(s) + "]";
    const json& sj = slices[s];
    if (!sj.is_object()) r.fail(ws, "expected an object with \"w\" and \"contours\"");
    SliceContours slice;
    slice.w = r.number(r.member(sj, "w", ws), ws + ".w");
    if (s > 0 && !(slice.w > stack.slices.back().w)) {
      r.fail(ws + ".w", "slices must be ordered by increasing w (" + number_text(slice.w) + " follows " +
                            number_text(stack.slices.back().w) + ")");
    }
    const json& cj = r.member(sj, "contours", ws);
    if (!cj.is_array()) r.fail(ws + ".contours", "expected an array");
    std::vector<std::optional<bool>> holes;
    for (std::size_t c = 0; c < cj.size(); ++c) {
      const std::string wc = ws + ".contours[" + std::to_string(c) + "]";
      const json& k = cj[c];
      if (!k.is_object()) r.fail(wc, "expected an object with \"points\"");
      const json& pts = r.member(k, "points", wc);
      if (!pts.is_array()) r.fail(wc + ".points", "expected an array of [u, v] pairs");
      if (pts.size() < 3)
        r.fail(wc + ".points", "a contour needs at least 3 points, got " + std::to_string(pts.size()));
      Contour contour;
      contour.points.reserve(pts.size());
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const std::string wp = wc + ".points[" + std::to_string(i) + "]";
        if (!pts[i].is_array() || pts[i].size() != 2) r.fail(wp, "expected [u, v]");
        contour.points.emplace_back(r.number(pts[i][0], wp), r.number(pts[i][1], wp));
      }
      std::optional<bool> hole;
      if (const auto it = k.find("hole"); it != k.end()) {
        if (!it->is_boolean()) r.fail(wc + ".hole", "expected true or false");
        hole = it->get<bool>();
        contour.is_hole = *hole;
      }
      if (const auto it = k.find("parent"); it != k.end()) {
        if (!it->is_number_integer()) r.fail(wc + ".parent", "expected an integer");
        const long long p = it->get<long long>();
        if (p < -1 || p >= static_cast<long long>(cj.size())) r.fail(wc + ".parent", "not a contour of this slice");
        contour.parent = static_cast<int>(p);
      }
      slice.contours.push_back(std::move(contour));
      holes.push_back(hole);
    }
    stack.slices.push_back(std::move(slice));
    out.declared_holes.push_back(std::move(holes));
  }
  return out;
}

std::string contour_stack_json(const ContourStackFile& file) {
  const ContourStack& st = file.stack;
  auto vec = [](const Eigen::Vector3d& v) {
    std::ostringstream t;  // (string concatenation here trips a false -Wrestrict of gcc 12)
    t << "[" << number_text(v.x()) << ", " << number_text(v.y()) << ", " << number_text(v.z()) << "]";
    return t.str();
  };
  std::ostringstream o;
  o << "{\n  \"format\": \"" << kFormat << "\",\n  \"version\": 1,\n";
  if (!file.name.empty())
    o << "  \"name\": " << json(file.name).dump(-1, ' ', false, json::error_handler_t::replace) << ",\n";
  if (file.color)
    o << "  \"color\": [" << (*file.color)[0] << ", " << (*file.color)[1] << ", " << (*file.color)[2] << "],\n";
  o << "  \"frame\": {\"origin\": " << vec(st.origin) << ", \"axis_u\": " << vec(st.axis_u)
    << ", \"axis_v\": " << vec(st.axis_v) << ", \"axis_w\": " << vec(st.axis_w) << "},\n";
  o << "  \"slices\": [";
  for (std::size_t s = 0; s < st.slices.size(); ++s) {
    const SliceContours& sl = st.slices[s];
    o << (s ? ",\n" : "\n") << "    {\"w\": " << number_text(sl.w) << ", \"contours\": [";
    for (std::size_t c = 0; c < sl.contours.size(); ++c) {
      const Contour& k = sl.contours[c];
      o << (c ? ",\n" : "\n") << "      {\"hole\": " << (k.is_hole ? "true" : "false") << ", \"parent\": " << k.parent
        << ", \"points\": [";
      for (std::size_t i = 0; i < k.points.size(); ++i) {
        o << (i ? ", " : "") << "[" << number_text(k.points[i].x()) << ", " << number_text(k.points[i].y()) << "]";
      }
      o << "]}";
    }
    o << (sl.contours.empty() ? "]}" : "\n    ]}");
  }
  o << (st.slices.empty() ? "]\n}\n" : "\n  ]\n}\n");
  return o.str();
}

void write_contour_stack(const ContourStackFile& file, const std::filesystem::path& path) {
  write_text_atomically(path, contour_stack_json(file));
}

}  // namespace contourmesh
