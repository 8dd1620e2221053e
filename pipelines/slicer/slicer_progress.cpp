// SPDX-License-Identifier: BSD-3-Clause
#include "slicer_progress.h"

#include <algorithm>
#include <array>
#include <iostream>
#include <utility>

namespace contourmesh::slicer {

namespace {

// Each stage's share of the whole run (measured on phantoms: smoothing and tiling dominate).
struct StageShare {
  std::string_view name;
  double start, span;
};
constexpr std::array<StageShare, 7> kStages{{{"read", 0.0, 0.05},
                                             {"segment", 0.05, 0.15},
                                             {"tile", 0.2, 0.25},
                                             {"detect", 0.45, 0.1},
                                             {"subdivide", 0.55, 0.05},
                                             {"smooth", 0.6, 0.35},
                                             {"write", 0.95, 0.05}}};

}  // namespace

FilterProgress::FilterProgress(std::string name) : name_(std::move(name)), start_(std::chrono::steady_clock::now()) {
  std::cout << "<filter-start><filter-name>" << name_ << "</filter-name><filter-comment>reconstruct and smooth"
            << "</filter-comment></filter-start>" << std::endl;
}

void FilterProgress::stage(std::string_view name) {
  if (name == stage_) return;
  stage_ = std::string(name);
  const auto it = std::find_if(kStages.begin(), kStages.end(), [&](const StageShare& s) { return s.name == name; });
  if (it != kStages.end()) {
    base_ = it->start;
    span_ = it->span;
  }
  std::cout << "<filter-comment>" << stage_ << "</filter-comment>" << std::endl;
  report(0.0);
}

ProgressCallback FilterProgress::callback() {
  return [this](std::string_view name, double fraction) {
    stage(name);
    report(fraction);
    return true;
  };
}

void FilterProgress::report(double stage_fraction) {
  const double f = std::clamp(stage_fraction, 0.0, 1.0);
  const double overall = std::max(last_, base_ + span_ * f);  // never backwards
  if (overall - last_ < 0.01 && f < 1.0) return;
  last_ = overall;
  std::cout << "<filter-stage-progress>" << f << "</filter-stage-progress>\n"
            << "<filter-progress>" << overall << "</filter-progress>" << std::endl;
}

void FilterProgress::finish() {
  std::cout << "<filter-progress>1</filter-progress>\n<filter-end><filter-name>" << name_
            << "</filter-name><filter-time>"
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count()
            << "</filter-time></filter-end>" << std::endl;
}

}  // namespace contourmesh::slicer
