// SPDX-License-Identifier: BSD-3-Clause
// Items filed by bucket in one array: each bucket holds its items in the order filed, empty buckets
// hold none, and an item filed in several buckets is in each.
#include "detail/bucket_lists.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <utility>
#include <vector>

namespace contourmesh::detail {
namespace {

TEST(BucketLists, EachBucketHoldsItsItemsInTheOrderFiled) {
  const std::vector<std::pair<std::size_t, int>> filed = {{3, 10}, {0, 11}, {3, 12}, {1, 13},
                                                          {3, 14}, {0, 15}, {1, 11}};
  std::vector<int> start, items;
  file_in_buckets(
      5,
      [&](const auto& file) {
        for (const auto& [bucket, item] : filed) file(bucket, item);
      },
      start, items);
  ASSERT_EQ(start, (std::vector<int>{0, 2, 4, 4, 7, 7}));
  EXPECT_EQ(items, (std::vector<int>{11, 15, 13, 11, 10, 12, 14}));
}

TEST(BucketLists, NothingFiledLeavesEveryBucketEmpty) {
  std::vector<std::size_t> start{9, 9}, items{1, 2, 3};
  file_in_buckets(3, [](const auto&) {}, start, items);
  EXPECT_EQ(start, (std::vector<std::size_t>{0, 0, 0, 0}));
  EXPECT_TRUE(items.empty());
}

}  // namespace
}  // namespace contourmesh::detail
