// SPDX-License-Identifier: BSD-3-Clause
// The evaluation harness's method table and variants, noise regimes, seeds and means over them, and the
// verdicts of the quality bars.
#include <compare/method_table.h>
#include <compare/report.h>
#include <compare/series.h>
#include <compare/verdicts.h>
#include <contourmesh/smooth/errors.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>
#include <variant>
#include <vector>

#include "compare_support.h"
#include "test_support.h"

namespace contourmesh {
namespace {

using namespace compare_test;
namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------------
// The method table and its variants

TEST(MethodTable, StandardMethodsKeyedByEnumAndTheSharedIterationCount) {
  EXPECT_EQ(standard_method_ids(), kMethods);
  MethodTableOptions o;
  o.iterations = 12;
  const std::vector<MethodSpec> table = method_table(o);
  ASSERT_EQ(table.size(), kMethods.size());
  for (const MethodSpec& s : table) {
    EXPECT_FALSE(s.variant);
    EXPECT_TRUE(static_cast<bool>(s.run)) << s.id;
    EXPECT_FALSE(s.title.empty() || s.legend.empty() || s.settings.empty()) << s.id;
    if (const auto* m = std::get_if<SmoothingMethod>(&s.key)) {
      EXPECT_EQ(s.id, std::string(to_string(*m)));
      EXPECT_EQ(s.route, Route::Contour);
      const int want = *m == SmoothingMethod::None ? 0 : (*m == SmoothingMethod::FeaturePreserving ? 40 : 12);
      if (*m != SmoothingMethod::CrossSlice) {
        EXPECT_EQ(iterations_of(*m, s.options), want) << s.id;
      }
    } else {
      EXPECT_EQ(s.id, std::string(to_string(std::get<ExternalMethod>(s.key))));
    }
  }
  EXPECT_EQ(table[5].preset, "xu2006");
  EXPECT_EQ(table[6].preset, "default");
  EXPECT_EQ(table[6].key, MethodKey(preset(Preset::Default).method));
  EXPECT_NE(table[7].settings.find("12 iterations"), std::string::npos) << "VTK's filters share the count";
  o.only = {"none", "cross-slice"};
  ASSERT_EQ(method_table(o).size(), 2u);
  o.only = {"none", "slicer"};
  EXPECT_THROW((void)method_table(o), InvalidInputError);
}

TEST(MethodTable, VariantsParseIntoRowsOfTheirOwn) {
  MethodVariant v = parse_variant("across:stages=across-only,reach=4");
  EXPECT_EQ(v.id, "across");
  EXPECT_EQ(v.method, SmoothingMethod::CrossSlice);
  EXPECT_EQ(v.options.cross_slice.stages, CrossSliceStages::AcrossOnly);
  EXPECT_EQ(v.options.cross_slice.reach, 4);
  EXPECT_EQ(v.options.cross_slice.across_model, ProfileModel::Parabola);
  EXPECT_EQ(parse_variant("circle:profile-model=circle").options.cross_slice.across_model, ProfileModel::Circle);
  EXPECT_EQ(v.options.cross_slice.across_kinks, ProfileKinks::Bound);
  v = parse_variant("plain-windows:kinks=ignore,kink-rate=0.05");
  EXPECT_EQ(v.options.cross_slice.across_kinks, ProfileKinks::Ignore);
  EXPECT_DOUBLE_EQ(v.options.cross_slice.kink_false_rate, 0.05);
  EXPECT_THROW((void)parse_variant("cut:kinks=cut"), InvalidInputError);
  EXPECT_EQ(v.options.cross_slice.kink_sides, KinkSides::Curves);
  EXPECT_EQ(parse_variant("straight-sides:kink-sides=lines").options.cross_slice.kink_sides, KinkSides::Lines);
  EXPECT_THROW((void)parse_variant("flat-sides:kink-sides=flat"), InvalidInputError);
  EXPECT_EQ(v.options.cross_slice.crease_restoration, CreaseRestoration::None);
  v = parse_variant("sharp:creases=restore,restore-levels=2");
  EXPECT_EQ(v.options.cross_slice.crease_restoration, CreaseRestoration::Subdivide);
  EXPECT_EQ(v.options.cross_slice.restoration.levels, 2);
  EXPECT_THROW((void)parse_variant("sharp:creases=sharpen"), InvalidInputError);
  v = parse_variant("paper-normal:preset=xu2006,measure=normal,in-slice=along-line");
  EXPECT_EQ(v.method, SmoothingMethod::FeaturePreserving);
  EXPECT_EQ(v.options.paper.detection.measure, UmbrellaMeasure::NormalComponent);
  EXPECT_GT(v.options.paper.detection.corner_spread, 1.0 / 3.0) << "the rest is the preset's";
  v = parse_variant("taubin40:method=taubin,iterations=40");
  EXPECT_EQ(v.method, SmoothingMethod::Taubin);
  EXPECT_EQ(v.options.iterations, 40);
  EXPECT_EQ(parse_variant("plain").method, preset(Preset::Default).method);

  for (const char* bad : {":reach=3", "a b:reach=3", "x:reach", "x:reach=three", "x:colour=red", "x:measure=normal",
                          "x:method=taubin,reach=3", "x:stages=sideways", "x:method=bilateral",
                          "x:profile-model=ellipse"}) {
    EXPECT_THROW((void)parse_variant(bad), InvalidInputError) << bad;
  }
  try {
    (void)parse_variant("x:method=taubin,reach=3");
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("'reach' is not an option of taubin"), std::string::npos) << e.what();
  }

