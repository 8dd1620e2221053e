// SPDX-License-Identifier: BSD-3-Clause
#include "report_format.h"

#include <contourmesh/vtk/atomic_file.h>
#include <contourmesh/smooth/errors.h>

#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

namespace contourmesh::report_detail {

std::string fixed(double v, int digits) {
  if (!std::isfinite(v)) return "";
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

std::string signed_fixed(double v, int digits) {
  if (!std::isfinite(v)) return "";
  const std::string s = fixed(v, digits);
  return v >= 0.0 ? "+" + s : s;
}

std::string csv_number(double v) {
  if (!std::isfinite(v)) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string csv_number(std::optional<double> v) { return v ? csv_number(*v) : ""; }

std::string html_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

nlohmann::json json_number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

void ensure_directory(const std::filesystem::path& dir) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec)) {
    throw InvalidInputError(dir.string() + ": exists and is not a directory");
  }
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InvalidInputError(dir.string() + ": cannot create the directory: " + ec.message());
  check_output_path(dir / "metrics.csv");
}

const char* definitions() {
  return "Distances are measured over the surfaces, not at vertices: uniform random samples on each result (4 per "
         "mm^2; their distance to the true surface) and samples of the true surface (the crossings of a 0.4 mm grid "
         "for a phantom, uniform samples of a reference mesh; their distance to the nearest triangle of the result). "
         "RMS is two-sided, sqrt((mesh-to-truth^2 + truth-to-mesh^2) / 2); Hausdorff is the larger one-sided "
         "maximum. The feature region is the part of both surfaces within the feature radius (1.5 mm) of the "
         "phantom's sharp edges and corners, the smooth region the rest. Normal errors are the area-weighted mean "
         "angle between the result's face normals and the true normal. Vertex RMS (secondary) weighs each vertex by "
         "its area: a contour mesh's vertices lie on the contours by construction, so it flatters the unsmoothed "
         "mesh. 'Volume vs truth' compares the enclosed volume with the phantom's exact volume; 'volume change' "
         "with the mesh the method started from (the contour mesh, or the unsmoothed flying-edges mesh for the "
         "voxel route). Labels are scored against the contour-mesh vertices within the detection radius (1.5 mm) "
         "of a true feature: precision = true features found / vertices labelled edge or corner; recall (all) "
         "counts every true feature vertex, so a vertex no rule could examine counts as missed; recall (on "
         "contours) leaves out the vertices off the slice planes (end-cap and branching copies), which have no "
         "adjacent contours for a contour-continuity rule to examine. Numbers are means over the seeds listed; "
         "seconds are wall-clock times of the fastest of the timing repeats. Bold: the best in the column among "
         "the smoothed methods (unsmoothed meshes are not ranked).";
}

const char* html_style() {
  return "body{font-family:sans-serif;margin:2em;max-width:1500px}table{border-collapse:collapse;margin:1em 0}"
         "td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}th{background:#eee}"
         "td:first-child,th:first-child{text-align:left}td.best{font-weight:bold;background:#e6f4e6}"
         "td.fail{color:#b00}figure{display:inline-block;margin:0.5em;width:31%;vertical-align:top}"
         "figure img{width:100%;border:1px solid #ccc}figcaption{font-size:85%}code{background:#f4f4f4}";
}

}  // namespace contourmesh::report_detail
