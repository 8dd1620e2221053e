// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/threads.h"

#include "contourmesh/smooth/errors.h"
#include "detail/parallel.h"

#include <algorithm>
#include <string>

namespace contourmesh {

SmoothThreadLimit::SmoothThreadLimit(int threads) : threads_(threads) {
  if (threads < 0)
    throw InvalidInputError("the thread count must be >= 0 (0: every core), got " + std::to_string(threads));
  previous_ = detail::thread_cap().load();
  if (threads == 0) return;
  const auto cap = static_cast<unsigned>(threads);
  detail::thread_cap() = previous_ == 0 ? cap : std::min(previous_, cap);
}

SmoothThreadLimit::~SmoothThreadLimit() { detail::thread_cap() = previous_; }

int smooth_threads() { return static_cast<int>(detail::worker_count()); }

}  // namespace contourmesh
