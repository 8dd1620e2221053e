// SPDX-License-Identifier: BSD-3-Clause
// Progress in the form 3D Slicer reads from a CLI module's standard output (Slicer Execution Model):
// <filter-start>, <filter-progress> (overall fraction), <filter-stage-progress> and <filter-end>.
#pragma once

#include <contourmesh/smooth/progress.h>

#include <chrono>
#include <string>
#include <string_view>

namespace contourmesh::slicer {

class FilterProgress {
 public:
  /// Prints <filter-start> with the module's name.
  explicit FilterProgress(std::string name);
  /// Starts a stage ("read", "segment", "tile", "detect", "subdivide", "smooth", "write").
  void stage(std::string_view name);
  /// A library callback: stage switches and the fraction within the stage. Never cancels (Slicer stops
  /// a CLI module by killing it).
  [[nodiscard]] ProgressCallback callback();
  /// Prints the last <filter-progress>1</filter-progress> and <filter-end>.
  void finish();

 private:
  void report(double stage_fraction);
  std::string name_;
  std::string stage_;
  double base_ = 0.0, span_ = 0.0;  ///< the overall fraction the current stage covers
  double last_ = -1.0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace contourmesh::slicer
