#include "pipelines/comparison_report.h"

#include "comparison_render.h"
#include "pipelines/atomic_file.h"
#include "png_canvas.h"

#include <smooth/errors.h>

#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <sstream>

namespace contourmesh {

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------------------------------
// Formatting

std::string fixed(double v, int digits) {
  if (!std::isfinite(v)) return "";
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

std::string signed_fixed(double v, int digits) {
  if (!std::isfinite(v)) return "";
  std::string s = fixed(v, digits);
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
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

// Display names of the methods, in the reports.
std::string title_of(const std::string& name) {
  static const std::map<std::string, std::string> titles = {
      {"none", "none (reconstructed mesh)"},
      {"laplacian", "Laplacian"},
      {"taubin", "Taubin"},
      {"mcf", "mean curvature flow"},
      {"mindist", "MIN-DIST flow"},
      {"paper", "the paper's method"},
      {"vtk-windowed-sinc", "vtkWindowedSincPolyDataFilter"},
      {"vtk-smooth-feature-edges", "vtkSmoothPolyDataFilter + feature edges"},
      {"voxel-flying-edges", "voxel route: flying edges"},
      {"voxel-windowed-sinc", "voxel route: flying edges + windowed sinc (3D Slicer)"},
  };
  const auto it = titles.find(name);
  return it != titles.end() ? it->second : name;
}

// Shorter names for the plot's legend.
std::string legend_of(const std::string& name) {
  static const std::map<std::string, std::string> names = {
      {"vtk-windowed-sinc", "vtkWindowedSinc"},
      {"vtk-smooth-feature-edges", "vtkSmoothPolyData + features"},
      {"voxel-windowed-sinc", "voxel route (3D Slicer)"},
  };
  const auto it = names.find(name);
  return it != names.end() ? it->second : title_of(name);
}

detail::Rgb color_of(const std::string& name) {
  static const std::map<std::string, detail::Rgb> colors = {
      {"none", {0.5, 0.5, 0.5}},
      {"laplacian", {0.12, 0.47, 0.71}},
      {"taubin", {0.17, 0.63, 0.17}},
      {"mcf", {0.58, 0.40, 0.74}},
      {"mindist", {0.55, 0.34, 0.29}},
      {"paper", {0.84, 0.15, 0.16}},
      {"vtk-windowed-sinc", {1.0, 0.50, 0.05}},
      {"vtk-smooth-feature-edges", {0.09, 0.75, 0.81}},
      {"voxel-flying-edges", {0.3, 0.3, 0.3}},
      {"voxel-windowed-sinc", {0.74, 0.74, 0.13}},
  };
  const auto it = colors.find(name);
  return it != colors.end() ? it->second : detail::Rgb{0.0, 0.0, 0.0};
}

std::string render_file(const std::string& method) { return "render_" + method + ".png"; }

bool smoothed(const MethodResult& m) { return m.name != "none" && m.name != "voxel-flying-edges"; }

// ---------------------------------------------------------------------------------------------------
// JSON

nlohmann::json distance_json(const std::optional<RegionMetrics>& r) {
  if (!r) return nullptr;
  return {{"mean", number(r->distance.mean)},
          {"rms", number(r->distance.rms)},
          {"max", number(r->distance.max)},
          {"vertices", r->distance.count}};
}

nlohmann::json normals_json(const std::optional<RegionMetrics>& r) {
  if (!r || r->normals.count == 0) return nullptr;
  return {
      {"mean", number(r->normals.mean_degrees)}, {"max", number(r->normals.max_degrees)}, {"faces", r->normals.count}};
}

nlohmann::json comparison_json(const Comparison& c) {
  nlohmann::json j;
  j["source"] = c.source;
  j["truth"] = std::string(to_string(c.truth));
  j["truth_description"] = c.truth_description;
  j["truth_volume_mm3"] = c.truth_volume > 0.0 ? number(c.truth_volume) : nlohmann::json(nullptr);
  j["feature_radius_mm"] = c.feature_radius;
  j["detection_radius_mm"] = c.detection_radius;
  const ReconstructionReport& r = c.reconstruction;
  j["reconstruction"] = {{"slices", r.slices},
                         {"slices_with_contours", r.slices_with_contours},
                         {"contours", r.contours},
                         {"threshold", r.threshold},
                         {"vertices", c.contour_mesh.num_vertices()},
                         {"faces", c.contour_mesh.num_faces()},
                         {"seconds_segment", r.seconds_segment},
                         {"seconds_tile", r.seconds_tile}};
  if (!c.feature_region.empty()) {
    j["reconstruction"]["feature_region_vertices"] = std::count(c.feature_region.begin(), c.feature_region.end(), 1);
  }
  nlohmann::json methods = nlohmann::json::array();
  for (const MethodResult& m : c.methods) {
    nlohmann::json e;
    e["name"] = m.name;
    e["route"] = m.route;
    e["settings"] = m.settings;
    e["iterations"] = m.iterations;
    e["vertices"] = m.mesh.num_vertices();
    e["faces"] = m.mesh.num_faces();
    e["volume_input_mm3"] = number(m.volume_input);
    e["volume_output_mm3"] = number(m.volume_output);
    e["volume_change_percent"] = number(m.volume_change_percent);
    e["volume_error_percent"] = m.volume_error_percent ? number(*m.volume_error_percent) : nlohmann::json(nullptr);
    if (m.all) {
      e["distance_mm"] = {
          {"all", distance_json(m.all)}, {"feature", distance_json(m.feature)}, {"smooth", distance_json(m.smooth)}};
    } else {
      e["distance_mm"] = nullptr;
    }
    if (m.all && m.all->normals.count > 0) {
      e["normal_error_degrees"] = {
          {"all", normals_json(m.all)}, {"feature", normals_json(m.feature)}, {"smooth", normals_json(m.smooth)}};
    } else {
      e["normal_error_degrees"] = nullptr;
    }
    nlohmann::json seconds = nlohmann::json::object();
    for (const StageTime& s : m.seconds) seconds[s.stage] = s.seconds;
    e["seconds"] = seconds;
    if (m.labels) {
      const LabelSummary& l = *m.labels;
      nlohmann::json labels = {{"candidates", l.candidates},
                               {"edge", l.edges},
                               {"corner", l.corners},
                               {"noise", l.noise},
                               {"subdivided_vertices", l.subdivided_vertices},
                               {"adaptive_vertices", l.adaptive_vertices}};
      if (l.true_features) {
        labels["true_feature_vertices"] = *l.true_features;
        labels["detected_vertices"] = *l.detected;
        labels["true_positives"] = *l.true_positives;
        labels["precision"] = number(l.precision);
        labels["recall"] = number(l.recall);
      }
      e["labels"] = labels;
    } else {
      e["labels"] = nullptr;
    }
    nlohmann::json curve = nlohmann::json::array();
    for (double v : m.volume_curve) curve.push_back(number(v));
    e["volume_curve"] = curve;
    methods.push_back(e);
  }
  j["methods"] = methods;
  return j;
}

// ---------------------------------------------------------------------------------------------------
// Plot

// Tick step of about `target` ticks over `range`: 1, 2 or 5 times a power of ten.
double nice_step(double range, int target) {
  const double raw = range / std::max(target, 1);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * p >= raw) return m * p;
  }
  return 10.0 * p;
}

std::string tick_label(double v, double step) {
  const int digits = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
  return fixed(std::abs(v) < 1e-12 ? 0.0 : v, digits);
}

// ---------------------------------------------------------------------------------------------------
// Tables shared by the HTML and Markdown reports

struct Cell {
  std::string text;
  bool best = false;
};

std::string rms_cell(const std::optional<RegionMetrics>& r) { return r ? fixed(r->distance.rms, 3) : ""; }

// Index of the smoothed method with the smallest value (NaN ignored), or -1.
int best_of(const Comparison& c, const std::function<double(const MethodResult&)>& value) {
  int best = -1;
  double best_value = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < c.methods.size(); ++i) {
    if (!smoothed(c.methods[i])) continue;
    const double v = value(c.methods[i]);
    if (std::isfinite(v) && v < best_value) {
      best_value = v;
      best = static_cast<int>(i);
    }
  }
  return best;
}

