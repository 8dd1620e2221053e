// SPDX-License-Identifier: BSD-3-Clause
#include "detail/parallel.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#if defined(__unix__)
#include <pthread.h>
#endif

namespace contourmesh::detail {

namespace {

// Set on the pool's own threads, and on a caller while the pool runs its loop: a loop started from a
// chunk (a nested loop) runs on its thread alone.
thread_local bool t_in_loop = false;

// Threads that wait for the next loop instead of being made and joined for each one. Making two
// threads and joining them cost 0.1-0.2 ms on the machines we measured, and the default smoothing runs
// about two hundred loops per call: on a 10k-vertex mesh that was more than the loops' work at two threads.
class WorkerPool {
 public:
  bool run(unsigned helpers, void (*job)(void*), void* context) noexcept {
    if (t_in_loop) return false;
    std::unique_lock<std::mutex> busy(busy_, std::try_to_lock);
    if (!busy.owns_lock()) return false;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      try {
        while (threads_.size() < helpers) {
          const auto index = static_cast<unsigned>(threads_.size());
          threads_.emplace_back([this, index] { serve(index); });
        }
      } catch (...) {  // no thread to be had: the caller runs the loop alone
        if (threads_.empty()) return false;
      }
      job_ = job;
      context_ = context;
      wanted_ = std::min<unsigned>(helpers, static_cast<unsigned>(threads_.size()));
      running_ = wanted_;
      ++generation_;
    }
    wake_.notify_all();
    t_in_loop = true;
    job(context);
    t_in_loop = false;
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return running_ == 0; });
    return true;
  }

 private:
  // Thread `index` of the pool: runs each loop that asks for more than `index` helpers, once.
  void serve(unsigned index) {
    t_in_loop = true;
    std::uint64_t seen = 0;
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      wake_.wait(lock, [&] { return generation_ != seen; });
      seen = generation_;
      if (index >= wanted_) continue;
      void (*job)(void*) = job_;
      void* context = context_;
      lock.unlock();
      job(context);
      lock.lock();
      if (--running_ == 0) done_.notify_one();
    }
  }

  std::mutex busy_;   // held by the thread whose loop the pool runs, for the whole loop
  std::mutex mutex_;  // guards what follows
  std::condition_variable wake_, done_;
  std::vector<std::thread> threads_;
  std::uint64_t generation_ = 0;  // loops started
  unsigned wanted_ = 0;           // helpers of the current loop: threads 0 .. wanted_ - 1
  unsigned running_ = 0;          // helpers still running it
  void (*job_)(void*) = nullptr;
  void* context_ = nullptr;
};

// The process's pool, made on first use and never destroyed: its threads wait until the process ends,
// and a loop run from a static destructor still finds it. A forked child has none of its threads, so
// it forgets the parent's pool (leaving it, and any lock another thread held at the fork, untouched) and
// makes its own.
std::atomic<WorkerPool*> g_pool{nullptr};

WorkerPool& pool() {
  WorkerPool* current = g_pool.load(std::memory_order_acquire);
  if (current != nullptr) return *current;
#if defined(__unix__)
  static const int registered = pthread_atfork(nullptr, nullptr, [] { g_pool.store(nullptr); });
  (void)registered;
#endif
  auto* fresh = new WorkerPool;
  if (g_pool.compare_exchange_strong(current, fresh, std::memory_order_acq_rel)) return *fresh;
  delete fresh;
  return *current;
}

}  // namespace

bool run_on_pool(unsigned helpers, void (*job)(void*), void* context) noexcept {
  if (helpers == 0) return false;
  try {
    return pool().run(helpers, job, context);
  } catch (...) {  // the pool itself could not be made
    return false;
  }
}

}  // namespace contourmesh::detail
