// SPDX-License-Identifier: BSD-3-Clause
// A minimal parallel loop for libsmooth (which depends on Eigen only), on a pool of std::threads kept for
// the process's life. Work is cut into fixed chunks that do not depend on the number of threads, so a
// reduction over chunks in chunk order gives the same result on any machine.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace contourmesh::detail {

/// When non-zero, the number of worker threads instead of the cores' (tests: results must not depend on
/// it). Set it through ScopedWorkerCount.
inline std::atomic<unsigned>& worker_count_override() {
  static std::atomic<unsigned> count{0};
  return count;
}

/// When non-zero, the most threads a parallel loop may use (SmoothThreadLimit, threads.h).
inline std::atomic<unsigned>& thread_cap() {
  static std::atomic<unsigned> cap{0};
  return cap;
}

/// Number of worker threads: the override if set, else hardware concurrency under the live cap; at
/// least 1, at most 64.
inline unsigned worker_count() {
  const unsigned forced = worker_count_override();
  if (forced != 0) return std::clamp(forced, 1u, 64u);
  const unsigned cap = thread_cap();
  const unsigned cores = std::thread::hardware_concurrency();
  return std::clamp(cap != 0 ? std::min(cap, std::max(cores, 1u)) : cores, 1u, 64u);
}

/// Runs parallel loops on `count` threads while it lives (even beyond the number of cores).
class ScopedWorkerCount {
 public:
  explicit ScopedWorkerCount(unsigned count) : previous_(worker_count_override().exchange(count)) {}
  ~ScopedWorkerCount() { worker_count_override() = previous_; }
  ScopedWorkerCount(const ScopedWorkerCount&) = delete;
  ScopedWorkerCount& operator=(const ScopedWorkerCount&) = delete;

 private:
  unsigned previous_;
};

/// An allocator whose value-less construction leaves a scalar uninitialised: a vector resized with it
/// touches no memory, so that the parallel loop that then writes every element faults its pages in on
/// every core instead of the calling thread zeroing them first.
template <typename T>
struct DefaultInitAllocator : std::allocator<T> {
  using std::allocator<T>::allocator;
  template <typename U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// A vector for buffers that a parallel loop fills completely after resize().
template <typename T>
using FillVector = std::vector<T, DefaultInitAllocator<T>>;

/// Runs job(context) on the calling thread and on `helpers` threads of the process's worker pool at
/// once, and returns true when every run has returned. The pool's threads are made on first use (as many
/// as the largest loop asked for) and then wait for work; a process forked from this one starts a pool of
/// its own. Returns false at once, having run nothing, where the pool cannot serve: it runs another loop
/// (another thread's, or this one called from a pool thread: a nested loop), or a thread could not be
/// made. `job` must not throw.
bool run_on_pool(unsigned helpers, void (*job)(void*), void* context) noexcept;

/// Calls body(chunk, begin, end) for the chunks [k * chunk_size, min(n, (k + 1) * chunk_size)), on all
/// cores: the calling thread and up to worker_count() - 1 pool threads take chunks in turn. A loop the
/// pool cannot serve (see run_on_pool) runs on the calling thread alone, with the same result. The first
/// exception thrown by a body is rethrown after every thread has stopped.
template <typename Body>
void parallel_chunks(std::size_t n, std::size_t chunk_size, const Body& body) {
  chunk_size = std::max<std::size_t>(chunk_size, 1);
  const std::size_t chunks = (n + chunk_size - 1) / chunk_size;
  const unsigned threads = static_cast<unsigned>(std::min<std::size_t>(worker_count(), chunks));
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&] {
    for (std::size_t k = next++; k < chunks; k = next++) {
      try {
        body(k, k * chunk_size, std::min(n, (k + 1) * chunk_size));
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = chunks;
      }
    }
  };
  const auto run = [](void* context) { (*static_cast<decltype(work)*>(context))(); };
  if (threads <= 1 || !run_on_pool(threads - 1, run, &work)) work();
  if (error) std::rethrow_exception(error);
}

/// parallel_chunks for a result per chunk: body(chunk, begin, end) returns the chunk's result (a count, a
/// list, partial sums), and the results come back in chunk order, so a reduction over them in that order
/// does not depend on the thread count. Each result is stored once, when its chunk ends: a body that
/// wrote into a shared per-chunk array as it went (a count per vertex, a vector's header per append) made
/// the threads take the cache line its neighbours' entries share from each other (docs/benchmarks.md).
template <typename Result, typename Body>
std::vector<Result> map_chunks(std::size_t n, std::size_t chunk_size, const Body& body) {
  chunk_size = std::max<std::size_t>(chunk_size, 1);
  std::vector<Result> results((n + chunk_size - 1) / chunk_size);
  parallel_chunks(n, chunk_size, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    results[chunk] = body(chunk, begin, end);
  });
  return results;
}

}  // namespace contourmesh::detail
