// SPDX-License-Identifier: BSD-3-Clause
#include "detail/correspondence.h"

#include "contourmesh/internal/union_find.h"

#include <algorithm>

namespace contourmesh::detail {

namespace {

bool overlaps(const LevelContour& a, const LevelContour& b, double of_smaller, double of_larger) {
  const double needed = std::max(of_smaller * std::min(a.area, b.area), of_larger * std::max(a.area, b.area));
  // The regions cannot overlap by more than their boxes do.
  if (!a.box.intersects(b.box) || a.box.intersection(b.box).volume() <= needed) return false;
  // A coarse estimate decides unless it is near the threshold (its error is about 1/32 of the common
  // height times the width).
  const double coarse = overlap_area(a.points, b.points, 32);
  if (coarse > 2.0 * needed) return true;
  if (coarse < 0.5 * needed) return false;
  return overlap_area(a.points, b.points) > needed;
}

// Shares of hole `h` that the regions of `outers` of `other` cover (their holes excluded), and that
// their holes cover.
struct Coverage {
  double material = 1.0;
  double holes = 0.0;
};
Coverage covered_fractions(const LevelContour& h, const Level& other, const std::vector<int>& outers) {
  double outlines = 0.0, holes = 0.0;
  for (int o : outers) {
    const LevelContour& outer = other.contours[static_cast<std::size_t>(o)];
    if (!outer.box.intersects(h.box)) continue;
    outlines += overlap_area(h.points, outer.points);
    for (const LevelContour& g : other.contours) {
      if (g.is_hole && g.parent == o && g.box.intersects(h.box)) holes += overlap_area(h.points, g.points);
    }
  }
  if (!(h.area > 0.0)) return {};
  return {(outlines - holes) / h.area, holes / h.area};
}

}  // namespace

Correspondence correspond(const Level& lower, const Level& upper, const TilingOptions& options) {
  return correspond(lower, upper, options.min_overlap_fraction, options.min_overlap_of_larger);
}

Correspondence correspond(const Level& lower, const Level& upper, double of_smaller, double of_larger) {
  const auto& a = lower.contours;
  const auto& b = upper.contours;
  Correspondence c;
  c.up.resize(a.size());
  c.down.resize(b.size());
  c.opens_up.assign(a.size(), 0);
  c.opens_down.assign(b.size(), 0);
  auto link = [&](std::size_t i, std::size_t j) {
    c.up[i].push_back(static_cast<int>(j));
    c.down[j].push_back(static_cast<int>(i));
  };
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].is_hole) continue;
    for (std::size_t j = 0; j < b.size(); ++j) {
      if (!b[j].is_hole && overlaps(a[i], b[j], of_smaller, of_larger)) link(i, j);
    }
  }
  // Holes correspond only when their outer contours do.
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!a[i].is_hole || a[i].parent < 0) continue;
    const auto& parents_up = c.up[static_cast<std::size_t>(a[i].parent)];
    for (std::size_t j = 0; j < b.size(); ++j) {
      if (!b[j].is_hole || b[j].parent < 0) continue;
      if (std::find(parents_up.begin(), parents_up.end(), b[j].parent) == parents_up.end()) continue;
      if (overlaps(a[i], b[j], of_smaller, of_larger)) link(i, j);
    }
  }
  // A hole with no partner whose outer continues either ends (the material on the other side covers it)
  // or opens (its region is background there): to the outside, or over a hole of the other side.
  c.over_hole_up.assign(a.size(), 0);
  c.over_hole_down.assign(b.size(), 0);
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].is_hole && a[i].parent >= 0 && c.up[i].empty() && !c.up[static_cast<std::size_t>(a[i].parent)].empty()) {
      const Coverage k = covered_fractions(a[i], upper, c.up[static_cast<std::size_t>(a[i].parent)]);
      c.opens_up[i] = k.material < 0.5;
      c.over_hole_up[i] = c.opens_up[i] && k.holes >= 0.5;
    }
  }
  for (std::size_t j = 0; j < b.size(); ++j) {
    if (b[j].is_hole && b[j].parent >= 0 && c.down[j].empty() &&
        !c.down[static_cast<std::size_t>(b[j].parent)].empty()) {
      const Coverage k = covered_fractions(b[j], lower, c.down[static_cast<std::size_t>(b[j].parent)]);
      c.opens_down[j] = k.material < 0.5;
      c.over_hole_down[j] = c.opens_down[j] && k.holes >= 0.5;
    }
  }
  return c;
}

