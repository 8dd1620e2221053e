// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/threads.h>

#include "detail/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <numeric>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#if defined(__unix__)
#include <sys/wait.h>
#include <unistd.h>
#endif

namespace contourmesh {
namespace {

// The threads that run the chunks of one parallel loop.
std::size_t threads_seen() {
  std::mutex m;
  std::set<std::thread::id> ids;
  detail::parallel_chunks(64, 1, [&](std::size_t, std::size_t, std::size_t) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    const std::lock_guard lock(m);
    ids.insert(std::this_thread::get_id());
  });
  return ids.size();
}

TEST(SmoothThreads, ALimitCapsTheLoopsAndEndsWithIt) {
  const int before = smooth_threads();
  EXPECT_GE(before, 1);
  {
    const SmoothThreadLimit one(1);
    EXPECT_EQ(one.threads(), 1);
    EXPECT_EQ(smooth_threads(), 1);
    EXPECT_EQ(threads_seen(), 1u);
    {
      const SmoothThreadLimit more(4);  // an inner limit never raises an outer one
      EXPECT_EQ(smooth_threads(), 1);
    }
    EXPECT_EQ(smooth_threads(), 1);
  }
  EXPECT_EQ(smooth_threads(), before);
  {
    const SmoothThreadLimit none(0);  // no cap
    EXPECT_EQ(smooth_threads(), before);
  }
  EXPECT_THROW(SmoothThreadLimit(-1), InvalidInputError);
}

// Sum of 0 .. n - 1 through a parallel loop of one-element chunks, reduced in chunk order.
long long chunked_sum(std::size_t n) {
  std::vector<long long> parts(n, 0);
  detail::parallel_chunks(
      n, 1, [&](std::size_t k, std::size_t begin, std::size_t) { parts[k] = static_cast<long long>(begin); });
  return std::accumulate(parts.begin(), parts.end(), 0LL);
}

thread_local int t_loops_seen = 0;

TEST(ParallelChunks, TheSameThreadsServeOneLoopAfterAnother) {
  const detail::ScopedWorkerCount three(3);
  std::mutex m;
  std::set<std::thread::id> ids;
  std::atomic<int> fresh_helpers{0};
  const std::thread::id caller = std::this_thread::get_id();
  for (int loop = 0; loop < 2; ++loop) {
    detail::parallel_chunks(48, 1, [&](std::size_t, std::size_t, std::size_t) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      const std::lock_guard lock(m);
      if (loop == 1 && std::this_thread::get_id() != caller && t_loops_seen == 0) ++fresh_helpers;
      if (t_loops_seen <= loop) t_loops_seen = loop + 1;
      ids.insert(std::this_thread::get_id());
    });
  }
  EXPECT_EQ(ids.size(), 3u);  // the caller and two helpers
  EXPECT_EQ(ids.count(caller), 1u);
  EXPECT_EQ(fresh_helpers.load(), 0) << "the second loop ran on threads made for it";
}

TEST(ParallelChunks, ALoopInsideAChunkRunsOnItsThreadAndGivesTheSameSum) {
  const detail::ScopedWorkerCount two(2);
  std::vector<long long> inner(8, 0);
  detail::parallel_chunks(8, 1, [&](std::size_t k, std::size_t, std::size_t) { inner[k] = chunked_sum(100 + k); });
  for (std::size_t k = 0; k < inner.size(); ++k) {
    const auto n = static_cast<long long>(100 + k);
    EXPECT_EQ(inner[k], n * (n - 1) / 2);
  }
}

TEST(ParallelChunks, LoopsStartedOnTwoThreadsAtOnceBothFinish) {
  const detail::ScopedWorkerCount two(2);
  std::vector<long long> sums(2, 0);
  std::vector<std::thread> callers;
  for (int c = 0; c < 2; ++c) {
    callers.emplace_back([&, c] {
      long long total = 0;
      for (int loop = 0; loop < 200; ++loop) total += chunked_sum(64);
      sums[static_cast<std::size_t>(c)] = total;
    });
  }
  for (std::thread& t : callers) t.join();
  EXPECT_EQ(sums[0], 200LL * 64 * 63 / 2);
  EXPECT_EQ(sums[1], 200LL * 64 * 63 / 2);
}

TEST(ParallelChunks, AnExceptionReachesTheCallerAndThePoolServesTheNextLoop) {
  const detail::ScopedWorkerCount two(2);
  EXPECT_THROW(detail::parallel_chunks(64, 1,
                                       [](std::size_t k, std::size_t, std::size_t) {
                                         if (k == 17) throw std::runtime_error("chunk 17");
                                       }),
               std::runtime_error);
  EXPECT_EQ(chunked_sum(64), 64LL * 63 / 2);
}

#if defined(__unix__)
TEST(MapChunks, ReturnsEachChunksResultInChunkOrderOnAnyThreadCount) {
  // 10 elements in chunks of 3: [0, 3) [3, 6) [6, 9) [9, 10); each chunk returns its range and the sum of
  // its elements, in the same order on one thread and on four.
  const auto run = [] {
    return detail::map_chunks<std::vector<std::size_t>>(10, 3,
                                                        [](std::size_t chunk, std::size_t begin, std::size_t end) {
                                                          std::vector<std::size_t> r{chunk, begin, end, 0};
                                                          for (std::size_t k = begin; k < end; ++k) r[3] += k;
                                                          return r;
                                                        });
  };
  const std::vector<std::vector<std::size_t>> expected{{0, 0, 3, 3}, {1, 3, 6, 12}, {2, 6, 9, 21}, {3, 9, 10, 9}};
  for (const unsigned threads : {1u, 4u}) {
    const detail::ScopedWorkerCount count(threads);
    EXPECT_EQ(run(), expected) << threads << " threads";
  }
  EXPECT_TRUE(detail::map_chunks<int>(0, 3, [](std::size_t, std::size_t, std::size_t) { return 1; }).empty());
}

TEST(ParallelChunks, AForkedChildRunsLoopsOnAPoolOfItsOwn) {
  const detail::ScopedWorkerCount two(2);
  ASSERT_EQ(chunked_sum(64), 64LL * 63 / 2);  // the parent's pool exists before the fork
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    alarm(20);  // a child waiting for the parent's threads would hang: end it instead
    _exit(threads_seen() == 2 && chunked_sum(64) == 64LL * 63 / 2 ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
}
#endif

}  // namespace
}  // namespace contourmesh
