// SPDX-License-Identifier: BSD-3-Clause
#include "report_tables.h"

#include "report_format.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace contourmesh::report_detail {

namespace {


std::string mm(double v) { return fixed(v, 3); }

// Index of the smoothed method with the smallest value (NaN ignored), or -1.
int best_of(const std::vector<MethodSummary>& methods, const std::function<double(const MethodSummary&)>& value) {
  int best = -1;
  double best_value = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < methods.size(); ++i) {
    if (!smoothed(methods[i].spec)) continue;
    const double v = value(methods[i]);
    if (std::isfinite(v) && v < best_value) {
      best_value = v;
      best = static_cast<int>(i);
    }
  }
  return best;
}

// A cell's text for Markdown: '|' escaped (it would end the cell), bold when best.
std::string cell_text(const Cell& c) {
  std::string text;
  for (char ch : c.text) text += ch == '|' ? std::string("\\|") : std::string(1, ch);
  return c.best && !text.empty() ? "**" + text + "**" : text;
}

}  // namespace

std::string markdown_table(const Table& t) {
  std::ostringstream s;
  s << "|";
  for (const std::string& h : t.header) s << " " << h << " |";
  s << "\n|";
  for (std::size_t i = 0; i < t.header.size(); ++i) s << " --- |";
  s << "\n";
  for (const auto& row : t.rows) {
    s << "|";
    for (const Cell& cell : row) s << " " << cell_text(cell) << " |";
    s << "\n";
  }
  return s.str();
}

std::string html_table(const Table& t) {
  std::ostringstream s;
  s << "<table>\n<tr>";
  for (const std::string& h : t.header) s << "<th>" << html_escape(h) << "</th>";
  s << "</tr>\n";
  for (const auto& row : t.rows) {
    s << "<tr>";
    for (const Cell& cell : row) {
      s << (cell.best ? "<td class=\"best\">" : cell.fail ? "<td class=\"fail\">" : "<td>") << html_escape(cell.text)
        << "</td>";
    }
    s << "</tr>\n";
  }
  s << "</table>\n";
  return s.str();
}

bool smoothed(const MethodSpec& spec) {
  return spec.key != MethodKey(SmoothingMethod::None) && spec.key != MethodKey(ExternalMethod::VoxelFlyingEdges);
}

Table accuracy_table(const Series& series) {
  const Comparison& c = series.first();
  const bool phantom = c.truth == TruthKind::Phantom;
  const bool distance = c.truth != TruthKind::None;
  Table t;
  t.header = {"method", "route", "iterations", "vertices"};
  if (distance) t.header.insert(t.header.end(), {"RMS mm", "Hausdorff mm"});
  if (phantom) {
    t.header.insert(t.header.end(), {"feature RMS mm", "smooth RMS mm", "normal err. deg", "feature normal err. deg",
                                     "mean signed mm"});
  }
  if (distance) t.header.push_back("vertex RMS mm");
  t.header.push_back("volume change %");
  if (phantom) t.header.push_back("volume vs truth %");
  t.header.push_back("seconds");
  const auto& m = series.mean;
  const int best_rms = best_of(m, [](const MethodSummary& s) { return s.rms; });
  const int best_hausdorff = best_of(m, [](const MethodSummary& s) { return s.hausdorff; });
  const int best_feature = best_of(m, [](const MethodSummary& s) { return s.feature_rms; });
  const int best_normal = best_of(m, [](const MethodSummary& s) { return s.normal_error; });
  const int best_volume = best_of(m, [](const MethodSummary& s) { return std::abs(s.volume_error_percent); });
  for (std::size_t i = 0; i < m.size(); ++i) {
    const MethodSummary& s = m[i];
    const int k = static_cast<int>(i);
    std::vector<Cell> row = {{s.spec.title},
                             {std::string(to_string(s.spec.route))},
                             {s.iterations > 0 ? std::to_string(s.iterations) : "-"},
                             {fixed(s.vertices, 0)}};
    if (distance) {
      row.push_back({mm(s.rms), k == best_rms});
      row.push_back({mm(s.hausdorff), k == best_hausdorff});
    }
    if (phantom) {
      row.push_back({mm(s.feature_rms), k == best_feature});
      row.push_back({mm(s.smooth_rms)});
      row.push_back({fixed(s.normal_error, 2), k == best_normal});
      row.push_back({fixed(s.feature_normal_error, 2)});
      row.push_back({signed_fixed(s.mean_signed, 3)});
    }
    if (distance) row.push_back({mm(s.vertex_rms)});
    row.push_back({signed_fixed(s.volume_change_percent, 2)});
    if (phantom) row.push_back({signed_fixed(s.volume_error_percent, 2), k == best_volume});
    row.push_back({fixed(s.stage_seconds("total"), 3)});
    t.rows.push_back(std::move(row));
  }
  return t;
}

std::vector<std::string> regimes_of(std::span<const SeriesEntry> entries) {
  std::vector<std::string> regimes;
  for (const SeriesEntry& e : entries) {
    if (std::find(regimes.begin(), regimes.end(), e.series->regime.name) == regimes.end()) {
      regimes.push_back(e.series->regime.name);
    }
  }
  return regimes;
}