double feature_rms(const MethodResult& m) { return m.feature ? m.feature->distance.rms : kNaN; }
double abs_volume_change(const MethodResult& m) { return std::abs(m.volume_change_percent); }

// The accuracy table of one comparison: header and rows of cells.
std::pair<std::vector<std::string>, std::vector<std::vector<Cell>>> accuracy_table(const Comparison& c) {
  const bool phantom = c.truth == TruthKind::Phantom;
  const bool distance = c.truth != TruthKind::None;
  std::vector<std::string> header = {"method", "route", "vertices"};
  if (distance) {
    header.insert(header.end(), {"mean dist. mm", "RMS dist. mm", "max dist. mm"});
  }
  if (phantom) {
    header.insert(header.end(), {"feature RMS mm", "smooth RMS mm", "normal err. deg", "feature normal err. deg",
                                 "smooth normal err. deg"});
  }
  header.insert(header.end(), {"volume change %"});
  if (phantom) header.push_back("volume vs truth %");
  header.push_back("seconds");
  const int best_rms = best_of(c, [](const MethodResult& m) { return m.all ? m.all->distance.rms : kNaN; });
  const int best_feature = best_of(c, feature_rms);
  const int best_volume = best_of(c, abs_volume_change);
  std::vector<std::vector<Cell>> rows;
  for (std::size_t i = 0; i < c.methods.size(); ++i) {
    const MethodResult& m = c.methods[i];
    const int k = static_cast<int>(i);
    std::vector<Cell> row = {{title_of(m.name)}, {m.route}, {std::to_string(m.mesh.num_vertices())}};
    if (distance) {
      row.push_back({m.all ? fixed(m.all->distance.mean, 3) : ""});
      row.push_back({rms_cell(m.all), k == best_rms});
      row.push_back({m.all ? fixed(m.all->distance.max, 3) : ""});
    }
    if (phantom) {
      row.push_back({rms_cell(m.feature), k == best_feature});
      row.push_back({rms_cell(m.smooth)});
      row.push_back({m.all ? fixed(m.all->normals.mean_degrees, 2) : ""});
      row.push_back({m.feature ? fixed(m.feature->normals.mean_degrees, 2) : ""});
      row.push_back({m.smooth ? fixed(m.smooth->normals.mean_degrees, 2) : ""});
    }
    row.push_back({signed_fixed(m.volume_change_percent, 2), k == best_volume});
    if (phantom) row.push_back({m.volume_error_percent ? signed_fixed(*m.volume_error_percent, 2) : ""});
    row.push_back({fixed(m.stage_seconds("total"), 3)});
    rows.push_back(std::move(row));
  }
  return {header, rows};
}

std::vector<std::string> timing_header() {
  return {"volume",
          "contour mesh vertices",
          "segment + tile s",
          "paper: detect s",
          "subdivide s",
          "smooth s",
          "total s",
          "Taubin 20 s",
          "vtkWindowedSinc 20 s",
          "paper / windowed sinc",
          "voxel mesh vertices",
          "voxel: threshold + flying edges s",
          "voxel: windowed sinc s"};
}

