// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/contour_deviation.h"

#include "detail/cross_section.h"

#include <contourmesh/smooth/errors.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace contourmesh {

namespace {

double point_segment_distance(const Eigen::Vector2d& p, const SectionSegment& s) {
  const Eigen::Vector2d d = s[1] - s[0];
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - s[0]).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (s[0] + t * d - p).norm();
}

// Nearest-segment queries on a uniform grid of the segments' bounding boxes.
class SegmentGrid {
 public:
  explicit SegmentGrid(const std::vector<SectionSegment>& segments) : segments_(segments) {
    Eigen::AlignedBox2d box;
    double length = 0.0;
    for (const auto& s : segments) {
      box.extend(s[0]);
      box.extend(s[1]);
      length += (s[1] - s[0]).norm();
    }
    origin_ = box.min();
    const Eigen::Vector2d size = box.sizes();
    // About two segments per cell along a contour, and at most ~4 million cells.
    cell_ = std::max({2.0 * length / static_cast<double>(std::max<std::size_t>(segments.size(), 1)), 1e-6,
                      std::sqrt(size.x() * size.y() / 4e6)});
    nx_ = static_cast<long>(size.x() / cell_) + 1;
    ny_ = static_cast<long>(size.y() / cell_) + 1;
    cells_.assign(static_cast<std::size_t>(nx_ * ny_), {});
    for (std::size_t i = 0; i < segments.size(); ++i) {
      const auto& s = segments[i];
      const long x0 = column(std::min(s[0].x(), s[1].x())), x1 = column(std::max(s[0].x(), s[1].x()));
      const long y0 = row(std::min(s[0].y(), s[1].y())), y1 = row(std::max(s[0].y(), s[1].y()));
      for (long y = y0; y <= y1; ++y) {
        for (long x = x0; x <= x1; ++x) cells_[static_cast<std::size_t>(y * nx_ + x)].push_back(i);
      }
    }
  }

  [[nodiscard]] double distance(const Eigen::Vector2d& p) const {
    const long cx = column(p.x()), cy = row(p.y());
    double best = std::numeric_limits<double>::infinity();
    const long rings = std::max(nx_, ny_);
    for (long r = 0; r <= rings; ++r) {
      for (long y = cy - r; y <= cy + r; ++y) {
        if (y < 0 || y >= ny_) continue;
        const bool edge_row = y == cy - r || y == cy + r;
        for (long x = cx - r; x <= cx + r; x += (edge_row ? 1 : 2 * r)) {
          if (x >= 0 && x < nx_) {
            for (const std::size_t i : cells_[static_cast<std::size_t>(y * nx_ + x)]) {
              best = std::min(best, point_segment_distance(p, segments_[i]));
            }
          }
          if (r == 0) break;
        }
      }
      // Cells beyond ring r are at least r cells away.
      if (best <= static_cast<double>(r) * cell_) break;
    }
    return best;
  }

 private:
  long column(double x) const { return std::clamp(static_cast<long>((x - origin_.x()) / cell_), 0L, nx_ - 1); }
  long row(double y) const { return std::clamp(static_cast<long>((y - origin_.y()) / cell_), 0L, ny_ - 1); }

  const std::vector<SectionSegment>& segments_;
  Eigen::Vector2d origin_;
  double cell_ = 1.0;
  long nx_ = 1, ny_ = 1;
  std::vector<std::vector<std::size_t>> cells_;
};

struct Accumulator {
  double weighted = 0.0, squared = 0.0, weight = 0.0, max = 0.0;
};

// Distances from points sampled along `from` to the nearest segment of `to`.
void measure(const std::vector<SectionSegment>& from, const SegmentGrid& to, double step, Accumulator& acc,
             double& slice_max) {
  for (const auto& s : from) {
    const double len = (s[1] - s[0]).norm();
    const auto pieces = static_cast<std::size_t>(std::max(1.0, std::ceil(len / step)));
    for (std::size_t k = 0; k < pieces; ++k) {
      const Eigen::Vector2d p = s[0] + (s[1] - s[0]) * ((static_cast<double>(k) + 0.5) / static_cast<double>(pieces));
      const double d = to.distance(p);
      const double w = len / static_cast<double>(pieces);
      acc.weighted += w * d;
      acc.squared += w * d * d;
      acc.weight += w;
      slice_max = std::max(slice_max, d);
    }
    slice_max = std::max(slice_max, to.distance(s[0]));
  }
}

}  // namespace

