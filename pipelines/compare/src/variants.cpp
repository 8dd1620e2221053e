// SPDX-License-Identifier: BSD-3-Clause
// parse_variant: "NAME:key=value,..." -> a libsmooth method with some options changed. The key table
// follows the options of smooth.h's families; keep it in step when an option is added there.
#include "compare/method_table.h"

#include <contourmesh/smooth/errors.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace contourmesh {

namespace {

enum Family : unsigned { kBaseline = 1, kPaper = 2, kCrossSlice = 4 };

unsigned family_of(SmoothingMethod m) {
  if (m == SmoothingMethod::FeaturePreserving) return kPaper;
  if (m == SmoothingMethod::CrossSlice) return kCrossSlice;
  return kBaseline;
}

struct Value {
  const std::string& text;
  const std::string& key;
  const std::string& variant;

  [[noreturn]] void fail(const std::string& what) const {
    throw InvalidInputError("--variant '" + variant + "': " + key + "=" + text + ": " + what);
  }
  [[nodiscard]] double number() const {
    double v = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v)) fail("not a number");
    return v;
  }
  [[nodiscard]] int integer() const {
    int v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size()) fail("not an integer");
    return v;
  }
  template <typename E>
  [[nodiscard]] E choice(std::initializer_list<std::pair<const char*, E>> words) const {
    std::string known;
    for (const auto& [word, value] : words) {
      if (text == word) return value;
      known += (known.empty() ? "" : " | ") + std::string(word);
    }
    fail("expected " + known);
  }
};

struct Key {
  const char* name;
  unsigned families;
  std::function<void(SmoothOptions&, const Value&)> set;
};

