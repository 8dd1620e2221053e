// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/planar_contours.h"

#include <contourmesh/smooth/errors.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <sstream>

namespace contourmesh {

namespace {

using Polygon = std::vector<Eigen::Vector2d>;

std::string mm(double v) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << v;
  return s.str();
}

void check_options(const PlanarStackOptions& o) {
  if (!(o.planarity_tolerance > 0.0) || !std::isfinite(o.planarity_tolerance)) {
    throw InvalidInputError("the planarity tolerance must be a finite number > 0 mm");
  }
  if (!(o.slice_tolerance > 0.0) || !std::isfinite(o.slice_tolerance)) {
    throw InvalidInputError("the slice tolerance must be a finite number > 0 mm");
  }
  if (!(o.gap_factor > 1.0)) throw InvalidInputError("the gap factor must be > 1");
  if (!(o.min_area >= 0.0) || !std::isfinite(o.min_area)) {
    throw InvalidInputError("the minimum contour area must be a finite number >= 0 mm^2");
  }
  if (o.slice_axis && (!o.slice_axis->allFinite() || !(o.slice_axis->norm() > 0.0))) {
    throw InvalidInputError("the slice axis must be a finite non-zero vector");
  }
}

// Area vector of a closed 3-D polygon (Newell): normal times area.
Eigen::Vector3d area_vector(const std::vector<Eigen::Vector3d>& p) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  if (p.size() < 3) return n;
  const Eigen::Vector3d& o = p.front();
  for (std::size_t i = 1; i + 1 < p.size(); ++i) n += (p[i] - o).cross(p[i + 1] - o);
  return 0.5 * n;
}

// The axis pointing so that its largest component is positive; snapped to a coordinate axis when
// within 1e-6 rad of one.
Eigen::Vector3d canonical_axis(Eigen::Vector3d w) {
  w.normalize();
  Eigen::Index k = 0;
  w.cwiseAbs().maxCoeff(&k);
  if (w[k] < 0.0) w = -w;
  if (std::abs(w[k] - 1.0) < 0.5e-12 || (w - Eigen::Vector3d::Unit(k)).norm() < 1e-6) w = Eigen::Vector3d::Unit(k);
  return w;
}

// Right-handed frame around w: the next two coordinate axes when w is one of them.
void frame_for(const Eigen::Vector3d& w, ContourStack& stack) {
  stack.origin = Eigen::Vector3d::Zero();
  stack.axis_w = w;
  for (int k = 0; k < 3; ++k) {
    if (w == Eigen::Vector3d::Unit(k)) {
      stack.axis_u = Eigen::Vector3d::Unit((k + 1) % 3);
      stack.axis_v = Eigen::Vector3d::Unit((k + 2) % 3);
      return;
    }
  }
  // The coordinate axis least aligned with w, made orthogonal to it.
  Eigen::Index k = 0;
  w.cwiseAbs().minCoeff(&k);
  Eigen::Vector3d u = Eigen::Vector3d::Unit(k);
  u = (u - u.dot(w) * w).normalized();
  stack.axis_u = u;
  stack.axis_v = w.cross(u);
}

std::string axis_label(const ContourStack& stack) {
  if (stack.axis_w == Eigen::Vector3d::UnitX()) return "x";
  if (stack.axis_w == Eigen::Vector3d::UnitY()) return "y";
  if (stack.axis_w == Eigen::Vector3d::UnitZ()) return "z";
  return "w";
}

// One contour of a slice on its way through normalisation.
struct Work {
  Polygon points;
  std::size_t source = 0;
  std::string name;   // full name for messages, "<what>: contour 12 (z = 3.00 mm)"
  std::string label;  // short name, "contour 12"
  double area = 0.0;
};

// Drops consecutive repeated points; returns how many. A closing point equal to the first (the usual
// way to write a closed polyline) is dropped too but not counted.
std::size_t drop_repeated(Polygon& p) {
  // Points closer than this are the same point: far below any drawing or scanner resolution.
  constexpr double kSame = 1e-9;
  Polygon out;
  out.reserve(p.size());
  std::size_t repeated = 0;
  for (const Eigen::Vector2d& q : p) {
    if (out.empty() || (q - out.back()).norm() > kSame) {
      out.push_back(q);
    } else {
      ++repeated;
    }
  }
  bool closing = true;  // the first trailing copy of the first point closes the polyline
  while (out.size() > 1 && (out.back() - out.front()).norm() <= kSame) {
    out.pop_back();
    if (!closing) ++repeated;
    closing = false;
  }
  p = std::move(out);
  return repeated;
}

