// SPDX-License-Identifier: BSD-3-Clause
// Private to ContourMesh (not installed): disjoint sets over the integers 0..size()-1, shared by
// libsmooth and libreconstruct (mesh components, manifold fans, contour groups, pixel runs).
#pragma once

#include <cstddef>
#include <numeric>
#include <type_traits>
#include <utility>
#include <vector>

namespace contourmesh::detail {

/// Union-find with path halving. The root of a set is always its smallest element, so a set's root is
/// the first of its elements in index order: callers that number sets by their roots in index order get
/// the numbering of a scan in that order, whatever order the unions came in. `T` is the element type
/// (a signed or unsigned integer); reset() keeps the buffer, so one object serves many problems.
template <typename T = std::size_t>
class UnionFind {
  static_assert(std::is_integral_v<T>);

 public:
  UnionFind() = default;
  explicit UnionFind(std::size_t n) { reset(n); }

  /// n singletons {0}, {1}, ..., {n - 1}.
  void reset(std::size_t n) {
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), T{0});
  }

  /// Adds the singleton {size()} and returns it.
  T add() {
    const T x = static_cast<T>(parent_.size());
    parent_.push_back(x);
    return x;
  }

  [[nodiscard]] std::size_t size() const { return parent_.size(); }

  /// The root (smallest element) of x's set.
  T find(T x) {
    while (parent_[static_cast<std::size_t>(x)] != x) {
      T& p = parent_[static_cast<std::size_t>(x)];
      p = parent_[static_cast<std::size_t>(p)];  // path halving
      x = p;
    }
    return x;
  }

  /// Joins the sets of a and b; returns the root of the joined set (the smaller of the two roots).
  T unite(T a, T b) {
    a = find(a);
    b = find(b);
    if (b < a) std::swap(a, b);
    if (a != b) parent_[static_cast<std::size_t>(b)] = a;
    return a;
  }

  [[nodiscard]] bool same(T a, T b) { return find(a) == find(b); }

 private:
  std::vector<T> parent_;
};

}  // namespace contourmesh::detail