namespace detail {

std::vector<SectionSegment> cross_section_of(const Mesh& mesh, const std::vector<Index>* faces,
                                             const ContourStack& frame, double w, bool just_above) {
  std::vector<SectionSegment> out;
  const auto& P = mesh.positions;
  auto height = [&](Index i) { return (P.col(i) - frame.origin).dot(frame.axis_w) - w; };
  auto uv = [&](const Eigen::Vector3d& x) {
    return Eigen::Vector2d((x - frame.origin).dot(frame.axis_u), (x - frame.origin).dot(frame.axis_v));
  };
  const std::size_t count = faces ? faces->size() : mesh.triangles.size();
  for (std::size_t k = 0; k < count; ++k) {
    const Triangle& t = mesh.triangles[faces ? static_cast<std::size_t>((*faces)[k]) : k];
    const std::array<double, 3> d{height(t[0]), height(t[1]), height(t[2])};
    const auto up = [&](int j) { return just_above ? d[j] > 0.0 : d[j] >= 0.0; };
    const int above = up(0) + up(1) + up(2);
    if (above == 0 || above == 3) continue;
    std::array<Eigen::Vector3d, 2> ends;
    int found = 0;
    for (int j = 0; j < 3; ++j) {
      const int a = j, b = (j + 1) % 3;
      if (up(a) == up(b)) continue;
      const double s = d[a] / (d[a] - d[b]);
      ends[found++] = P.col(t[a]) + s * (P.col(t[b]) - P.col(t[a]));
    }
    if (found != 2) continue;
    const Eigen::Vector3d n = (P.col(t[1]) - P.col(t[0])).cross(P.col(t[2]) - P.col(t[0]));
    // Inside (against the outward normal) on the left of the segment, seen from +w.
    if (frame.axis_w.cross(ends[1] - ends[0]).dot(n) > 0.0) std::swap(ends[0], ends[1]);
    SectionSegment seg{uv(ends[0]), uv(ends[1])};
    if ((seg[1] - seg[0]).squaredNorm() > 0.0) out.push_back(seg);
  }
  return out;
}

}  // namespace detail

std::vector<SectionSegment> cross_section(const Mesh& mesh, const ContourStack& frame, double w, bool just_above) {
  return detail::cross_section_of(mesh, nullptr, frame, w, just_above);
}

double section_area(const std::vector<SectionSegment>& section) {
  double a = 0.0;
  for (const auto& s : section) a += s[0].x() * s[1].y() - s[1].x() * s[0].y();
  return 0.5 * a;
}

ContourDeviation contour_deviation(const Mesh& mesh, const ContourStack& contours,
                                   const ContourDeviationOptions& options) {
  if (!(options.sample_step > 0.0) || !std::isfinite(options.sample_step)) {
    throw InvalidInputError("contour deviation: the sample step must be > 0 mm");
  }
  ContourDeviation out;
  out.slice_max.assign(contours.slices.size(), 0.0);
  Accumulator acc;
  for (std::size_t s = 0; s < contours.slices.size(); ++s) {
    const SliceContours& slice = contours.slices[s];
    std::vector<SectionSegment> drawn;
    for (const Contour& c : slice.contours) {
      for (std::size_t i = 0; i < c.points.size(); ++i)
        drawn.push_back({c.points[i], c.points[(i + 1) % c.points.size()]});
    }
    if (drawn.empty()) continue;
    std::vector<SectionSegment> section = cross_section(mesh, contours, slice.w);
    if (section.empty()) section = cross_section(mesh, contours, slice.w, true);
    if (section.empty()) {
      ++out.slices_without_section;
      out.slice_max[s] = std::numeric_limits<double>::infinity();
      continue;
    }
    ++out.slices;
    double slice_max = 0.0;
    measure(section, SegmentGrid(drawn), options.sample_step, acc, slice_max);
    measure(drawn, SegmentGrid(section), options.sample_step, acc, slice_max);
    out.slice_max[s] = slice_max;
    out.max = std::max(out.max, slice_max);
  }
  if (acc.weight > 0.0) {
    out.mean = acc.weighted / acc.weight;
    out.rms = std::sqrt(acc.squared / acc.weight);
  }
  return out;
}

}  // namespace contourmesh