// All points on one line (a contour drawn as a stroke), within a nanometre.
bool collinear(const Polygon& p) {
  std::size_t far = 0;
  for (std::size_t i = 1; i < p.size(); ++i) {
    if ((p[i] - p[0]).squaredNorm() > (p[far] - p[0]).squaredNorm()) far = i;
  }
  const Eigen::Vector2d d = p[far] - p[0];
  const double len = d.norm();
  if (!(len > 0.0)) return true;
  for (const Eigen::Vector2d& q : p) {
    const Eigen::Vector2d r = q - p[0];
    if (std::abs(d.x() * r.y() - d.y() * r.x()) / len > 1e-6) return false;
  }
  return true;
}

// Cleans, checks, nests and orients the contours of one slice; degenerate contours are dropped with a
// warning. Returns the slice's contours, `sources` their entries of `work`.
std::vector<Contour> normalize_slice(std::vector<Work>& work, const PlanarStackOptions& options,
                                     PlanarStackReport& report, std::vector<std::string>& repeated_names,
                                     std::vector<std::size_t>& sources) {
  std::vector<Work> kept;
  for (Work& k : work) {
    for (std::size_t i = 0; i < k.points.size(); ++i) {
      if (!k.points[i].allFinite())
        throw InvalidInputError(k.name + ": point " + std::to_string(i + 1) + " is not finite");
    }
    const std::size_t removed = drop_repeated(k.points);
    if (removed > 0) {
      report.repeated_points += removed;
      repeated_names.push_back(k.name);
    }
    k.area = k.points.size() >= 3 ? signed_area(k.points) : 0.0;
    const auto crossing = k.points.size() >= 3 ? find_self_intersection(k.points) : std::nullopt;
    if (k.points.size() < 3 || (!(std::abs(k.area) > options.min_area) && (!crossing || collinear(k.points)))) {
      ++report.dropped_contours;
      report.warnings.push_back(k.name + " has " +
                                (k.points.size() < 3 ? std::to_string(k.points.size()) + " distinct point" +
                                                           (k.points.size() == 1 ? "" : "s")
                                                     : "no area (" + mm(std::abs(k.area)) + " mm^2)") +
                                ": skipped");
      continue;
    }
    if (crossing) {
      std::ostringstream msg;
      msg << k.name << " intersects itself: its segments " << crossing->first + 1 << " and " << crossing->second + 1
          << " meet at (" << mm(crossing->where.x()) << ", " << mm(crossing->where.y()) << ") mm in its plane";
      throw InvalidInputError(msg.str());
    }
    kept.push_back(std::move(k));
  }
  work = std::move(kept);
  const std::size_t n = work.size();
  if (n > 1) {
    std::vector<Polygon> outlines;
    outlines.reserve(n);
    for (const Work& k : work) outlines.push_back(k.points);
    if (const auto x = find_polygon_crossing(outlines)) {
      std::ostringstream msg;
      msg << work[x->first].name << " and " << work[x->second].label << " meet at (" << mm(x->where.x()) << ", "
          << mm(x->where.y()) << ") mm: the contours of one slice must bound separate regions";
      throw InvalidInputError(msg.str());
    }
  }
  // Nesting: with no crossings, one vertex tells whether a contour lies inside another. The parent is
  // the smallest contour that contains it.
  std::vector<Eigen::AlignedBox2d> boxes(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (const auto& p : work[i].points) boxes[i].extend(p);
  }
  std::vector<int> depth(n, 0), parent(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    double smallest = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < n; ++j) {
      if (i == j || !boxes[j].contains(work[i].points[0]) || !point_in_polygon(work[j].points, work[i].points[0])) {
        continue;
      }
      ++depth[i];
      if (std::abs(work[j].area) < smallest) {
        smallest = std::abs(work[j].area);
        parent[i] = static_cast<int>(j);
      }
    }
  }
  std::vector<Contour> out(n);
  sources.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    Contour& c = out[i];
    c.is_hole = depth[i] % 2 == 1;
    c.parent = c.is_hole ? parent[i] : -1;
    c.points = std::move(work[i].points);
    if ((c.is_hole && work[i].area > 0.0) || (!c.is_hole && work[i].area < 0.0)) {
      std::reverse(c.points.begin(), c.points.end());
      ++report.reversed;
    }
    report.hole_contours += c.is_hole ? 1 : 0;
    sources[i] = work[i].source;
  }
  report.contours += n;
  return out;
}

