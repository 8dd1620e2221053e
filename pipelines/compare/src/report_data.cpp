// SPDX-License-Identifier: BSD-3-Clause
#include "report_data.h"

#include "compare/report.h"
#include "report_format.h"

#include <algorithm>
#include <sstream>
#include <variant>

namespace contourmesh {

using namespace report_detail;

namespace report_detail {

namespace {

std::string key_name(const MethodKey& key) {
  return std::visit([](auto k) { return std::string(to_string(k)); }, key);
}

nlohmann::json region_json(const RegionAccuracy& r) {
  return {{"rms", json_number(r.rms)},
          {"hausdorff", json_number(r.hausdorff)},
          {"mesh_to_truth_rms", json_number(r.mesh_to_truth_rms)},
          {"truth_to_mesh_rms", json_number(r.truth_to_mesh_rms)},
          {"mesh_to_truth_max", json_number(r.mesh_to_truth_max)},
          {"truth_to_mesh_max", json_number(r.truth_to_mesh_max)},
          {"mean_signed", json_number(r.mean_signed)},
          {"normal_error_degrees", json_number(r.normal_error_degrees)},
          {"mesh_area_mm2", json_number(r.mesh_area)},
          {"truth_area_mm2", json_number(r.truth_area)}};
}

nlohmann::json labels_json(const LabelSummary& l) {
  nlohmann::json j = {{"edge", l.edges}, {"corner", l.corners}, {"noise", l.noise}};
  if (l.candidates) j["candidates"] = *l.candidates;
  if (l.adaptive_vertices > 0) {
    j["subdivided_vertices"] = l.subdivided_vertices;
    j["adaptive_vertices"] = l.adaptive_vertices;
  }
  if (l.true_features) {
    j["true_feature_vertices"] = *l.true_features;
    j["true_feature_vertices_on_contours"] = *l.examinable_true_features;
    j["detected_vertices"] = *l.detected;
    j["true_positives"] = *l.true_positives;
    j["true_positives_on_contours"] = *l.examinable_true_positives;
    j["precision"] = json_number(l.precision);
    j["recall"] = json_number(l.recall);
    j["recall_on_contours"] = json_number(l.recall_examinable);
  }
  return j;
}

nlohmann::json spec_json(const MethodSpec& s) {
  nlohmann::json j = {{"id", s.id},       {"title", s.title}, {"method", key_name(s.key)},
                      {"route", std::string(to_string(s.route))}, {"settings", s.settings}};
  j["preset"] = s.preset.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.preset);
  j["variant"] = s.variant;
  return j;
}

nlohmann::json seconds_json(const std::vector<StageTime>& seconds) {
  nlohmann::json j = nlohmann::json::object();
  for (const StageTime& s : seconds) j[s.stage] = json_number(s.seconds);
  return j;
}

}  // namespace

nlohmann::json comparison_json(const Comparison& c) {
  nlohmann::json j;
  j["source"] = c.source;
  j["truth"] = std::string(to_string(c.truth));
  j["truth_description"] = c.truth_description;
  j["truth_volume_mm3"] = c.truth_volume > 0.0 ? json_number(c.truth_volume) : nlohmann::json(nullptr);
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
  if (!c.true_features.empty()) {
    j["reconstruction"]["true_feature_vertices"] = std::count(c.true_features.begin(), c.true_features.end(), 1);
  }
  nlohmann::json methods = nlohmann::json::array();
  for (const MethodResult& m : c.methods) {
    nlohmann::json e = spec_json(m.spec);
    e["iterations"] = m.iterations;
    e["vertices"] = m.mesh.num_vertices();
    e["faces"] = m.mesh.num_faces();
    e["volume_input_mm3"] = json_number(m.volume_input);
    e["volume_output_mm3"] = json_number(m.volume_output);
    e["volume_change_percent"] = json_number(m.volume_change_percent);
    e["volume_error_percent"] = m.volume_error_percent ? json_number(*m.volume_error_percent) : nlohmann::json(nullptr);
    if (m.accuracy) {
      e["accuracy"] = {{"all", region_json(m.accuracy->all)},
                       {"feature", region_json(m.accuracy->feature)},
                       {"smooth", region_json(m.accuracy->smooth)},
                       {"vertex_rms", json_number(m.accuracy->vertex_rms)},
                       {"feature_vertex_rms", json_number(m.accuracy->feature_vertex_rms)}};
    } else {
      e["accuracy"] = nullptr;
    }
    e["seconds"] = seconds_json(m.seconds);
    e["labels"] = m.labels ? labels_json(*m.labels) : nlohmann::json(nullptr);
    nlohmann::json curve = nlohmann::json::array();
    for (double v : m.volume_curve) curve.push_back(json_number(v));
    e["volume_curve"] = curve;
    methods.push_back(e);
  }
  j["methods"] = methods;
  return j;
}

nlohmann::json summary_json(const MethodSummary& m) {
  nlohmann::json j = spec_json(m.spec);
  j["iterations"] = m.iterations;
  j["runs"] = m.runs;
  j["vertices"] = json_number(m.vertices);
  const std::pair<const char*, double> values[] = {
      {"rms_mm", m.rms},
      {"hausdorff_mm", m.hausdorff},
      {"feature_rms_mm", m.feature_rms},
      {"feature_hausdorff_mm", m.feature_hausdorff},
      {"smooth_rms_mm", m.smooth_rms},
      {"mesh_to_truth_rms_mm", m.mesh_to_truth_rms},
      {"truth_to_mesh_rms_mm", m.truth_to_mesh_rms},
      {"mean_signed_mm", m.mean_signed},
      {"normal_error_degrees", m.normal_error},
      {"feature_normal_error_degrees", m.feature_normal_error},
      {"smooth_normal_error_degrees", m.smooth_normal_error},
      {"vertex_rms_mm", m.vertex_rms},
      {"feature_vertex_rms_mm", m.feature_vertex_rms},
      {"volume_change_percent", m.volume_change_percent},
      {"volume_error_percent", m.volume_error_percent}};
  for (const auto& [name, value] : values) j[name] = json_number(value);
  j["seconds"] = seconds_json(m.seconds);
  if (m.has_labels) {
    j["labels"] = {{"edge", json_number(m.edges)},           {"corner", json_number(m.corners)},
                   {"noise", json_number(m.noise)},          {"precision", json_number(m.precision)},
                   {"recall", json_number(m.recall)},        {"recall_on_contours", json_number(m.recall_examinable)}};
  } else {
    j["labels"] = nullptr;
  }
  return j;
}

nlohmann::json series_json(const Series& s) {
  nlohmann::json j;
  j["name"] = s.name;
  j["regime"] = {{"name", s.regime.name},
                 {"ct_noise_hu", s.regime.ct_noise_hu},
                 {"contour_noise_mm", s.regime.contour_noise_mm}};
  j["seeds"] = s.seeds;
  j["truth"] = std::string(to_string(s.first().truth));
  j["truth_description"] = s.first().truth_description;
  nlohmann::json mean = nlohmann::json::array();
  for (const MethodSummary& m : s.mean) mean.push_back(summary_json(m));
  j["mean"] = mean;
  nlohmann::json runs = nlohmann::json::array();
  for (std::size_t k = 0; k < s.runs.size(); ++k) {
    nlohmann::json run = comparison_json(s.runs[k]);
    run["seed"] = k < s.seeds.size() ? nlohmann::json(s.seeds[k]) : nlohmann::json(nullptr);
    runs.push_back(run);
  }
  j["runs"] = runs;
  return j;
}

std::string summary_csv_header() {
  return "method,route,iterations,runs,vertices,rms_mm,hausdorff_mm,feature_rms_mm,feature_hausdorff_mm,smooth_rms_mm,"
         "mesh_to_truth_rms_mm,truth_to_mesh_rms_mm,mean_signed_mm,normal_error_deg,feature_normal_error_deg,"
         "smooth_normal_error_deg,vertex_rms_mm,feature_vertex_rms_mm,volume_change_percent,volume_error_percent,"
         "seconds_detect,seconds_subdivide,seconds_threshold,seconds_surface,seconds_smooth,seconds_total,edge,corner,"
         "noise,precision,recall,recall_on_contours";
}

std::string summary_csv_row(const MethodSummary& m) {
  std::ostringstream s;
  s << m.spec.id << "," << to_string(m.spec.route) << "," << m.iterations << "," << m.runs << ","
    << csv_number(m.vertices);
  for (double v : {m.rms, m.hausdorff, m.feature_rms, m.feature_hausdorff, m.smooth_rms, m.mesh_to_truth_rms,
                   m.truth_to_mesh_rms, m.mean_signed, m.normal_error, m.feature_normal_error, m.smooth_normal_error,
                   m.vertex_rms, m.feature_vertex_rms, m.volume_change_percent, m.volume_error_percent}) {
    s << "," << csv_number(v);
  }
  for (const char* stage : {"detect", "subdivide", "threshold", "surface", "smooth", "total"}) {
    const bool has =
        std::any_of(m.seconds.begin(), m.seconds.end(), [&](const StageTime& t) { return t.stage == stage; });
    s << "," << (has ? csv_number(m.stage_seconds(stage)) : "");
  }
  for (double v : {m.edges, m.corners, m.noise, m.precision, m.recall, m.recall_examinable}) s << "," << csv_number(v);
  return s.str();
}

}  // namespace report_detail

std::string metrics_csv(const Series& series) {
  std::ostringstream s;
  s << summary_csv_header() << "\n";
  for (const MethodSummary& m : series.mean) s << summary_csv_row(m) << "\n";
  return s.str();
}

std::string metrics_json(const Series& series) { return series_json(series).dump(2) + "\n"; }

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
  for (const MethodResult* m : curves) s << "," << m->spec.id;
  s << "\n";
  for (std::size_t k = 0; k < rows; ++k) {
    s << k;
    for (const MethodResult* m : curves) s << "," << (k < m->volume_curve.size() ? csv_number(m->volume_curve[k]) : "");
    s << "\n";
  }
  return s.str();
}

}  // namespace contourmesh
