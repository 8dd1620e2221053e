// SPDX-License-Identifier: BSD-3-Clause
#include "detail/band_tiling.h"

#include <contourmesh/smooth/limits.h>
#include <contourmesh/smooth/mesh_quality.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

namespace contourmesh::detail {

namespace {

// The span weight that breaks ties in untwisted_band. Between two nearly congruent contours (a cylinder's,
// traced through pixels, on two slices) many ways across have the least area to within rounding, and the
// programme drifted along straight stretches of the rings into fans of slivers; with a hundredth of a
// percent of a square millimetre per square millimetre of span added, the shortest way across wins the
// ties. The first band gets it only where it has slivers between contours less than the gap apart (not on
// flat bands, whose triangulations all have the same area: there it would decide every choice, and the
// heights read from the image on a gently tilted face got worse); a twisted band's other starts always.
constexpr double kTieSpanWeight = 1e-4;

// Above this many point pairs the programme first solves every k-th point and then the full rings in a
// corridor around that path.
constexpr double kCoarseToFineCells = 90'000.0;
constexpr double kCoarseCells = 40'000.0;
// Programmes smaller than this are not checked against the available memory.
constexpr double kCheckedBytes = 16e6;

double triangle_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}

// The least-cost monotone path through grid nodes (i, j), 0 <= i <= m, 0 <= j <= n, row i restricted to
// lo[i] <= j <= hi[i], between rings P (m + 1 points, P[m] = P[0]) and Q (likewise). Node (i, j) is the
// edge P[i] - Q[j]; (0, j) and (m, j) are the same edge, as are (i, 0) and (i, n). So that the start
// edge (0, 0) = (m, n) is the only edge met twice, the path leaves (0, 0) along P and enters (m, n) along
// Q: nodes (0, j > 0), (m, 0) and (i < m, n) are never used. Moves: 1 = advance i (triangle P[i-1] P[i]
// Q[j]), 0 = advance j (triangle P[i] Q[j] Q[j-1]), listed from the end; empty when (m, n) cannot be
// reached in the corridor.
std::vector<std::uint8_t> least_cost_path(const std::vector<Eigen::Vector3d>& P, const std::vector<Eigen::Vector3d>& Q,
                                          const std::vector<int>& lo, const std::vector<int>& hi, double span_weight,
                                          const TilingOptions& options) {
  const int m = static_cast<int>(P.size()) - 1, n = static_cast<int>(Q.size()) - 1;
  std::vector<std::size_t> row_start(static_cast<std::size_t>(m) + 2, 0);
  for (int i = 0; i <= m; ++i) row_start[i + 1] = row_start[i] + static_cast<std::size_t>(hi[i] - lo[i] + 1);
  const double bytes = static_cast<double>(row_start[m + 1]) * (sizeof(double) + sizeof(std::uint8_t));
  if (bytes > kCheckedBytes || options.limits.max_memory_bytes > 0) {  // asking the system costs a file read
    check_allocation("tiling: contours of " + std::to_string(m) + " and " + std::to_string(n) + " points", 0.0, bytes,
                     options.limits);
  }
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> cost(row_start[m + 1], inf);
  std::vector<std::uint8_t> from_lower(row_start[m + 1], 0);
  auto at = [&](int i, int j) { return row_start[i] + static_cast<std::size_t>(j - lo[i]); };
  cost[at(0, 0)] = 0.0;
  // Row by row, the two triangle areas written out with what the rings' planes make constant hoisted out
  // of the loops. P lies on one plane and Q on another (all P[i].z equal, all Q[j].z equal, h = Q.z -
  // P.z), so P[i] - P[i-1] = (ax, ay, 0) and every edge across has z component h:
  //   |(ax, ay, 0) x (gx, gy, h)|^2 = ((ay h)^2 + (ax h)^2) + (ax gy - ay gx)^2,
  //   |(dx, dy, h) x (ex, ey, h)|^2 = ((dy h - ey h)^2 + (ex h - dx h)^2) + (dx ey - dy ex)^2.
  // These are the very operations, in the same order, that Eigen's cross() and squaredNorm() perform
  // on those vectors (a product with an exact zero drops out exactly), so the costs, and the path, are
  // the same as with triangle_area. Neither area depends on the costs: a row's areas are computed first,
  // over whole arrays (two lanes at a time, sqrt correctly rounded in each), and the recurrence then only
  // adds and compares.
  // Row 0 holds only the start; (m, 0) and (i < m, n) stay unreachable.
  const double h = Q[0].z() - P[0].z();
  // Q shifted by one: qx[j + 1] = Q[j].x(), and qx[0] = Q[0].x(), so that the segment from j holds Q[j - 1]
  // (Q[0] for j = 0) and the segment from j + 1 holds Q[j]. Likewise dx[j + 1] = Q[j].x() - P[i].x().
  const Eigen::Index nq = static_cast<Eigen::Index>(Q.size());
  Eigen::ArrayXd qx(nq + 1), qy(nq + 1);
  for (Eigen::Index j = 0; j < nq; ++j) {
    qx[j + 1] = Q[static_cast<std::size_t>(j)].x();
    qy[j + 1] = Q[static_cast<std::size_t>(j)].y();
  }
  qx[0] = qx[1];
  qy[0] = qy[1];
  Eigen::ArrayXd dx(nq + 1), dy(nq + 1), along_area(nq), across_area(nq), span(nq);
  for (int i = 1; i <= m; ++i) {
    const int l = lo[i], pl = lo[i - 1], ph = hi[i - 1];
    const int jb = i == m ? std::max(l, 1) : l;
    const int je = i < m ? std::min(hi[i], n - 1) : hi[i];
    if (je < jb) continue;
    double* row = cost.data() + row_start[i];
    std::uint8_t* row_from = from_lower.data() + row_start[i];
    const double* prev = cost.data() + row_start[i - 1];
    const double p0x = P[i - 1].x(), p0y = P[i - 1].y(), p1x = P[i].x(), p1y = P[i].y();
    const double ax = p1x - p0x, ay = p1y - p0y;
    const double ayh = ay * h, axh = ax * h;
    const double along = ayh * ayh + axh * axh;
    const Eigen::Index b = jb, len = je - jb + 1;
    // Triangle P[i-1] P[i] Q[j] (g = Q[j] - P[i-1]), and triangle P[i] Q[j] Q[j-1] (d = Q[j] - P[i], e =
    // Q[j-1] - P[i]: the segments of dx and dy from j + 1 and from j).
    along_area.segment(b, len) =
        0.5 * (along + (ax * (qy.segment(b + 1, len) - p0y) - ay * (qx.segment(b + 1, len) - p0x)).square()).sqrt();
    dx.segment(b, len + 1) = qx.segment(b, len + 1) - p1x;
    dy.segment(b, len + 1) = qy.segment(b, len + 1) - p1y;
    const auto d_x = dx.segment(b + 1, len), d_y = dy.segment(b + 1, len);
    const auto e_x = dx.segment(b, len), e_y = dy.segment(b, len);
    across_area.segment(b, len) =
        0.5 * (((d_y * h - e_y * h).square() + (e_x * h - d_x * h).square()) + (d_x * e_y - d_y * e_x).square()).sqrt();
    if (span_weight > 0.0) {
      span.segment(b, len) = span_weight * ((d_x.square() + d_y.square()) + h * h);
    }
    // The recurrence, in three stretches of j: before the previous row's range (from the left only),
    // within it (from below or from the left; below wins ties), after it (from the left only), so that
    // the cells within need no range tests. A cell is reached when its cost is < inf; a cost that is not
    // (inf, or NaN where coordinates overflow) is never extended, and the costs stored are those of the
    // textbook recurrence in every case.
    const bool spans = span_weight > 0.0;
    auto store = [&](int j, double c, std::uint8_t fl) {
      row[j - l] = spans && c < inf ? c + span[j] : c;
      row_from[j - l] = fl;
    };
    auto from_left = [&](int j) {
      if (j > l && row[j - 1 - l] < inf) {
        const double c = row[j - 1 - l] + across_area[j];
        if (c < inf) return c;
      }
      return inf;
    };
    const int mid_begin = std::max(jb, pl), mid_end = std::min(je, ph);
    int j = jb;
    for (; j <= je && j < mid_begin; ++j) store(j, from_left(j), 0);
    if (j == l && j <= mid_end) {  // the row's first cell: from below only
      const bool below = prev[j - pl] < inf;
      store(j, below ? prev[j - pl] + along_area[j] : inf, below ? 1 : 0);
      ++j;
    }
    for (; j <= mid_end; ++j) {
      const double p = prev[j - pl], r = row[j - 1 - l];
      const bool below = p < inf;
      const double c = below ? p + along_area[j] : inf;
      const double c2 = r + across_area[j];
      const bool left = r < inf && c2 < c;
      store(j, left ? c2 : c, left ? 0 : (below ? 1 : 0));
    }
    for (; j <= je; ++j) store(j, from_left(j), 0);
  }
  std::vector<std::uint8_t> moves;
  if (!(cost[at(m, n)] < inf)) return moves;
  moves.reserve(static_cast<std::size_t>(m + n));
  for (int i = m, j = n; i > 0 || j > 0;) {
    const std::uint8_t fl = from_lower[at(i, j)];
    moves.push_back(fl);
    if (fl) --i;
    else --j;
  }
  return moves;
}

// The corridor around the arc-length diagonal j = i n / m: +/- half points.
void diagonal_corridor(int m, int n, int half, std::vector<int>& lo, std::vector<int>& hi) {
  lo.assign(static_cast<std::size_t>(m) + 1, 0);
  hi.assign(static_cast<std::size_t>(m) + 1, n);
  for (int i = 0; i <= m; ++i) {
    const double c = static_cast<double>(i) * n / m;
    lo[i] = std::max(0, static_cast<int>(std::floor(c)) - half);
    hi[i] = std::min(n, static_cast<int>(std::ceil(c)) + half);
  }
  lo[0] = 0;
  hi[m] = n;
}

// The programme on every k-th point, and the corridor of +/- margin points around its path at full
// resolution.
void coarse_corridor(const std::vector<Eigen::Vector3d>& P, const std::vector<Eigen::Vector3d>& Q, int k, int margin,
                     double span_weight, const TilingOptions& options, std::vector<int>& lo, std::vector<int>& hi) {
  const int m = static_cast<int>(P.size()) - 1, n = static_cast<int>(Q.size()) - 1;
  const int mc = (m + k - 1) / k, nc = (n + k - 1) / k;
  std::vector<Eigen::Vector3d> Pc(static_cast<std::size_t>(mc) + 1), Qc(static_cast<std::size_t>(nc) + 1);
  for (int i = 0; i <= mc; ++i) Pc[i] = P[std::min(i * k, m)];
  for (int j = 0; j <= nc; ++j) Qc[j] = Q[std::min(j * k, n)];
  std::vector<int> clo, chi;
  diagonal_corridor(mc, nc, nc, clo, chi);
  const std::vector<std::uint8_t> moves = least_cost_path(Pc, Qc, clo, chi, span_weight, options);
  lo.assign(static_cast<std::size_t>(m) + 1, n);
  hi.assign(static_cast<std::size_t>(m) + 1, 0);
  // Each coarse node (ic, jc) covers fine rows ic k - k .. ic k + k around column jc k.
  auto cover = [&](int ic, int jc) {
    const int j = std::min(jc * k, n);
    for (int i = std::max(0, ic * k - k); i <= std::min(m, ic * k + k); ++i) {
      lo[i] = std::min(lo[i], std::max(0, j - margin));
      hi[i] = std::max(hi[i], std::min(n, j + margin));
    }
  };
  int ic = mc, jc = nc;
  cover(ic, jc);
  for (std::uint8_t fl : moves) {
    if (fl) --ic;
    else --jc;
    cover(ic, jc);
  }
  lo[0] = 0;
  hi[m] = n;
  for (int i = 0; i <= m; ++i) hi[i] = std::max(hi[i], lo[i]);
}

}  // namespace