void report_repeated(PlanarStackReport& report, const std::vector<std::string>& names, const std::string& what) {
  if (names.empty()) return;
  std::ostringstream msg;
  msg << what << ": dropped " << report.repeated_points << " repeated point" << (report.repeated_points == 1 ? "" : "s")
      << " (consecutive copies) from " << names.size() << " contour" << (names.size() == 1 ? "" : "s") << ": ";
  for (std::size_t i = 0; i < names.size() && i < 5; ++i) msg << (i ? "; " : "") << names[i];
  if (names.size() > 5) msg << "; ...";
  report.warnings.push_back(msg.str());
}

// Median spacing, largest gap and the gap warnings of an ordered stack.
void check_spacing(const ContourStack& stack, const PlanarStackOptions& options, const std::string& what,
                   PlanarStackReport& report) {
  const auto& sl = stack.slices;
  if (sl.size() < 2) return;
  std::vector<double> gaps;
  for (std::size_t s = 1; s < sl.size(); ++s) gaps.push_back(sl[s].w - sl[s - 1].w);
  // The lower median: structures skip slices, which makes gaps larger, never smaller.
  std::vector<double> sorted = gaps;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[(sorted.size() - 1) / 2];
  report.typical_spacing = median;
  report.largest_gap = *std::max_element(gaps.begin(), gaps.end());
  const std::string axis = axis_label(stack);
  for (std::size_t s = 1; s < sl.size(); ++s) {
    if (gaps[s - 1] > options.gap_factor * median) {
      report.warnings.push_back(what + ": slices " + std::to_string(s - 1) + " (" + axis + " = " + mm(sl[s - 1].w) +
                                " mm) and " + std::to_string(s) + " (" + axis + " = " + mm(sl[s].w) + " mm) are " +
                                mm(gaps[s - 1]) + " mm apart, more than " + mm(options.gap_factor) +
                                " x the typical spacing " + mm(median) + " mm: tiled across the gap");
    }
  }
}

// The contours' common normal: the direction shared (within 1 degree) by the largest total area,
// averaged over the contours that share it. One tilted contour among axial ones does not tilt the axis.
Eigen::Vector3d common_normal(const std::vector<Eigen::Vector3d>& areas) {
  const double cos_limit = std::cos(std::numbers::pi / 180.0);
  std::size_t best = 0;
  double best_support = -1.0;
  for (std::size_t i = 0; i < areas.size(); ++i) {
    const double ni = areas[i].norm();
    if (!(ni > 0.0)) continue;
    double support = 0.0;
    for (const Eigen::Vector3d& a : areas) {
      const double na = a.norm();
      if (na > 0.0 && std::abs(a.dot(areas[i])) >= cos_limit * na * ni) support += na;
    }
    if (support > best_support) {
      best_support = support;
      best = i;
    }
  }
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const double nb = areas.empty() ? 0.0 : areas[best].norm();
  for (const Eigen::Vector3d& a : areas) {
    const double na = a.norm();
    if (na > 0.0 && std::abs(a.dot(areas[best])) >= cos_limit * na * nb) sum += a.dot(areas[best]) < 0.0 ? -a : a;
  }
  return sum;
}

}  // namespace

