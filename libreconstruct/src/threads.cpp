// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/threads.h"

#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/threads.h>

#include <itkMultiThreaderBase.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <optional>
#include <string>

namespace contourmesh {

struct ThreadLimit::Impl {
  explicit Impl(int threads) : smooth_limit(threads) {}
  SmoothThreadLimit smooth_limit;
  std::optional<tbb::global_control> tbb_limit;
  itk::ThreadIdType previous_itk = 0;
};

ThreadLimit::ThreadLimit(int threads) : threads_(threads) {
  if (threads < 0)
    throw InvalidInputError("the thread count must be >= 0 (0: every core), got " + std::to_string(threads));
  if (threads == 0) return;
  impl_ = std::make_unique<Impl>(threads);
  impl_->tbb_limit.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  impl_->previous_itk = itk::MultiThreaderBase::GetGlobalDefaultNumberOfThreads();
  const auto itk_threads = std::min(static_cast<itk::ThreadIdType>(threads), impl_->previous_itk);
  itk::MultiThreaderBase::SetGlobalDefaultNumberOfThreads(std::max<itk::ThreadIdType>(itk_threads, 1));
}

ThreadLimit::~ThreadLimit() {
  if (impl_) itk::MultiThreaderBase::SetGlobalDefaultNumberOfThreads(impl_->previous_itk);
}

}  // namespace contourmesh