  MethodTableOptions o;
  o.only = {"none"};
  o.variants = {parse_variant("across:stages=across-only"), parse_variant("xu-normal:preset=xu2006,measure=normal"),
                parse_variant("lap:method=laplacian")};
  const std::vector<MethodSpec> table = method_table(o);
  ASSERT_EQ(table.size(), 4u);
  EXPECT_TRUE(table[1].variant);
  EXPECT_NE(table[1].settings.find("stages=across-only"), std::string::npos) << table[1].settings;
  EXPECT_EQ(iterations_of(SmoothingMethod::FeaturePreserving, table[2].options), 40) << "a preset keeps its count";
  EXPECT_EQ(iterations_of(SmoothingMethod::Laplacian, table[3].options), 20) << "others share the table's";
  o.variants.push_back(parse_variant("taubin:method=taubin"));
  EXPECT_THROW((void)method_table(o), InvalidInputError) << "a standard method's id";
  o.variants.back() = parse_variant("across:reach=2");
  EXPECT_THROW((void)method_table(o), InvalidInputError) << "twice";
}

// ---------------------------------------------------------------------------------------------------
// Regimes, seeds, means and verdicts

TEST(Series, RegimesAndSeedsParse) {
  const Regime ct = parse_regime("ct60");
  EXPECT_EQ(ct.ct_noise_hu, 60.0);
  EXPECT_FALSE(ct.contour());
  const Regime contour = parse_regime("contour0.4");
  EXPECT_EQ(contour.contour_noise_mm, 0.4);
  EXPECT_EQ(contour.ct_noise_hu, 20.0);
  EXPECT_TRUE(contour.contour());
  EXPECT_EQ(parse_regime("contour1-ct60").ct_noise_hu, 60.0);
  const std::vector<Regime> all = parse_regimes("all");
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].name, "ct20");
  EXPECT_EQ(all[1].name, "ct60");
  EXPECT_EQ(all[2].name, "contour0.4");
  for (const char* bad : {"ct", "ct-5", "mri20", "contour0", "contourx", "ct20,ct20"}) {
    EXPECT_THROW((void)parse_regimes(bad), InvalidInputError) << bad;
  }
  EXPECT_EQ(parse_seeds("1-3"), (std::vector<std::uint64_t>{1, 2, 3}));
  EXPECT_EQ(parse_seeds("7,1-2"), (std::vector<std::uint64_t>{7, 1, 2}));
  for (const char* bad : {"", "3-1", "1,1", "a", "1-", "0-200"})
    EXPECT_THROW((void)parse_seeds(bad), InvalidInputError) << bad;
}

TEST(Series, MeansAreOverTheSeeds) {
  const Phantom phantom = make_phantom(PhantomShape::RidgeBox);
  const ComparisonTruth truth = coarse_truth(phantom);
  ComparisonOptions o = fast_options();
  o.methods.only = {"none", "taubin"};
  o.volume_curves = false;
  std::vector<Comparison> runs;
  for (std::uint64_t seed : {1u, 2u}) {
    PhantomVolumeOptions v;
    v.spacing = {2.0, 2.0, 4.0};
    v.noise = 150.0;
    v.seed = seed;
    runs.push_back(run_comparison(*render_phantom(phantom, v), "seed " + std::to_string(seed), truth, o));
  }
  const double a = runs[0].find("taubin")->accuracy->all.rms, b = runs[1].find("taubin")->accuracy->all.rms;
  EXPECT_NE(a, b) << "different noise, different results";
  const Series s = make_series("ridge-box", parse_regime("ct150"), {1, 2}, std::move(runs));
  ASSERT_EQ(s.mean.size(), 2u);
  EXPECT_EQ(s.find("taubin")->runs, 2u);
  EXPECT_DOUBLE_EQ(s.find("taubin")->rms, 0.5 * (a + b));
  EXPECT_EQ(s.find(SmoothingMethod::Taubin), s.find("taubin"));
  const auto j = nlohmann::json::parse(metrics_json(s));
  ASSERT_EQ(j["runs"].size(), 2u);
  EXPECT_EQ(j["runs"][1]["seed"], 2);
  EXPECT_DOUBLE_EQ(j["runs"][1]["methods"][1]["accuracy"]["all"]["rms"].get<double>(), b);
  EXPECT_THROW((void)make_series("x", parse_regime("ct20"), {}, {}), InvalidInputError);
}

