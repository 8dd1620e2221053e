// SPDX-License-Identifier: BSD-3-Clause
// Private to ContourMesh (not installed): transparent huge pages for the large buffers of libsmooth and
// libreconstruct (docs/benchmarks.md, "Page faults and huge pages"). Compiled into libsmooth
// (src/detail/huge_pages.cpp). A fresh buffer of n bytes costs n / 4 KiB page faults on its first
// writes; on a virtual machine each costs several microseconds of kernel time: a fifth of the default
// smoothing's CPU time on the benchmarks' 1M-vertex mesh. Where Linux keeps transparent huge pages on
// advice ("madvise", its usual default), a buffer advised before its first write takes one fault per
// 2 MiB.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <type_traits>
#include <vector>

namespace contourmesh::detail {

/// Buffers smaller than this are left alone: they hold no whole 2 MiB page worth the advice.
inline constexpr std::size_t kHugePageAdviceBytes = std::size_t{4} << 20;

/// Asks the kernel to back the whole 2 MiB pages inside [data, data + bytes) with huge pages where it
/// can. Only advice: a no-op below kHugePageAdviceBytes, off Linux, or where the kernel refuses; the
/// contents are untouched. Call it before the buffer's first write: pages already written stay small
/// until the kernel's background collapse, if any.
void advise_huge_pages(void* data, std::size_t bytes) noexcept;

/// Reserves room for `n` elements in `v` and advises the new storage, before any element is written;
/// follow with resize or assign.
template <typename T, typename Alloc>
void reserve_huge(std::vector<T, Alloc>& v, std::size_t n) {
  if (n <= v.capacity()) return;
  v.reserve(n);
  advise_huge_pages(v.data(), n * sizeof(T));
}

/// `v` resized to `n` elements (value-initialised, or left uninitialised by a FillVector), its new
/// storage advised first.
template <typename T, typename Alloc>
void resize_huge(std::vector<T, Alloc>& v, std::size_t n) {
  reserve_huge(v, n);
  v.resize(n);
}

/// `v` resized to `n` copies of `value` (value-initialised with the default), its storage advised first.
template <typename T, typename Alloc>
void assign_huge(std::vector<T, Alloc>& v, std::size_t n, const std::type_identity_t<T>& value = T()) {
  if (n > v.capacity()) {
    std::vector<T, Alloc>().swap(v);
    reserve_huge(v, n);
  }
  v.assign(n, value);
}

/// An uninitialised Eigen matrix of the given shape, advised before its first write.
template <typename Matrix>
Matrix huge_matrix(Eigen::Index rows, Eigen::Index cols) {
  Matrix m(rows, cols);
  advise_huge_pages(m.data(), static_cast<std::size_t>(m.size()) * sizeof(typename Matrix::Scalar));
  return m;
}

/// A zero Eigen matrix of the given shape, advised before it is zeroed.
template <typename Matrix>
Matrix huge_zero(Eigen::Index rows, Eigen::Index cols) {
  Matrix m = huge_matrix<Matrix>(rows, cols);
  m.setZero();
  return m;
}

}  // namespace contourmesh::detail