namespace {

// One slice of the input: its position and its contours (input indices, in input order).
struct InputSlice {
  double w = 0.0;
  std::vector<std::size_t> members;
};

// The slice axis: the given one, or the contours' common normal.
Eigen::Vector3d slice_axis(const std::vector<PlanarContour>& contours, const std::string& what,
                           const PlanarStackOptions& options) {
  if (options.slice_axis) return *options.slice_axis;
  std::vector<Eigen::Vector3d> areas;
  areas.reserve(contours.size());
  for (const PlanarContour& c : contours) areas.push_back(area_vector(c.points));
  const Eigen::Vector3d axis = common_normal(areas);
  if (!(axis.norm() > 0.0) || !axis.allFinite()) {
    throw InvalidInputError(what + ": the contours enclose no area, so they define no slice plane");
  }
  return axis;
}

// Contours grouped into slices (by id when every contour has one, else by position), ordered by w.
std::vector<InputSlice> group_slices(const std::vector<PlanarContour>& contours, const std::vector<double>& mean_w,
                                     const std::string& what, const std::string& axis_name,
                                     const PlanarStackOptions& options) {
  const std::size_t n = contours.size();
  const bool by_id =
      std::all_of(contours.begin(), contours.end(), [](const PlanarContour& c) { return c.slice_id.has_value(); });
  std::vector<std::vector<std::size_t>> groups;
  if (by_id) {
    std::map<long long, std::vector<std::size_t>> by;
    for (std::size_t i = 0; i < n; ++i) by[*contours[i].slice_id].push_back(i);
    for (auto& [id, members] : by) groups.push_back(std::move(members));
  } else {
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return mean_w[a] < mean_w[b]; });
    for (std::size_t i : order) {
      if (groups.empty() || mean_w[i] - mean_w[groups.back().front()] > options.slice_tolerance) groups.emplace_back();
      groups.back().push_back(i);
    }
  }
  std::vector<InputSlice> slices;
  for (auto& g : groups) {
    std::sort(g.begin(), g.end());  // a slice's contours in input order
    double w = 0.0, weight = 0.0;
    for (std::size_t i : g) {
      const double a = static_cast<double>(contours[i].points.size());
      w += a * mean_w[i];
      weight += a;
    }
    slices.push_back({weight > 0.0 ? w / weight : mean_w[g.front()], std::move(g)});
  }
  std::stable_sort(slices.begin(), slices.end(), [](const InputSlice& a, const InputSlice& b) { return a.w < b.w; });
  if (by_id) {
    for (std::size_t s = 1; s < slices.size(); ++s) {
      if (!(slices[s].w - slices[s - 1].w > 1e-9)) {
        throw InvalidInputError(what + ": slices " + std::to_string(*contours[slices[s - 1].members.front()].slice_id) +
                                " and " + std::to_string(*contours[slices[s].members.front()].slice_id) +
                                " lie in the same plane (" + axis_name + " = " + mm(slices[s].w) + " mm)");
      }
    }
  }
  return slices;
}

// Every point within the planarity tolerance of its slice plane; otherwise an error saying whether the
// contour is bent or tilted.
void check_planarity(const PlanarContour& contour, const std::string& name, double slice_w, double mean_w,
                     const ContourStack& stack, const std::string& what, const PlanarStackOptions& options) {
  double worst = 0.0;
  for (const Eigen::Vector3d& q : contour.points) worst = std::max(worst, std::abs(q.dot(stack.axis_w) - slice_w));
  if (worst <= options.planarity_tolerance) return;
  std::ostringstream msg;
  msg << what << ": " << name << " (" << axis_label(stack) << " = " << mm(mean_w) << " mm) is ";
  const Eigen::Vector3d own = area_vector(contour.points);
  double own_spread = std::numeric_limits<double>::infinity();
  if (own.norm() > 0.0) {
    const Eigen::Vector3d nrm = own.normalized();
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Eigen::Vector3d& q : contour.points) {
      lo = std::min(lo, q.dot(nrm));
      hi = std::max(hi, q.dot(nrm));
    }
    own_spread = hi - lo;
  }
  if (own_spread <= 2.0 * options.planarity_tolerance) {
    const double angle =
        std::acos(std::min(1.0, std::abs(own.normalized().dot(stack.axis_w)))) * 180.0 / std::numbers::pi;
    msg << "planar but tilted " << mm(angle) << " degrees from the slice planes of the others";
  } else {
    msg << "not planar: its points lie up to " << mm(worst) << " mm from its slice plane (tolerance "
        << options.planarity_tolerance << " mm)";
  }
  throw InvalidInputError(msg.str());
}

}  // namespace

