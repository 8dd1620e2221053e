// SPDX-License-Identifier: BSD-3-Clause
// The one union-find of the project, against a plain relabelling and its root contract.
#include "contourmesh/internal/union_find.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <random>
#include <utility>
#include <vector>

namespace contourmesh::detail {
namespace {

TEST(UnionFind, StartsAsSingletons) {
  UnionFind<int> uf(5);
  EXPECT_EQ(uf.size(), 5u);
  for (int k = 0; k < 5; ++k) EXPECT_EQ(uf.find(k), k);
  EXPECT_FALSE(uf.same(0, 4));
}

TEST(UnionFind, TheRootIsTheSmallestElementWhateverTheOrderOfUnions) {
  UnionFind<> uf(6);
  EXPECT_EQ(uf.unite(5, 3), 3u);
  EXPECT_EQ(uf.unite(4, 5), 3u);
  EXPECT_EQ(uf.unite(4, 1), 1u);
  for (std::size_t k : {1u, 3u, 4u, 5u}) EXPECT_EQ(uf.find(k), 1u);
  EXPECT_EQ(uf.find(0), 0u);
  EXPECT_EQ(uf.find(2), 2u);
  EXPECT_EQ(uf.unite(3, 5), 1u);  // already joined
}

TEST(UnionFind, AddAndResetKeepTheContract) {
  UnionFind<int> uf;
  EXPECT_EQ(uf.add(), 0);
  EXPECT_EQ(uf.add(), 1);
  uf.unite(1, 0);
  EXPECT_TRUE(uf.same(0, 1));
  uf.reset(3);
  EXPECT_EQ(uf.size(), 3u);
  EXPECT_FALSE(uf.same(0, 1));
}

// Random unions against a naive relabelling (every element carries its set's smallest member).
TEST(UnionFind, AgreesWithNaiveRelabelling) {
  std::mt19937 rng(7);
  constexpr std::size_t n = 200;
  UnionFind<> uf(n);
  std::vector<std::size_t> label(n);
  for (std::size_t k = 0; k < n; ++k) label[k] = k;
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  for (int step = 0; step < 150; ++step) {
    const std::size_t a = pick(rng), b = pick(rng);
    uf.unite(a, b);
    const std::size_t from = std::max(label[a], label[b]), to = std::min(label[a], label[b]);
    for (std::size_t& l : label) {
      if (l == from) l = to;
    }
    if (step % 10 == 0) {
      for (std::size_t k = 0; k < n; ++k) ASSERT_EQ(uf.find(k), label[k]) << "element " << k << " step " << step;
    }
  }
  for (std::size_t k = 0; k < n; ++k) EXPECT_EQ(uf.find(k), label[k]);
}

}  // namespace
}  // namespace contourmesh::detail
