// SPDX-License-Identifier: BSD-3-Clause
// Writing comparisons: per series (one object in one regime, over seeds) metrics tables (CSV, JSON with
// every seed's numbers), the volume-shrinking curve (CSV and a PNG plot, the paper's Figure 13),
// flat-shaded renders of the methods from one camera (Figures 9-12), renders of the labels (Figure 6)
// and report.html; over several series a summary (CSV, JSON, HTML) with the verdicts, and a Markdown page.
// Every file is written atomically. Part of the contourmesh_compare target.
#pragma once

#include "compare/series.h"
#include "compare/verdicts.h"

#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace contourmesh {

struct ComparisonReportOptions {
  /// Render the meshes (VTK, offscreen). Debian's VTK draws through X: without a usable display
  /// (see rendering_available) the renders are skipped and the report says so.
  bool renders = true;
  int render_width = 640;
  int render_height = 480;
  /// Levels per colour channel in the renders (2 to 256): 32 halves the PNG files with no visible
  /// change on flat-shaded meshes (used for the pictures in the repository's docs).
  int color_levels = 256;
  /// Ids of the methods to render (and whose labels to render); empty: every method.
  std::vector<std::string> render_methods;
  /// Runs the renders (a call of write_renders) and returns "" on success or why they are missing.
  /// VTK aborts the whole process when the X display goes away, so a program that must survive that
  /// runs them in a child process here. Empty: in this process, an exception is the reason.
  std::function<std::string(const std::function<void()>& render)> isolate;
  /// The command that produced the comparison, quoted in the reports.
  std::string command_line;
  /// A paragraph added under the title of the reports (HTML escaped; Markdown as is).
  std::string note;
};

/// What write_series wrote.
struct ComparisonFiles {
  std::vector<std::filesystem::path> files;  ///< every file, in the order written
  bool rendered = false;
  std::string render_note;  ///< why the renders are missing, when they are
};

/// A series and where its files are, for the summary and the Markdown page.
struct SeriesEntry {
  const Series* series = nullptr;
  std::filesystem::path directory;
  ComparisonFiles files;
};

/// One row per method: the means over the seeds of the volumes, distances (two-sided RMS and Hausdorff,
/// feature and smooth regions, vertex RMS), normal errors, seconds, labels and detection scores. Empty
/// cells where a value does not apply.
[[nodiscard]] std::string metrics_csv(const Series& series);

/// The series as JSON: source, truth, regime, seeds, the means per method, and every run (per method:
/// settings, every metric, stages, labels, volume curve). null where a value does not apply.
[[nodiscard]] std::string metrics_json(const Series& series);

/// Columns: iteration, then the volume shrinking rate (V0 - Vk) / V0 of each iterative method.
[[nodiscard]] std::string volume_curve_csv(const Comparison& comparison);

/// Plots the volume curves (in %) against the iteration into a PNG, drawn without OpenGL (no display
/// needed). Throws InvalidInputError naming the file when it cannot be written.
void write_volume_curve_png(const Comparison& comparison, const std::filesystem::path& path, int width = 900,
                            int height = 520);

/// True when VTK can open a render window: an X display is reachable (DISPLAY set and the server
/// accepts a connection). Otherwise false, with the reason in `reason`. Run under `xvfb-run -a` on a
/// machine without a display.
[[nodiscard]] bool rendering_available(std::string* reason = nullptr);

/// The PNG files write_renders makes in `directory`: render_<id>.png per rendered method, and for each
/// rendered method with labels labels_<id>.png and (phantom) detection_<id>.png.
[[nodiscard]] std::vector<std::filesystem::path> render_files(const Comparison& comparison,
                                                              const std::filesystem::path& directory,
                                                              const ComparisonReportOptions& options);

/// Renders in this process (VTK may abort it when the display goes away: see
/// ComparisonReportOptions::isolate). Throws on failure.
void write_renders(const Comparison& comparison, const std::filesystem::path& directory,
                   const ComparisonReportOptions& options);

/// Writes into `directory` (created if missing): metrics.csv, metrics.json, volume_curve.csv,
/// volume_curve.png (of the first run), the renders of the first run when rendering is available and
/// enabled, and report.html linking them. Throws InvalidInputError naming the path when the directory
/// cannot be created or written.
ComparisonFiles write_series(const Series& series, const std::filesystem::path& directory,
                             const ComparisonReportOptions& options = {});

/// Writes summary.csv, summary.json and report.html (tables per regime, the verdicts) into `directory`
/// for several series already written with write_series (their reports are linked); returns the files.
std::vector<std::filesystem::path> write_summary(std::span<const SeriesEntry> entries,
                                                 const std::filesystem::path& directory,
                                                 const ComparisonReportOptions& options = {});

/// A Markdown page of the series (verdicts, tables per regime, detection, timing, renders of the default
/// and the voxel route) whose links are relative to the directory of `markdown_path`, written atomically.
void write_markdown(std::span<const SeriesEntry> entries, const std::filesystem::path& markdown_path,
                    const ComparisonReportOptions& options = {});

}  // namespace contourmesh
