// SPDX-License-Identifier: BSD-3-Clause
#include "compare/series.h"

#include <contourmesh/smooth/errors.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>

namespace contourmesh {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool parse_number(std::string_view text, double& value) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size() && std::isfinite(value) && value >= 0.0;
}

}  // namespace

Regime parse_regime(std::string_view text) {
  const auto fail = [&] {
    throw InvalidInputError("unknown regime '" + std::string(text) +
                            "' (expected ct<HU>, contour<MM> or contour<MM>-ct<HU>, e.g. ct20, ct60, contour0.4)");
  };
  Regime r;
  r.name = std::string(text);
  std::string_view rest = text;
  if (rest.starts_with("contour")) {
    rest.remove_prefix(7);
    const std::size_t dash = rest.find("-ct");
    if (!parse_number(rest.substr(0, dash), r.contour_noise_mm) || !(r.contour_noise_mm > 0.0)) fail();
    if (dash != std::string_view::npos && !parse_number(rest.substr(dash + 3), r.ct_noise_hu)) fail();
  } else if (rest.starts_with("ct")) {
    if (!parse_number(rest.substr(2), r.ct_noise_hu)) fail();
  } else {
    fail();
  }
  return r;
}

std::vector<Regime> parse_regimes(std::string_view text) {
  if (text == "all") return default_regimes();
  std::vector<Regime> regimes;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::string_view item = text.substr(start, comma == std::string_view::npos ? text.npos : comma - start);
    Regime r = parse_regime(item);
    for (const Regime& seen : regimes) {
      if (seen.name == r.name) throw InvalidInputError("regime '" + r.name + "' is listed twice");
    }
    regimes.push_back(std::move(r));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return regimes;
}

std::vector<Regime> default_regimes() {
  return {parse_regime("ct20"), parse_regime("ct60"), parse_regime("contour0.4")};
}

void apply_regime(const Regime& regime, PhantomVolumeOptions& volume) {
  volume.noise = regime.ct_noise_hu;
  volume.contour_noise = regime.contour_noise_mm;
}

std::vector<std::uint64_t> parse_seeds(std::string_view text) {
  const auto fail = [&](const std::string& why) {
    throw InvalidInputError("--seeds '" + std::string(text) + "': " + why + " (e.g. 1-3, or 1,4,7)");
  };
  const auto number = [&](std::string_view s) {
    std::uint64_t v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || end != s.data() + s.size()) fail("'" + std::string(s) + "' is not a seed");
    return v;
  };
  std::vector<std::uint64_t> seeds;
  const auto add = [&](std::uint64_t s) {
    for (std::uint64_t seen : seeds) {
      if (seen == s) fail("seed " + std::to_string(s) + " is listed twice");
    }
    seeds.push_back(s);
    if (seeds.size() > 100) fail("more than 100 seeds");
  };
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string_view item = text.substr(start, comma == std::string_view::npos ? text.npos : comma - start);
    const std::size_t dash = item.find('-');
    if (dash == std::string_view::npos) {
      add(number(item));
    } else {
      const std::uint64_t a = number(item.substr(0, dash)), b = number(item.substr(dash + 1));
      if (b < a || b - a >= 100) fail("a range must go up, by fewer than 100");
      for (std::uint64_t s = a; s <= b; ++s) add(s);
    }
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return seeds;
}

double MethodSummary::stage_seconds(std::string_view stage) const {
  for (const StageTime& s : seconds) {
    if (s.stage == stage) return s.seconds;
  }
  return 0.0;
}

