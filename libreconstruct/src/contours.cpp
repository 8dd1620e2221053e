#include "reconstruct/contours.h"

#include <smooth/errors.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace contourmesh {

double signed_area(const std::vector<Eigen::Vector2d>& p) {
  double a = 0.0;
  const std::size_t n = p.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) a += p[j].x() * p[i].y() - p[i].x() * p[j].y();
  return 0.5 * a;
}

double perimeter(const std::vector<Eigen::Vector2d>& p) {
  double len = 0.0;
  const std::size_t n = p.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) len += (p[i] - p[j]).norm();
  return len;
}

bool point_in_polygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  bool in = false;
  const std::size_t n = poly.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Eigen::Vector2d& a = poly[j];
    const Eigen::Vector2d& b = poly[i];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y())) {
      in = !in;
    }
  }
  return in;
}

std::vector<Eigen::Vector2d> resample_closed(const std::vector<Eigen::Vector2d>& poly, double spacing) {
  if (!(spacing > 0.0)) throw InvalidInputError("resample_closed: spacing must be > 0");
  if (poly.size() < 3) throw InvalidInputError("resample_closed: a closed contour needs at least 3 points");
  const double total = perimeter(poly);
  const auto count = static_cast<std::size_t>(std::max(3.0, std::round(total / spacing)));
  const double step = total / static_cast<double>(count);
  std::vector<Eigen::Vector2d> out;
  out.reserve(count);
  std::size_t seg = 0;         // current segment poly[seg] -> poly[seg + 1 mod n]
  double seg_start = 0.0;      // arc length at poly[seg]
  const std::size_t n = poly.size();
  for (std::size_t k = 0; k < count; ++k) {
    const double s = k * step;
    double seg_len = (poly[(seg + 1) % n] - poly[seg]).norm();
    while (seg_start + seg_len < s && seg + 1 < n) {
      seg_start += seg_len;
      ++seg;
      seg_len = (poly[(seg + 1) % n] - poly[seg]).norm();
    }
    const double t = seg_len > 0.0 ? std::clamp((s - seg_start) / seg_len, 0.0, 1.0) : 0.0;
    out.push_back(poly[seg] + t * (poly[(seg + 1) % n] - poly[seg]));
  }
  return out;
}

}  // namespace contourmesh
