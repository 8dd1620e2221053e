// SPDX-License-Identifier: BSD-3-Clause
// Private to the reports: number formatting for text, CSV, HTML and JSON, and the definitions paragraph.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>

namespace contourmesh::report_detail {

/// `digits` decimals; "" for a non-finite value.
[[nodiscard]] std::string fixed(double v, int digits);
/// The same with a sign: "+0.12", "-3.40".
[[nodiscard]] std::string signed_fixed(double v, int digits);
/// Nine significant digits; "" for a non-finite or missing value.
[[nodiscard]] std::string csv_number(double v);
[[nodiscard]] std::string csv_number(std::optional<double> v);
/// &, <, >, " escaped.
[[nodiscard]] std::string html_escape(const std::string& text);
/// A JSON number, or null when not finite.
[[nodiscard]] nlohmann::json json_number(double v);

/// Creates `directory` (and parents) and checks that files can be written in it; throws
/// InvalidInputError naming it otherwise.
void ensure_directory(const std::filesystem::path& directory);

/// What the reports' numbers mean (HTML-escape it for HTML).
[[nodiscard]] const char* definitions();

/// The style sheet of the HTML reports.
[[nodiscard]] const char* html_style();

}  // namespace contourmesh::report_detail
