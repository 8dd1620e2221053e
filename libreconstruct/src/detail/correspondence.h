// SPDX-License-Identifier: BSD-3-Clause
// Private: which contours of two adjacent levels belong to the same piece of surface.
#pragma once

#include "detail/tiling_types.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace contourmesh::detail {

/// Links between the contours of a lower and an upper level.
struct Correspondence {
  std::vector<std::vector<int>> up;    ///< per lower contour: the upper contours it corresponds to
  std::vector<std::vector<int>> down;  ///< per upper contour: the lower contours it corresponds to
  /// A hole with no partner whose outer contour continues, and whose region is mostly background on the
  /// other level: the cavity opens to the outside there (as the inside of a skull through an orbit).
  std::vector<std::uint8_t> opens_up;    ///< per lower contour
  std::vector<std::uint8_t> opens_down;  ///< per upper contour
  /// Of the opening holes, those whose region on the other level lies mostly in the holes of their outer
  /// contour's partners rather than outside them: a pocket in a wall above (or below) a large cavity, as
  /// the diploe over the cranial cavity where the skull's roof is nearly flat. The slices cannot tell
  /// whether the two cavities meet between them; joined to the outer contour's composite, the pocket's
  /// bridge would cross the whole wall.
  std::vector<std::uint8_t> over_hole_up;    ///< per lower contour
  std::vector<std::uint8_t> over_hole_down;  ///< per upper contour
};

/// Two outer contours correspond when their filled regions overlap by more than `of_smaller` of the
/// smaller region and `of_larger` of the larger; two holes when their regions overlap so and their outer
/// contours correspond.
[[nodiscard]] Correspondence correspond(const Level& lower, const Level& upper, double of_smaller, double of_larger);
/// The same with the fractions of `options`.
[[nodiscard]] Correspondence correspond(const Level& lower, const Level& upper, const TilingOptions& options);

/// The contours of one connected piece: outer contours joined by correspondence, with their holes.
/// Indices into the lower and upper level, increasing.
struct ContourGroup {
  std::vector<int> lower;
  std::vector<int> upper;
};

/// The groups of the two levels, ordered by their first contour (lower level first).
[[nodiscard]] std::vector<ContourGroup> contour_groups(const Level& lower, const Level& upper,
                                                       const Correspondence& links);

/// `links` among the contours of `group` only, numbered as restrict_level numbers them: what correspond
/// gives for the two restricted levels (a group holds every contour its contours' links and the
/// coverage of its holes read), without computing the overlaps again.
[[nodiscard]] Correspondence restrict_correspondence(const Correspondence& links, const ContourGroup& group);

/// How a group passes from one level to the other.
enum class GroupChange {
  EndsAbove,   ///< no upper contour: the lower contours are capped
  EndsBelow,   ///< no lower contour: the upper contours are capped
  OneToOne,    ///< one outer contour each side, every hole paired with exactly one hole
  Topology,    ///< anything else: a split or merge, a hole that opens, closes or starts
};

/// The kind of `group`; for OneToOne, `pairs` receives the (lower, upper) pairs, outer first.
[[nodiscard]] GroupChange classify_group(const ContourGroup& group, const Level& lower, const Level& upper,
                                         const Correspondence& links,
                                         std::vector<std::pair<int, int>>* pairs = nullptr);

}  // namespace contourmesh::detail
