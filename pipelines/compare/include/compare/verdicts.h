// SPDX-License-Identifier: BSD-3-Clause
// The quality bars of the default smoothing (docs/results.md, "Verdicts"), judged per phantom and regime
// on the means over seeds:
// 1. Do no harm (CT-noise regimes): two-sided RMS and feature-region RMS at most 1.05 x the unsmoothed
//    mesh's + 0.01 mm, normal error at most 0.7 x.
// 2. Beat the voxel route (CT noise at 20 HU): two-sided RMS at most 3D Slicer's voxel route's.
// 3. Denoise (contour-noise regimes): two-sided RMS at most 0.6 x the unsmoothed mesh's, feature-region
//    RMS at most 0.7 x, the lowest two-sided RMS of all standard methods, and |volume - true volume| at
//    most the unsmoothed mesh's + 0.3 % of the true volume.
// 4. Detection (every regime): the default's edge + corner labels reach precision 0.8 and recall 0.7
//    against the contour-mesh vertices within the detection radius of a true feature.
// Part of the contourmesh_compare target.
#pragma once

#include "compare/series.h"

#include <span>
#include <string>
#include <vector>

namespace contourmesh {

enum class BarState { NotApplicable, Pass, Fail, Missing };

/// One bar on one series: its state and the numbers behind it, in words.
struct BarVerdict {
  BarState state = BarState::NotApplicable;
  std::string detail;
};

struct VerdictRow {
  std::string phantom;
  std::string regime;
  bool original = false;  ///< one of the seven phantoms the bars 2 and 3 count (ridge-box ... cavity)
  BarVerdict harm, voxel, denoise, detection;
};

/// A bar over every row it applies to: passes and rows (and for bars 2 and 3 those of the original seven
/// phantoms, against the required count).
struct BarTotal {
  std::string bar;      ///< "1. do no harm", ...
  std::string regime;   ///< the regime the count is over
  int passed = 0, rows = 0;
  int original_passed = 0, original_rows = 0;
  int required = 0;  ///< passes required among the original phantoms (bars 2, 3), or all rows (0)
  [[nodiscard]] bool met() const;
};

struct Verdicts {
  std::vector<VerdictRow> rows;
  std::vector<BarTotal> totals;
};

/// Judges the default method (libsmooth's Preset::Default) of every series with a phantom truth. Series
/// without the default, the unsmoothed mesh or the voxel route give BarState::Missing for the bars that
/// need them.
[[nodiscard]] Verdicts judge(std::span<const Series* const> series);

/// "pass", "FAIL", "-", "n/a".
[[nodiscard]] std::string_view to_string(BarState state);

}  // namespace contourmesh