std::vector<std::string> timing_row(const ComparisonEntry& e) {
  const Comparison& c = *e.comparison;
  const MethodResult* paper = c.find("paper");
  const MethodResult* taubin = c.find("taubin");
  const MethodResult* sinc = c.find("vtk-windowed-sinc");
  const MethodResult* voxel = c.find("voxel-windowed-sinc");
  const auto s = [](const MethodResult* m, const char* stage) { return m ? fixed(m->stage_seconds(stage), 3) : ""; };
  std::string ratio;
  if (paper && sinc && sinc->stage_seconds("total") > 0.0) {
    ratio = fixed(paper->stage_seconds("total") / sinc->stage_seconds("total"), 1);
  }
  return {e.name,
          std::to_string(c.contour_mesh.num_vertices()),
          fixed(c.reconstruction.seconds_segment + c.reconstruction.seconds_tile, 3),
          s(paper, "detect"),
          s(paper, "subdivide"),
          s(paper, "smooth"),
          s(paper, "total"),
          s(taubin, "total"),
          s(sinc, "total"),
          ratio,
          voxel ? std::to_string(voxel->mesh.num_vertices()) : "",
          voxel ? fixed(voxel->stage_seconds("threshold") + voxel->stage_seconds("surface"), 3) : "",
          s(voxel, "smooth")};
}

std::string markdown_table(const std::vector<std::string>& header, const std::vector<std::vector<Cell>>& rows) {
  std::ostringstream s;
  s << "|";
  for (const std::string& h : header) s << " " << h << " |";
  s << "\n|";
  for (std::size_t i = 0; i < header.size(); ++i) s << " --- |";
  s << "\n";
  for (const auto& row : rows) {
    s << "|";
    for (const Cell& cell : row)
      s << " " << (cell.best && !cell.text.empty() ? "**" + cell.text + "**" : cell.text) << " |";
    s << "\n";
  }
  return s.str();
}

std::vector<std::vector<Cell>> plain_rows(const std::vector<std::vector<std::string>>& rows) {
  std::vector<std::vector<Cell>> out;
  for (const auto& row : rows) {
    std::vector<Cell> r;
    for (const std::string& t : row) r.push_back({t});
    out.push_back(std::move(r));
  }
  return out;
}

std::string html_table(const std::vector<std::string>& header, const std::vector<std::vector<Cell>>& rows) {
  std::ostringstream s;
  s << "<table>\n<tr>";
  for (const std::string& h : header) s << "<th>" << html_escape(h) << "</th>";
  s << "</tr>\n";
  for (const auto& row : rows) {
    s << "<tr>";
    for (const Cell& cell : row) {
      s << (cell.best ? "<td class=\"best\">" : "<td>") << html_escape(cell.text) << "</td>";
    }
    s << "</tr>\n";
  }
  s << "</table>\n";
  return s.str();
}

// The paper's labels and detection scores, as rows.
std::pair<std::vector<std::string>, std::vector<std::vector<std::string>>> label_table(
    std::span<const ComparisonEntry> entries) {
  std::vector<std::string> header = {"volume",
                                     "candidates",
                                     "edge",
                                     "corner",
                                     "noise",
                                     "subdivided",
                                     "adaptive vertices",
                                     "true feature vertices",
                                     "detected (edge + corner)",
                                     "precision",
                                     "recall"};
  std::vector<std::vector<std::string>> rows;
  for (const ComparisonEntry& e : entries) {
    const MethodResult* paper = e.comparison->find("paper");
    if (!paper || !paper->labels) continue;
    const LabelSummary& l = *paper->labels;
    rows.push_back({e.name, std::to_string(l.candidates), std::to_string(l.edges), std::to_string(l.corners),
                    std::to_string(l.noise), std::to_string(l.subdivided_vertices), std::to_string(l.adaptive_vertices),
                    l.true_features ? std::to_string(*l.true_features) : "",
                    l.detected ? std::to_string(*l.detected) : "", fixed(l.precision, 3), fixed(l.recall, 3)});
  }
  return {header, rows};
}

const char* kDefinitions =
    "Distances are from each vertex to the true surface (the phantom's signed distance function, or the "
    "nearest triangle of the reference surface), in mm. The feature region is the set of vertices within the "
    "feature radius of the phantom's sharp edges and corners, the smooth region the rest; for the voxel route "
    "both are taken on its own mesh. Normal errors are the mean angle between each face normal and the true "
    "normal at the face centroid; a face belongs to the feature region when one of its vertices does. The "
    "volume change is relative to the mesh the method started from (the contour mesh, or the unsmoothed "
    "flying-edges mesh for the voxel route); 'volume vs truth' compares with the phantom's exact volume. "
    "Precision and recall score the paper's edge and corner labels against the vertices within the detection "
    "radius of a true feature. Seconds are wall-clock times of the smoothing (for the paper: detection, "
    "subdivision and smoothing; for the voxel route: threshold, flying edges and smoothing), the fastest of "
    "the timing repeats; the reconstruction shared by the contour route is timed once. Bold: the best smoothed "
    "result in the column (unsmoothed meshes are not ranked).";

std::string render_caption(const MethodResult& m) { return title_of(m.name) + ": " + m.settings; }