PlanarStack build_contour_stack(const std::vector<PlanarContour>& contours, const std::string& what,
                                const PlanarStackOptions& options) {
  check_options(options);
  PlanarStack out;
  PlanarStackReport& report = out.report;
  ContourStack& stack = out.stack;
  report.input_contours = contours.size();
  if (contours.empty()) throw InvalidInputError(what + ": no contours");
  auto name_of = [&](std::size_t i) {
    return contours[i].name.empty() ? "contour " + std::to_string(i + 1) : contours[i].name;
  };
  for (std::size_t i = 0; i < contours.size(); ++i) {
    for (std::size_t k = 0; k < contours[i].points.size(); ++k) {
      if (!contours[i].points[k].allFinite()) {
        throw InvalidInputError(what + ": " + name_of(i) + ": point " + std::to_string(k + 1) + " is not finite");
      }
    }
  }
  frame_for(canonical_axis(slice_axis(contours, what, options)), stack);
  const std::string axis_name = axis_label(stack);

  // Slice coordinates, and each contour's mean position along the axis.
  const std::size_t n = contours.size();
  std::vector<Polygon> uv(n);
  std::vector<double> mean_w(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& p = contours[i].points;
    uv[i].reserve(p.size());
    for (const Eigen::Vector3d& q : p) {
      uv[i].emplace_back(q.dot(stack.axis_u), q.dot(stack.axis_v));
      mean_w[i] += q.dot(stack.axis_w);
    }
    if (!p.empty()) mean_w[i] /= static_cast<double>(p.size());
  }
  const std::vector<InputSlice> slices = group_slices(contours, mean_w, what, axis_name, options);
  for (const InputSlice& sl : slices) {
    for (std::size_t i : sl.members) check_planarity(contours[i], name_of(i), sl.w, mean_w[i], stack, what, options);
  }

  // Per slice: clean, check, nest, orient.
  std::vector<std::string> repeated_names;
  for (const InputSlice& sl : slices) {
    std::vector<Work> work;
    for (std::size_t i : sl.members) {
      work.push_back({std::move(uv[i]), i, what + ": " + name_of(i) + " (" + axis_name + " = " + mm(sl.w) + " mm)",
                      name_of(i), 0.0});
    }
    std::vector<std::size_t> sources;
    std::vector<Contour> cs = normalize_slice(work, options, report, repeated_names, sources);
    if (cs.empty()) continue;
    stack.slices.push_back({sl.w, std::move(cs)});
    report.source.push_back(std::move(sources));
  }
  report_repeated(report, repeated_names, what);
  report.slices = stack.slices.size();
  if (stack.slices.empty()) throw InvalidInputError(what + ": every contour is degenerate (no area)");
  check_spacing(stack, options, what, report);
  return out;
}

PlanarStackReport normalize_contour_stack(ContourStack& stack, const std::string& what,
                                          const PlanarStackOptions& options) {
  check_options(options);
  PlanarStackReport report;
  const std::string axis_name = axis_label(stack);
  std::vector<std::string> repeated_names;
  for (std::size_t s = 0; s < stack.slices.size(); ++s) {
    SliceContours& sl = stack.slices[s];
    if (!std::isfinite(sl.w))
      throw InvalidInputError(what + ": slice " + std::to_string(s) + " has no finite position");
    if (s > 0 && !(sl.w > stack.slices[s - 1].w)) {
      throw InvalidInputError(what + ": slice " + std::to_string(s) + " (" + axis_name + " = " + mm(sl.w) +
                              " mm) is not above slice " + std::to_string(s - 1) + " (" + axis_name + " = " +
                              mm(stack.slices[s - 1].w) + " mm): slices must be ordered by increasing position");
    }
    report.input_contours += sl.contours.size();
    std::vector<Work> work;
    for (std::size_t c = 0; c < sl.contours.size(); ++c) {
      const std::string label = "contour " + std::to_string(c) + " of slice " + std::to_string(s);
      work.push_back({std::move(sl.contours[c].points), c,
                      what + ": " + label + " (" + axis_name + " = " + mm(sl.w) + " mm)", label, 0.0});
    }
    std::vector<std::size_t> sources;
    sl.contours = normalize_slice(work, options, report, repeated_names, sources);
    report.source.push_back(std::move(sources));
  }
  report_repeated(report, repeated_names, what);
  report.slices = stack.slices.size();
  check_spacing(stack, options, what, report);
  return report;
}

std::vector<double> slice_thicknesses(const ContourStack& stack) {
  const auto& sl = stack.slices;
  const std::size_t n = sl.size();
  std::vector<double> t(n, 0.0);
  if (n < 2) return t;
  for (std::size_t s = 0; s < n; ++s) {
    const double below = s > 0 ? sl[s].w - sl[s - 1].w : sl[1].w - sl[0].w;
    const double above = s + 1 < n ? sl[s + 1].w - sl[s].w : sl[n - 1].w - sl[n - 2].w;
    t[s] = 0.5 * (below + above);
  }
  return t;
}

double slicewise_volume(const ContourStack& stack) {
  const std::vector<double> t = slice_thicknesses(stack);
  double v = 0.0;
  for (std::size_t s = 0; s < stack.slices.size(); ++s) {
    double area = 0.0;
    for (const Contour& c : stack.slices[s].contours) {
      const double a = std::abs(signed_area(c.points));
      area += c.is_hole ? -a : a;
    }
    v += area * t[s];
  }
  return v;
}

}  // namespace contourmesh