std::vector<BandTriangle> minimum_area_band(const Polygon& lower, double wl, const Polygon& upper, double wu,
                                            const TilingOptions& options, int lower_start, double span_weight) {
  const int m = static_cast<int>(lower.size());
  const int r0 = ((lower_start % m) + m) % m;
  const int n = static_cast<int>(upper.size());
  // The start: lower[r0] and the nearest upper point where the upper contour runs the same way. On a
  // thin wall or a narrow crack the nearest point may lie on the far side, running back: starting there
  // twists the whole band.
  int q0 = -1;
  {
    const Eigen::Vector2d tangent =
        lower[static_cast<std::size_t>((r0 + 1) % m)] - lower[static_cast<std::size_t>((r0 + m - 1) % m)];
    double best = std::numeric_limits<double>::infinity(), best_any = best;
    int any = 0;
    for (int j = 0; j < n; ++j) {
      const double d = (upper[static_cast<std::size_t>(j)] - lower[static_cast<std::size_t>(r0)]).squaredNorm();
      if (d < best_any) {
        best_any = d;
        any = j;
      }
      if (d < best && tangent.dot(upper[static_cast<std::size_t>((j + 1) % n)] -
                                  upper[static_cast<std::size_t>((j + n - 1) % n)]) > 0.0) {
        best = d;
        q0 = j;
      }
    }
    if (q0 < 0) q0 = any;
  }
  // The rings as 3-D points in programme order (lower from r0, upper from q0), made once: each cell of
  // the programme reads four of them, and wrapping the index (two integer divisions per point read)
  // was a quarter of the tiler's instructions.
  std::vector<Eigen::Vector3d> P(static_cast<std::size_t>(m) + 1), Q(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= m; ++i) {
    const Eigen::Vector2d& p = lower[static_cast<std::size_t>((r0 + i) % m)];
    P[i] = Eigen::Vector3d(p.x(), p.y(), wl);
  }
  for (int j = 0; j <= n; ++j) {
    const Eigen::Vector2d& q = upper[static_cast<std::size_t>((q0 + j) % n)];
    Q[j] = Eigen::Vector3d(q.x(), q.y(), wu);
  }
  const double cells = static_cast<double>(m) * static_cast<double>(n);
  std::vector<int> lo, hi;
  std::vector<std::uint8_t> moves;
  // Large pairs of rings: coarse to fine, whatever their size (a few percent of the full grid's cells).
  // Pairs it cannot serve (a ring under 32 points) get the full grid up to options.full_dp_limit cells,
  // and above it the band around the arc-length diagonal; so would a corridor that missed the end.
  if (cells > kCoarseToFineCells && std::min(m, n) >= 32) {
    const int k = std::max(2, static_cast<int>(std::round(std::sqrt(cells / kCoarseCells))));
    coarse_corridor(P, Q, k, 2 * k + 2, span_weight, options, lo, hi);
    moves = least_cost_path(P, Q, lo, hi, span_weight, options);
  }
  if (moves.empty() && cells > static_cast<double>(options.full_dp_limit)) {
    diagonal_corridor(m, n, std::max({8, static_cast<int>(std::ceil(options.band_fraction * n)), (n + m - 1) / m + 2}),
                      lo, hi);
    moves = least_cost_path(P, Q, lo, hi, span_weight, options);
  }
  if (moves.empty()) {  // small rings, or a corridor or band that missed the end
    diagonal_corridor(m, n, n, lo, hi);
    moves = least_cost_path(P, Q, lo, hi, span_weight, options);
  }
  std::vector<BandTriangle> band;
  band.reserve(moves.size());
  auto L = [&](int k) { return BandCorner{0, (r0 + k) % m}; };
  auto U = [&](int k) { return BandCorner{1, (q0 + k) % n}; };
  int i = m, j = n;
  for (std::uint8_t fl : moves) {
    if (fl) {
      band.push_back({L(i - 1), L(i), U(j)});
      --i;
    } else {
      band.push_back({L(i), U(j), U(j - 1)});
      --j;
    }
  }
  return band;
}