// The HTML report of one comparison; `files` says what was rendered.
std::string comparison_html(const Comparison& c, const ComparisonFiles& files, const ComparisonReportOptions& o) {
  std::ostringstream s;
  s << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>ContourMesh comparison: " << html_escape(c.source)
    << "</title>\n<style>\n"
    << "body{font-family:sans-serif;margin:2em;max-width:1400px}table{border-collapse:collapse;margin:1em 0}"
    << "td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}th{background:#eee}"
    << "td:first-child,th:first-child{text-align:left}td.best{font-weight:bold;background:#e6f4e6}"
    << "figure{display:inline-block;margin:0.5em;width:31%;vertical-align:top}figure img{width:100%;border:1px solid "
       "#ccc}"
    << "figcaption{font-size:85%}code{background:#f4f4f4}\n</style></head><body>\n";
  s << "<h1>ContourMesh comparison</h1>\n";
  if (!o.note.empty()) s << "<p>" << html_escape(o.note) << "</p>\n";
  s << "<p>Volume: " << html_escape(c.source) << "<br>\n";
  if (!o.command_line.empty()) s << "Command: <code>" << html_escape(o.command_line) << "</code><br>\n";
  s << "Truth: "
    << (c.truth == TruthKind::None ? std::string("none: no reference surface was given (--truth), so no distance or "
                                                 "normal metrics are reported")
                                   : html_escape(c.truth_description));
  if (c.truth_volume > 0.0) s << " (volume " << fixed(c.truth_volume, 1) << " mm&sup3;)";
  s << "<br>\nContour mesh: " << c.contour_mesh.num_vertices() << " vertices, " << c.contour_mesh.num_faces()
    << " triangles from " << c.reconstruction.contours << " contours on " << c.reconstruction.slices_with_contours
    << " slices (threshold " << fixed(c.reconstruction.threshold, 0) << ")";
  if (c.truth == TruthKind::Phantom) {
    s << "<br>\nFeature region: vertices within " << fixed(c.feature_radius, 2)
      << " mm of a sharp edge or corner; detection scored against vertices within " << fixed(c.detection_radius, 2)
      << " mm";
  }
  s << "</p>\n<p>Data: <a href=\"metrics.csv\">metrics.csv</a>, <a href=\"metrics.json\">metrics.json</a>, "
    << "<a href=\"volume_curve.csv\">volume_curve.csv</a></p>\n";

  s << "<h2>Accuracy, volume and time</h2>\n";
  const auto [header, rows] = accuracy_table(c);
  s << html_table(header, rows);
  s << "<p>" << html_escape(kDefinitions) << "</p>\n";

  s << "<h2>Time per stage (the paper's Table 1)</h2>\n";
  const ComparisonEntry self{"this volume", ".", &c, files};
  s << html_table(timing_header(), plain_rows({timing_row(self)}));

  const auto [lheader, lrows] = label_table(std::span<const ComparisonEntry>(&self, 1));
  if (!lrows.empty()) {
    s << "<h2>Feature labels of the paper's method</h2>\n" << html_table(lheader, plain_rows(lrows));
  }

  s << "<h2>Volume shrinking rate (the paper's Figure 13)</h2>\n"
    << "<p><img src=\"volume_curve.png\" alt=\"volume shrinking rate against iteration\"></p>\n"
    << "<p>Rate (V<sub>0</sub> - V<sub>k</sub>) / V<sub>0</sub> after k iterations; positive means the mesh "
       "shrank. vtkWindowedSincPolyDataFilter has no intermediate results (its iteration count is the degree of "
       "one polynomial filter), so it is a marker at its iteration count.</p>\n";

  s << "<h2>Renders (the paper's Figures 6 and 9-12)</h2>\n";
  if (!files.rendered) {
    s << "<p><b>No renders:</b> " << html_escape(files.render_note) << "</p>\n";
  } else {
    s << "<p>Every mesh from the same camera, flat shaded.</p>\n";
    s << "<figure><img src=\"labels.png\" alt=\"labels\"><figcaption>The paper's labels on the contour mesh: edge "
         "green, corner blue (large), noise red.</figcaption></figure>\n";
    if (c.truth == TruthKind::Phantom) {
      s << "<figure><img src=\"detection.png\" alt=\"detection\"><figcaption>Detection against the truth: true "
           "feature vertices found (green) and missed (orange), false detections (red).</figcaption></figure>\n";
    }
    for (const MethodResult& m : c.methods) {
      s << "<figure><img src=\"" << render_file(m.name) << "\" alt=\"" << html_escape(m.name) << "\"><figcaption>"
        << html_escape(render_caption(m)) << "</figcaption></figure>\n";
    }
  }
  s << "</body></html>\n";
  return s.str();
}

// The PNG files write_renders makes.
std::vector<fs::path> render_files(const Comparison& c, const fs::path& dir) {
  std::vector<fs::path> files;
  for (const MethodResult& m : c.methods) files.push_back(dir / render_file(m.name));
  if (!c.labels.empty()) files.push_back(dir / "labels.png");
  if (!c.true_features.empty() && !c.labels.empty()) files.push_back(dir / "detection.png");
  return files;
}

void write_renders(const Comparison& c, const fs::path& dir, const ComparisonReportOptions& o) {
  detail::SceneRenderer renderer(c.contour_mesh, o.render_width, o.render_height, o.color_levels);
  for (const MethodResult& m : c.methods) renderer.surface(m.mesh, title_of(m.name), dir / render_file(m.name));
  if (!c.labels.empty()) {
    std::vector<int> group(c.labels.size(), -1);
    for (std::size_t i = 0; i < c.labels.size(); ++i) {
      switch (c.labels[i]) {
        case VertexLabel::Edge:
          group[i] = 0;
          break;
        case VertexLabel::Corner:
          group[i] = 1;
          break;
        case VertexLabel::Noise:
          group[i] = 2;
          break;
        default:
          break;
      }
    }
    const fs::path png = dir / "labels.png";
    renderer.points(
        c.contour_mesh, group,
        {{"edge", {0.0, 0.65, 0.0}, 6.0}, {"corner", {0.1, 0.3, 1.0}, 12.0}, {"noise", {0.9, 0.1, 0.1}, 6.0}},
        "labels of the paper's method", png);
  }
  if (!c.true_features.empty() && !c.labels.empty()) {
    std::vector<int> group(c.labels.size(), -1);
    for (std::size_t i = 0; i < c.labels.size(); ++i) {
      const bool detected = c.labels[i] == VertexLabel::Edge || c.labels[i] == VertexLabel::Corner;
      if (c.true_features[i])
        group[i] = detected ? 0 : 1;
      else if (detected)
        group[i] = 2;
    }
    const fs::path png = dir / "detection.png";
    renderer.points(c.contour_mesh, group,
                    {{"true feature, found", {0.0, 0.65, 0.0}, 6.0},
                     {"true feature, missed", {1.0, 0.55, 0.0}, 6.0},
                     {"false detection", {0.9, 0.1, 0.1}, 6.0}},
                    "detection vs. true features", png);
  }
}

