// Writing a comparison (comparison.h): metrics tables (CSV, JSON), the volume-shrinking curve (CSV and a
// PNG plot, the paper's Figure 13), flat-shaded renders of every method from one camera (Figures
// 9-12), a render of the feature labels (Figure 6), a timing table (Table 1) and report.html. Several
// comparisons (one per phantom) also get a summary. Every file is written atomically.
#pragma once

#include "pipelines/comparison.h"

#include <filesystem>
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
  /// The command that produced the comparison, quoted in the reports.
  std::string command_line;
  /// A paragraph added under the title of the reports (HTML escaped; Markdown as is).
  std::string note;
};

/// What write_comparison wrote.
struct ComparisonFiles {
  std::vector<std::filesystem::path> files;  ///< every file, in the order written
  bool rendered = false;
  std::string render_note;  ///< why the renders are missing, when they are
};

/// One comparison of a set (e.g. one phantom of `--phantom all`), for the summary.
struct ComparisonEntry {
  std::string name;                 ///< e.g. the phantom's name
  std::filesystem::path directory;  ///< where its files are
  const Comparison* comparison = nullptr;
  ComparisonFiles files;
};

/// One row per method: volumes, distance and normal error (all / feature / smooth), seconds per
/// stage, the paper's label counts and detection scores. Empty cells where a value does not apply.
[[nodiscard]] std::string metrics_csv(const Comparison& comparison);

/// The same as a JSON document (null where a value does not apply or is not finite), plus the source,
/// the truth, the reconstruction and each method's settings and volume curve.
[[nodiscard]] std::string metrics_json(const Comparison& comparison);

/// Columns: iteration, then the volume shrinking rate (V0 - Vk) / V0 of each iterative method.
[[nodiscard]] std::string volume_curve_csv(const Comparison& comparison);

/// Plots the volume curves (in %) against the iteration into a PNG, drawn without OpenGL (no display
/// needed). Throws InvalidInputError naming the file when it cannot be written.
void write_volume_curve_png(const Comparison& comparison, const std::filesystem::path& path, int width = 900,
                            int height = 520);

/// The timing table of the paper's Table 1 for one or several comparisons, as Markdown: per volume
/// the contour mesh's size, the paper's detect / subdivide / smooth / total, Taubin and
/// vtkWindowedSincPolyDataFilter on the same mesh, and the voxel route.
[[nodiscard]] std::string timing_table_markdown(std::span<const ComparisonEntry> entries);

/// True when VTK can open a render window: an X display is reachable (DISPLAY set and the server
/// accepts a connection). Otherwise false, with the reason in `reason`. Run under `xvfb-run -a` on a
/// machine without a display.
[[nodiscard]] bool rendering_available(std::string* reason = nullptr);

/// Writes into `directory` (created if missing): metrics.csv, metrics.json, volume_curve.csv,
/// volume_curve.png, render_<method>.png for every method and labels.png (the paper's labels on the
/// contour mesh: edge green, corner blue, noise red) and, for a phantom, detection.png (true feature
/// vertices found / missed, false detections) when rendering is available and enabled (in a child
/// process: VTK aborts when the X display goes away, and the rest must survive that), and
/// report.html linking them. Throws InvalidInputError naming the path when the directory cannot be
/// created or written.
ComparisonFiles write_comparison(const Comparison& comparison, const std::filesystem::path& directory,
                                 const ComparisonReportOptions& options = {});

/// Writes summary.csv, summary.json and report.html into `directory` for several comparisons already
/// written with write_comparison (their reports are linked); returns the files written.
std::vector<std::filesystem::path> write_comparison_summary(std::span<const ComparisonEntry> entries,
                                                            const std::filesystem::path& directory,
                                                            const ComparisonReportOptions& options = {});

/// A Markdown page of the comparisons (tables and pictures) whose links are relative to the directory
/// of `markdown_path`, written atomically there.
void write_comparison_markdown(std::span<const ComparisonEntry> entries, const std::filesystem::path& markdown_path,
                               const ComparisonReportOptions& options = {});

}  // namespace contourmesh
