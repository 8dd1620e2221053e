// SPDX-License-Identifier: BSD-3-Clause
// Progress reporting and cancellation for long-running work.
#pragma once

#include <functional>
#include <string_view>

namespace contourmesh {

/// Called with the name of the current stage ("smooth", "detect", ...) and the fraction of that stage
/// done, in [0, 1]. Return false to cancel: the operation then throws CancelledError and returns nothing.
/// Called at most once per iteration (never inside per-vertex loops), from the calling thread.
using ProgressCallback = std::function<bool(std::string_view stage, double fraction)>;

}  // namespace contourmesh