// Renders in a child process: Debian's VTK aborts the process when the X server goes away or
// refuses a connection (a display that vanished mid-run, a deleted Xauthority file), and the metrics
// must survive that. Returns an empty string on success, otherwise why the renders are missing.
std::string write_renders_isolated(const Comparison& c, const fs::path& dir, const ComparisonReportOptions& o) {
  std::cout.flush();
  std::cerr.flush();
  const pid_t pid = fork();
  if (pid < 0) return std::string("cannot start the rendering process: ") + std::strerror(errno);
  if (pid == 0) {
    int code = 0;
    try {
      write_renders(c, dir, o);
    } catch (const std::exception& e) {
      std::cerr << "rendering: " << e.what() << "\n";
      code = 2;
    }
    std::cerr.flush();
    _exit(code);  // no destructors or atexit handlers of the parent's state in the child
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return std::string("lost the rendering process: ") + std::strerror(errno);
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return {};
  if (WIFSIGNALED(status)) {
    return "rendering failed (signal " + std::to_string(WTERMSIG(status)) +
           "; VTK aborts when the X display goes away, see the message above)";
  }
  return "rendering failed (exit code " + std::to_string(WEXITSTATUS(status)) + ", see the message above)";
}

void ensure_directory(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) {
    throw InvalidInputError(dir.string() + ": exists and is not a directory");
  }
  fs::create_directories(dir, ec);
  if (ec) throw InvalidInputError(dir.string() + ": cannot create the directory: " + ec.message());
  check_output_path(dir / "metrics.csv");
}

}  // namespace

// ---------------------------------------------------------------------------------------------------

std::string metrics_csv(const Comparison& c) {
  std::ostringstream s;
  s << "method,route,vertices,faces,volume_input_mm3,volume_output_mm3,volume_change_percent,volume_error_percent,"
       "distance_mean_mm,distance_rms_mm,distance_max_mm,feature_distance_mean_mm,feature_distance_rms_mm,"
       "feature_distance_max_mm,smooth_distance_mean_mm,smooth_distance_rms_mm,smooth_distance_max_mm,"
       "normal_error_mean_deg,feature_normal_error_mean_deg,smooth_normal_error_mean_deg,"
       "seconds_detect,seconds_subdivide,seconds_threshold,seconds_surface,seconds_smooth,seconds_total,"
       "candidates,edge,corner,noise,subdivided_vertices,adaptive_vertices,true_feature_vertices,detected_vertices,"
       "true_positives,precision,recall\n";
  const auto dist = [](const std::optional<RegionMetrics>& r) {
    if (!r) return std::string(",,");
    return csv_number(r->distance.mean) + "," + csv_number(r->distance.rms) + "," + csv_number(r->distance.max);
  };
  const auto normal = [](const std::optional<RegionMetrics>& r) {
    return r && r->normals.count > 0 ? csv_number(r->normals.mean_degrees) : std::string();
  };
  for (const MethodResult& m : c.methods) {
    s << m.name << "," << m.route << "," << m.mesh.num_vertices() << "," << m.mesh.num_faces() << ","
      << csv_number(m.volume_input) << "," << csv_number(m.volume_output) << "," << csv_number(m.volume_change_percent)
      << "," << csv_number(m.volume_error_percent) << "," << dist(m.all) << "," << dist(m.feature) << ","
      << dist(m.smooth) << "," << normal(m.all) << "," << normal(m.feature) << "," << normal(m.smooth);
    for (const char* stage : {"detect", "subdivide", "threshold", "surface", "smooth", "total"}) {
      const bool has =
          std::any_of(m.seconds.begin(), m.seconds.end(), [&](const StageTime& t) { return t.stage == stage; });
      s << "," << (has ? csv_number(m.stage_seconds(stage)) : "");
    }
    if (m.labels) {
      const LabelSummary& l = *m.labels;
      s << "," << l.candidates << "," << l.edges << "," << l.corners << "," << l.noise << "," << l.subdivided_vertices
        << "," << l.adaptive_vertices << ",";
      if (l.true_features) {
        s << *l.true_features << "," << *l.detected << "," << *l.true_positives << "," << csv_number(l.precision) << ","
          << csv_number(l.recall);
      } else {
        s << ",,,,";
      }
    } else {
      s << ",,,,,,,,,,,";
    }
    s << "\n";
  }
  return s.str();
}

std::string metrics_json(const Comparison& c) { return comparison_json(c).dump(2) + "\n"; }

std::string volume_curve_csv(const Comparison& c) {
  std::vector<const MethodResult*> curves;
  std::size_t rows = 0;
  for (const MethodResult& m : c.methods) {
    if (m.volume_curve.empty()) continue;
    curves.push_back(&m);
    rows = std::max(rows, m.volume_curve.size());
  }
  std::ostringstream s;
  s << "iteration";
  for (const MethodResult* m : curves) s << "," << m->name;
  s << "\n";
  for (std::size_t k = 0; k < rows; ++k) {
    s << k;
    for (const MethodResult* m : curves) s << "," << (k < m->volume_curve.size() ? csv_number(m->volume_curve[k]) : "");
    s << "\n";
  }
  return s.str();
}

