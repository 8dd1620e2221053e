// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target: the contour tiler (contourmesh/reconstruct/tiling.h). The bytes decode to a small contour stack,
// mostly valid (star-shaped outer contours clear of each other, one hole inside each at most, in slices
// of increasing w) or, with a flag, with invalid pieces (arbitrary polygons that may cross themselves or
// their neighbours, overlapping contours and holes, repeated points, non-finite or huge coordinates,
// slices out of order), and random tiling options. tile_contours must
// either throw an InvalidInputError (LimitError included) with a one-line message or return a closed,
// consistently oriented, edge-manifold mesh with finite coordinates and ids in range.
#include "fuzz_support.h"

#include <contourmesh/reconstruct/tiling.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/metrics.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <limits>
#include <map>
#include <new>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace contourmesh::fuzz {
namespace {

// Distance from point p to segment ab.
double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

// A star-shaped polygon around `centre`: n points at increasing angles (each within a quarter step of
// uniform), radii in [0.2, 1] x radius. Simple by construction. Counter-clockwise.
std::vector<Eigen::Vector2d> star(ByteReader& in, const Eigen::Vector2d& centre, double radius, int n) {
  std::vector<Eigen::Vector2d> pts;
  const double step = 2.0 * std::numbers::pi / n;
  const double phase = in.real(0.0, step);
  for (int k = 0; k < n; ++k) {
    const double angle = phase + step * (k + 0.25 * in.symmetric());
    const double r = radius * (1.0 - 0.8 * in.unit());
    pts.emplace_back(centre.x() + r * std::cos(angle), centre.y() + r * std::sin(angle));
  }
  return pts;
}

struct Outer {
  int index;             // in its slice
  Eigen::Vector2d centre;
  double inner_radius;   // a disc of this radius around the centre lies inside the contour
  double outer_radius;   // and the contour inside a disc of this radius
  bool has_hole = false;
};

ContourStack decode_stack(ByteReader& in, TilingOptions& options) {
  const std::uint8_t modes = in.byte();
  options.end_caps = (modes & 1) ? EndCaps::AtEndSlice : EndCaps::HalfSpacing;
  options.cap_refinement = (modes & 2) ? CapRefinement::EarClipping : CapRefinement::Interior;
  if (modes & 4) options.min_overlap_fraction = in.real(0.001, 1.0);
  if (modes & 8) options.full_dp_limit = static_cast<std::size_t>(in.integer(1, 4000));  // banded programme
  if (modes & 16) options.band_fraction = in.real(0.01, 1.0);
  const bool allow_invalid = (modes & 32) != 0;
  options.limits.max_vertices = 50'000;
  options.limits.max_memory_bytes = std::size_t{256} << 20;

  ContourStack stack;
  if (modes & 64) {  // a rotated, shifted frame (still orthonormal and right-handed)
    const Eigen::Vector3d xyz = in.symmetric3();
    const Eigen::Quaterniond q(1.0, xyz.x(), xyz.y(), xyz.z());
    const Eigen::Matrix3d r = q.normalized().toRotationMatrix();
    stack.axis_u = r.col(0);
    stack.axis_v = r.col(1);
    stack.axis_w = r.col(2);
    stack.origin = in.vec3(-100, 100);
  }
  const int slices = in.integer(1, 8);
  const double spacing = in.real(0.05, 8.0);
  const double scale = std::pow(10.0, in.integer(-3, 3));  // the stack's size, mm
  double w = in.real(-50.0, 50.0);
  for (int s = 0; s < slices; ++s) {
    SliceContours slice;
    if (s > 0) {
      w += spacing * in.real(0.5, 1.5);
      if (allow_invalid && in.byte() == 255) w -= 2.0 * spacing;  // out of order
    }
    slice.w = w;
    std::vector<Outer> outers;
    const int contours = in.integer(0, 3);
    for (int c = 0; c < contours; ++c) {
      const int kind = in.integer(0, 7);
      Contour contour;
      if (kind == 7 && allow_invalid) {
        // An arbitrary polygon: may cross itself, another contour, repeat points, or be degenerate.
        const int n = in.integer(0, 12);
        for (int k = 0; k < n; ++k) {
          const std::uint8_t how = in.byte();
          if (how == 255) {
            const double x = in.raw_double();
            contour.points.emplace_back(x, in.raw_double());
          }
          else if (how == 254 && !contour.points.empty()) contour.points.push_back(contour.points.back());
          else contour.points.push_back(scale * in.vec2(-30, 30));
        }
        contour.is_hole = in.flag();
        contour.parent = in.integer(-1, 3);
      } else if (kind == 6 && !outers.empty()) {
        // A hole inside one of this slice's outer contours, clockwise. A second one in the same outer
        // would overlap the first: only with invalid pieces allowed.
        Outer& o = outers[static_cast<std::size_t>(in.integer(0, static_cast<int>(outers.size()) - 1))];
        const double radius = o.inner_radius * in.real(0.2, 0.9);
        if (radius <= 0.0 || (o.has_hole && !allow_invalid)) continue;
        o.has_hole = true;
        const Eigen::Vector2d offset = in.symmetric3().head<2>();
        const Eigen::Vector2d centre = o.centre + 0.05 * o.inner_radius * offset;
        contour.points = star(in, centre, radius, in.integer(3, 32));
        std::reverse(contour.points.begin(), contour.points.end());
        contour.is_hole = true;
        contour.parent = in.flag() ? o.index : -1;  // -1: the tiler finds the parent
      } else {
        // A star-shaped outer contour, kept clear of the slice's other outers unless invalid pieces are
        // allowed (contours of a slice must not meet).
        const Eigen::Vector2d centre = scale * in.vec2(-30, 30);
        double radius = scale * in.real(0.5, 20.0);
        if (!allow_invalid) {
          for (const Outer& o : outers) radius = std::min(radius, 0.98 * ((centre - o.centre).norm() - o.outer_radius));
          if (radius < 0.1 * scale) continue;
        }
        contour.points = star(in, centre, radius, in.integer(3, 48));
        double inner = std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k < contour.points.size(); ++k) {
          inner = std::min(inner, segment_distance(centre, contour.points[k],
                                                   contour.points[(k + 1) % contour.points.size()]));
        }
        outers.push_back({static_cast<int>(slice.contours.size()), centre, inner, radius});
        if (allow_invalid && in.byte() == 255) contour.points.push_back(contour.points.front());  // closed explicitly
      }
      slice.contours.push_back(std::move(contour));
    }
    stack.slices.push_back(std::move(slice));
  }
  return stack;
}