BandQuality band_quality(const Polygon& lower, double wl, const Polygon& upper, double wu,
                         const std::vector<BandTriangle>& band, const Eigen::Vector2d& shear) {
  BandQuality q;
  auto point = [&](const BandCorner& c) {
    const Eigen::Vector2d& p =
        c.ring == 0 ? lower[static_cast<std::size_t>(c.index)] : upper[static_cast<std::size_t>(c.index)];
    const double w = c.ring == 0 ? wl : wu;
    const Eigen::Vector2d judged = p + shear * w;
    return Eigen::Vector3d(judged.x(), judged.y(), w);
  };
  for (const BandTriangle& t : band) {
    const Eigen::Vector3d a = point(t[0]), b = point(t[1]), c = point(t[2]);
    const double area = triangle_area(a, b, c);
    q.area += area;
    if (is_sliver(a, b, c)) q.sliver_area += area;
    for (int k = 0; k < 3; ++k) {
      if (t[k].ring != t[(k + 1) % 3].ring) {
        q.longest_cross_edge = std::max(q.longest_cross_edge, (point(t[k]) - point(t[(k + 1) % 3])).norm());
      }
    }
  }
  return q;
}

namespace {

// max over p in a of the distance from p to the nearest point of b. Each point's search stops as soon as
// it finds a point of b nearer than the current maximum (it cannot raise it); starting the search where
// the previous point's ended makes that quick for curves sampled in order.
double directed_distance(const Polygon& a, const Polygon& b) {
  double worst2 = 0.0;
  std::size_t start = 0;
  const std::size_t n = b.size();
  for (const Eigen::Vector2d& p : a) {
    double best2 = std::numeric_limits<double>::infinity();
    std::size_t nearest = start;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t j = (start + k) % n;
      const double d2 = (b[j] - p).squaredNorm();
      if (d2 < best2) {
        best2 = d2;
        nearest = j;
        if (best2 <= worst2) break;
      }
    }
    start = nearest;
    worst2 = std::max(worst2, best2);
  }
  return std::sqrt(worst2);
}

}  // namespace

