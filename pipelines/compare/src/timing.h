// SPDX-License-Identifier: BSD-3-Clause
// Private helper of the comparison: wall-clock timing of a method's stages over repeated runs.
#pragma once

#include <algorithm>
#include <chrono>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace contourmesh::compare_detail {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// Called by a timed body for each stage it ran.
using StageRecorder = std::function<void(const std::string& stage, double seconds)>;

/// Runs `body` `repeats` times (what the last run computes is what `body` keeps) and returns the fastest
/// time of each stage it recorded, then "total" (the fastest sum).
inline std::vector<std::pair<std::string, double>> timed(int repeats,
                                                         const std::function<void(const StageRecorder&)>& body) {
  std::vector<std::pair<std::string, double>> best;
  for (int r = 0; r < std::max(repeats, 1); ++r) {
    std::vector<std::pair<std::string, double>> run;
    body([&](const std::string& stage, double seconds) { run.emplace_back(stage, seconds); });
    double total = 0.0;
    for (const auto& s : run) total += s.second;
    run.emplace_back("total", total);
    if (best.empty()) {
      best = std::move(run);
    } else {
      for (std::size_t i = 0; i < best.size() && i < run.size(); ++i)
        best[i].second = std::min(best[i].second, run[i].second);
    }
  }
  return best;
}

}  // namespace contourmesh::compare_detail