MethodSummary summarize(const MethodResult& m) {
  MethodSummary s;
  s.spec = m.spec;
  s.iterations = m.iterations;
  s.vertices = static_cast<double>(m.mesh.num_vertices());
  s.runs = 1;
  const std::optional<SurfaceAccuracy>& a = m.accuracy;
  s.rms = a ? a->all.rms : kNaN;
  s.hausdorff = a ? a->all.hausdorff : kNaN;
  s.feature_rms = a ? a->feature.rms : kNaN;
  s.feature_hausdorff = a ? a->feature.hausdorff : kNaN;
  s.smooth_rms = a ? a->smooth.rms : kNaN;
  s.mesh_to_truth_rms = a ? a->all.mesh_to_truth_rms : kNaN;
  s.truth_to_mesh_rms = a ? a->all.truth_to_mesh_rms : kNaN;
  s.mean_signed = a ? a->all.mean_signed : kNaN;
  s.normal_error = a ? a->all.normal_error_degrees : kNaN;
  s.feature_normal_error = a ? a->feature.normal_error_degrees : kNaN;
  s.smooth_normal_error = a ? a->smooth.normal_error_degrees : kNaN;
  s.vertex_rms = a ? a->vertex_rms : kNaN;
  s.feature_vertex_rms = a ? a->feature_vertex_rms : kNaN;
  s.volume_change_percent = m.volume_change_percent;
  s.volume_error_percent = m.volume_error_percent.value_or(kNaN);
  s.seconds = m.seconds;
  s.has_labels = m.labels.has_value();
  s.edges = s.corners = s.noise = s.precision = s.recall = s.recall_examinable = kNaN;
  if (m.labels) {
    s.edges = static_cast<double>(m.labels->edges);
    s.corners = static_cast<double>(m.labels->corners);
    s.noise = static_cast<double>(m.labels->noise);
    s.precision = m.labels->precision;
    s.recall = m.labels->recall;
    s.recall_examinable = m.labels->recall_examinable;
  }
  return s;
}

namespace {

// The mean of the finite values, NaN when there is none.
class Mean {
 public:
  void add(double v) {
    if (std::isfinite(v)) {
      sum_ += v;
      ++n_;
    }
  }
  [[nodiscard]] double value() const { return n_ > 0 ? sum_ / static_cast<double>(n_) : kNaN; }

 private:
  double sum_ = 0.0;
  std::size_t n_ = 0;
};

MethodSummary mean_of(const std::vector<MethodSummary>& runs) {
  MethodSummary m = runs.front();
  m.runs = runs.size();
  // Every averaged member, once.
  double MethodSummary::*const members[] = {
      &MethodSummary::vertices,          &MethodSummary::rms,
      &MethodSummary::hausdorff,         &MethodSummary::feature_rms,
      &MethodSummary::feature_hausdorff, &MethodSummary::smooth_rms,
      &MethodSummary::mesh_to_truth_rms, &MethodSummary::truth_to_mesh_rms,
      &MethodSummary::mean_signed,       &MethodSummary::normal_error,
      &MethodSummary::feature_normal_error, &MethodSummary::smooth_normal_error,
      &MethodSummary::vertex_rms,        &MethodSummary::feature_vertex_rms,
      &MethodSummary::volume_change_percent, &MethodSummary::volume_error_percent,
      &MethodSummary::edges,             &MethodSummary::corners,
      &MethodSummary::noise,             &MethodSummary::precision,
      &MethodSummary::recall,            &MethodSummary::recall_examinable};
  for (double MethodSummary::*member : members) {
    Mean mean;
    for (const MethodSummary& r : runs) mean.add(r.*member);
    m.*member = mean.value();
  }
  for (StageTime& stage : m.seconds) {
    Mean mean;
    for (const MethodSummary& r : runs) mean.add(r.stage_seconds(stage.stage));
    stage.seconds = mean.value();
  }
  return m;
}

}  // namespace

const MethodSummary* Series::find(std::string_view id) const {
  for (const MethodSummary& m : mean) {
    if (m.spec.id == id) return &m;
  }
  return nullptr;
}

const MethodSummary* Series::find(const MethodKey& key) const {
  for (const MethodSummary& m : mean) {
    if (!m.spec.variant && m.spec.key == key) return &m;
  }
  return nullptr;
}

Series make_series(std::string name, Regime regime, std::vector<std::uint64_t> seeds, std::vector<Comparison> runs) {
  if (runs.empty()) throw InvalidInputError("a series needs at least one run");
  Series s;
  s.name = std::move(name);
  s.regime = std::move(regime);
  s.seeds = std::move(seeds);
  s.runs = std::move(runs);
  for (const MethodResult& m : s.first().methods) {
    std::vector<MethodSummary> per_run;
    for (const Comparison& c : s.runs) {
      const MethodResult* r = c.find(m.spec.id);
      if (r == nullptr) throw InvalidInputError("the runs of a series must have the same methods");
      per_run.push_back(summarize(*r));
    }
    s.mean.push_back(mean_of(per_run));
  }
  return s;
}

}  // namespace contourmesh