const std::vector<Key>& keys() {
  static const std::vector<Key> table = {
      // Every family.
      {"iterations", kBaseline | kPaper, [](SmoothOptions& o, const Value& v) { o.iterations = v.integer(); }},
      {"lambda", kBaseline | kPaper,
       [](SmoothOptions& o, const Value& v) { o.baseline.lambda = o.paper.lambda = v.number(); }},
      {"mu", kBaseline | kPaper, [](SmoothOptions& o, const Value& v) { o.baseline.mu = o.paper.mu = v.number(); }},
      {"beta", kBaseline, [](SmoothOptions& o, const Value& v) { o.baseline.beta = v.number(); }},
      // The paper's method.
      {"max-levels", kPaper, [](SmoothOptions& o, const Value& v) { o.paper.max_levels = v.integer(); }},
      {"diffusion", kPaper,
       [](SmoothOptions& o, const Value& v) {
         o.paper.diffusion = v.choice<SmoothingMethod>(
             {{"taubin", SmoothingMethod::Taubin}, {"laplacian", SmoothingMethod::Laplacian}});
       }},
      {"measure", kPaper,
       [](SmoothOptions& o, const Value& v) {
         o.paper.detection.measure = v.choice<UmbrellaMeasure>(
             {{"length", UmbrellaMeasure::Length}, {"normal", UmbrellaMeasure::NormalComponent}});
       }},
      {"in-slice", kPaper,
       [](SmoothOptions& o, const Value& v) {
         o.paper.detection.in_slice = v.choice<InSliceFeatures>(
             {{"noise", InSliceFeatures::Noise}, {"along-line", InSliceFeatures::AlongFeatureLine}});
       }},
      {"gamma-factor", kPaper, [](SmoothOptions& o, const Value& v) { o.paper.detection.gamma_factor = v.number(); }},
      {"delta-factor", kPaper, [](SmoothOptions& o, const Value& v) { o.paper.detection.delta_factor = v.number(); }},
      {"window", kPaper, [](SmoothOptions& o, const Value& v) { o.paper.detection.window = v.integer(); }},
      {"corner-spread", kPaper, [](SmoothOptions& o, const Value& v) { o.paper.detection.corner_spread = v.number(); }},
      {"prefilter", kPaper,
       [](SmoothOptions& o, const Value& v) { o.paper.detection.prefilter_iterations = v.integer(); }},
      // Cross-slice smoothing (cross_slice.h).
      {"reach", kCrossSlice, [](SmoothOptions& o, const Value& v) { o.cross_slice.reach = v.integer(); }},
      {"along-reach", kCrossSlice, [](SmoothOptions& o, const Value& v) { o.cross_slice.along_reach = v.integer(); }},
      {"gamma", kCrossSlice, [](SmoothOptions& o, const Value& v) { o.cross_slice.gamma = v.number(); }},
      {"precise-noise", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.precise_noise = v.number(); }},
      {"noisy-reach-length", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.noisy_reach_length = v.number(); }},
      {"noise-across", kCrossSlice, [](SmoothOptions& o, const Value& v) { o.cross_slice.noise_across = v.number(); }},
      {"noise-along", kCrossSlice, [](SmoothOptions& o, const Value& v) { o.cross_slice.noise_along = v.number(); }},
      {"min-profile-share", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.min_profile_share = v.number(); }},
      {"profile-model", kCrossSlice,
       [](SmoothOptions& o, const Value& v) {
         o.cross_slice.across_model =
             v.choice<ProfileModel>({{"parabola", ProfileModel::Parabola}, {"circle", ProfileModel::Circle}});
       }},
      {"kinks", kCrossSlice,
       [](SmoothOptions& o, const Value& v) {
         o.cross_slice.across_kinks =
             v.choice<ProfileKinks>({{"ignore", ProfileKinks::Ignore}, {"bound", ProfileKinks::Bound}});
       }},
      {"kink-sides", kCrossSlice,
       [](SmoothOptions& o, const Value& v) {
         o.cross_slice.kink_sides = v.choice<KinkSides>({{"curves", KinkSides::Curves}, {"lines", KinkSides::Lines}});
       }},
      {"kink-rate", kCrossSlice, [](SmoothOptions& o, const Value& v) { o.cross_slice.kink_false_rate = v.number(); }},
      {"stages", kCrossSlice,
       [](SmoothOptions& o, const Value& v) {
         o.cross_slice.stages = v.choice<CrossSliceStages>(
             {{"across-then-along", CrossSliceStages::AcrossThenAlong}, {"across-only", CrossSliceStages::AcrossOnly}});
       }},
      {"extension-iterations", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.extension_iterations = v.integer(); }},
      {"off-slice-filter", kCrossSlice,
       [](SmoothOptions& o, const Value& v) {
         o.cross_slice.off_slice.filter = v.choice<OffSliceFilter>(
             {{"bilateral", OffSliceFilter::BilateralNormals}, {"none", OffSliceFilter::None}});
       }},
      {"off-slice-motion", kCrossSlice,
       [](SmoothOptions& o, const Value& v) {
         o.cross_slice.off_slice.motion =
             v.choice<OffSliceMotion>({{"axis", OffSliceMotion::AlongAxis}, {"free", OffSliceMotion::Free}});
       }},
      {"off-slice-volume", kCrossSlice,
       [](SmoothOptions& o, const Value& v) {
         o.cross_slice.off_slice.volume = v.choice<OffSliceVolume>(
             {{"free", OffSliceVolume::Free}, {"preserve", OffSliceVolume::Preserve}});
       }},
      {"off-slice-range", kCrossSlice,
       [](SmoothOptions& o, const Value& v) {
         o.cross_slice.off_slice.range = v.choice<OffSliceRange>(
             {{"faces", OffSliceRange::FaceNormals}, {"patches", OffSliceRange::PatchGuidance}});
       }},
      {"normal-iterations", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.off_slice.normal_iterations = v.integer(); }},
      {"normal-sigma", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.off_slice.sigma_angle_degrees = v.number(); }},
      {"guidance-interval", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.off_slice.guidance_interval = v.integer(); }},
      {"rim-iterations", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.off_slice.rim_iterations = v.integer(); }},
      {"rim-angle", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.off_slice.rim_angle_degrees = v.number(); }},
      {"rim-rings", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.off_slice.rim_rings = v.integer(); }},
      {"vertex-iterations", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.off_slice.vertex_iterations = v.integer(); }},
      {"vertex-step", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.off_slice.vertex_step = v.number(); }},
      {"max-move", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.off_slice.max_move = v.number(); }},
      {"contour-max-move", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.off_slice.contour_max_move = v.number(); }},
      {"crease-radius", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.features.radius = v.number(); }},
      {"edge-threshold", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.features.edge_threshold = v.number(); }},
      {"corner-threshold", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.features.corner_threshold = v.number(); }},
      {"min-extent", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.features.min_extent = v.number(); }},
      {"band", kCrossSlice, [](SmoothOptions& o, const Value& v) { o.cross_slice.features.band = v.number(); }},
      {"creases", kCrossSlice,
       [](SmoothOptions& o, const Value& v) {
         o.cross_slice.crease_restoration = v.choice<CreaseRestoration>(
             {{"none", CreaseRestoration::None}, {"restore", CreaseRestoration::Subdivide}});
       }},
      {"restore-levels", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.restoration.levels = v.integer(); }},
      {"link-radius", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.features.link_radius = v.number(); }},
      {"link-angle", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.features.link_angle_degrees = v.number(); }},
      {"crease-confirm", kCrossSlice,
       [](SmoothOptions& o, const Value& v) {
         o.cross_slice.features.confirm =
             v.choice<CreaseConfirmation>({{"ball", CreaseConfirmation::Ball}, {"none", CreaseConfirmation::None}});
       }},
      {"confirm-radius", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.features.confirm_radius = v.number(); }},
      {"confirm-threshold", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.features.confirm_threshold = v.number(); }},
      {"crease-sampling", kCrossSlice,
       [](SmoothOptions& o, const Value& v) {
         o.cross_slice.features.sampling = v.choice<CreaseSampling>(
             {{"slice-aware", CreaseSampling::SliceAware}, {"isotropic", CreaseSampling::Isotropic}});
       }},
      {"steep-confirm-threshold", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.features.steep_confirm_threshold = v.number(); }},
      {"crease-noise", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.features.noise = v.number(); }},
      {"crease-noise-factor", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.features.noise_factor = v.number(); }},
      {"confirm-corner-threshold", kCrossSlice,
       [](SmoothOptions& o, const Value& v) { o.cross_slice.features.confirm_corner_threshold = v.number(); }},
  };
  return table;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = text.find(separator, start);
    parts.push_back(text.substr(start, end - start));
    if (end == std::string::npos) return parts;
    start = end + 1;
  }
}

}  // namespace

