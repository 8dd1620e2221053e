// SPDX-License-Identifier: BSD-3-Clause
// Wall-clock seconds for the stage times that results report.
#pragma once

#include <chrono>

namespace contourmesh::detail {

/// Seconds of the steady clock since `t`.
inline double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace contourmesh::detail
