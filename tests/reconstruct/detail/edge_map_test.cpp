// SPDX-License-Identifier: BSD-3-Clause
// The tiler's flat edge map: the same answers as std::unordered_map under insertions, overwrites and
// erasures, across its growth, and for keys whose home slots crowd together (erasure's backward shift).
#include "detail/edge_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <unordered_map>
#include <vector>

namespace contourmesh::detail {
namespace {

// Checks every key of `keys` against the reference.
void expect_same(const EdgeMap& map, const std::unordered_map<std::uint64_t, std::int32_t>& reference,
                 const std::vector<std::uint64_t>& keys) {
  ASSERT_EQ(map.size(), reference.size());
  for (const std::uint64_t key : keys) {
    const auto it = reference.find(key);
    const std::int32_t* value = map.find(key);
    if (it == reference.end()) {
      EXPECT_EQ(value, nullptr) << key;
    } else {
      ASSERT_NE(value, nullptr) << key;
      EXPECT_EQ(*value, it->second) << key;
    }
  }
}

TEST(EdgeMap, RandomEditsAnswerAsAnUnorderedMap) {
  // Edges of a few hundred vertices, so that keys come back after being erased; no reservation, so the
  // table grows several times on the way.
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<std::int32_t> vertex(0, 300);
  std::uniform_int_distribution<int> op(0, 9);
  EdgeMap map;
  std::unordered_map<std::uint64_t, std::int32_t> reference;
  std::vector<std::uint64_t> keys;
  for (int step = 0; step < 60000; ++step) {
    const std::uint64_t key = EdgeMap::key(vertex(rng), vertex(rng));
    keys.push_back(key);
    const auto value = static_cast<std::int32_t>(step);
    const int what = op(rng);
    if (what < 4) {
      EXPECT_EQ(map.insert(key, value), reference.emplace(key, value).second);
    } else if (what < 6) {
      map.assign(key, value);
      reference[key] = value;
    } else {
      EXPECT_EQ(map.erase(key), reference.erase(key) == 1);
    }
    if (step % 5000 == 0) expect_same(map, reference, keys);
  }
  expect_same(map, reference, keys);
}

TEST(EdgeMap, InsertKeepsThePresentValueAndAssignReplacesIt) {
  EdgeMap map;
  EXPECT_TRUE(map.insert(EdgeMap::key(1, 2), 10));
  EXPECT_FALSE(map.insert(EdgeMap::key(1, 2), 20));
  EXPECT_EQ(*map.find(EdgeMap::key(1, 2)), 10);
  map.assign(EdgeMap::key(1, 2), 30);
  EXPECT_EQ(*map.find(EdgeMap::key(1, 2)), 30);
  EXPECT_EQ(map.find(EdgeMap::key(2, 1)), nullptr);  // directed
  EXPECT_EQ(map.size(), 1u);
}

TEST(EdgeMap, ErasingFromCrowdedRunsKeepsTheRestFindable) {
  // A full table's worth of keys at its largest load (half the slots), then every other one erased in
  // an order unrelated to the insertion: each erasure moves later entries of its probe run back, and a
  // key left behind an empty slot would no longer be found.
  EdgeMap map(512);
  std::unordered_map<std::uint64_t, std::int32_t> reference;
  std::vector<std::uint64_t> keys;
  for (std::int32_t u = 0; u < 32; ++u) {
    for (std::int32_t v = 0; v < 16; ++v) {
      keys.push_back(EdgeMap::key(u, v));
      map.assign(keys.back(), u * 16 + v);
      reference[keys.back()] = u * 16 + v;
    }
  }
  std::mt19937_64 rng(3);
  std::vector<std::uint64_t> order = keys;
  std::shuffle(order.begin(), order.end(), rng);
  for (std::size_t k = 0; k < order.size(); k += 2) {
    EXPECT_TRUE(map.erase(order[k]));
    reference.erase(order[k]);
    EXPECT_FALSE(map.erase(order[k]));
  }
  expect_same(map, reference, keys);
}

TEST(EdgeMap, TheEmptyMarkIsNeverAKey) {
  // (-1, -1) gives the key the table marks empty slots with: it is refused, and never found.
  EdgeMap map;
  map.assign(EdgeMap::key(0, 1), 5);
  EXPECT_FALSE(map.insert(EdgeMap::key(-1, -1), 1));
  EXPECT_EQ(map.find(EdgeMap::key(-1, -1)), nullptr);
  EXPECT_FALSE(map.erase(EdgeMap::key(-1, -1)));
  EXPECT_EQ(map.size(), 1u);
}

}  // namespace
}  // namespace contourmesh::detail
