// SPDX-License-Identifier: BSD-3-Clause
#include "compare/verdicts.h"

#include <contourmesh/smooth/errors.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>

namespace contourmesh {

std::string_view to_string(BarState state) {
  switch (state) {
    case BarState::NotApplicable: return "-";
    case BarState::Pass: return "pass";
    case BarState::Fail: return "FAIL";
    case BarState::Missing: return "n/a";
  }
  return "-";
}

bool BarTotal::met() const {
  if (required > 0) return original_passed >= required;
  return rows > 0 && passed == rows;
}

namespace {

// The seven phantoms the bars on the voxel route and on denoising count ("at least 5 / 6 of 7").
constexpr PhantomShape kOriginal[] = {PhantomShape::RidgeBox, PhantomShape::Femur,      PhantomShape::Pelvis,
                                      PhantomShape::Skull,    PhantomShape::Branch,     PhantomShape::TwoObjects,
                                      PhantomShape::Cavity};

bool is_original(const std::string& name) {
  return std::any_of(std::begin(kOriginal), std::end(kOriginal),
                     [&](PhantomShape s) { return to_string(s) == name; });
}

std::string mm(double v) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(3) << v;
  return s.str();
}

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

BarVerdict verdict(bool pass, std::string detail) {
  return {pass ? BarState::Pass : BarState::Fail, std::move(detail)};
}

BarVerdict missing(const std::string& what) { return {BarState::Missing, what + " was not run"}; }

// Bar 1: the default does no harm to the unsmoothed mesh.
BarVerdict harm(const MethodSummary& d, const MethodSummary& none) {
  const double rms_bound = 1.05 * none.rms + 0.01, feature_bound = 1.05 * none.feature_rms + 0.01;
  const double normal_bound = 0.7 * none.normal_error;
  const bool pass = d.rms <= rms_bound && d.feature_rms <= feature_bound && d.normal_error <= normal_bound;
  return verdict(pass, "RMS " + mm(d.rms) + " (<= " + mm(rms_bound) + "), feature " + mm(d.feature_rms) + " (<= " +
                           mm(feature_bound) + "), normals " + fixed(d.normal_error, 2) + " deg (<= " +
                           fixed(normal_bound, 2) + ")");
}

// Bar 2: the default beats 3D Slicer's voxel route.
BarVerdict voxel(const MethodSummary& d, const MethodSummary& slicer) {
  return verdict(d.rms <= slicer.rms, "RMS " + mm(d.rms) + " vs " + mm(slicer.rms));
}

// Bar 3: the default removes most of the contour noise, best of all, without changing the volume.
BarVerdict denoise(const MethodSummary& d, const MethodSummary& none, const Series& s) {
  const double rms_bound = 0.6 * none.rms, feature_bound = 0.7 * none.feature_rms;
  const MethodSummary* best = &d;
  for (const MethodSummary& m : s.mean) {
    if (!m.spec.variant && std::isfinite(m.rms) && m.rms < best->rms) best = &m;
  }
  const double volume_bound = std::abs(none.volume_error_percent) + 0.3;
  const bool lowest = best == &d;
  const bool pass = d.rms <= rms_bound && d.feature_rms <= feature_bound && lowest &&
                    std::abs(d.volume_error_percent) <= volume_bound;
  std::string detail = "RMS " + mm(d.rms) + " (<= " + mm(rms_bound) + "), feature " + mm(d.feature_rms) + " (<= " +
                       mm(feature_bound) + "), " +
                       (lowest ? std::string("lowest") : "not lowest (" + best->spec.id + " " + mm(best->rms) + ")") +
                       ", |dV| " + fixed(std::abs(d.volume_error_percent), 2) + " % (<= " + fixed(volume_bound, 2) +
                       ")";
  return verdict(pass, detail);
}

// Bar 4: the default's labels find the true features.
BarVerdict detection(const MethodSummary& d) {
  if (!d.has_labels) return {BarState::Missing, "the default has no labels"};
  const bool pass = d.precision >= 0.8 && d.recall >= 0.7;
  return verdict(pass, "precision " + fixed(d.precision, 2) + ", recall " + fixed(d.recall, 2) + " (" +
                           fixed(d.recall_examinable, 2) + " on contours)");
}

}  // namespace

Verdicts judge(std::span<const Series* const> all) {
  Verdicts v;
  const SmoothingMethod default_method = preset(Preset::Default).method;
  for (const Series* series : all) {
    const Series& s = *series;
    if (s.first().truth != TruthKind::Phantom) continue;
    VerdictRow row;
    row.phantom = s.name;
    row.regime = s.regime.name;
    row.original = is_original(s.name);
    const MethodSummary* d = s.find(default_method);
    const MethodSummary* none = s.find(SmoothingMethod::None);
    const MethodSummary* slicer = s.find(ExternalMethod::VoxelWindowedSinc);
    const bool ct = !s.regime.contour();
    if (ct) {
      row.harm = !d ? missing("the default") : !none ? missing("none") : harm(*d, *none);
      if (s.regime.ct_noise_hu == 20.0) {
        row.voxel = !d ? missing("the default") : !slicer ? missing("the voxel route") : voxel(*d, *slicer);
      }
    } else {
      row.denoise = !d ? missing("the default") : !none ? missing("none") : denoise(*d, *none, s);
    }
    row.detection = d ? detection(*d) : missing("the default");
    v.rows.push_back(std::move(row));
  }
  // Totals per bar and regime.
  const auto total = [&](const char* bar, BarVerdict VerdictRow::*member, int required) {
    std::map<std::string, BarTotal> by_regime;
    std::vector<std::string> order;
    for (const VerdictRow& r : v.rows) {
      const BarVerdict& b = r.*member;
      if (b.state == BarState::NotApplicable) continue;
      if (!by_regime.count(r.regime)) order.push_back(r.regime);
      BarTotal& t = by_regime[r.regime];
      t.bar = bar;
      t.regime = r.regime;
      t.required = required;
      ++t.rows;
      t.passed += b.state == BarState::Pass;
      if (r.original) {
        ++t.original_rows;
        t.original_passed += b.state == BarState::Pass;
      }
    }
    for (const std::string& regime : order) v.totals.push_back(by_regime[regime]);
  };
  total("1. do no harm", &VerdictRow::harm, 0);
  total("2. beat the voxel route", &VerdictRow::voxel, 5);
  total("3. denoise", &VerdictRow::denoise, 6);
  total("4. detection", &VerdictRow::detection, 0);
  return v;
}

}  // namespace contourmesh
