// SPDX-License-Identifier: BSD-3-Clause
// One object measured over noise regimes and seeds: the regimes (CT noise in HU, per-slice contour noise
// in mm), seed lists, and a series of comparisons of one object in one regime with the means over its
// seeds, the numbers the tables and verdicts are made of. Part of the contourmesh_compare target.
#pragma once

#include "compare/comparison.h"

#include <contourmesh/reconstruct/phantom.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace contourmesh {

/// A noise regime of the phantom volumes.
struct Regime {
  std::string name;           ///< "ct20", "ct60", "contour0.4", ...
  double ct_noise_hu = 20.0;  ///< Gaussian noise on the rendered volume, HU
  double contour_noise_mm = 0.0;  ///< per-slice contour noise (the paper's model), RMS mm; 0: none
  [[nodiscard]] bool contour() const { return contour_noise_mm > 0.0; }
};

/// "ct<HU>" (CT noise, no contour noise), "contour<MM>" (contour noise at 20 HU) or
/// "contour<MM>-ct<HU>"; throws InvalidInputError quoting the text otherwise.
[[nodiscard]] Regime parse_regime(std::string_view text);
/// A comma-separated list of regimes; "all" is default_regimes().
[[nodiscard]] std::vector<Regime> parse_regimes(std::string_view text);
/// ct20, ct60, contour0.4: the two regimes of the evaluation (CT noise at 20 and 60 HU, contour noise of
/// 0.4 mm at 20 HU).
[[nodiscard]] std::vector<Regime> default_regimes();
/// Sets the regime's noise in the volume options.
void apply_regime(const Regime& regime, PhantomVolumeOptions& volume);

/// "3", "1-3", "1,4,7" or a mix ("1-3,9"): distinct seeds in the order given; throws InvalidInputError
/// quoting the text for anything else, an empty list or more than 100 seeds.
[[nodiscard]] std::vector<std::uint64_t> parse_seeds(std::string_view text);

/// The numbers of one method that the tables and verdicts use: of one run, or the mean over seeds
/// (of the finite values; NaN when there is none). Distances in mm, angles in degrees, volumes in %.
struct MethodSummary {
  MethodSpec spec;
  int iterations = 0;
  double vertices = 0.0;
  std::size_t runs = 0;  ///< how many runs the mean is over
  double rms = 0, hausdorff = 0, feature_rms = 0, feature_hausdorff = 0, smooth_rms = 0;
  double mesh_to_truth_rms = 0, truth_to_mesh_rms = 0, mean_signed = 0;
  double normal_error = 0, feature_normal_error = 0, smooth_normal_error = 0;
  double vertex_rms = 0, feature_vertex_rms = 0;
  double volume_change_percent = 0, volume_error_percent = 0;
  std::vector<StageTime> seconds;  ///< per stage, as the method reports them
  bool has_labels = false;
  double edges = 0, corners = 0, noise = 0;
  double precision = 0, recall = 0, recall_examinable = 0;

  [[nodiscard]] double stage_seconds(std::string_view stage) const;
};

/// One run's numbers (NaN where a value does not apply).
[[nodiscard]] MethodSummary summarize(const MethodResult& result);

/// One object in one regime, over seeds.
struct Series {
  std::string name;  ///< the phantom's name, or the input volume's file name
  Regime regime;
  std::vector<std::uint64_t> seeds;  ///< one per run (empty for an input volume)
  std::vector<Comparison> runs;      ///< one per seed, in seed order
  std::vector<MethodSummary> mean;   ///< per method of the first run, the mean over the runs

  /// The first run: its meshes are the ones rendered, its curves the ones plotted.
  [[nodiscard]] const Comparison& first() const { return runs.front(); }
  /// The mean of the method with this id / the standard method of this key, or nullptr.
  [[nodiscard]] const MethodSummary* find(std::string_view id) const;
  [[nodiscard]] const MethodSummary* find(const MethodKey& key) const;
};

/// A series from its runs (one per seed, at least one, with the same methods): computes the means.
[[nodiscard]] Series make_series(std::string name, Regime regime, std::vector<std::uint64_t> seeds,
                                 std::vector<Comparison> runs);

}  // namespace contourmesh
