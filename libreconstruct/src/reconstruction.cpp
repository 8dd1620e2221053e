#include "reconstruct/reconstruction.h"

#include <smooth/errors.h>

#include <chrono>
#include <sstream>

namespace contourmesh {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

Reconstruction reconstruct(const CtImage& image, const ReconstructionOptions& options, const ProgressCallback& progress) {
  Reconstruction out;
  auto t0 = std::chrono::steady_clock::now();
  SegmentationResult seg = segment_contours(image, options.segmentation, progress);
  out.report.seconds_segment = seconds_since(t0);
  out.report.slices = seg.stack.slices.size();
  out.report.threshold = seg.threshold;
  out.report.dropped_regions = seg.dropped_regions;
  for (const SliceContours& s : seg.stack.slices) {
    out.report.slices_with_contours += s.contours.empty() ? 0 : 1;
    for (const Contour& c : s.contours) {
      ++out.report.contours;
      out.report.hole_contours += c.is_hole ? 1 : 0;
    }
  }
  if (out.report.contours == 0) {
    std::ostringstream msg;
    msg << "no region at or above the threshold " << seg.threshold << " in any of the " << out.report.slices
        << " slices (all air, or a threshold above the data?)";
    throw InvalidInputError(msg.str());
  }
  if (out.report.slices_with_contours < 2) {
    throw InvalidInputError("contours found in " + std::to_string(out.report.slices_with_contours) +
                            " slice only: a surface needs at least two slices");
  }
  t0 = std::chrono::steady_clock::now();
  TilingResult tiled = tile_contours(seg.stack, options.tiling, progress);
  out.report.seconds_tile = seconds_since(t0);
  out.report.tiling = tiled.stats;
  if (tiled.mesh.num_faces() == 0) {
    throw InvalidInputError("no contour continues into an adjacent slice: nothing to tile (slices too far apart?)");
  }
  out.mesh = std::move(tiled.mesh);
  out.contours = std::move(seg.stack);
  return out;
}

}  // namespace contourmesh
