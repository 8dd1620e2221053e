// SPDX-License-Identifier: BSD-3-Clause
// Private to the reports: tables as rows of cells, rendered as Markdown or HTML, and the tables the
// reports are made of (accuracy per series, methods x phantoms per regime, labels, timing, verdicts).
#pragma once

#include "compare/report.h"

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace contourmesh::report_detail {

struct Cell {
  std::string text;
  bool best = false;  ///< bold / highlighted
  bool fail = false;  ///< a missed bar
};

struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<Cell>> rows;
};

[[nodiscard]] std::string markdown_table(const Table& table);
[[nodiscard]] std::string html_table(const Table& table);

/// True for the methods that are ranked: everything but the unsmoothed meshes.
[[nodiscard]] bool smoothed(const MethodSpec& spec);

/// Per method of a series (means over its seeds): distances, normals, volume, seconds.
[[nodiscard]] Table accuracy_table(const Series& series);

/// Methods (rows) x the entries' objects (columns) of one regime; each cell from `cell`, the smoothed
/// method with the lowest `rank` value of a column in bold.
[[nodiscard]] Table regime_table(std::span<const SeriesEntry> entries, const std::string& regime,
                                 const std::function<std::string(const MethodSummary&)>& cell,
                                 const std::function<double(const MethodSummary&)>& rank);

/// The regimes of the entries, in order of first appearance.
[[nodiscard]] std::vector<std::string> regimes_of(std::span<const SeriesEntry> entries);

/// Per series and method with labels: counts, precision, recall over all true features and over those
/// on contours.
[[nodiscard]] Table label_table(std::span<const SeriesEntry> entries);

/// Per series: contour mesh size, reconstruction time, the default's and the xu2006 preset's stages,
/// Taubin, vtkWindowedSincPolyDataFilter and the voxel route.
[[nodiscard]] Table timing_table(std::span<const SeriesEntry> entries);

/// Per phantom and regime, the four bars; and the totals.
[[nodiscard]] Table verdict_table(const Verdicts& verdicts);
[[nodiscard]] Table verdict_totals_table(const Verdicts& verdicts);

}  // namespace contourmesh::report_detail
