// SPDX-License-Identifier: BSD-3-Clause
// The files of one series (write_series, its report.html) and the summary of several (write_summary).
#include "compare/report.h"

#include "report_data.h"
#include "report_format.h"
#include "report_tables.h"

#include <contourmesh/vtk/atomic_file.h>

#include <sstream>

namespace contourmesh {

namespace fs = std::filesystem;
using namespace report_detail;

namespace {

std::string seeds_text(const Series& s) {
  if (s.seeds.empty()) return "";
  std::ostringstream t;
  t << (s.seeds.size() == 1 ? "seed " : "means over seeds ");
  for (std::size_t k = 0; k < s.seeds.size(); ++k) t << (k ? ", " : "") << s.seeds[k];
  return t.str();
}

std::string series_html(const Series& s, const ComparisonFiles& files, const ComparisonReportOptions& o) {
  const Comparison& c = s.first();
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>ContourMesh comparison: " << html_escape(s.name)
    << " (" << html_escape(s.regime.name) << ")</title>\n<style>" << html_style() << "</style></head><body>\n"
    << "<h1>ContourMesh comparison: " << html_escape(s.name) << ", " << html_escape(s.regime.name) << "</h1>\n";
  if (!o.note.empty()) h << "<p>" << html_escape(o.note) << "</p>\n";
  h << "<p>Volume: " << html_escape(c.source);
  if (!s.seeds.empty()) h << "; " << html_escape(seeds_text(s));
  h << "<br>\n";
  if (!o.command_line.empty()) h << "Command: <code>" << html_escape(o.command_line) << "</code><br>\n";
  h << "Truth: "
    << (c.truth == TruthKind::None ? std::string("none: no reference surface was given (--truth), so no distance or "
                                                 "normal metrics are reported")
                                   : html_escape(c.truth_description));
  if (c.truth_volume > 0.0) h << " (volume " << fixed(c.truth_volume, 1) << " mm&sup3;)";
  h << "<br>\nContour mesh: " << c.contour_mesh.num_vertices() << " vertices, " << c.contour_mesh.num_faces()
    << " triangles from " << c.reconstruction.contours << " contours on " << c.reconstruction.slices_with_contours
    << " slices (threshold " << fixed(c.reconstruction.threshold, 0) << ")";
  if (c.truth == TruthKind::Phantom) {
    h << "<br>\nFeature region: within " << fixed(c.feature_radius, 2)
      << " mm of a sharp edge or corner; labels scored against the vertices within " << fixed(c.detection_radius, 2)
      << " mm";
  }
  h << "</p>\n<p>Data: <a href=\"metrics.csv\">metrics.csv</a>, <a href=\"metrics.json\">metrics.json</a> (every "
    << "seed), <a href=\"volume_curve.csv\">volume_curve.csv</a></p>\n";
  h << "<h2>Accuracy, volume and time</h2>\n" << html_table(accuracy_table(s));
  h << "<p>" << html_escape(definitions()) << "</p>\n";
  const SeriesEntry self{&s, ".", files};
  h << "<h2>Time per stage (the paper's Table 1)</h2>\n"
    << html_table(timing_table(std::span<const SeriesEntry>(&self, 1)));
  const Table labels = label_table(std::span<const SeriesEntry>(&self, 1));
  if (!labels.rows.empty()) h << "<h2>Feature labels</h2>\n" << html_table(labels);
  h << "<h2>Volume shrinking rate (the paper's Figure 13)</h2>\n"
    << "<p><img src=\"volume_curve.png\" alt=\"volume shrinking rate against iteration\"></p>\n"
    << "<p>Rate (V<sub>0</sub> - V<sub>k</sub>) / V<sub>0</sub> after k iterations (the first seed); positive means "
       "the mesh shrank. Methods without intermediate results are markers.</p>\n";
  h << "<h2>Renders (the paper's Figures 6 and 9-12)</h2>\n";
  if (!files.rendered) {
    h << "<p><b>No renders:</b> " << html_escape(files.render_note) << "</p>\n";
  } else {
    h << "<p>The first seed's meshes from one camera, flat shaded; labels: edge green, corner blue (large), noise "
         "red; detection: true feature vertices found (green) and missed (orange), false detections (red).</p>\n";
    for (const fs::path& png : render_files(c, ".", o)) {
      const std::string name = png.filename().string();
      h << "<figure><img src=\"" << html_escape(name) << "\" alt=\"" << html_escape(name) << "\"><figcaption>"
        << html_escape(name) << "</figcaption></figure>\n";
    }
    h << "<p>Settings:</p><ul>\n";
    for (const MethodResult& m : c.methods) {
      h << "<li><b>" << html_escape(m.spec.title) << "</b>: " << html_escape(m.spec.settings) << "</li>\n";
    }
    h << "</ul>\n";
  }
  h << "</body></html>\n";
  return h.str();
}

}  // namespace

ComparisonFiles write_series(const Series& s, const fs::path& dir, const ComparisonReportOptions& o) {
  ensure_directory(dir);
  ComparisonFiles files;
  const auto text = [&](const char* name, const std::string& content) {
    write_text_atomically(dir / name, content);
    files.files.push_back(dir / name);
  };
  text("metrics.csv", metrics_csv(s));
  text("metrics.json", metrics_json(s));
  text("volume_curve.csv", volume_curve_csv(s.first()));
  write_volume_curve_png(s.first(), dir / "volume_curve.png");
  files.files.push_back(dir / "volume_curve.png");
  if (!o.renders) {
    files.render_note = "rendering was turned off (--no-render)";
  } else if (std::string why; !rendering_available(&why)) {
    files.render_note = why;
  } else {
    const auto render = [&] { write_renders(s.first(), dir, o); };
    if (o.isolate) {
      files.render_note = o.isolate(render);
    } else {
      try {
        render();
      } catch (const std::exception& e) {
        files.render_note = std::string("rendering failed: ") + e.what();
      }
    }
    if (files.render_note.empty()) {
      for (const fs::path& f : render_files(s.first(), dir, o)) files.files.push_back(f);
      files.rendered = true;
    }
  }
  text("report.html", series_html(s, files, o));
  return files;
}

std::vector<fs::path> write_summary(std::span<const SeriesEntry> entries, const fs::path& dir,
                                    const ComparisonReportOptions& o) {
  ensure_directory(dir);
  std::vector<fs::path> written;
  std::ostringstream csv;
  csv << "regime,volume," << summary_csv_header() << "\n";
  nlohmann::json json = nlohmann::json::array();
  for (const SeriesEntry& e : entries) {
    for (const MethodSummary& m : e.series->mean) {
      csv << e.series->regime.name << "," << e.series->name << "," << summary_csv_row(m) << "\n";
    }
    nlohmann::json j = series_json(*e.series);
    j.erase("runs");  // every run is in the series' own metrics.json
    j["metrics"] = fs::relative(e.directory / "metrics.json", dir).generic_string();
    json.push_back(j);
  }
  write_text_atomically(dir / "summary.csv", csv.str());
  written.push_back(dir / "summary.csv");
  std::vector<const Series*> all;
  for (const SeriesEntry& e : entries) all.push_back(e.series);
  const Verdicts verdicts = judge(all);
  nlohmann::json summary = {{"series", json}};
  nlohmann::json rows = nlohmann::json::array();
  for (const VerdictRow& r : verdicts.rows) {
    nlohmann::json row = {{"phantom", r.phantom}, {"regime", r.regime}, {"original", r.original}};
    const std::pair<const char*, const BarVerdict*> bars[] = {
        {"do_no_harm", &r.harm}, {"beat_voxel_route", &r.voxel}, {"denoise", &r.denoise}, {"detection", &r.detection}};
    for (const auto& [name, bar] : bars) {
      row[name] = bar->state == BarState::NotApplicable
                      ? nlohmann::json(nullptr)
                      : nlohmann::json({{"state", std::string(to_string(bar->state))}, {"detail", bar->detail}});
    }
    rows.push_back(row);
  }
  summary["verdicts"] = rows;
  write_text_atomically(dir / "summary.json", summary.dump(2) + "\n");
  written.push_back(dir / "summary.json");

  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>ContourMesh comparison summary</title>\n<style>"
    << html_style() << "</style></head><body>\n<h1>ContourMesh comparison summary</h1>\n";
  if (!o.note.empty()) h << "<p>" << html_escape(o.note) << "</p>\n";
  if (!o.command_line.empty()) h << "<p>Command: <code>" << html_escape(o.command_line) << "</code></p>\n";
  h << "<p>Reports: ";
  for (const SeriesEntry& e : entries) {
    h << "<a href=\"" << html_escape(fs::relative(e.directory / "report.html", dir).generic_string()) << "\">"
      << html_escape(e.series->name + " (" + e.series->regime.name + ")") << "</a> ";
  }
  h << "</p>\n";
  if (!verdicts.rows.empty()) {
    h << "<h2>Verdicts of the default</h2>\n"
      << html_table(verdict_totals_table(verdicts)) << html_table(verdict_table(verdicts));
  }
  for (const std::string& regime : regimes_of(entries)) {
    h << "<h2>" << html_escape(regime) << ": two-sided RMS / feature-region RMS (mm)</h2>\n"
      << html_table(regime_table(
             entries, regime, [](const MethodSummary& m) { return fixed(m.rms, 3) + " / " + fixed(m.feature_rms, 3); },
             [](const MethodSummary& m) { return m.rms; }));
  }
  const Table labels = label_table(entries);
  if (!labels.rows.empty()) h << "<h2>Feature labels</h2>\n" << html_table(labels);
  h << "<h2>Time per stage (the paper's Table 1)</h2>\n" << html_table(timing_table(entries));
  h << "<p>" << html_escape(definitions()) << "</p>\n</body></html>\n";
  write_text_atomically(dir / "report.html", h.str());
  written.push_back(dir / "report.html");
  return written;
}

}  // namespace contourmesh
