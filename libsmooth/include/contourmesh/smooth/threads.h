// SPDX-License-Identifier: BSD-3-Clause
// How many threads the parallel stages of libsmooth use (cross-slice smoothing, crease detection): one
// cap for the whole process.
#pragma once

namespace contourmesh {

/// While alive, caps the threads of libsmooth's parallel loops at `threads`, the calling thread
/// included; 0 = no cap (every core). Nested limits: the smallest live cap holds, and the previous cap
/// comes back when a limit ends, so end limits in the reverse order of their creation. Results never
/// depend on the thread count: the loops cut their work into fixed chunks and join them in order.
/// libreconstruct's ThreadLimit creates one, so a process that caps its threads there (the command
/// line's --threads) caps the smoothing too. Throws InvalidInputError for a negative count.
class SmoothThreadLimit {
 public:
  explicit SmoothThreadLimit(int threads);
  ~SmoothThreadLimit();
  SmoothThreadLimit(const SmoothThreadLimit&) = delete;
  SmoothThreadLimit& operator=(const SmoothThreadLimit&) = delete;
  /// The cap asked for (0: none).
  [[nodiscard]] int threads() const { return threads_; }

 private:
  int threads_ = 0;
  unsigned previous_ = 0;
};

/// The number of threads a libsmooth parallel loop started now may use: the smallest live
/// SmoothThreadLimit, else the cores available; at least 1, at most 64.
[[nodiscard]] int smooth_threads();

}  // namespace contourmesh
