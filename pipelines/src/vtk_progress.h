// SPDX-License-Identifier: BSD-3-Clause
// Private helper of the VTK filters: libsmooth / libreconstruct progress reports -> vtkAlgorithm
// progress, and the algorithm's abort flag -> cancellation.
#pragma once

#include <contourmesh/smooth/progress.h>

#include <vtkAlgorithm.h>
#include <vtkVersionMacros.h>

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

namespace contourmesh::filter_detail {

/// Maps each named stage of a library call onto a part [start, start + width] of the filter's
/// progress (reported only when it grows), and cancels when `abort` says so.
class StageProgress {
 public:
  explicit StageProgress(vtkAlgorithm* algorithm, bool (*abort)(vtkAlgorithm*))
      : algorithm_(algorithm), abort_(abort) {}

  void add(std::string stage, double start, double width) { stages_.push_back({std::move(stage), start, width}); }

  /// A callback that reports through this object; valid while it lives.
  [[nodiscard]] ProgressCallback callback() {
    return [this](std::string_view stage, double fraction) {
      for (const Stage& s : stages_) {
        if (s.name != stage) continue;
        const double amount = s.start + s.width * std::clamp(fraction, 0.0, 1.0);
        if (amount > reported_) {
          reported_ = amount;
          algorithm_->UpdateProgress(amount);
        }
        break;
      }
      return !abort_(algorithm_);
    };
  }

 private:
  struct Stage {
    std::string name;
    double start = 0.0;
    double width = 0.0;
  };
  vtkAlgorithm* algorithm_;
  bool (*abort_)(vtkAlgorithm*);
  std::vector<Stage> stages_;
  double reported_ = 0.0;
};

}  // namespace contourmesh::filter_detail
