// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/segmentation.h"

#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/limits.h>

#include "detail/flat_crossings.h"
#include "detail/region_boundaries.h"
#include "detail/slice_components.h"

#include <Eigen/Geometry>
#include <itkCurvatureAnisotropicDiffusionImageFilter.h>
#include <itkMedianImageFilter.h>
#include <itkOtsuThresholdImageFilter.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdio>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <utility>
#include <string>
#include <thread>
#include <vector>

namespace contourmesh {

namespace {

CtImage::Pointer smoothed(const CtImage& image, ImageSmoothing smoothing) {
  CtImage::Pointer input = const_cast<CtImage*>(&image);  // ITK filters take non-const inputs; not modified
  switch (smoothing) {
    case ImageSmoothing::None: return input;
    case ImageSmoothing::Median: {
      auto filter = itk::MedianImageFilter<CtImage, CtImage>::New();
      filter->SetInput(input);
      CtImage::SizeType radius;
      radius[0] = 1;
      radius[1] = 1;
      radius[2] = 0;
      filter->SetRadius(radius);
      filter->Update();
      return filter->GetOutput();
    }
    case ImageSmoothing::CurvatureAnisotropic: {
      auto filter = itk::CurvatureAnisotropicDiffusionImageFilter<CtImage, CtImage>::New();
      filter->SetInput(input);
      filter->SetNumberOfIterations(5);
      const auto sp = image.GetSpacing();
      const double min_spacing = std::min({sp[0], sp[1], sp[2]});
      filter->SetTimeStep(min_spacing / 16.0);  // stable for 3-D: < min spacing / 2^(N+1)
      filter->SetConductanceParameter(3.0);
      filter->Update();
      return filter->GetOutput();
    }
  }
  return input;
}

double otsu_threshold(CtImage* image) {
  auto filter = itk::OtsuThresholdImageFilter<CtImage, itk::Image<std::uint8_t, 3>>::New();
  filter->SetInput(image);
  filter->SetNumberOfHistogramBins(256);
  filter->Update();
  return static_cast<double>(filter->GetThreshold());
}

// A pixel bounding box, inclusive; empty while x1 < 0.
struct Box {
  int x0 = std::numeric_limits<int>::max(), y0 = std::numeric_limits<int>::max(), x1 = -1, y1 = -1;
  void add(int x, int y) {
    x0 = std::min(x0, x);
    y0 = std::min(y0, y);
    x1 = std::max(x1, x);
    y1 = std::max(y1, y);
  }
};

// A contour as extracted, and the resampled points the stack gets. Resampling can cut across a narrow
// part of a loop and make it cross itself or a neighbouring contour of the slice (the extractor's loops
// never do): such a contour is resampled more finely (`level` halvings of the spacing) until it does
// not, or keeps its loop as extracted (level kRawLevel).
struct PendingContour {
  std::vector<Eigen::Vector2d> loop;
  Contour contour;
  int level = 0;
};
constexpr int kRawLevel = 4;

void resample(PendingContour& c, double sampling) {
  const bool hole = c.contour.is_hole;
  for (; c.level < kRawLevel; ++c.level) {
    c.contour.points = resample_closed(c.loop, sampling / static_cast<double>(1 << c.level));
    if (!find_self_intersection(c.contour.points)) break;
  }
  if (c.level == kRawLevel) c.contour.points = c.loop;
  const double area = signed_area(c.contour.points);
  if ((hole && area > 0.0) || (!hole && area < 0.0)) std::reverse(c.contour.points.begin(), c.contour.points.end());
}

// The two contours of the first crossing between contours of a slice, in find_polygon_crossing's
// order, if any. Only contours whose bounding boxes touch can meet: find_polygon_crossing runs on each
// group of such contours (a region's holes with their outer, nested islands) rather than on the whole
// slice, whose grid would be coarse where the contours are spread out; the first crossing over all
// groups is the first overall, since every crossing lies within a group.
std::optional<std::pair<std::size_t, std::size_t>> first_crossing(const std::vector<PendingContour>& pending) {
  const std::size_t n = pending.size();
  std::vector<Eigen::AlignedBox2d> boxes(n);
  for (std::size_t k = 0; k < n; ++k) {
    for (const Eigen::Vector2d& p : pending[k].contour.points) {
      if (!p.allFinite()) return std::nullopt;  // as find_polygon_crossing: not comparable
      boxes[k].extend(p);
    }
  }
  // Groups of touching boxes (union-find, sweep along x).
  detail::UnionFind<> groups(n);
  std::vector<std::size_t> by_x(n);
  std::iota(by_x.begin(), by_x.end(), std::size_t{0});
  const auto root = [&](std::size_t k) { return groups.find(k); };
  std::sort(by_x.begin(), by_x.end(),
            [&](std::size_t a, std::size_t b) { return boxes[a].min().x() < boxes[b].min().x(); });
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::AlignedBox2d& a = boxes[by_x[i]];
    for (std::size_t j = i + 1; j < n && boxes[by_x[j]].min().x() <= a.max().x(); ++j) {
      const Eigen::AlignedBox2d& b = boxes[by_x[j]];
      if (b.min().y() <= a.max().y() && a.min().y() <= b.max().y()) {
        groups.unite(by_x[i], by_x[j]);
      }
    }
  }
  std::optional<std::array<std::size_t, 4>> best;  // first contour, its edge, second contour, its edge
  std::vector<std::size_t> members;
  std::vector<std::vector<Eigen::Vector2d>> outlines;
  for (std::size_t g = 0; g < n; ++g) {
    if (root(g) != g) continue;
    members.clear();
    for (std::size_t k = g; k < n; ++k) {
      if (root(k) == g) members.push_back(k);
    }
    if (members.size() < 2) continue;
    outlines.clear();
    for (std::size_t k : members) outlines.push_back(pending[k].contour.points);
    if (const auto x = find_polygon_crossing(outlines)) {
      const std::array<std::size_t, 4> found{members[x->first], x->first_edge, members[x->second], x->second_edge};
      if (!best || found < *best) best = found;
    }
  }
  if (!best) return std::nullopt;
  return std::make_pair((*best)[0], (*best)[2]);
}

// The contours of a slice bound disjoint regions and must not meet (the tiler rejects a slice whose
// contours do): refine the resampling of both contours of a meeting pair until none meet.
std::vector<Contour> separated(std::vector<PendingContour> pending, double sampling) {
  for (PendingContour& c : pending) resample(c, sampling);
  for (;;) {
    const auto x = first_crossing(pending);
    if (!x) break;
    bool refined = false;
    for (std::size_t k : {x->first, x->second}) {
      PendingContour& c = pending[k];
      if (c.level >= kRawLevel) continue;
      ++c.level;
      resample(c, sampling);
      refined = true;
    }
    if (!refined) break;  // the extracted loops themselves meet: the tiler names them
  }
  std::vector<Contour> out;
  out.reserve(pending.size());
  for (PendingContour& c : pending) out.push_back(std::move(c.contour));
  return out;
}

void check_options(const SegmentationOptions& o) {
  if (!std::isfinite(o.threshold)) throw InvalidInputError("segmentation: threshold must be finite");
  if (!(o.min_region_area >= 0.0)) throw InvalidInputError("segmentation: min_region_area must be >= 0");
  if (!(o.sampling >= 0.0)) throw InvalidInputError("segmentation: sampling must be >= 0 mm");
  if (!(o.min_contour_length >= 0.0)) throw InvalidInputError("segmentation: min_contour_length must be >= 0 mm");
}

// The values a region's contour is interpolated from (marching squares at the threshold t, linear
// interpolation along pixel edges). The region's own pixels are raised to t + 1 where smoothing left
// them below (a region is what the mask says), pixels of the holes it fills are t + 1, and the rest is
// lowered to just under t: background keeps its values up to t - 0.001, pixels of other regions and
// dropped specks count as far below (t - 1000). The contour therefore follows the real values at the
// region's rim but never merges with a neighbouring region. Where t is so large that t + 1 or
// t - 0.001 round to t in single precision, the nearest floats above and below t stand in.
struct IsoLevels {
  explicit IsoLevels(float t)
      : threshold(t),
        above(t + 1.0f > t ? t + 1.0f : std::nextafter(t, std::numeric_limits<float>::infinity())),
        below(t - 1e-3f < t ? t - 1e-3f : std::nextafter(t, -std::numeric_limits<float>::infinity())),
        far_below(t - 1000.0f < t ? t - 1000.0f : below) {}
  float threshold, above, below, far_below;
};

// One slice's regions: foreground components (4-connected) that are large enough, the holes they
// fill, and for every pixel the region it belongs to. Reused from slice to slice by one thread.
struct SliceRegions {
  std::vector<std::uint8_t> mask;  // at or above the threshold (after 3-D component selection)
  std::vector<std::uint8_t> kept;  // mask without the dropped small regions
  std::vector<detail::PixelRun> fg, kept_fg, bg, owned;
  detail::UnionFind<int> union_find;
  detail::RegionImage owner;       // the region of each pixel: its own, or the one whose hole it fills
  std::vector<Box> boxes;          // per fg label: box of its own pixels (x1 < 0: dropped)
  std::vector<std::size_t> area;
  std::vector<int> enclosing;      // per bg label: the region around it (0: touches the border)
  std::vector<std::uint8_t> visited;
  std::vector<detail::RegionLoop> loops;
  std::vector<float> values;       // the slice's values with the flat crossings' sides set, when any are
};

// Labels the slice's regions and holes from s.mask, drops regions smaller than the minimum area and
// assigns the filled holes to their regions (s.owner). Returns the number of regions dropped.
std::size_t find_regions(int nx, int ny, double pixel_area, const SegmentationOptions& options, SliceRegions& s) {
  const auto small = [&](std::size_t pixels) {
    return static_cast<double>(pixels) * pixel_area < options.min_region_area;
  };
  detail::find_runs(s.mask.data(), nx, ny, s.fg);
  const int regions = detail::label_runs(s.fg, detail::Connectivity::Four, s.union_find);
  s.area.assign(static_cast<std::size_t>(regions) + 1, 0);
  for (const detail::PixelRun& r : s.fg) s.area[r.label] += static_cast<std::size_t>(r.x1 - r.x0);
  std::size_t dropped = 0;
  for (int l = 1; l <= regions; ++l) dropped += small(s.area[l]) ? 1 : 0;
  s.kept = s.mask;
  s.kept_fg.clear();
  s.boxes.assign(static_cast<std::size_t>(regions) + 1, Box{});
  // Clear the previous slice's regions (cheaper than clearing every pixel).
  if (s.owner.nx() == nx && s.owner.ny() == ny) {
    for (const detail::PixelRun& r : s.owned) s.owner.paint(r, 0);
  } else {
    s.owner.reset(nx, ny);
  }
  for (const detail::PixelRun& r : s.fg) {
    if (small(s.area[r.label])) {
      std::fill_n(s.kept.begin() + static_cast<std::ptrdiff_t>(r.y) * nx + r.x0, r.x1 - r.x0, std::uint8_t{0});
    } else {
      s.kept_fg.push_back(r);
      s.boxes[r.label].add(r.x0, r.y);
      s.boxes[r.label].add(r.x1 - 1, r.y);
      s.owner.paint(r, r.label);
    }
  }
  // Holes: background components (8-connected) that do not touch the border. The region left of a
  // hole's first pixel encloses it (that pixel cannot be background: it would come first).
  detail::complement_runs(s.kept_fg, nx, ny, s.bg);
  const int backgrounds = detail::label_runs(s.bg, detail::Connectivity::Eight, s.union_find);
  s.area.assign(static_cast<std::size_t>(backgrounds) + 1, 0);
  s.enclosing.assign(static_cast<std::size_t>(backgrounds) + 1, -1);
  for (const detail::PixelRun& r : s.bg) {
    s.area[r.label] += static_cast<std::size_t>(r.x1 - r.x0);
    int& e = s.enclosing[r.label];
    if (e < 0) e = r.x0 > 0 && r.y > 0 ? s.owner.at(r.x0 - 1, r.y) : 0;
    if (r.x0 == 0 || r.x1 == nx || r.y == 0 || r.y == ny - 1) e = 0;
  }
  s.owned = s.kept_fg;
  for (const detail::PixelRun& r : s.bg) {
    const int e = s.enclosing[r.label];
    if (e > 0 && (options.fill_holes || small(s.area[r.label]))) {
      s.owner.paint(r, e);
      s.owned.push_back(r);
    }
  }
  return dropped;
}

// The outer contour and holes of each region of a slice (regions in label order; for each, its
// loops as marching squares on the region's own values lists them), as traced: not yet resampled.
// Sub-pixel positions in mm, computed in the frame of a crop two pixels around the region (the
// rounding the contours have always had).
std::vector<PendingContour> region_contours(const float* val, int nx, int ny, double sx, double sy,
                                            const IsoLevels& iso, const SegmentationOptions& options,
                                            SliceRegions& s, std::size_t& dropped) {
  detail::trace_region_boundaries(s.owner, s.owned, s.visited, s.loops);
  const auto value = [&](int l, int x, int y) -> float {
    if (x < 0 || y < 0 || x >= nx || y >= ny) return iso.far_below;
    const std::size_t p = static_cast<std::size_t>(y) * nx + x;
    if (s.owner.at(x, y) == l) return s.kept[p] ? std::max(val[p], iso.above) : iso.above;
    return s.mask[p] ? iso.far_below : std::min(val[p], iso.below);
  };
  const double t = iso.threshold;
  std::vector<PendingContour> pending;
  std::vector<std::vector<Eigen::Vector2d>> loops;
  for (std::size_t first = 0; first < s.loops.size();) {
    const int l = s.loops[first].region;
    std::size_t end = first;
    while (end < s.loops.size() && s.loops[end].region == l) ++end;
    const int x0 = s.boxes[l].x0 - 2, y0 = s.boxes[l].y0 - 2;
    loops.clear();
    for (std::size_t k = first; k < end; ++k) {
      const detail::RegionLoop& loop = s.loops[k];
      if (loop.crossings.size() < 3) continue;
      std::vector<Eigen::Vector2d>& pts = loops.emplace_back();
      pts.reserve(loop.crossings.size());
      for (const detail::EdgeCrossing& c : loop.crossings) {
        const int ox = c.horizontal ? 1 : 0, oy = 1 - ox;
        const double from = value(l, c.x, c.y), to = value(l, c.x + ox, c.y + oy);
        const double f = (t - from) / (to - from);
        const double cx = static_cast<double>(c.x - x0) + f * ox, cy = static_cast<double>(c.y - y0) + f * oy;
        pts.emplace_back((cx + x0) * sx, (cy + y0) * sy);
      }
    }
    first = end;
    if (loops.empty()) continue;
    // The outer boundary encloses the most area; the others are holes.
    std::size_t outer = 0;
    double outer_area = std::abs(signed_area(loops[0]));
    for (std::size_t k = 1; k < loops.size(); ++k) {
      const double area = std::abs(signed_area(loops[k]));
      if (area > outer_area) {
        outer = k;
        outer_area = area;
      }
    }
    if (perimeter(loops[outer]) < options.min_contour_length) {
      ++dropped;
      continue;
    }
    const int parent = static_cast<int>(pending.size());
    pending.push_back({std::move(loops[outer]), Contour{}, 0});
    for (std::size_t k = 0; k < loops.size(); ++k) {
      if (k == outer) continue;
      if (perimeter(loops[k]) < options.min_contour_length) {
        ++dropped;
        continue;
      }
      PendingContour hole{std::move(loops[k]), Contour{}, 0};
      hole.contour.is_hole = true;
      hole.contour.parent = parent;
      pending.push_back(std::move(hole));
    }
  }
  return pending;
}

// mask[p] = values[p] >= threshold. Arguments by value, so that the byte stores cannot alias them and
// the loop vectorises.
void threshold_pixels(const float* values, std::uint8_t* mask, std::size_t count, float threshold) {
  for (std::size_t p = 0; p < count; ++p) mask[p] = values[p] >= threshold;
}

// What every slice shares.
struct SliceSetup {
  int nx, ny;
  double sx, sy, sampling;
  IsoLevels iso;
  const SegmentationOptions& options;
};

struct SliceOutput {
  std::vector<Contour> contours;
  std::size_t dropped = 0;     // regions dropped as too small or too short
  std::size_t foreground = 0;  // pixels at or above the threshold
};

// One slice's regions and holes and their contours as traced, not yet resampled. `mask` = the slice's
// part of the 3-D component selection, or null to threshold `values` here.
std::vector<PendingContour> trace_slice(const SliceSetup& setup, const float* values, const std::uint8_t* mask,
                                        const std::vector<detail::PixelValue>& flat, SliceRegions& s,
                                        SliceOutput& out) {
  const std::size_t pixels = static_cast<std::size_t>(setup.nx) * static_cast<std::size_t>(setup.ny);
  if (!flat.empty()) {
    s.values.assign(values, values + pixels);
    for (const detail::PixelValue& f : flat) s.values[f.pixel] = f.value;
    values = s.values.data();
  }
  s.mask.resize(pixels);
  if (mask) std::copy_n(mask, pixels, s.mask.begin());
  else threshold_pixels(values, s.mask.data(), pixels, setup.iso.threshold);
  out.dropped = find_regions(setup.nx, setup.ny, setup.sx * setup.sy, setup.options, s);
  for (const detail::PixelRun& r : s.fg) out.foreground += static_cast<std::size_t>(r.x1 - r.x0);
  return region_contours(values, setup.nx, setup.ny, setup.sx, setup.sy, setup.iso, setup.options, s, out.dropped);
}

// The contour points the resampling at `sampling` will make, checked against the limits before any is
// made: a tiny `sampling` is refused at once instead of growing until memory runs out. (A contour
// resampled more finely to keep it apart from another adds a few more; the estimate is of the first pass.)
void check_point_budget(const std::vector<std::vector<PendingContour>>& pending, double sampling,
                        const ResourceLimits& limits) {
  constexpr double kBytesPerPoint = 64.0;  // the 2-D point, then the tiled mesh's vertex and its ids
  double points = 0.0;
  for (const auto& slice : pending) {
    for (const PendingContour& c : slice) points += perimeter(c.loop) / sampling + 1.0;
  }
  char what[64];
  std::snprintf(what, sizeof what, "contour resampling at %g mm", sampling);
  check_allocation(what, points, points * kBytesPerPoint, limits);
}

// The voxel values, x fastest. ITK's buffer when it holds the whole image (always, for images that
// come out of a reader or a filter).
const float* dense_values(const CtImage& image) {
  if (image.GetBufferedRegion() != image.GetLargestPossibleRegion() || image.GetBufferPointer() == nullptr) {
    throw InvalidInputError("segmentation: the image's buffer does not hold its whole region");
  }
  return image.GetBufferPointer();
}

}  // namespace

