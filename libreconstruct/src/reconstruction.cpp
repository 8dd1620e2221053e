// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/reconstruction.h"

#include "detail/moved_face_flips.h"
#include "detail/single_slice.h"

#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/metrics.h>
#include <contourmesh/smooth/topology.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <set>
#include <sstream>

namespace contourmesh {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// Removes the connected components enclosing less than `min_volume` (cavity surfaces, which enclose a
// negative volume, are kept) and vertices in no triangle, and compacts the vertex array; `roles` (one
// per face) follow the faces. A mesh with nothing to remove is returned as it is.
Mesh drop_small_components(Mesh mesh, std::vector<FaceRole>& roles, double min_volume, std::size_t& dropped) {
  const Index n = mesh.num_vertices();
  const ComponentLabels components = component_labels(mesh);
  std::vector<double> volume(static_cast<std::size_t>(components.count), 0.0);
  for (const Triangle& t : mesh.triangles) {
    volume[components.of_vertex[t[0]]] +=
        mesh.positions.col(t[0]).dot(mesh.positions.col(t[1]).cross(mesh.positions.col(t[2]))) / 6.0;
  }
  auto too_small = [&](Index label) { return volume[label] >= 0.0 && volume[label] < min_volume; };
  std::vector<std::uint8_t> small(static_cast<std::size_t>(components.count), 0);
  std::size_t small_count = 0;
  for (Index label = 0; label < components.count; ++label) {
    small[label] = too_small(label) ? 1 : 0;
    small_count += small[label];
  }
  dropped += small_count;
  std::vector<Index> remap(static_cast<std::size_t>(n), -1);
  Index kept_vertices = 0;
  for (Index i = 0; i < n; ++i) {
    const Index label = components.of_vertex[i];
    if (label >= 0 && !small[label]) remap[i] = kept_vertices++;
  }
  if (kept_vertices == n) return mesh;  // every vertex kept, in order: the compaction is the identity
  Mesh kept;
  kept.positions.resize(3, kept_vertices);
  kept.slice_ids.resize(static_cast<std::size_t>(kept_vertices));
  kept.contour_ids.resize(static_cast<std::size_t>(kept_vertices));
  for (Index i = 0; i < n; ++i) {
    const Index k = remap[i];
    if (k < 0) continue;
    kept.positions.col(k) = mesh.positions.col(i);
    kept.slice_ids[k] = mesh.slice_ids[i];
    kept.contour_ids[k] = mesh.contour_ids[i];
  }
  kept.triangles.reserve(mesh.triangles.size());
  std::vector<FaceRole> kept_roles;
  kept_roles.reserve(roles.size());
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (remap[t[0]] < 0) continue;
    kept.triangles.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});
    kept_roles.push_back(roles[f]);
  }
  roles = std::move(kept_roles);
  return kept;
}

// A contour on one slice only whose region the regions of an adjacent slice cover by more than this share
// is left out (it touches a piece there, which the tiler did not join it to): a small tongue of a piece at
// its end, as the femur phantom's intercondylar notch at its apex.
constexpr double kMaxSlabCover = 0.01;

// Outer contours of one slice only become slabs (appended to `mesh`, before the off-slice heights place
// their caps); returns the holes of one slice only whose outer contour is part of the tiled surface.
std::vector<std::pair<std::size_t, std::size_t>> add_single_slice_slabs(Mesh& mesh, std::vector<FaceRole>& roles,
                                                                        const ContourStack& stack,
                                                                        const ReconstructionOptions& options,
                                                                        ReconstructionReport& report) {
  const detail::UnmeshedContours unmeshed = detail::unmeshed_contours(mesh, stack);
  std::vector<std::pair<std::size_t, std::size_t>> holes;
  if (unmeshed.list.empty()) return holes;
  const bool make_slabs =
      options.single_slice == SingleSliceContours::Slab && options.tiling.end_caps == EndCaps::HalfSpacing;
  // Outer contours first: whether each became a slab decides what its holes are.
  std::set<std::pair<std::size_t, std::size_t>> left_out;
  for (const auto& [s, c] : unmeshed.list) {
    if (stack.slices[s].contours[c].is_hole) continue;
    // Overlapping a region next to it, it belongs to that piece: a slab would float beside it.
    if (!make_slabs || detail::covered_by_adjacent_slices(stack, s, c) > kMaxSlabCover) {
      left_out.emplace(s, c);
      continue;
    }
    const auto [below, above] = detail::half_gaps(stack, s);
    detail::append_part(mesh, detail::single_slice_slab(stack, s, c, below, above, options.tiling), &roles);
    ++report.single_slice_slabs;
  }
  report.single_slice_left_out += left_out.size();
  for (const auto& [s, c] : unmeshed.list) {
    const Contour& contour = stack.slices[s].contours[c];
    if (!contour.is_hole) continue;
    if (left_out.count({s, static_cast<std::size_t>(contour.parent)}) > 0) {
      ++report.single_slice_left_out;  // inside a contour left out
    } else if (!make_slabs) {
      ++report.single_slice_filled;  // its outer contour is meshed without it
    } else if (!unmeshed.contains(s, contour.parent)) {
      holes.emplace_back(s, c);  // (a hole of a slab is part of it)
    }
  }
  return holes;
}

