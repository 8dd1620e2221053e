// SPDX-License-Identifier: BSD-3-Clause
// Private: a map from mesh edges to faces (or any 32-bit value) for the tiler's local mesh edits (the
// slabs' face-quality pass, the flips after the off-slice heights, the refinement of caps). An edge is a
// 64-bit key made of two vertex ids; the map is one flat table with open addressing and linear probing,
// about three times faster to fill and search than std::unordered_map, which allocates a node per entry.
// It has no iteration: the edits only look edges up, so their results do not depend on the table's order.
#pragma once

#include "contourmesh/internal/huge_pages.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace contourmesh::detail {

class EdgeMap {
 public:
  /// The key of the directed edge (u, v), u and v >= 0.
  [[nodiscard]] static std::uint64_t key(std::int32_t u, std::int32_t v) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(u)) << 32) | static_cast<std::uint32_t>(v);
  }

  EdgeMap() = default;
  /// Room for `entries` without growing.
  explicit EdgeMap(std::size_t entries) { reserve(entries); }

  /// Makes room for `entries` entries in all (the table keeps at most half its slots filled).
  void reserve(std::size_t entries) {
    std::size_t capacity = 16;
    while (capacity < 2 * entries) capacity *= 2;
    if (capacity > keys_.size()) rehash(capacity);
  }

  [[nodiscard]] std::size_t size() const { return size_; }

  /// The value of `key`, or nullptr when it is absent (valid until the next insertion or erasure).
  [[nodiscard]] const std::int32_t* find(std::uint64_t key) const {
    if (keys_.empty() || key == kEmpty) return nullptr;
    for (std::size_t i = home(key);; i = (i + 1) & mask_) {
      if (keys_[i] == key) return &values_[i];
      if (keys_[i] == kEmpty) return nullptr;
    }
  }
  [[nodiscard]] bool contains(std::uint64_t key) const { return find(key) != nullptr; }

  /// Adds key -> value unless the key is present; whether it was added (the value stays as it was if not).
  bool insert(std::uint64_t key, std::int32_t value) { return put(key, value, false); }
  /// Sets key -> value, adding the key if it is absent.
  void assign(std::uint64_t key, std::int32_t value) { (void)put(key, value, true); }

  /// Removes `key`; whether it was present.
  bool erase(std::uint64_t key) {
    if (keys_.empty() || key == kEmpty) return false;
    std::size_t i = home(key);
    for (;; i = (i + 1) & mask_) {
      if (keys_[i] == key) break;
      if (keys_[i] == kEmpty) return false;
    }
    // Backward shift: every later entry of the probe run that may live at i moves there, so that no search
    // meets an empty slot before its key.
    for (std::size_t j = (i + 1) & mask_; keys_[j] != kEmpty; j = (j + 1) & mask_) {
      const std::size_t h = home(keys_[j]);
      const bool stays = i <= j ? (i < h && h <= j) : (i < h || h <= j);  // h cyclically in (i, j]
      if (stays) continue;
      keys_[i] = keys_[j];
      values_[i] = values_[j];
      i = j;
    }
    keys_[i] = kEmpty;
    --size_;
    return true;
  }

 private:
  // The empty slot's mark: the key of (-1, -1), which no edge has (vertex ids are non-negative); the map
  // never holds it.
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};

  [[nodiscard]] std::size_t home(std::uint64_t key) const {
    // The splitmix64 finaliser: neighbouring vertex ids land far apart.
    key ^= key >> 30;
    key *= 0xbf58476d1ce4e5b9ULL;
    key ^= key >> 27;
    key *= 0x94d049bb133111ebULL;
    key ^= key >> 31;
    return static_cast<std::size_t>(key) & mask_;
  }

  bool put(std::uint64_t key, std::int32_t value, bool overwrite) {
    if (key == kEmpty) return false;  // the edge (-1, -1): no vertex
    if (2 * (size_ + 1) > keys_.size()) rehash(keys_.empty() ? 16 : 2 * keys_.size());
    for (std::size_t i = home(key);; i = (i + 1) & mask_) {
      if (keys_[i] == key) {
        if (overwrite) values_[i] = value;
        return false;
      }
      if (keys_[i] == kEmpty) {
        keys_[i] = key;
        values_[i] = value;
        ++size_;
        return true;
      }
    }
  }

  void rehash(std::size_t capacity) {
    // A large table is written all over at once: huge pages take its page faults (and its random
    // probes' TLB misses) down by 512.
    std::vector<std::uint64_t> keys;
    std::vector<std::int32_t> values;
    assign_huge(keys, capacity, kEmpty);
    assign_huge(values, capacity, 0);
    keys.swap(keys_);
    values.swap(values_);
    mask_ = capacity - 1;
    size_ = 0;
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (keys[i] != kEmpty) (void)put(keys[i], values[i], false);
    }
  }

  std::vector<std::uint64_t> keys_;
  std::vector<std::int32_t> values_;
  std::size_t mask_ = 0;
  std::size_t size_ = 0;
};

}  // namespace contourmesh::detail