SegmentationResult segment_contours(const CtImage& input, const SegmentationOptions& options,
                                    const ProgressCallback& progress) {
  check_options(options);
  const auto region = input.GetLargestPossibleRegion();
  const std::array<std::size_t, 3> size = {region.GetSize()[0], region.GetSize()[1], region.GetSize()[2]};
  if (size[0] == 0 || size[1] == 0 || size[2] == 0) throw InvalidInputError("segmentation: the volume is empty");
  const int nx = static_cast<int>(size[0]);
  const int ny = static_cast<int>(size[1]);
  const std::size_t slice_pixels = size[0] * size[1];
  const auto spacing = input.GetSpacing();

  const CtImage::Pointer image = smoothed(input, options.smoothing);
  SegmentationResult result;
  if (options.smoothing != ImageSmoothing::None) result.smoothed_image = image;
  result.threshold = options.threshold_method == ThresholdMethod::Otsu ? otsu_threshold(image) : options.threshold;
  const SliceSetup setup{nx,
                         ny,
                         spacing[0],
                         spacing[1],
                         options.sampling > 0.0
                             ? options.sampling
                             : std::min({spacing[0], spacing[1], SegmentationOptions::kMaxDefaultSampling}),
                         IsoLevels(static_cast<float>(result.threshold)),
                         options};
  const float* values = dense_values(*image);
  result.voxels = slice_pixels * size[2];

  // The sides of the flat crossings, slice by slice (they read the slices on either side).
  std::vector<std::vector<detail::PixelValue>> flat(size[2]);
  if (options.flat_crossings == FlatCrossings::Patches && size[2] >= 3) {
    tbb::enumerable_thread_specific<detail::FlatCrossingScratch> buffers;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(1, size[2] - 1, 1),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        detail::FlatCrossingScratch& scratch = buffers.local();
                        for (std::size_t z = range.begin(); z != range.end(); ++z) {
                          flat[z] = detail::flat_crossing_values(values, nx, ny, static_cast<int>(size[2]),
                                                                 static_cast<int>(z), setup.iso.threshold,
                                                                 setup.iso.above, setup.iso.below, {}, scratch);
                        }
                      });
  }

  // 3-D component selection needs the whole mask first; otherwise each slice makes its own.
  std::vector<std::uint8_t> volume_mask;
  if (options.components == ComponentSelection::KeepLargest) {
    volume_mask.resize(result.voxels);
    threshold_pixels(values, volume_mask.data(), volume_mask.size(), setup.iso.threshold);
    for (std::size_t z = 0; z < size[2]; ++z) {
      for (const detail::PixelValue& f : flat[z]) {
        volume_mask[z * slice_pixels + f.pixel] = f.value >= setup.iso.threshold ? 1 : 0;
      }
    }
    result.foreground_voxels =
        static_cast<std::size_t>(std::count(volume_mask.begin(), volume_mask.end(), std::uint8_t{1}));
    detail::keep_largest_component(volume_mask, nx, ny, static_cast<int>(size[2]));
  }

  // The slice frame.
  ContourStack& stack = result.stack;
  const auto dir = input.GetDirection();
  const auto origin = input.GetOrigin();
  stack.origin = Eigen::Vector3d(origin[0], origin[1], origin[2]);
  stack.axis_u = Eigen::Vector3d(dir[0][0], dir[1][0], dir[2][0]).normalized();
  stack.axis_v = Eigen::Vector3d(dir[0][1], dir[1][1], dir[2][1]).normalized();
  stack.axis_w = Eigen::Vector3d(dir[0][2], dir[1][2], dir[2][2]).normalized();
  stack.slices.resize(size[2]);

  // Slices are independent: each is segmented on its own, on every core the caller allows, in two
  // passes with the point budget checked between them (trace, then resample). Progress is reported (and
  // cancellation asked) from the calling thread only, as ProgressCallback promises.
  std::vector<SliceOutput> slices(size[2]);
  std::vector<std::vector<PendingContour>> pending(size[2]);
  tbb::enumerable_thread_specific<SliceRegions> scratch;
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<std::size_t> done{0};
  std::atomic<bool> cancelled{false};
  const auto pass = [&](auto&& work) {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, size[2], 1), [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t z = range.begin(); z != range.end(); ++z) {
            if (cancelled.load(std::memory_order_relaxed)) return;
            work(z);
            const std::size_t finished = done.fetch_add(1) + 1;
            if (progress && std::this_thread::get_id() == caller &&
                !progress("segment", 0.5 * static_cast<double>(finished) / static_cast<double>(size[2]))) {
              cancelled = true;
            }
          }
        });
    if (cancelled) throw CancelledError("segmentation");
  };
  pass([&](std::size_t z) {
    pending[z] = trace_slice(setup, values + z * slice_pixels,
                             volume_mask.empty() ? nullptr : volume_mask.data() + z * slice_pixels, flat[z],
                             scratch.local(), slices[z]);
  });
  check_point_budget(pending, setup.sampling, options.limits);
  pass([&](std::size_t z) { slices[z].contours = separated(std::move(pending[z]), setup.sampling); });
  if (progress && !progress("segment", 1.0)) throw CancelledError("segmentation");
  for (std::size_t z = 0; z < size[2]; ++z) {
    stack.slices[z].w = static_cast<double>(z) * spacing[2];
    stack.slices[z].contours = std::move(slices[z].contours);
    result.dropped_regions += slices[z].dropped;
    if (volume_mask.empty()) result.foreground_voxels += slices[z].foreground;
  }
  return result;
}

}  // namespace contourmesh
