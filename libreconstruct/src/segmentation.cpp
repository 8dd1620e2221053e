#include "reconstruct/segmentation.h"

#include <smooth/errors.h>

#include <itkContourExtractor2DImageFilter.h>
#include <itkCurvatureAnisotropicDiffusionImageFilter.h>
#include <itkImageRegionConstIterator.h>
#include <itkMedianImageFilter.h>
#include <itkOtsuThresholdImageFilter.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <limits>
#include <array>
#include <string>
#include <vector>

namespace contourmesh {

namespace {

using Image2D = itk::Image<float, 2>;

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

// Keeps only the largest 6-connected component of a binary volume (x fastest).
void keep_largest_component(std::vector<std::uint8_t>& mask, const std::array<std::size_t, 3>& size) {
  const std::size_t nx = size[0], ny = size[1], nz = size[2];
  std::vector<std::int32_t> label(mask.size(), 0);
  std::vector<std::size_t> stack;
  std::int32_t best_label = 0;
  std::size_t best_size = 0;
  std::int32_t next = 0;
  for (std::size_t start = 0; start < mask.size(); ++start) {
    if (!mask[start] || label[start]) continue;
    ++next;
    std::size_t count = 0;
    stack.push_back(start);
    label[start] = next;
    while (!stack.empty()) {
      const std::size_t v = stack.back();
      stack.pop_back();
      ++count;
      const std::size_t x = v % nx, y = (v / nx) % ny, z = v / (nx * ny);
      auto visit = [&](std::size_t w) {
        if (mask[w] && !label[w]) {
          label[w] = next;
          stack.push_back(w);
        }
      };
      if (x > 0) visit(v - 1);
      if (x + 1 < nx) visit(v + 1);
      if (y > 0) visit(v - nx);
      if (y + 1 < ny) visit(v + nx);
      if (z > 0) visit(v - nx * ny);
      if (z + 1 < nz) visit(v + nx * ny);
    }
    if (count > best_size) {
      best_size = count;
      best_label = next;
    }
  }
  for (std::size_t v = 0; v < mask.size(); ++v) mask[v] = label[v] == best_label && best_label != 0;
}

// Connected components of one slice: `fg` with 4-connectivity when `foreground`, else 8-connectivity
// on the complement (the duality that matches marching squares with high pixels kept apart at saddles).
int label_slice(const std::uint8_t* fg, int nx, int ny, bool foreground, std::vector<int>& label) {
  label.assign(static_cast<std::size_t>(nx) * ny, 0);
  std::vector<int> stack;
  int next = 0;
  for (int start = 0; start < nx * ny; ++start) {
    if ((fg[start] != 0) != foreground || label[start]) continue;
    label[start] = ++next;
    stack.push_back(start);
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      const int x = v % nx, y = v / nx;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          if ((dx == 0 && dy == 0) || (foreground && dx != 0 && dy != 0)) continue;
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= nx || yy >= ny) continue;
          const int w = yy * nx + xx;
          if ((fg[w] != 0) == foreground && !label[w]) {
            label[w] = next;
            stack.push_back(w);
          }
        }
      }
    }
  }
  return next;
}

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

// The contour points of the stack against the resource limits, checked before each resampling.
struct PointBudget {
  ResourceLimits limits;
  double sampling = 0.0;
  double points = 0.0;  // resampled points in the stack so far
  void check(double more) const {
    constexpr double kBytesPerPoint = 64.0;  // the 2-D point, then the tiled mesh's vertex and its ids
    char what[64];
    std::snprintf(what, sizeof what, "contour resampling at %g mm", sampling);
    check_allocation(what, points + more, (points + more) * kBytesPerPoint, limits);
  }
};

void resample(PendingContour& c, double sampling, PointBudget& budget) {
  const bool hole = c.contour.is_hole;
  budget.points -= static_cast<double>(c.contour.points.size());  // replaced below
  for (; c.level < kRawLevel; ++c.level) {
    const double spacing = sampling / static_cast<double>(1 << c.level);
    budget.check(perimeter(c.loop) / spacing + 1.0);
    c.contour.points = resample_closed(c.loop, spacing);
    if (!find_self_intersection(c.contour.points)) break;
  }
  if (c.level == kRawLevel) c.contour.points = c.loop;
  budget.points += static_cast<double>(c.contour.points.size());
  const double area = signed_area(c.contour.points);
  if ((hole && area > 0.0) || (!hole && area < 0.0)) std::reverse(c.contour.points.begin(), c.contour.points.end());
}

