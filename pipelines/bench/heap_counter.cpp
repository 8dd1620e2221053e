// SPDX-License-Identifier: BSD-3-Clause
#include "heap_counter.h"

#include <atomic>
#include <cerrno>
#include <cstddef>

#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
#include <malloc.h>
#include <unistd.h>
#define CONTOURMESH_COUNT_HEAP 1
#endif

namespace contourmesh::bench {

namespace {

std::atomic<std::int64_t> g_live{0};
std::atomic<std::int64_t> g_peak{0};

}  // namespace

bool heap_counting_available() {
#ifdef CONTOURMESH_COUNT_HEAP
  return true;
#else
  return false;
#endif
}

std::int64_t live_heap_bytes() { return g_live.load(std::memory_order_relaxed); }
std::int64_t peak_heap_bytes() { return g_peak.load(std::memory_order_relaxed); }
void reset_heap_peak() { g_peak.store(g_live.load(std::memory_order_relaxed), std::memory_order_relaxed); }

}  // namespace contourmesh::bench

#ifdef CONTOURMESH_COUNT_HEAP

// glibc's own allocator entry points, which stay reachable when malloc is interposed (noexcept, as
// glibc declares its allocator with __THROW).
extern "C" {
void* __libc_malloc(std::size_t size) noexcept;
void* __libc_calloc(std::size_t count, std::size_t size) noexcept;
void* __libc_realloc(void* ptr, std::size_t size) noexcept;
void* __libc_memalign(std::size_t alignment, std::size_t size) noexcept;
void __libc_free(void* ptr) noexcept;
}

namespace {

using contourmesh::bench::g_live;
using contourmesh::bench::g_peak;

void count_alloc(void* p) {
  if (p == nullptr) return;
  const auto bytes = static_cast<std::int64_t>(malloc_usable_size(p));
  const std::int64_t now = g_live.fetch_add(bytes, std::memory_order_relaxed) + bytes;
  std::int64_t peak = g_peak.load(std::memory_order_relaxed);
  while (now > peak && !g_peak.compare_exchange_weak(peak, now, std::memory_order_relaxed)) {
  }
}

void count_free(void* p) {
  if (p != nullptr) g_live.fetch_sub(static_cast<std::int64_t>(malloc_usable_size(p)), std::memory_order_relaxed);
}

}  // namespace

extern "C" {

void* malloc(std::size_t size) noexcept {
  void* p = __libc_malloc(size);
  count_alloc(p);
  return p;
}

void* calloc(std::size_t count, std::size_t size) noexcept {
  void* p = __libc_calloc(count, size);
  count_alloc(p);
  return p;
}

void* realloc(void* ptr, std::size_t size) noexcept {
  const auto old_bytes = ptr ? static_cast<std::int64_t>(malloc_usable_size(ptr)) : 0;
  void* p = __libc_realloc(ptr, size);
  if (p != nullptr || size == 0) g_live.fetch_sub(old_bytes, std::memory_order_relaxed);  // old block gone
  count_alloc(p);
  return p;
}

void free(void* ptr) noexcept {
  count_free(ptr);
  __libc_free(ptr);
}

void* memalign(std::size_t alignment, std::size_t size) noexcept {
  void* p = __libc_memalign(alignment, size);
  count_alloc(p);
  return p;
}

void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept { return memalign(alignment, size); }

int posix_memalign(void** out, std::size_t alignment, std::size_t size) noexcept {
  if (alignment < sizeof(void*) || (alignment & (alignment - 1)) != 0) return EINVAL;
  void* p = memalign(alignment, size);
  if (p == nullptr && size != 0) return ENOMEM;
  *out = p;
  return 0;
}

void* valloc(std::size_t size) noexcept { return memalign(static_cast<std::size_t>(sysconf(_SC_PAGESIZE)), size); }

void* pvalloc(std::size_t size) noexcept {
  const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  return memalign(page, (size + page - 1) / page * page);
}

}  // extern "C"

#endif  // CONTOURMESH_COUNT_HEAP