double contour_distance(const Polygon& a, const Polygon& b) {
  return std::max(directed_distance(a, b), directed_distance(b, a));
}

namespace {

// band_is_twisted, with the contours' distance in the plane (contour_distance) and the planes' gap given.
bool twisted_apart(const BandQuality& quality, double apart, double gap, double spacing) {
  return quality.longest_cross_edge > 2.0 * std::hypot(apart, gap) + 2.0 * spacing;
}

}  // namespace

bool band_is_twisted(const Polygon& lower, double wl, const Polygon& upper, double wu, const BandQuality& quality,
                     double spacing) {
  return twisted_apart(quality, contour_distance(lower, upper), wu - wl, spacing);
}

std::vector<BandTriangle> untwisted_band(const Polygon& lower, double wl, const Polygon& upper, double wu,
                                         const TilingOptions& options, double spacing, bool* twisted) {
  std::vector<BandTriangle> first = minimum_area_band(lower, wl, upper, wu, options);
  BandQuality q = band_quality(lower, wl, upper, wu, first);
  const double gap = wu - wl, apart = contour_distance(lower, upper);
  if (q.sliver_area > 0.0 && apart < gap) {
    // Nearly congruent contours with slivers between them: the ties broken by the shorter spans.
    std::vector<BandTriangle> tied = minimum_area_band(lower, wl, upper, wu, options, 0, kTieSpanWeight);
    const BandQuality qt = band_quality(lower, wl, upper, wu, tied);
    if (qt.sliver_area < q.sliver_area) {
      first = std::move(tied);
      q = qt;
    }
  }
  if (twisted) *twisted = false;
  if (!twisted_apart(q, apart, gap, spacing)) return first;
  // Other starts, and the least area plus the squared lengths across (which keeps the band from jumping
  // along a crack narrower than the spacing, whose two sides the least area alone cannot tell apart).
  std::vector<BandTriangle> best = std::move(first), untwisted;
  double best_edge = q.longest_cross_edge, untwisted_area = std::numeric_limits<double>::infinity();
  const int m = static_cast<int>(lower.size());
  for (int k = 0; k < 5; ++k) {
    // A start four quarters round is the first band's own start: that band is known, and twisted.
    if (k < 4 && (k + 1) * m / 4 % m == 0) continue;
    std::vector<BandTriangle> band =
        k < 4 ? minimum_area_band(lower, wl, upper, wu, options, (k + 1) * m / 4 % m, kTieSpanWeight)
              : minimum_area_band(lower, wl, upper, wu, options, 0, 1.0);
    q = band_quality(lower, wl, upper, wu, band);
    if (!twisted_apart(q, apart, gap, spacing)) {  // the same contours: their distance once
      if (q.area < untwisted_area) {
        untwisted_area = q.area;
        untwisted = std::move(band);
      }
    } else if (q.longest_cross_edge < best_edge) {
      best_edge = q.longest_cross_edge;
      best = std::move(band);
    }
  }
  if (!untwisted.empty()) return untwisted;
  if (twisted) *twisted = true;
  return best;
}

void emit_band(const LevelContour& lower, const LevelContour& upper, const std::vector<BandTriangle>& band,
               SlabMesh& out) {
  auto id = [&](const BandCorner& c) {
    return c.ring == 0 ? lower.ids[static_cast<std::size_t>(c.index)] : upper.ids[static_cast<std::size_t>(c.index)];
  };
  for (const BandTriangle& t : band) out.add_triangle(id(t[0]), id(t[1]), id(t[2]), FaceRole::Band);
}

void emit_copy_band(const std::vector<VertexRef>& lower, const std::vector<VertexRef>& upper, SlabMesh& out) {
  const std::size_t n = lower.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = (i + 1) % n;
    out.add_triangle(lower[i], lower[k], upper[k], FaceRole::Band);
    out.add_triangle(lower[i], upper[k], upper[i], FaceRole::Band);
  }
}

LevelContour copy_contour(const LevelContour& c, double w, SlabMesh& out) {
  LevelContour copy = c;
  for (std::size_t k = 0; k < c.points.size(); ++k) copy.ids[k] = out.add_vertex(c.points[k], w);
  return copy;
}

}  // namespace contourmesh::detail
