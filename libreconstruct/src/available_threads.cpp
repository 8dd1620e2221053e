// SPDX-License-Identifier: BSD-3-Clause
// available_threads() on its own, without ITK: the tiler needs it, and the fuzz build (clang, which
// Debian's ITK headers refuse) compiles the tiler without the rest of threads.cpp.
#include "contourmesh/reconstruct/threads.h"

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>

namespace contourmesh {

int available_threads() {
  const auto cap = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  const auto cores = static_cast<std::size_t>(std::max(tbb::this_task_arena::max_concurrency(), 1));
  return static_cast<int>(std::max<std::size_t>(std::min(cap, cores), 1));
}

}  // namespace contourmesh