MethodVariant parse_variant(std::string_view text_view) {
  const std::string text(text_view);
  const auto fail = [&](const std::string& what) { throw InvalidInputError("--variant '" + text + "': " + what); };
  const std::size_t colon = text.find(':');
  MethodVariant v;
  v.id = text.substr(0, colon);
  if (v.id.empty()) fail("give it a name: NAME:key=value,...");
  for (char c : v.id) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') {
      fail("the name may hold letters, digits, '-', '_' and '.' only");
    }
  }
  std::vector<std::pair<std::string, std::string>> pairs;
  if (colon != std::string::npos && colon + 1 < text.size()) {
    for (const std::string& item : split(text.substr(colon + 1), ',')) {
      const std::size_t eq = item.find('=');
      if (eq == std::string::npos || eq == 0) fail("'" + item + "' is not key=value");
      pairs.emplace_back(item.substr(0, eq), item.substr(eq + 1));
    }
  }
  // The base first: a method with the library's defaults, or a preset.
  MethodConfig base = preset(Preset::Default);
  for (const auto& [key, value] : pairs) {
    if (key == "method") {
      base.method = parse_smoothing_method(value);
      base.options = {};
    } else if (key == "preset") {
      base = preset(parse_preset(value));
      v.preset = value;
    }
  }
  v.method = base.method;
  v.options = base.options;
  const unsigned family = family_of(v.method);
  for (const auto& [key, value] : pairs) {
    if (key == "method" || key == "preset") continue;
    const auto it = std::find_if(keys().begin(), keys().end(), [&](const Key& k) { return key == k.name; });
    if (it == keys().end()) fail("unknown key '" + key + "'");
    if ((it->families & family) == 0) {
      fail("'" + key + "' is not an option of " + std::string(to_string(v.method)));
    }
    it->set(v.options, Value{value, key, text});
    v.changes += (v.changes.empty() ? "" : ", ") + key + "=" + value;
  }
  if (v.changes.empty()) v.changes = "its defaults";
  return v;
}

}  // namespace contourmesh