void check_tiling(const ContourStack& stack, const TilingResult& result) {
  const Mesh& mesh = result.mesh;
  check_mesh_is_sane(mesh, "tile_contours");
  if (!mesh.has_contour_ids() && mesh.num_vertices() > 0) fail("tile_contours: a mesh without contour ids");
  std::size_t max_contours = 0;
  for (const SliceContours& s : stack.slices) max_contours = std::max(max_contours, s.contours.size());
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    const std::int32_t s = mesh.slice_ids[i], c = mesh.contour_ids[i];
    const bool off = s == kNoId && c == kNoId;
    const bool on = s >= 0 && static_cast<std::size_t>(s) < stack.slices.size() && c >= 0 &&
                    static_cast<std::size_t>(c) < stack.slices[s].contours.size();
    if (!off && !on) fail("tile_contours: vertex " + std::to_string(i) + " has ids (" + std::to_string(s) + ", " +
                          std::to_string(c) + ") outside the stack");
  }
  // Closed, edge-manifold and consistently oriented: every directed edge once, and its reverse once.
  std::map<std::pair<Index, Index>, int> directed;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      fail("tile_contours: triangle " + std::to_string(f) + " repeats a vertex");
    for (int k = 0; k < 3; ++k) {
      if (++directed[{t[k], t[(k + 1) % 3]}] > 1) {
        fail("tile_contours: edge (" + std::to_string(t[k]) + ", " + std::to_string(t[(k + 1) % 3]) +
             ") is used twice in the same direction (non-manifold or inconsistent orientation)");
      }
    }
  }
  for (const auto& [edge, count] : directed) {
    if (directed.find({edge.second, edge.first}) == directed.end()) {
      fail("tile_contours: boundary edge (" + std::to_string(edge.first) + ", " + std::to_string(edge.second) +
           "): the mesh is not closed");
    }
  }
  const double volume = enclosed_volume(mesh);
  if (!std::isfinite(volume)) fail("tile_contours: the enclosed volume is not finite");
}

}  // namespace
}  // namespace contourmesh::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace contourmesh;
  fuzz::ByteReader in(data, size);
  TilingOptions options;
  const ContourStack stack = fuzz::decode_stack(in, options);
  if (fuzz::verbose()) {
    std::fprintf(stderr, "stack: %zu slices, contours per slice:", stack.slices.size());
    for (const SliceContours& s : stack.slices) std::fprintf(stderr, " %zu", s.contours.size());
    std::fprintf(stderr, "\n");
    for (std::size_t s = 0; s < stack.slices.size(); ++s) {
      for (std::size_t c = 0; c < stack.slices[s].contours.size(); ++c) {
        const Contour& k = stack.slices[s].contours[c];
        Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
        for (const Eigen::Vector2d& p : k.points) {
          lo = lo.cwiseMin(p);
          hi = hi.cwiseMax(p);
        }
        std::fprintf(stderr,
                     "  slice %zu (w %g) contour %zu: %s, parent %d, %zu points, area %g, box (%g, %g)-(%g, %g)\n", s,
                     stack.slices[s].w, c, k.is_hole ? "hole" : "outer", k.parent, k.points.size(),
                     k.points.size() >= 3 ? signed_area(k.points) : 0.0, lo.x(), lo.y(), hi.x(), hi.y());
      }
    }
  }
  TilingResult result;
  try {
    result = tile_contours(stack, options);
  } catch (const InvalidInputError& e) {
    fuzz::check_message_is_one_line(e.what(), "tile_contours");
    if (fuzz::verbose()) std::fprintf(stderr, "rejected: %s\n", e.what());
    return 0;
  } catch (const std::bad_alloc&) {
    fuzz::fail("tile_contours ran out of memory (a limit check is missing)");
  } catch (const std::exception& e) {
    fuzz::fail(std::string("tile_contours threw an untyped exception: ") + e.what());
  }
  fuzz::check_tiling(stack, result);
  if (fuzz::verbose()) {
    std::fprintf(stderr, "tiled: %d vertices, %d triangles, %zu one-to-one, %zu branchings, %zu caps, %zu holes\n",
                 result.mesh.num_vertices(), result.mesh.num_faces(), result.stats.one_to_one, result.stats.branchings,
                 result.stats.caps, result.stats.hole_contours);
  }
  return 0;
}
