// SPDX-License-Identifier: BSD-3-Clause
// Private to the reports: the JSON and CSV forms of comparisons, method summaries and series.
#pragma once

#include "compare/series.h"

#include <nlohmann/json.hpp>

#include <string>

namespace contourmesh::report_detail {

/// One run: source, truth, reconstruction, and per method every metric, stage, label score and curve.
[[nodiscard]] nlohmann::json comparison_json(const Comparison& comparison);
/// One method's numbers (a run's or the mean over seeds).
[[nodiscard]] nlohmann::json summary_json(const MethodSummary& summary);
/// A series: name, regime, seeds, the means, and every run.
[[nodiscard]] nlohmann::json series_json(const Series& series);

/// The CSV columns of a method summary (after any leading columns of the caller), and one row.
[[nodiscard]] std::string summary_csv_header();
[[nodiscard]] std::string summary_csv_row(const MethodSummary& summary);

}  // namespace contourmesh::report_detail