void write_volume_curve_png(const Comparison& c, const fs::path& path, int width, int height) {
  using detail::Align;
  detail::Canvas canvas(width, height, {1.0, 1.0, 1.0});
  const double left = 80, right = width - 270.0, bottom = 60, top = height - 50.0;
  // Iterative methods are curves; a filter without intermediate results (windowed sinc) is a marker
  // at its iteration count.
  const auto marker = [](const MethodResult& m) { return m.volume_curve.empty() && smoothed(m) && m.iterations > 0; };
  std::size_t iterations = 1;
  double lo = 0.0, hi = 0.0;
  const auto extend = [&](double rate) {
    if (!std::isfinite(rate)) return;
    lo = std::min(lo, 100.0 * rate);
    hi = std::max(hi, 100.0 * rate);
  };
  for (const MethodResult& m : c.methods) {
    if (!m.volume_curve.empty()) {
      iterations = std::max(iterations, m.volume_curve.size() - 1);
      for (double v : m.volume_curve) extend(v);
    } else if (marker(m)) {
      iterations = std::max(iterations, static_cast<std::size_t>(m.iterations));
      extend(-m.volume_change_percent / 100.0);
    }
  }
  if (hi - lo < 1e-6) {
    lo -= 0.5;
    hi += 0.5;
  }
  const double ystep = nice_step(hi - lo, 8);
  lo = std::floor(lo / ystep) * ystep;
  hi = std::ceil(hi / ystep) * ystep;
  const double xmax = static_cast<double>(iterations);
  const auto X = [&](double k) { return left + (right - left) * k / xmax; };
  const auto Y = [&](double v) { return bottom + (top - bottom) * (v - lo) / (hi - lo); };
  const detail::Rgb grid = {0.88, 0.88, 0.88}, ink = {0.1, 0.1, 0.1};

  for (double v = lo; v <= hi + 1e-9 * ystep; v += ystep) {
    canvas.line(left, Y(v), right, Y(v), std::abs(v) < 1e-9 * ystep ? detail::Rgb{0.6, 0.6, 0.6} : grid, 1.0);
    canvas.text(tick_label(v, ystep), left - 8, Y(v), ink, 13, Align::End, Align::Center);
  }
  const double xstep = nice_step(xmax, 8);
  for (double k = 0; k <= xmax + 1e-9; k += xstep) {
    canvas.line(X(k), bottom, X(k), top, grid, 1.0);
    canvas.text(tick_label(k, 1.0), X(k), bottom - 8, ink, 13, Align::Center, Align::End);
  }
  canvas.line(left, bottom, right, bottom, ink, 1.2);
  canvas.line(left, bottom, left, top, ink, 1.2);
  canvas.text("iteration", 0.5 * (left + right), 12, ink, 15, Align::Center, Align::Start);
  canvas.text("volume shrinking rate (V0 - Vk) / V0, %", 22, 0.5 * (bottom + top), ink, 15, Align::Center,
              Align::Center, false, true);
  canvas.text("Volume shrinking rate against iteration", 0.5 * (left + right), height - 15.0, ink, 17, Align::Center,
              Align::End, true);

  const auto diamond = [&](double x, double y, const detail::Rgb& color) {
    constexpr double r = 6.0;
    for (double d = -r; d <= r; d += 0.5)
      canvas.line(x - (r - std::abs(d)), y + d, x + (r - std::abs(d)), y + d, color, 1.0);
  };
  int legend_row = 0;
  for (const MethodResult& m : c.methods) {
    const bool is_marker = marker(m);
    if (m.volume_curve.empty() && !is_marker) continue;
    const detail::Rgb color = color_of(m.name);
    const double w = m.name == "paper" ? 3.0 : 2.0;
    for (std::size_t k = 1; k < m.volume_curve.size(); ++k) {
      const double a = m.volume_curve[k - 1], b = m.volume_curve[k];
      if (!std::isfinite(a) || !std::isfinite(b)) continue;
      canvas.line(X(static_cast<double>(k - 1)), Y(100.0 * a), X(static_cast<double>(k)), Y(100.0 * b), color, w);
    }
    const double ly = top - 10.0 - 24.0 * legend_row++;
    if (is_marker) {
      diamond(X(m.iterations), Y(-m.volume_change_percent), color);
      diamond(right + 35, ly, color);
    } else {
      canvas.line(right + 20, ly, right + 50, ly, color, w);
    }
    canvas.text(legend_of(m.name), right + 58, ly, ink, 13, Align::Start, Align::Center);
  }
  canvas.text("markers: filters without intermediate steps", right + 20, top - 14.0 - 24.0 * legend_row,
              {0.4, 0.4, 0.4}, 11, Align::Start, Align::Center);
  canvas.write_png(path);
}

std::string timing_table_markdown(std::span<const ComparisonEntry> entries) {
  std::vector<std::vector<std::string>> rows;
  for (const ComparisonEntry& e : entries) rows.push_back(timing_row(e));
  return markdown_table(timing_header(), plain_rows(rows));
}

bool rendering_available(std::string* reason) { return detail::x_display_available(reason); }

ComparisonFiles write_comparison(const Comparison& c, const fs::path& dir, const ComparisonReportOptions& o) {
  ensure_directory(dir);
  ComparisonFiles files;
  const auto text = [&](const char* name, const std::string& content) {
    write_text_atomically(dir / name, content);
    files.files.push_back(dir / name);
  };
  text("metrics.csv", metrics_csv(c));
  text("metrics.json", metrics_json(c));
  text("volume_curve.csv", volume_curve_csv(c));
  write_volume_curve_png(c, dir / "volume_curve.png");
  files.files.push_back(dir / "volume_curve.png");
  if (!o.renders) {
    files.render_note = "rendering was turned off (--no-render)";
  } else if (std::string why; !rendering_available(&why)) {
    files.render_note = why;
  } else if (std::string failed = write_renders_isolated(c, dir, o); !failed.empty()) {
    files.render_note = failed;
  } else {
    for (const fs::path& f : render_files(c, dir)) files.files.push_back(f);
    files.rendered = true;
  }
  text("report.html", comparison_html(c, files, o));
  return files;
}

