// SPDX-License-Identifier: BSD-3-Clause
#include "compare/report.h"

#include "comparison_render.h"

#include <algorithm>

namespace contourmesh {

namespace fs = std::filesystem;

namespace {

bool rendered(const MethodResult& m, const ComparisonReportOptions& o) {
  return o.render_methods.empty() ||
         std::find(o.render_methods.begin(), o.render_methods.end(), m.spec.id) != o.render_methods.end();
}

}  // namespace

bool rendering_available(std::string* reason) { return detail::x_display_available(reason); }

std::vector<fs::path> render_files(const Comparison& c, const fs::path& dir, const ComparisonReportOptions& o) {
  std::vector<fs::path> files;
  for (const MethodResult& m : c.methods) {
    if (!rendered(m, o)) continue;
    files.push_back(dir / ("render_" + m.spec.id + ".png"));
    if (!m.vertex_labels.empty()) {
      files.push_back(dir / ("labels_" + m.spec.id + ".png"));
      if (!c.true_features.empty()) files.push_back(dir / ("detection_" + m.spec.id + ".png"));
    }
  }
  return files;
}

void write_renders(const Comparison& c, const fs::path& dir, const ComparisonReportOptions& o) {
  detail::SceneRenderer renderer(c.contour_mesh, o.render_width, o.render_height, o.color_levels);
  for (const MethodResult& m : c.methods) {
    if (!rendered(m, o)) continue;
    renderer.surface(m.mesh, m.spec.title, dir / ("render_" + m.spec.id + ".png"));
    if (m.vertex_labels.empty()) continue;
    // The labels on the contour mesh (the paper's Figure 6): edge green, corner blue, noise red.
    std::vector<int> group(m.vertex_labels.size(), -1);
    for (std::size_t i = 0; i < m.vertex_labels.size(); ++i) {
      switch (m.vertex_labels[i]) {
        case VertexLabel::Edge: group[i] = 0; break;
        case VertexLabel::Corner: group[i] = 1; break;
        case VertexLabel::Noise: group[i] = 2; break;
        default: break;
      }
    }
    renderer.points(
        c.contour_mesh, group,
        {{"edge", {0.0, 0.65, 0.0}, 6.0}, {"corner", {0.1, 0.3, 1.0}, 12.0}, {"noise", {0.9, 0.1, 0.1}, 6.0}},
        "labels: " + m.spec.title, dir / ("labels_" + m.spec.id + ".png"));
    if (c.true_features.empty()) continue;
    // Against the truth: true feature vertices found and missed, false detections.
    for (std::size_t i = 0; i < m.vertex_labels.size(); ++i) {
      const bool detected = m.vertex_labels[i] == VertexLabel::Edge || m.vertex_labels[i] == VertexLabel::Corner;
      group[i] = c.true_features[i] ? (detected ? 0 : 1) : (detected ? 2 : -1);
    }
    renderer.points(c.contour_mesh, group,
                    {{"true feature, found", {0.0, 0.65, 0.0}, 6.0},
                     {"true feature, missed", {1.0, 0.55, 0.0}, 6.0},
                     {"false detection", {0.9, 0.1, 0.1}, 6.0}},
                    "detection vs. true features: " + m.spec.title, dir / ("detection_" + m.spec.id + ".png"));
  }
}

}  // namespace contourmesh
