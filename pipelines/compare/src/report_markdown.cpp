// SPDX-License-Identifier: BSD-3-Clause
// write_markdown: the page docs/results.md is made of.
#include "compare/report.h"

#include "report_format.h"
#include "report_tables.h"

#include <contourmesh/vtk/atomic_file.h>

#include <cmath>
#include <functional>
#include <set>
#include <sstream>

namespace contourmesh {

namespace fs = std::filesystem;
using namespace report_detail;

namespace {

std::string regime_description(const Regime& r) {
  std::ostringstream s;
  if (r.contour()) {
    s << "contour noise of " << r.contour_noise_mm << " mm RMS per slice (the paper's noise model) at " << r.ct_noise_hu
      << " HU of CT noise";
  } else {
    s << r.ct_noise_hu << " HU of CT noise";
  }
  return s.str();
}

std::string seeds_of(std::span<const SeriesEntry> entries) {
  std::set<std::uint64_t> seen;
  std::ostringstream s;
  for (const SeriesEntry& e : entries) {
    for (std::uint64_t seed : e.series->seeds) {
      if (seen.insert(seed).second) s << (seen.size() > 1 ? ", " : "") << seed;
    }
  }
  return s.str();
}

}  // namespace

namespace {

void header(std::ostringstream& s, std::span<const SeriesEntry> entries, const std::vector<std::string>& regimes,
            const ComparisonReportOptions& o) {
  s << "# Results: the default smoothing against the unsmoothed mesh, the paper's method, the baselines, VTK's "
       "filters and 3D Slicer's voxel route\n\n"
    << "Generated from a real run of `contourmesh compare`; do not edit by hand. To regenerate (under "
       "`xvfb-run -a` on a machine without a display, for the renders):\n\n```sh\n"
    << (o.command_line.empty() ? std::string("contourmesh compare --phantom all --out DIR") : o.command_line)
    << "\n```\n\n";
  if (!o.note.empty()) s << o.note << "\n\n";
  if (entries.empty()) return;
  s << "Every method starts from the same reconstructed contour mesh of a phantom's CT volume; the voxel route "
       "starts from the same volume and threshold. Regimes: ";
  bool first = true;
  for (const std::string& name : regimes) {
    for (const SeriesEntry& e : entries) {
      if (e.series->regime.name != name) continue;
      s << (first ? "" : "; ") << "**" << name << "**: " << regime_description(e.series->regime);
      first = false;
      break;
    }
  }
  const std::string seeds = seeds_of(entries);
  if (!seeds.empty())
    s << ". Every number is the mean over the noise seeds " << seeds << " (metrics.json keeps each seed's)";
  s << ". Method settings:\n\n";
  for (const MethodResult& m : entries.front().series->first().methods) {
    s << "- **" << m.spec.title << "** (`" << m.spec.id << "`): " << m.spec.settings << "\n";
  }
  s << "\n";
}

void verdict_section(std::ostringstream& s, std::span<const SeriesEntry> entries) {
  std::vector<const Series*> all;
  for (const SeriesEntry& e : entries) all.push_back(e.series);
  const Verdicts verdicts = judge(all);
  if (verdicts.rows.empty()) return;
  s << "## Verdicts of the default\n\n"
    << "The bars, judged on the means over the seeds: **1. do no harm** (CT noise): two-sided RMS and feature-region "
       "RMS at most 1.05 x the unsmoothed mesh's + 0.01 mm, normal error at most 0.7 x; **2. beat the voxel route** "
       "(20 HU): two-sided RMS at most 3D Slicer's voxel route's, on at least 5 of the 7 original phantoms; "
       "**3. denoise** (contour noise): RMS at most 0.6 x the unsmoothed mesh's, feature RMS at most 0.7 x, the "
       "lowest RMS of all methods, |volume - true volume| at most the unsmoothed mesh's + 0.3 % of the true volume, "
       "on at least 6 of 7; **4. detection**: edge + corner labels with precision >= 0.8 and recall >= 0.7 against "
       "the vertices within 1.5 mm of a true feature, in every regime. Phantoms marked (new) are not among the "
       "seven original ones that bars 2 and 3 count.\n\n"
    << markdown_table(verdict_totals_table(verdicts)) << "\n"
    << markdown_table(verdict_table(verdicts)) << "\n";
}

void regime_section(std::ostringstream& s, std::span<const SeriesEntry> entries, const std::string& regime) {
  s << "## " << regime << "\n\n";
  s << "Two-sided RMS / feature-region RMS distance to the true surface (mm); bold: the lowest RMS of the smoothed "
       "methods.\n\n"
    << markdown_table(regime_table(
           entries, regime, [](const MethodSummary& m) { return fixed(m.rms, 3) + " / " + fixed(m.feature_rms, 3); },
           [](const MethodSummary& m) { return m.rms; }))
    << "\nArea-weighted normal error (degrees) / Hausdorff distance (mm); bold: the lowest normal error.\n\n"
    << markdown_table(regime_table(
           entries, regime,
           [](const MethodSummary& m) { return fixed(m.normal_error, 2) + " / " + fixed(m.hausdorff, 2); },
           [](const MethodSummary& m) { return m.normal_error; }))
    << "\nVolume against the true volume (%) / vertex RMS (mm, secondary); bold: the smallest |volume error|.\n\n"
    << markdown_table(regime_table(
           entries, regime,
           [](const MethodSummary& m) {
             return signed_fixed(m.volume_error_percent, 2) + " / " + fixed(m.vertex_rms, 3);
           },
           [](const MethodSummary& m) { return std::abs(m.volume_error_percent); }))
    << "\n";
}

void render_section(std::ostringstream& s, std::span<const SeriesEntry> entries,
                    const std::function<std::string(const fs::path&)>& link) {
  s << "## Renders\n\nThe first seed's meshes, from one camera, flat shaded. Full reports per phantom and regime: ";
  for (const SeriesEntry& e : entries) {
    s << "[" << e.series->name << " " << e.series->regime.name << "](" << link(e.directory / "report.html") << ") ";
  }
  s << "\n\n";
  const MethodKey default_key = preset(Preset::Default).method;
  for (const SeriesEntry& e : entries) {
    const Comparison& c = e.series->first();
    if (!e.files.rendered) continue;
    s << "### " << e.series->name << ", " << e.series->regime.name << "\n\n";
    for (const MethodKey& key :
         {default_key, MethodKey(ExternalMethod::VoxelWindowedSinc), MethodKey(SmoothingMethod::None)}) {
      const MethodResult* m = c.find(key);
      if (!m) continue;
      const fs::path png = e.directory / ("render_" + m->spec.id + ".png");
      if (fs::exists(png)) s << "<img src=\"" << link(png) << "\" width=\"32%\" alt=\"" << m->spec.id << "\"> ";
    }
    if (const MethodResult* d = c.find(default_key)) {
      const fs::path detection = e.directory / ("detection_" + d->spec.id + ".png");
      if (fs::exists(detection)) s << "\n<img src=\"" << link(detection) << "\" width=\"32%\" alt=\"detection\">";
    }
    s << "\n\n";
  }
}

}  // namespace

void write_markdown(std::span<const SeriesEntry> entries, const fs::path& markdown_path,
                    const ComparisonReportOptions& o) {
  const fs::path base = markdown_path.has_parent_path() ? markdown_path.parent_path() : fs::path(".");
  const auto link = [&](const fs::path& file) { return fs::relative(file, base).generic_string(); };
  const std::vector<std::string> regimes = regimes_of(entries);
  std::ostringstream s;
  header(s, entries, regimes, o);
  verdict_section(s, entries);
  for (const std::string& regime : regimes) regime_section(s, entries, regime);
  const Table labels = label_table(entries);
  if (!labels.rows.empty()) {
    s << "## Feature labels\n\nBold: both bars of detection met (precision >= 0.8, recall >= 0.7).\n\n"
      << markdown_table(labels) << "\n";
  }
  if (!entries.empty()) {
    // Timing of the first regime (the work does not depend on the noise much).
    std::vector<SeriesEntry> first_regime;
    for (const SeriesEntry& e : entries) {
      if (e.series->regime.name == regimes.front()) first_regime.push_back(e);
    }
    s << "## Time per stage (the paper's Table 1), seconds, " << regimes.front() << "\n\n"
      << markdown_table(timing_table(first_regime)) << "\n";
  }
  s << "## Definitions\n\n" << definitions() << "\n\n";
  render_section(s, entries, link);
  write_text_atomically(markdown_path, s.str());
}

}  // namespace contourmesh