namespace {

// The phantom x method table of feature RMS / volume change, and each phantom's verdict on the targets.
std::string summary_markdown_tables(std::span<const ComparisonEntry> entries) {
  std::vector<std::string> methods;
  for (const ComparisonEntry& e : entries) {
    for (const MethodResult& m : e.comparison->methods) {
      if (std::find(methods.begin(), methods.end(), m.name) == methods.end()) methods.push_back(m.name);
    }
  }
  std::ostringstream s;
  const bool any_phantom = std::any_of(entries.begin(), entries.end(), [](const ComparisonEntry& e) {
    return e.comparison->truth == TruthKind::Phantom;
  });
  std::vector<std::string> header = {"method"};
  for (const ComparisonEntry& e : entries) header.push_back(e.name);
  std::vector<std::vector<Cell>> rows;
  for (const std::string& name : methods) {
    std::vector<Cell> row = {{title_of(name)}};
    for (const ComparisonEntry& e : entries) {
      const Comparison& c = *e.comparison;
      const MethodResult* m = c.find(name);
      if (!m) {
        row.push_back({""});
        continue;
      }
      const int best = best_of(c, feature_rms);
      const bool is_best = best >= 0 && &c.methods[static_cast<std::size_t>(best)] == m;
      const std::string rms = any_phantom ? rms_cell(m->feature) : rms_cell(m->all);
      row.push_back(
          {(rms.empty() ? std::string("-") : rms) + " / " + signed_fixed(m->volume_change_percent, 2), is_best});
    }
    rows.push_back(std::move(row));
  }
  s << markdown_table(header, rows);
  return s.str();
}

std::string targets_markdown(std::span<const ComparisonEntry> entries) {
  std::ostringstream s;
  for (const ComparisonEntry& e : entries) {
    const Comparison& c = *e.comparison;
    const MethodResult* paper = c.find("paper");
    if (!paper || c.truth != TruthKind::Phantom) continue;
    const int best_feature = best_of(c, feature_rms);
    const int best_volume = best_of(c, abs_volume_change);
    const MethodResult& bf = c.methods[static_cast<std::size_t>(best_feature)];
    const MethodResult& bv = c.methods[static_cast<std::size_t>(best_volume)];
    int rank = 1;
    for (const MethodResult& m : c.methods) {
      if (smoothed(m) && feature_rms(m) < feature_rms(*paper)) ++rank;
    }
    const double dv_gap = abs_volume_change(*paper) - abs_volume_change(bv);
    s << "- **" << e.name << "**: feature RMS " << fixed(feature_rms(*paper), 3) << " mm, rank " << rank
      << " of the smoothed methods";
    if (&bf != paper) s << " (best: " << title_of(bf.name) << ", " << fixed(feature_rms(bf), 3) << " mm)";
    s << "; |volume change| " << fixed(abs_volume_change(*paper), 2) << " %";
    if (&bv != paper) {
      s << ", " << fixed(dv_gap, 2) << " points above the smallest (" << title_of(bv.name) << ", "
        << fixed(abs_volume_change(bv), 2) << " %)" << (dv_gap <= 0.2 ? ": within 0.2" : ": not within 0.2");
    } else {
      s << ", the smallest";
    }
    if (const MethodResult* none = c.find("none"); none && none->feature) {
      int better = 0;
      for (const MethodResult& m : c.methods) better += smoothed(m) && feature_rms(m) < feature_rms(*none);
      s << ". Unsmoothed contour mesh: " << fixed(feature_rms(*none), 3) << " mm ("
        << (better == 0 ? std::string("no smoothed method is closer")
                        : std::to_string(better) + " smoothed method" + (better == 1 ? " is" : "s are") + " closer")
        << ")";
    }
    s << ".\n";
  }
  return s.str();
}

}  // namespace

std::vector<fs::path> write_comparison_summary(std::span<const ComparisonEntry> entries, const fs::path& dir,
                                               const ComparisonReportOptions& o) {
  ensure_directory(dir);
  std::vector<fs::path> written;
  // summary.csv: one row per volume and method.
  std::ostringstream csv;
  csv << "volume,method,route,vertices,distance_rms_mm,feature_distance_rms_mm,smooth_distance_rms_mm,"
         "normal_error_mean_deg,feature_normal_error_mean_deg,volume_change_percent,volume_error_percent,seconds_"
         "total\n";
  nlohmann::json json = nlohmann::json::array();
  for (const ComparisonEntry& e : entries) {
    for (const MethodResult& m : e.comparison->methods) {
      const auto rms = [](const std::optional<RegionMetrics>& r) { return r ? csv_number(r->distance.rms) : ""; };
      const auto normal = [](const std::optional<RegionMetrics>& r) {
        return r && r->normals.count > 0 ? csv_number(r->normals.mean_degrees) : "";
      };
      csv << e.name << "," << m.name << "," << m.route << "," << m.mesh.num_vertices() << "," << rms(m.all) << ","
          << rms(m.feature) << "," << rms(m.smooth) << "," << normal(m.all) << "," << normal(m.feature) << ","
          << csv_number(m.volume_change_percent) << "," << csv_number(m.volume_error_percent) << ","
          << csv_number(m.stage_seconds("total")) << "\n";
    }
    nlohmann::json j = comparison_json(*e.comparison);
    j["name"] = e.name;
    j["directory"] = fs::relative(e.directory, dir).generic_string();
    json.push_back(j);
  }
  write_text_atomically(dir / "summary.csv", csv.str());
  written.push_back(dir / "summary.csv");
  write_text_atomically(dir / "summary.json", json.dump(2) + "\n");
  written.push_back(dir / "summary.json");

  std::ostringstream html;
  html
      << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>ContourMesh comparison summary</title>\n<style>\n"
      << "body{font-family:sans-serif;margin:2em;max-width:1400px}table{border-collapse:collapse;margin:1em 0}"
      << "td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}th{background:#eee}"
      << "td:first-child,th:first-child{text-align:left}td.best{font-weight:bold;background:#e6f4e6}code{background:#"
         "f4f4f4}"
      << "\n</style></head><body>\n<h1>ContourMesh comparison summary</h1>\n";
  if (!o.note.empty()) html << "<p>" << html_escape(o.note) << "</p>\n";
  if (!o.command_line.empty()) html << "<p>Command: <code>" << html_escape(o.command_line) << "</code></p>\n";
  html << "<p>Reports: ";
  for (const ComparisonEntry& e : entries) {
    html << "<a href=\"" << html_escape(fs::relative(e.directory / "report.html", dir).generic_string()) << "\">"
         << html_escape(e.name) << "</a> ";
  }
  html << "</p>\n<h2>Feature-region RMS distance (mm) / volume change (%)</h2>\n";
  {
    // Reuse the Markdown table's cells.
    std::vector<std::string> header = {"method"};
    for (const ComparisonEntry& e : entries) header.push_back(e.name);
    std::vector<std::string> methods;
    for (const ComparisonEntry& e : entries) {
      for (const MethodResult& m : e.comparison->methods) {
        if (std::find(methods.begin(), methods.end(), m.name) == methods.end()) methods.push_back(m.name);
      }
    }
    std::vector<std::vector<Cell>> rows;
    for (const std::string& name : methods) {
      std::vector<Cell> row = {{title_of(name)}};
      for (const ComparisonEntry& e : entries) {
        const MethodResult* m = e.comparison->find(name);
        const int best = best_of(*e.comparison, feature_rms);
        const bool is_best = m && best >= 0 && &e.comparison->methods[static_cast<std::size_t>(best)] == m;
        const std::string rms = m ? rms_cell(m->feature) : "";
        row.push_back(
            {m ? (rms.empty() ? std::string("-") : rms) + " / " + signed_fixed(m->volume_change_percent, 2) : "",
             is_best});
      }
      rows.push_back(std::move(row));
    }
    html << html_table(header, rows);
  }
  html << "<h2>Time per stage (the paper's Table 1)</h2>\n";
  {
    std::vector<std::vector<std::string>> rows;
    for (const ComparisonEntry& e : entries) rows.push_back(timing_row(e));
    html << html_table(timing_header(), plain_rows(rows));
  }
  const auto [lheader, lrows] = label_table(entries);
  if (!lrows.empty())
    html << "<h2>Feature labels of the paper's method</h2>\n" << html_table(lheader, plain_rows(lrows));
  html << "<p>" << html_escape(kDefinitions) << "</p>\n</body></html>\n";
  write_text_atomically(dir / "report.html", html.str());
  written.push_back(dir / "report.html");
  return written;
}