// Holes of one slice only inside the finished surface: hollow slabs where they fit and enclose at least
// `min_volume`, else filled.
void add_single_slice_cavities(Mesh& mesh, std::vector<FaceRole>& roles, const ContourStack& stack,
                               const std::vector<std::pair<std::size_t, std::size_t>>& holes,
                               const TilingOptions& tiling, double min_volume, ReconstructionReport& report) {
  if (holes.empty()) return;
  const auto near = detail::faces_near_slices(mesh, stack);
  std::vector<TilingResult> parts;  // appended after every check, which cut the surface as it was
  for (const auto& [s, c] : holes) {
    bool thin = false;
    std::optional<TilingResult> part = detail::fitting_cavity(mesh, near[s], stack, s, c, tiling, thin);
    if (part && -enclosed_volume(part->mesh) >= min_volume) {
      parts.push_back(std::move(*part));
      ++report.single_slice_cavities;
      report.single_slice_thinned += thin ? 1 : 0;
    } else {
      ++report.single_slice_filled;
    }
  }
  for (const TilingResult& part : parts) detail::append_part(mesh, part, &roles);
}

}  // namespace

Reconstruction reconstruct(const CtImage& image, const ReconstructionOptions& options,
                           const ProgressCallback& progress) {
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
  if (seg.voxels > 0 && seg.foreground_voxels == seg.voxels) {
    std::ostringstream msg;
    msg << "every voxel is at or above the threshold " << seg.threshold
        << " (all bone, or a threshold below the data?): the surface would be the volume's bounding box";
    throw InvalidInputError(msg.str());
  }
  if (out.report.contours == 0) {
    std::ostringstream msg;
    if (seg.foreground_voxels == 0) {
      msg << "no region at or above the threshold " << seg.threshold << " in any of the " << out.report.slices
          << " slices (all air, or a threshold above the data?)";
    } else {
      msg << "no region at or above the threshold " << seg.threshold << " is large enough: " << seg.dropped_regions
          << " region" << (seg.dropped_regions == 1 ? " was" : "s were")
          << " smaller than the minimum area or contour length (lower them, or check the voxel spacing)";
    }
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
  const auto single_slice_holes =
      add_single_slice_slabs(tiled.mesh, tiled.face_roles, seg.stack, options, out.report);
  t0 = std::chrono::steady_clock::now();
  OffSliceResult placed = fit_off_slice_heights(std::move(tiled.mesh), seg.smoothed_image ? *seg.smoothed_image : image,
                                                seg.threshold, options.off_slice, tiled.face_roles);
  tiled.mesh = std::move(placed.mesh);
  const auto spacing = image.GetSpacing();
  if (options.off_slice.placement == OffSlicePlacement::ImageCrossing) {
    // The heights move vertices without ids between the slices; flips mend the slivers that makes, within
    // a quarter of the slice spacing of the surface (as the slabs' own face-quality pass) and within one
    // pixel: on thick slices a quarter spacing is wider than a small object (0.01 x 0.01 x 50 mm voxels:
    // 12.5 mm of flips on a needle 1.2 mm across cost it 4 % of its volume).
    const auto& direction = image.GetDirection();
    const Eigen::Vector3d axis(direction[0][2], direction[1][2], direction[2][2]);
    const double max_deviation = std::min(0.25 * spacing[2], std::min(spacing[0], spacing[1]));
    detail::flip_moved_slivers(tiled.mesh, tiled.face_roles, axis.normalized(), max_deviation);
  }
  out.report.off_slice = placed.report;
  out.report.seconds_off_slice = seconds_since(t0);
  const double min_volume = options.min_component_voxels * spacing[0] * spacing[1] * spacing[2];
  add_single_slice_cavities(tiled.mesh, tiled.face_roles, seg.stack, single_slice_holes, options.tiling, min_volume,
                            out.report);
  out.face_roles = std::move(tiled.face_roles);
  out.mesh = drop_small_components(std::move(tiled.mesh), out.face_roles, min_volume, out.report.dropped_components);
  if (out.mesh.num_faces() == 0) {
    throw InvalidInputError("every reconstructed piece is smaller than " +
                            std::to_string(options.min_component_voxels) + " voxels");
  }
  out.contours = std::move(seg.stack);
  return out;
}

}  // namespace contourmesh