std::vector<ContourGroup> contour_groups(const Level& lower, const Level& upper, const Correspondence& links) {
  const std::size_t na = lower.contours.size(), nb = upper.contours.size();
  UnionFind<> uf(na + nb);
  for (std::size_t i = 0; i < na; ++i) {
    for (int j : links.up[i]) uf.unite(i, na + static_cast<std::size_t>(j));
    if (lower.contours[i].is_hole && lower.contours[i].parent >= 0)
      uf.unite(i, static_cast<std::size_t>(lower.contours[i].parent));
  }
  for (std::size_t j = 0; j < nb; ++j) {
    if (upper.contours[j].is_hole && upper.contours[j].parent >= 0) {
      uf.unite(na + j, na + static_cast<std::size_t>(upper.contours[j].parent));
    }
  }
  // The union-find keeps the smallest index as the root: groups come out ordered by first contour.
  std::vector<int> slot(na + nb, -1);
  std::vector<ContourGroup> groups;
  for (std::size_t k = 0; k < na + nb; ++k) {
    const std::size_t r = uf.find(k);
    if (slot[r] < 0) {
      slot[r] = static_cast<int>(groups.size());
      groups.emplace_back();
    }
    ContourGroup& g = groups[static_cast<std::size_t>(slot[r])];
    if (k < na) g.lower.push_back(static_cast<int>(k));
    else g.upper.push_back(static_cast<int>(k - na));
  }
  return groups;
}

Correspondence restrict_correspondence(const Correspondence& links, const ContourGroup& group) {
  const std::vector<int> lower = positions_in(group.lower, links.up.size());
  const std::vector<int> upper = positions_in(group.upper, links.down.size());
  auto renumbered = [](const std::vector<int>& partners, const std::vector<int>& to) {
    std::vector<int> out;
    out.reserve(partners.size());
    for (int p : partners) out.push_back(to[static_cast<std::size_t>(p)]);
    return out;
  };
  Correspondence r;
  for (int i : group.lower) {
    const auto k = static_cast<std::size_t>(i);
    r.up.push_back(renumbered(links.up[k], upper));
    r.opens_up.push_back(links.opens_up[k]);
    r.over_hole_up.push_back(links.over_hole_up[k]);
  }
  for (int j : group.upper) {
    const auto k = static_cast<std::size_t>(j);
    r.down.push_back(renumbered(links.down[k], lower));
    r.opens_down.push_back(links.opens_down[k]);
    r.over_hole_down.push_back(links.over_hole_down[k]);
  }
  return r;
}

GroupChange classify_group(const ContourGroup& group, const Level& lower, const Level& upper,
                           const Correspondence& links, std::vector<std::pair<int, int>>* pairs) {
  if (group.upper.empty()) return GroupChange::EndsAbove;
  if (group.lower.empty()) return GroupChange::EndsBelow;
  int outer_lower = -1, outer_upper = -1, outers = 0;
  for (int i : group.lower) {
    if (!lower.contours[static_cast<std::size_t>(i)].is_hole) {
      outer_lower = i;
      ++outers;
    }
  }
  for (int j : group.upper) {
    if (!upper.contours[static_cast<std::size_t>(j)].is_hole) {
      outer_upper = j;
      ++outers;
    }
  }
  if (outers != 2 || outer_lower < 0 || outer_upper < 0) return GroupChange::Topology;
  std::vector<std::pair<int, int>> found{{outer_lower, outer_upper}};
  for (int i : group.lower) {
    if (!lower.contours[static_cast<std::size_t>(i)].is_hole) continue;
    const auto& up = links.up[static_cast<std::size_t>(i)];
    if (up.size() != 1 || links.down[static_cast<std::size_t>(up[0])].size() != 1) return GroupChange::Topology;
    found.emplace_back(i, up[0]);
  }
  for (int j : group.upper) {
    if (upper.contours[static_cast<std::size_t>(j)].is_hole && links.down[static_cast<std::size_t>(j)].size() != 1) {
      return GroupChange::Topology;
    }
  }
  if (pairs) *pairs = std::move(found);
  return GroupChange::OneToOne;
}

}  // namespace contourmesh::detail
