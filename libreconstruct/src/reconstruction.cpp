#include "reconstruct/reconstruction.h"

#include <smooth/errors.h>
#include <smooth/topology.h>

#include <chrono>
#include <sstream>

namespace contourmesh {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// Removes the connected components enclosing less than `min_volume` (cavity surfaces, which enclose a
// negative volume, are kept) and compacts the vertex array; `roles` (one per face) follow the faces.
Mesh drop_small_components(Mesh mesh, std::vector<FaceRole>& roles, double min_volume, std::size_t& dropped) {
  const Index n = mesh.num_vertices();
  const ComponentLabels components = component_labels(mesh);
  std::vector<double> volume(static_cast<std::size_t>(components.count), 0.0);
  for (const Triangle& t : mesh.triangles) {
    volume[components.of_vertex[t[0]]] +=
        mesh.positions.col(t[0]).dot(mesh.positions.col(t[1]).cross(mesh.positions.col(t[2]))) / 6.0;
  }
  auto too_small = [&](Index label) { return volume[label] >= 0.0 && volume[label] < min_volume; };
  std::vector<Index> remap(static_cast<std::size_t>(n), -1);
  Mesh kept;
  std::vector<Index> keep_vertices;
  for (Index i = 0; i < n; ++i) {
    const Index label = components.of_vertex[i];
    if (label < 0 || too_small(label)) continue;
    remap[i] = static_cast<Index>(keep_vertices.size());
    keep_vertices.push_back(i);
  }
  for (Index label = 0; label < components.count; ++label) dropped += too_small(label) ? 1 : 0;
  kept.positions.resize(3, static_cast<Eigen::Index>(keep_vertices.size()));
  for (std::size_t k = 0; k < keep_vertices.size(); ++k) {
    const Index i = keep_vertices[k];
    kept.positions.col(static_cast<Eigen::Index>(k)) = mesh.positions.col(i);
    kept.slice_ids.push_back(mesh.slice_ids[i]);
    kept.contour_ids.push_back(mesh.contour_ids[i]);
  }
  std::vector<FaceRole> kept_roles;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (remap[t[0]] < 0) continue;
    kept.triangles.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});
    kept_roles.push_back(roles[f]);
  }
  roles = std::move(kept_roles);
  return kept;
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
  const auto spacing = image.GetSpacing();
  const double min_volume = options.min_component_voxels * spacing[0] * spacing[1] * spacing[2];
  out.face_roles = std::move(tiled.face_roles);
  out.mesh = drop_small_components(std::move(tiled.mesh), out.face_roles, min_volume, out.report.dropped_components);
  if (out.mesh.num_faces() == 0) {
    throw InvalidInputError("every reconstructed piece is smaller than " + std::to_string(options.min_component_voxels) +
                            " voxels");
  }
  out.contours = std::move(seg.stack);
  return out;
}

}  // namespace contourmesh
