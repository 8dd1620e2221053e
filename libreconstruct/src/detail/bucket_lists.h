// SPDX-License-Identifier: BSD-3-Clause
// Private: items filed by bucket in one array (compressed rows), for the tiler's spatial look-ups (the
// crossing bands' edge grid, the Outline's strips): one allocation for all buckets instead of one each.
#pragma once

#include <cstddef>
#include <vector>

namespace contourmesh::detail {

/// Files items in `buckets` buckets: bucket b's items are items[start[b]] .. items[start[b + 1] - 1], in
/// the order they were filed. `each(file)` must call file(bucket, item) for every item, bucket <
/// `buckets`; it is called twice (to count, then to place) and must file the same items both times.
/// `Index` is the items' type and the type of `start`.
template <class Index, class Each>
void file_in_buckets(std::size_t buckets, const Each& each, std::vector<Index>& start, std::vector<Index>& items) {
  start.assign(buckets + 1, 0);
  each([&](std::size_t bucket, Index) { ++start[bucket + 1]; });
  for (std::size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  items.resize(static_cast<std::size_t>(start[buckets]));
  std::vector<Index> next(start.begin(), start.end() - 1);
  each([&](std::size_t bucket, Index item) { items[static_cast<std::size_t>(next[bucket]++)] = item; });
}

}  // namespace contourmesh::detail
