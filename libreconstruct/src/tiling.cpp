// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/tiling.h"

#include "detail/correspondence.h"
#include "detail/slab_tiling.h"
#include "detail/stack_preparation.h"
#include "detail/tiling_types.h"
#include "contourmesh/reconstruct/threads.h"

#include <contourmesh/smooth/errors.h>

#include <algorithm>
#include <cmath>
#include <atomic>
#include <exception>
#include <limits>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace contourmesh {

TilingStats& TilingStats::operator+=(const TilingStats& o) {
  one_to_one += o.one_to_one;
  branchings += o.branchings;
  refined_bands += o.refined_bands;
  intermediate_contours += o.intermediate_contours;
  composites += o.composites;
  partings += o.partings;
  caps += o.caps;
  dropped_contours += o.dropped_contours;
  hole_contours += o.hole_contours;
  return *this;
}

namespace {

using detail::Level;
using detail::LevelContour;
using detail::SlabMesh;

// Memory per vertex of a tiled mesh while it is built and checked: positions, ids, about two triangles
// and the builders' vectors.
constexpr double kBytesPerTiledVertex = 120.0;

void check_options(const TilingOptions& o) {
  auto fail = [](const std::string& what) { throw InvalidInputError("tiling: " + what); };
  if (!(o.min_overlap_fraction > 0.0 && o.min_overlap_fraction <= 1.0)) fail("min_overlap_fraction must be in (0, 1]");
  if (!(o.min_overlap_of_larger >= 0.0 && o.min_overlap_of_larger < 1.0))
    fail("min_overlap_of_larger must be in [0, 1)");
  if (o.max_branching_depth < 0) fail("max_branching_depth must be >= 0");
  if (!(o.max_band_sliver_share >= 0.0 && o.max_band_sliver_share <= 1.0))
    fail("max_band_sliver_share must be in [0, 1]");
  if (!(o.max_band_aspect > 0.0) || !std::isfinite(o.max_band_aspect)) fail("max_band_aspect must be > 0");
  if (o.max_intermediate_contours < 1) fail("max_intermediate_contours must be >= 1");
  if (!(o.interpolation_grid > 0.0 && o.interpolation_grid <= 1.0)) fail("interpolation_grid must be in (0, 1]");
  if (o.threads < 0) fail("threads must be >= 0");
}

// Runs task(k) for k = 0 .. count - 1 on `threads` threads (the caller's among them), taking tasks in
// order. The caller's thread reports progress before the first task and after each task it finishes; when that returns
// false, no new task starts and CancelledError is thrown. When tasks throw, the exception of the first such task is
// rethrown (every task before it has run), so the outcome does not depend on the thread count.
template <typename Task>
void run_in_order(std::size_t count, unsigned threads, const Task& task, const ProgressCallback& progress) {
  if (count == 0) return;
  // Asked once before any work: with few tasks the other threads may take them all, and the caller's
  // thread would never report.
  if (progress && !progress("tile", 0.0)) throw CancelledError("tiling");
  std::atomic<std::size_t> next{0}, done{0};
  std::atomic<std::size_t> first_failure{std::numeric_limits<std::size_t>::max()};
  std::atomic<bool> cancelled{false};
  std::vector<std::exception_ptr> errors(count);
  auto work = [&](bool reporting) {
    for (;;) {
      if (cancelled.load()) return;
      const std::size_t k = next.fetch_add(1);
      if (k >= count || k > first_failure.load()) return;
      try {
        task(k);
      } catch (...) {
        errors[k] = std::current_exception();
        std::size_t seen = first_failure.load();
        while (k < seen && !first_failure.compare_exchange_weak(seen, k)) {
        }
      }
      const std::size_t finished = done.fetch_add(1) + 1;
      if (reporting && progress && !progress("tile", static_cast<double>(finished) / static_cast<double>(count))) {
        cancelled = true;
      }
    }
  };
  std::vector<std::thread> pool;
  const unsigned extra = static_cast<unsigned>(std::min<std::size_t>(threads, count)) - 1U;
  for (unsigned t = 0; t < extra; ++t) pool.emplace_back(work, false);
  work(true);
  for (std::thread& t : pool) t.join();
  if (first_failure.load() < count) std::rethrow_exception(errors[first_failure.load()]);
  if (cancelled.load()) throw CancelledError("tiling");
}

}  // namespace