// A series with the given numbers of the default, the unsmoothed mesh and the voxel route.
Series synthetic(const std::string& name, const std::string& regime, double d_rms, double d_feature, double d_normal,
                 double n_rms, double n_feature, double n_normal, double voxel_rms) {
  Series s;
  s.name = name;
  s.regime = parse_regime(regime);
  s.runs.resize(1);
  s.runs[0].truth = TruthKind::Phantom;
  const auto summary = [](MethodKey key, double rms, double feature, double normal) {
    MethodSummary m;
    m.spec.key = key;
    m.spec.id = std::visit([](auto k) { return std::string(to_string(k)); }, key);
    m.rms = rms;
    m.feature_rms = feature;
    m.normal_error = normal;
    m.volume_error_percent = 0.1;
    return m;
  };
  s.mean.push_back(summary(SmoothingMethod::None, n_rms, n_feature, n_normal));
  MethodSummary d = summary(preset(Preset::Default).method, d_rms, d_feature, d_normal);
  d.has_labels = true;
  d.precision = 0.85;
  d.recall = 0.69;
  d.recall_examinable = 0.9;
  s.mean.push_back(d);
  s.mean.push_back(summary(ExternalMethod::VoxelWindowedSinc, voxel_rms, 1.0, 5.0));
  return s;
}

TEST(Verdicts, TheBarsAtTheirBounds) {
  // Do no harm: 1.05 x + 0.01 mm; normals 0.7 x. Beat the voxel route at 20 HU.
  const Series pass = synthetic("femur", "ct20", 0.2200, 0.1, 3.5, 0.2, 0.1, 5.0, 0.25);
  const Series fail = synthetic("pelvis", "ct20", 0.2201, 0.1, 3.5, 0.2, 0.1, 5.0, 0.21);
  const Series ct60 = synthetic("femur", "ct60", 0.2, 0.2, 3.6, 0.2, 0.2, 5.0, 0.1);
  // Denoise: 0.6 x, feature 0.7 x, lowest of all, volume.
  const Series denoise = synthetic("femur", "contour0.4", 0.239, 0.279, 3.0, 0.4, 0.4, 5.0, 0.3);
  const Series noisy = synthetic("skull", "contour0.4", 0.25, 0.28, 3.0, 0.4, 0.4, 5.0, 0.2);
  const std::vector<const Series*> all = {&pass, &fail, &ct60, &denoise, &noisy};
  const Verdicts v = judge(all);
  ASSERT_EQ(v.rows.size(), 5u);
  EXPECT_EQ(v.rows[0].harm.state, BarState::Pass) << v.rows[0].harm.detail;
  EXPECT_EQ(v.rows[0].voxel.state, BarState::Pass);
  EXPECT_EQ(v.rows[1].harm.state, BarState::Fail) << "0.2201 > 1.05 x 0.2 + 0.01";
  EXPECT_EQ(v.rows[1].voxel.state, BarState::Fail);
  EXPECT_EQ(v.rows[2].harm.state, BarState::Fail) << "normals 3.6 > 0.7 x 5";
  EXPECT_EQ(v.rows[2].voxel.state, BarState::NotApplicable) << "only at 20 HU";
  EXPECT_EQ(v.rows[3].denoise.state, BarState::Pass) << v.rows[3].denoise.detail;
  EXPECT_EQ(v.rows[3].harm.state, BarState::NotApplicable);
  EXPECT_EQ(v.rows[4].denoise.state, BarState::Fail) << "above 0.6 x, and the voxel route is lower";
  EXPECT_NE(v.rows[4].denoise.detail.find("not lowest"), std::string::npos) << v.rows[4].denoise.detail;
  for (const VerdictRow& r : v.rows) EXPECT_EQ(r.detection.state, BarState::Fail) << "recall 0.69 < 0.7";
  EXPECT_TRUE(v.rows[0].original);
  // Totals: bar 2 needs 5 of the 7 original phantoms.
  const auto total = [&](const std::string& bar, const std::string& regime) {
    for (const BarTotal& t : v.totals) {
      if (t.bar == bar && t.regime == regime) return t;
    }
    return BarTotal{};
  };
  const BarTotal voxel = total("2. beat the voxel route", "ct20");
  EXPECT_EQ(voxel.passed, 1);
  EXPECT_EQ(voxel.rows, 2);
  EXPECT_EQ(voxel.required, 5);
  EXPECT_FALSE(voxel.met());
  EXPECT_FALSE(total("1. do no harm", "ct20").met());
}

}  // namespace
}  // namespace contourmesh
