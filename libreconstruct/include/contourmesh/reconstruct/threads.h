// SPDX-License-Identifier: BSD-3-Clause
// How many threads the parallel stages of ContourMesh use: one setting for the whole process.
#pragma once

#include <memory>

namespace contourmesh {

/// While alive, caps the worker threads of every parallel stage in the process at `threads`:
/// the TBB loops of libreconstruct (segmentation runs its slices in parallel), libsmooth's loops
/// (cross-slice smoothing; through a SmoothThreadLimit, contourmesh/smooth/threads.h), VTK's SMP
/// tools when VTK runs them on TBB (as Debian's VTK does: flying edges, windowed sinc), and ITK's filters
/// (denoising, Otsu). 0 = no cap: every core the process may use. The calling thread counts as one
/// of the `threads`.
///
/// Nested limits: TBB obeys the smallest live cap, and so does ITK (a limit never raises ITK's
/// thread count above an enclosing one's); ITK's previous setting comes back when the limit ends.
/// Create it in the main thread before the parallel work (the command line does, from --threads).
/// Results never depend on the thread count. Throws InvalidInputError for a negative count.
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

  /// The cap asked for (0: none).
  [[nodiscard]] int threads() const { return threads_; }

 private:
  struct Impl;
  int threads_ = 0;
  std::unique_ptr<Impl> impl_;
};

/// The number of threads a parallel loop started now may use (calling thread included): the
/// smallest live ThreadLimit, else the cores available. >= 1.
[[nodiscard]] int available_threads();

}  // namespace contourmesh
