// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/threads.h>

#include "detail/parallel.h"

#include <gtest/gtest.h>

#include <chrono>
#include <mutex>
#include <set>
#include <thread>

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

}  // namespace
}  // namespace contourmesh