void write_comparison_markdown(std::span<const ComparisonEntry> entries, const fs::path& markdown_path,
                               const ComparisonReportOptions& o) {
  const fs::path base = markdown_path.has_parent_path() ? markdown_path.parent_path() : fs::path(".");
  const auto link = [&](const fs::path& file) { return fs::relative(file, base).generic_string(); };
  std::ostringstream s;
  s << "# Results: the paper's method against the baselines, VTK's filters and 3D Slicer's voxel route\n\n"
    << "Generated from a real run of `contourmesh compare`; do not edit by hand. To regenerate (under "
       "`xvfb-run -a` on a machine without a display, for the renders):\n\n```sh\n"
    << (o.command_line.empty() ? std::string("contourmesh compare --phantom all --out DIR") : o.command_line)
    << "\n```\n\n";
  if (!o.note.empty()) s << o.note << "\n\n";
  if (!entries.empty()) {
    const Comparison& c0 = *entries.front().comparison;
    s << "Every method starts from the same reconstructed contour mesh of a phantom's CT volume; the voxel route "
         "starts from the same volume and threshold. Method settings:\n\n";
    for (const MethodResult& m : c0.methods) s << "- **" << title_of(m.name) << "**: " << m.settings << "\n";
    s << "\n";
  }
  s << "## Feature-region RMS distance (mm) / volume change (%)\n\n"
    << summary_markdown_tables(entries) << "\n"
    << "Bold: the lowest feature-region RMS among the smoothed methods of that volume.\n\n";
  const std::string targets = targets_markdown(entries);
  if (!targets.empty()) s << "### The paper's method per phantom\n\n" << targets << "\n";
  s << "## Time per stage (the paper's Table 1), seconds\n\n" << timing_table_markdown(entries) << "\n";
  const auto [lheader, lrows] = label_table(entries);
  if (!lrows.empty())
    s << "## Feature labels of the paper's method\n\n" << markdown_table(lheader, plain_rows(lrows)) << "\n";
  s << "## Definitions\n\n" << kDefinitions << "\n\n";
  for (const ComparisonEntry& e : entries) {
    const Comparison& c = *e.comparison;
    s << "## " << e.name << "\n\n"
      << c.source << "; truth: " << (c.truth == TruthKind::None ? "none" : c.truth_description)
      << ". Contour mesh: " << c.contour_mesh.num_vertices() << " vertices. Full report: ["
      << link(e.directory / "report.html") << "](" << link(e.directory / "report.html") << ").\n\n";
    const auto [header, rows] = accuracy_table(c);
    s << markdown_table(header, rows) << "\n";
    s << "<img src=\"" << link(e.directory / "volume_curve.png") << "\" width=\"60%\" alt=\"volume curve\">\n\n";
    if (e.files.rendered) {
      for (const char* name :
           {"none", "taubin", "paper", "vtk-windowed-sinc", "vtk-smooth-feature-edges", "voxel-windowed-sinc"}) {
        if (c.find(name))
          s << "<img src=\"" << link(e.directory / render_file(name)) << "\" width=\"32%\" alt=\"" << name << "\"> ";
      }
      s << "\n\n<img src=\"" << link(e.directory / "labels.png") << "\" width=\"32%\" alt=\"labels\"> ";
      if (c.truth == TruthKind::Phantom) {
        s << "<img src=\"" << link(e.directory / "detection.png") << "\" width=\"32%\" alt=\"detection\">";
      }
      s << "\n\n";
    } else if (!e.files.render_note.empty()) {
      s << "No renders: " << e.files.render_note << "\n\n";
    }
  }
  write_text_atomically(markdown_path, s.str());
}

}  // namespace contourmesh