TilingResult tile_contours(const ContourStack& stack, const TilingOptions& options, const ProgressCallback& progress) {
  return detail::tile_contours_judged(stack, options, progress, {});
}

TilingResult detail::tile_contours_judged(const ContourStack& stack, const TilingOptions& options,
                                          const ProgressCallback& progress,
                                          const std::vector<Eigen::Vector2d>& judged_offsets) {
  check_options(options);
  if (!judged_offsets.empty() && judged_offsets.size() != stack.slices.size()) {
    throw InvalidInputError("tiling: one judged offset per slice expected");
  }
  const std::vector<std::vector<Contour>> slices = detail::prepare_stack(stack);
  const std::size_t S = slices.size();
  TilingResult result;
  // threads = 0: as many as the process allows (a ThreadLimit, such as the command line's --threads, caps it).
  const unsigned threads = static_cast<unsigned>(options.threads > 0 ? options.threads : available_threads());

  // Every contour as a level contour (ids later), and the correspondence of each pair of adjacent
  // slices, to find the contours that continue nowhere.
  std::vector<Level> levels(S);
  for (std::size_t s = 0; s < S; ++s) {
    levels[s].w = stack.slices[s].w;
    for (const Contour& c : slices[s]) {
      LevelContour k;
      k.points = c.points;
      k.is_hole = c.is_hole;
      k.parent = c.parent;
      detail::finish_contour(k);
      levels[s].contours.push_back(std::move(k));
    }
  }
  std::vector<detail::Correspondence> links(S > 0 ? S - 1 : 0);
  run_in_order(links.size(), threads,
               [&](std::size_t s) { links[s] = detail::correspond(levels[s], levels[s + 1], options); },
               {});
  // Contours with no partner on either side would be zero-thickness sheets: drop them (their holes too).
  std::vector<std::vector<int>> kept(S);
  double points = 0.0;
  for (std::size_t s = 0; s < S; ++s) {
    for (std::size_t c = 0; c < slices[s].size(); ++c) {
      const bool below = s > 0 && (!links[s - 1].down[c].empty() || links[s - 1].opens_down[c]);
      const bool above = s + 1 < S && (!links[s].up[c].empty() || links[s].opens_up[c]);
      if (!below && !above) {
        ++result.stats.dropped_contours;
        continue;
      }
      kept[s].push_back(static_cast<int>(c));
      points += static_cast<double>(slices[s][c].points.size());
      if (slices[s][c].is_hole) ++result.stats.hole_contours;
    }
  }
  // With the intermediate contours, copies and cap interiors, the mesh has about twice as many vertices
  // as the contours.
  check_allocation("tiling", points, 2.0 * points * kBytesPerTiledVertex, options.limits);

  // The contours' own vertices come first, slice by slice, with their slice and contour ids.
  std::vector<Level> tiled(S);
  std::vector<std::pair<std::int32_t, std::int32_t>> contour_vertex_ids;
  Index next_id = 0;
  for (std::size_t s = 0; s < S; ++s) {
    tiled[s] = detail::restrict_level(levels[s], kept[s]);
    for (std::size_t k = 0; k < kept[s].size(); ++k) {
      LevelContour& c = tiled[s].contours[k];
      c.ids.resize(c.points.size());
      for (auto& id : c.ids) {
        id = next_id++;
        contour_vertex_ids.emplace_back(static_cast<std::int32_t>(s), kept[s][k]);
      }
    }
  }

  std::vector<Eigen::Vector3d> contour_vertices(static_cast<std::size_t>(next_id));
  for (std::size_t s = 0; s < S; ++s) {
    for (const LevelContour& c : tiled[s].contours) {
      for (std::size_t p = 0; p < c.points.size(); ++p) {
        contour_vertices[static_cast<std::size_t>(c.ids[p])] =
            Eigen::Vector3d(c.points[p].x(), c.points[p].y(), tiled[s].w);
      }
    }
  }

  // Slab k lies between slice k - 1 and slice k; slabs 0 and S close the ends of the stack against an
  // empty level one spacing beyond.
  const std::size_t slabs = S + 1;
  std::vector<SlabMesh> meshes(slabs);
  auto gap = [&](std::size_t s) { return S > 1 ? stack.slices[s + 1].w - stack.slices[s].w : 1.0; };
  const Index budget = options.limits.max_vertices > next_id ? options.limits.max_vertices - next_id : 0;
  run_in_order(
      slabs, threads,
      [&](std::size_t k) {
        SlabMesh& out = meshes[k];
        out.stack_vertices = &contour_vertices;
        out.vertex_budget = budget;
        out.vertex_limit = options.limits.max_vertices;
        if (S == 0) return;
        Level empty;
        const Level* lower = &empty;
        const Level* upper = &empty;
        if (k == 0) {
          empty.w = stack.slices[0].w - gap(0);
          upper = &tiled[0];
        } else if (k == S) {
          empty.w = stack.slices[S - 1].w + gap(S > 1 ? S - 2 : 0);
          lower = &tiled[S - 1];
        } else {
          lower = &tiled[k - 1];
          upper = &tiled[k];
          if (!judged_offsets.empty()) out.shear = (judged_offsets[k] - judged_offsets[k - 1]) / (upper->w - lower->w);
        }
        detail::tile_slab(*lower, *upper, options, out);
      },
      progress);

  // Assembly in slab order: the mesh does not depend on the thread count.
  std::vector<Index> offset(slabs, next_id);
  double total = static_cast<double>(next_id);
  for (std::size_t k = 0; k < slabs; ++k) {
    offset[k] = static_cast<Index>(std::min(total, static_cast<double>(std::numeric_limits<Index>::max())));
    total += static_cast<double>(meshes[k].vertices.size());
  }
  if (total > static_cast<double>(options.limits.max_vertices)) {
    throw LimitError("tiling: the mesh would have more than " + std::to_string(options.limits.max_vertices) +
                     " vertices");
  }
  Mesh& mesh = result.mesh;
  const auto n = static_cast<Index>(total);
  mesh.positions.resize(3, n);
  mesh.slice_ids.assign(static_cast<std::size_t>(n), kNoId);
  mesh.contour_ids.assign(static_cast<std::size_t>(n), kNoId);
  for (std::size_t s = 0; s < S; ++s) {
    for (const LevelContour& c : tiled[s].contours) {
      for (std::size_t p = 0; p < c.points.size(); ++p) {
        const Index v = c.ids[p];
        mesh.positions.col(v) = stack.to_physical(c.points[p], tiled[s].w);
        mesh.slice_ids[static_cast<std::size_t>(v)] = contour_vertex_ids[static_cast<std::size_t>(v)].first;
        mesh.contour_ids[static_cast<std::size_t>(v)] = contour_vertex_ids[static_cast<std::size_t>(v)].second;
      }
    }
  }
  // Each slab's vertices and faces go to their own ranges (offsets in slab order), so the slabs are
  // copied on every core; the mesh is the same as copied one after the other.
  std::vector<std::size_t> face_offset(slabs + 1, 0);
  for (std::size_t k = 0; k < slabs; ++k) face_offset[k + 1] = face_offset[k] + meshes[k].triangles.size();
  mesh.triangles.resize(face_offset[slabs]);
  result.face_roles.resize(face_offset[slabs]);
  const bool left_handed = stack.axis_u.cross(stack.axis_v).dot(stack.axis_w) < 0.0;
  run_in_order(
      slabs, threads,
      [&](std::size_t k) {
        const SlabMesh& m = meshes[k];
        for (std::size_t v = 0; v < m.vertices.size(); ++v) {
          mesh.positions.col(offset[k] + static_cast<Index>(v)) =
              stack.to_physical(m.vertices[v].head<2>(), m.vertices[v].z());
        }
        auto global = [&](detail::VertexRef r) {
          return detail::is_local(r) ? offset[k] + static_cast<Index>(detail::local_index(r)) : r;
        };
        for (std::size_t f = 0; f < m.triangles.size(); ++f) {
          const Triangle& t = m.triangles[f];
          Triangle g{global(t[0]), global(t[1]), global(t[2])};
          if (left_handed) std::swap(g[1], g[2]);
          mesh.triangles[face_offset[k] + f] = g;
        }
        std::copy(m.roles.begin(), m.roles.end(),
                  result.face_roles.begin() + static_cast<std::ptrdiff_t>(face_offset[k]));
      },
      {});
  for (const SlabMesh& m : meshes) result.stats += m.stats;
  return result;
}

}  // namespace contourmesh
