// SPDX-License-Identifier: BSD-3-Clause
// Live-heap accounting for the benchmark program: heap_counter.cpp replaces malloc, calloc, realloc,
// free and the aligned allocators of this executable (glibc symbol interposition) with thin wrappers
// that forward to glibc's allocator and count the usable size of every block. operator new (libstdc++),
// Eigen's aligned_malloc, VTK and ITK all allocate through malloc, so every heap byte is seen.
// Elsewhere than glibc the counter is absent and peak_heap_bytes_during returns NaN.
#pragma once

#include <cstdint>
#include <limits>
#include <utility>

namespace contourmesh::bench {

/// True when allocations are counted (glibc builds).
[[nodiscard]] bool heap_counting_available();
/// Bytes currently allocated on the heap (usable sizes of live blocks).
[[nodiscard]] std::int64_t live_heap_bytes();
/// Highest live_heap_bytes since the last reset_heap_peak.
[[nodiscard]] std::int64_t peak_heap_bytes();
/// Sets the peak to the current live bytes.
void reset_heap_peak();

/// Runs `f()` and returns the peak of live heap bytes during the call above what was live before it
/// (so it includes whatever the call returns, while it is alive). NaN without counting.
template <typename F>
double peak_heap_bytes_during(F&& f) {
  reset_heap_peak();
  const std::int64_t before = live_heap_bytes();
  std::forward<F>(f)();
  if (!heap_counting_available()) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(peak_heap_bytes() - before);
}

}  // namespace contourmesh::bench