// The contours of a slice bound disjoint regions and must not meet (the tiler rejects a slice whose
// contours do): refine the resampling of both contours of a meeting pair until none meet.
std::vector<Contour> separated(std::vector<PendingContour> pending, double sampling, PointBudget& budget) {
  for (PendingContour& c : pending) resample(c, sampling, budget);
  for (;;) {
    std::vector<std::vector<Eigen::Vector2d>> outlines;
    outlines.reserve(pending.size());
    for (const PendingContour& c : pending) outlines.push_back(c.contour.points);
    const auto x = find_polygon_crossing(outlines);
    if (!x) break;
    bool refined = false;
    for (std::size_t k : {x->first, x->second}) {
      PendingContour& c = pending[k];
      if (c.level >= kRawLevel) continue;
      ++c.level;
      resample(c, sampling, budget);
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

}  // namespace

SegmentationResult segment_contours(const CtImage& input, const SegmentationOptions& options,
                                    const ProgressCallback& progress) {
  check_options(options);
  const auto region = input.GetLargestPossibleRegion();
  const std::array<std::size_t, 3> size = {region.GetSize()[0], region.GetSize()[1], region.GetSize()[2]};
  if (size[0] == 0 || size[1] == 0 || size[2] == 0) throw InvalidInputError("segmentation: the volume is empty");
  const int nx = static_cast<int>(size[0]);
  const int ny = static_cast<int>(size[1]);
  const auto spacing = input.GetSpacing();
  const double sx = spacing[0], sy = spacing[1], sz = spacing[2];
  const double pixel_area = sx * sy;

  const CtImage::Pointer image = smoothed(input, options.smoothing);
  SegmentationResult result;
  result.threshold = options.threshold_method == ThresholdMethod::Otsu ? otsu_threshold(image) : options.threshold;
  const float thr = static_cast<float>(result.threshold);

  // Dense copy of the values, x fastest (ITK's buffer order for the largest region).
  std::vector<float> values(size[0] * size[1] * size[2]);
  {
    itk::ImageRegionConstIterator<CtImage> it(image, image->GetLargestPossibleRegion());
    std::size_t k = 0;
    for (it.GoToBegin(); !it.IsAtEnd(); ++it) values[k++] = it.Get();
  }
  std::vector<std::uint8_t> mask(values.size());
  for (std::size_t v = 0; v < values.size(); ++v) mask[v] = values[v] >= thr;
  result.voxels = mask.size();
  result.foreground_voxels = static_cast<std::size_t>(std::count(mask.begin(), mask.end(), std::uint8_t{1}));
  if (options.components == ComponentSelection::KeepLargest) keep_largest_component(mask, size);

  // The slice frame.
  ContourStack& stack = result.stack;
  const auto dir = input.GetDirection();
  const auto origin = input.GetOrigin();
  stack.origin = Eigen::Vector3d(origin[0], origin[1], origin[2]);
  stack.axis_u = Eigen::Vector3d(dir[0][0], dir[1][0], dir[2][0]).normalized();
  stack.axis_v = Eigen::Vector3d(dir[0][1], dir[1][1], dir[2][1]).normalized();
  stack.axis_w = Eigen::Vector3d(dir[0][2], dir[1][2], dir[2][2]).normalized();
  stack.slices.resize(size[2]);
  const double sampling =
      options.sampling > 0.0 ? options.sampling : std::min({sx, sy, SegmentationOptions::kMaxDefaultSampling});

  // The loops of every slice are extracted first, so that the points their resampling will produce
  // are checked against the limits before any is made (a tiny `sampling` is refused at once).
  PointBudget budget{options.limits, sampling};
  std::vector<std::vector<PendingContour>> pending_of(size[2]);
  std::vector<int> fg_label, bg_label;
  std::vector<std::uint8_t> slice_mask(static_cast<std::size_t>(nx) * ny);
  for (std::size_t z = 0; z < size[2]; ++z) {
    SliceContours& out = stack.slices[z];
    out.w = static_cast<double>(z) * sz;
    std::vector<PendingContour>& pending = pending_of[z];
    const float* val = values.data() + z * size[0] * size[1];
    std::copy_n(mask.data() + z * size[0] * size[1], slice_mask.size(), slice_mask.begin());

    // Drop small regions, then find holes (background components not touching the border).
    const int nfg = label_slice(slice_mask.data(), nx, ny, true, fg_label);
    std::vector<std::size_t> area(static_cast<std::size_t>(nfg) + 1, 0);
    for (int v : fg_label) ++area[v];
    for (std::size_t p = 0; p < slice_mask.size(); ++p) {
      if (slice_mask[p] && static_cast<double>(area[fg_label[p]]) * pixel_area < options.min_region_area) {
        slice_mask[p] = 0;
        fg_label[p] = 0;
      }
    }
    for (int l = 1; l <= nfg; ++l) {
      if (area[l] > 0 && static_cast<double>(area[l]) * pixel_area < options.min_region_area) ++result.dropped_regions;
    }
    const int nbg = label_slice(slice_mask.data(), nx, ny, false, bg_label);
    std::vector<std::size_t> bg_area(static_cast<std::size_t>(nbg) + 1, 0);
    std::vector<std::uint8_t> touches_border(static_cast<std::size_t>(nbg) + 1, 0);
    std::vector<int> enclosing(static_cast<std::size_t>(nbg) + 1, 0);
    for (int y = 0; y < ny; ++y) {
      for (int x = 0; x < nx; ++x) {
        const int p = y * nx + x;
        const int b = bg_label[p];
        if (!b) continue;
        ++bg_area[b];
        if (x == 0 || y == 0 || x == nx - 1 || y == ny - 1) touches_border[b] = 1;
        if (!enclosing[b]) {
          if (x > 0 && fg_label[p - 1]) enclosing[b] = fg_label[p - 1];
          else if (y > 0 && fg_label[p - nx]) enclosing[b] = fg_label[p - nx];
        }
      }
    }
    // Filled holes join their enclosing region.
    std::vector<std::uint8_t> filled(static_cast<std::size_t>(nbg) + 1, 0);
    for (int b = 1; b <= nbg; ++b) {
      filled[b] = !touches_border[b] && enclosing[b] &&
                  (options.fill_holes || static_cast<double>(bg_area[b]) * pixel_area < options.min_region_area);
    }
    std::vector<Box> boxes(static_cast<std::size_t>(nfg) + 1);
    for (int y = 0; y < ny; ++y) {
      for (int x = 0; x < nx; ++x) {
        const int p = y * nx + x;
        if (fg_label[p]) boxes[fg_label[p]].add(x, y);
      }
    }

    for (int l = 1; l <= nfg; ++l) {
      const Box& box = boxes[l];
      if (box.x1 < 0) continue;  // dropped
      // Crop with two pixels of margin; outside the image counts as far below the threshold.
      const int x0 = box.x0 - 2, y0 = box.y0 - 2, w = box.x1 - box.x0 + 5, h = box.y1 - box.y0 + 5;
      auto crop = Image2D::New();
      Image2D::RegionType r;
      r.SetSize({{static_cast<itk::SizeValueType>(w), static_cast<itk::SizeValueType>(h)}});
      crop->SetRegions(r);
      crop->Allocate();
      const float low = thr - 1000.0f;
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          const int gx = x0 + x, gy = y0 + y;
          float v = low;
          if (gx >= 0 && gy >= 0 && gx < nx && gy < ny) {
            const int p = gy * nx + gx;
            if (fg_label[p] == l) v = std::max(val[p], thr + 1.0f);       // ours (smoothing may dip below)
            else if (bg_label[p] && filled[bg_label[p]] && enclosing[bg_label[p]] == l) v = thr + 1.0f;
            else if (fg_label[p] || (mask[z * size[0] * size[1] + p] && !slice_mask[p])) v = low;  // others
            else v = std::min(val[p], thr - 1e-3f);                         // background
          }
          crop->SetPixel({{x, y}}, v);
        }
      }
      auto extractor = itk::ContourExtractor2DImageFilter<Image2D>::New();
      extractor->SetInput(crop);
      extractor->SetContourValue(thr);
      extractor->Update();
      std::vector<std::vector<Eigen::Vector2d>> loops;
      for (unsigned k = 0; k < extractor->GetNumberOfIndexedOutputs(); ++k) {
        const auto* path = extractor->GetOutput(k);
        const auto* vertices = path->GetVertexList();
        if (vertices->Size() < 4) continue;
        const auto first = vertices->ElementAt(0);
        const auto last = vertices->ElementAt(vertices->Size() - 1);
        if (first[0] != last[0] || first[1] != last[1]) continue;  // open: cannot happen with the margin
        std::vector<Eigen::Vector2d> pts;
        for (unsigned i = 0; i + 1 < vertices->Size(); ++i) {
          const auto idx = vertices->ElementAt(i);
          pts.emplace_back((idx[0] + x0) * sx, (idx[1] + y0) * sy);
        }
        loops.push_back(std::move(pts));
      }
      if (loops.empty()) continue;
      // The outer boundary encloses the most area; the others are holes.
      std::size_t outer = 0;
      for (std::size_t k = 1; k < loops.size(); ++k) {
        if (std::abs(signed_area(loops[k])) > std::abs(signed_area(loops[outer]))) outer = k;
      }
      if (perimeter(loops[outer]) < options.min_contour_length) {
        ++result.dropped_regions;
        continue;
      }
      const int parent = static_cast<int>(pending.size());
      pending.push_back({std::move(loops[outer]), Contour{}, 0});
      for (std::size_t k = 0; k < loops.size(); ++k) {
        if (k == outer) continue;
        if (perimeter(loops[k]) < options.min_contour_length) {
          ++result.dropped_regions;
          continue;
        }
        PendingContour hole{std::move(loops[k]), Contour{}, 0};
        hole.contour.is_hole = true;
        hole.contour.parent = parent;
        pending.push_back(std::move(hole));
      }
    }
    if (progress && !progress("segment", 0.5 * static_cast<double>(z + 1) / static_cast<double>(size[2]))) {
      throw CancelledError("segmentation");
    }
  }
  {
    double points = 0.0;
    for (const auto& pending : pending_of) {
      for (const PendingContour& c : pending) points += perimeter(c.loop) / sampling + 1.0;
    }
    budget.check(points);
  }
  for (std::size_t z = 0; z < size[2]; ++z) {
    stack.slices[z].contours = separated(std::move(pending_of[z]), sampling, budget);
    if (progress && !progress("segment", 0.5 + 0.5 * static_cast<double>(z + 1) / static_cast<double>(size[2]))) {
      throw CancelledError("segmentation");
    }
  }
  return result;
}

}  // namespace contourmesh