Table regime_table(std::span<const SeriesEntry> entries, const std::string& regime,
                   const std::function<std::string(const MethodSummary&)>& cell,
                   const std::function<double(const MethodSummary&)>& rank) {
  std::vector<const Series*> columns;
  for (const SeriesEntry& e : entries) {
    if (e.series->regime.name == regime) columns.push_back(e.series);
  }
  Table t;
  t.header = {"method"};
  std::vector<std::string> ids, titles;
  for (const Series* s : columns) {
    t.header.push_back(s->name);
    for (const MethodSummary& m : s->mean) {
      if (std::find(ids.begin(), ids.end(), m.spec.id) == ids.end()) {
        ids.push_back(m.spec.id);
        titles.push_back(m.spec.title);
      }
    }
  }
  for (std::size_t i = 0; i < ids.size(); ++i) {
    std::vector<Cell> row = {{titles[i]}};
    for (const Series* s : columns) {
      const MethodSummary* m = s->find(ids[i]);
      const int best = best_of(s->mean, rank);
      const bool is_best = m != nullptr && best >= 0 && &s->mean[static_cast<std::size_t>(best)] == m;
      row.push_back({m ? cell(*m) : "", is_best});
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

Table label_table(std::span<const SeriesEntry> entries) {
  Table t;
  t.header = {"regime", "phantom", "method", "edge", "corner", "noise", "precision", "recall (all)",
              "recall (on contours)"};
  for (const SeriesEntry& e : entries) {
    for (const MethodSummary& m : e.series->mean) {
      if (!m.has_labels) continue;
      const bool pass = m.precision >= 0.8 && m.recall >= 0.7;
      t.rows.push_back({{e.series->regime.name},
                        {e.series->name},
                        {m.spec.title},
                        {fixed(m.edges, 0)},
                        {fixed(m.corners, 0)},
                        {fixed(m.noise, 0)},
                        {fixed(m.precision, 3), pass},
                        {fixed(m.recall, 3), pass},
                        {fixed(m.recall_examinable, 3)}});
    }
  }
  return t;
}

Table timing_table(std::span<const SeriesEntry> entries) {
  Table t;
  const MethodKey default_key = preset(Preset::Default).method;
  t.header = {"volume",          "contour mesh vertices", "segment + tile s", "default: smooth s",
              "detect s",        "total s",               "xu2006: detect s", "subdivide s",
              "smooth s",        "total s",               "Taubin s",         "vtkWindowedSinc s",
              "default / windowed sinc", "voxel mesh vertices", "voxel: threshold + flying edges s",
              "voxel: windowed sinc s"};
  for (const SeriesEntry& e : entries) {
    const Series& s = *e.series;
    const Comparison& c = s.first();
    const MethodSummary* d = s.find(default_key);
    const MethodSummary* xu = s.find(SmoothingMethod::FeaturePreserving);
    const MethodSummary* taubin = s.find(SmoothingMethod::Taubin);
    const MethodSummary* sinc = s.find(ExternalMethod::VtkWindowedSinc);
    const MethodSummary* voxel = s.find(ExternalMethod::VoxelWindowedSinc);
    const auto sec = [](const MethodSummary* m, const char* stage) {
      return m ? fixed(m->stage_seconds(stage), 3) : "";
    };
    std::string ratio;
    if (d && sinc && sinc->stage_seconds("total") > 0.0) {
      ratio = fixed(d->stage_seconds("total") / sinc->stage_seconds("total"), 1);
    }
    t.rows.push_back({{s.name + (entries.size() > 1 ? " (" + s.regime.name + ")" : "")},
                      {std::to_string(c.contour_mesh.num_vertices())},
                      {fixed(c.reconstruction.seconds_segment + c.reconstruction.seconds_tile, 3)},
                      {sec(d, "smooth")},
                      {sec(d, "detect")},
                      {sec(d, "total")},
                      {sec(xu, "detect")},
                      {sec(xu, "subdivide")},
                      {sec(xu, "smooth")},
                      {sec(xu, "total")},
                      {sec(taubin, "total")},
                      {sec(sinc, "total")},
                      {ratio},
                      {voxel ? fixed(voxel->vertices, 0) : ""},
                      {voxel ? fixed(voxel->stage_seconds("threshold") + voxel->stage_seconds("surface"), 3) : ""},
                      {sec(voxel, "smooth")}});
  }
  return t;
}

Table verdict_table(const Verdicts& v) {
  Table t;
  t.header = {"regime", "phantom", "1. do no harm", "2. beat the voxel route", "3. denoise", "4. detection"};
  const auto cell = [](const BarVerdict& b) {
    if (b.state == BarState::NotApplicable) return Cell{"-"};
    return Cell{std::string(to_string(b.state)) + ": " + b.detail, false, b.state == BarState::Fail};
  };
  for (const VerdictRow& r : v.rows) {
    t.rows.push_back({{r.regime}, {r.phantom + (r.original ? "" : " (new)")}, cell(r.harm), cell(r.voxel),
                      cell(r.denoise), cell(r.detection)});
  }
  return t;
}

Table verdict_totals_table(const Verdicts& v) {
  Table t;
  t.header = {"bar", "regime", "passed", "of the seven original phantoms", "required", "met"};
  for (const BarTotal& b : v.totals) {
    const std::string required =
        b.required > 0 ? std::to_string(b.required) + " of 7" : "every phantom (" + std::to_string(b.rows) + ")";
    t.rows.push_back({{b.bar},
                      {b.regime},
                      {std::to_string(b.passed) + " of " + std::to_string(b.rows)},
                      {std::to_string(b.original_passed) + " of " + std::to_string(b.original_rows)},
                      {required},
                      {b.met() ? "yes" : "no", false, !b.met()}});
  }
  return t;
}

}  // namespace contourmesh::report_detail
