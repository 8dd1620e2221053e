// SPDX-License-Identifier: BSD-3-Clause
// Tiling (docs/reconstruction.md, "Tiling"): stitching the contours of adjacent slices into a closed triangle mesh that
// keeps, for every vertex, the slice and contour it came from.
#pragma once

#include "contourmesh/reconstruct/contours.h"

#include <contourmesh/smooth/end_caps.h>
#include <contourmesh/smooth/limits.h>
#include <contourmesh/smooth/mesh.h>
#include <contourmesh/smooth/progress.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace contourmesh {

/// How caps are triangulated.
enum class CapRefinement {
  /// Ear clipping refined to a constrained Delaunay triangulation with interior vertices about one
  /// contour spacing apart (ids kNoId): well-shaped triangles, so umbrella-based smoothing does not drag
  /// the cap's rim inwards. Default.
  Interior,
  /// Ear clipping only: the fewest triangles, long and thin across the cap.
  EarClipping,
};

/// How the contours of adjacent slices whose topology differs (a contour that splits or merges, a hole
/// that opens to the outside or closes) are joined.
enum class Branching {
  /// Shape-based interpolation (Raya and Udupa 1990; Herman, Zheng and Bucholtz 1992): the regions of
  /// both slices become signed distance fields, the level where their average is zero is an
  /// intermediate set of contours, and each slice is tiled to it; halves that still change topology are
  /// split again, `max_branching_depth` times at most. Only what is left at the finest level is joined
  /// by a mid-plane composite, so its flat bridges are small. Default.
  Interpolated,
  /// Mid-plane composites only (Meyers, Skinner and Sloan 1992): the contours on the side with several
  /// are copied onto the mid-plane and bridged into one. Flat bridges span the gaps between branches.
  MidPlaneComposite,
};

/// Whether bands between very different contours are refined.
enum class BandRefinement {
  /// A band whose faces include slivers (a surface nearly parallel to the slices: the contours are many
  /// spacings apart in the plane) is tiled again through intermediate contours from the same
  /// interpolation, about `max_band_aspect` contour spacings apart, and, where the contours are nested
  /// in the plane, as a lifted triangulation of the region between them; the tiling with less flat and
  /// sliver area is kept. Then, in each slab, the edges around the remaining slivers are flipped (where
  /// the surface is nearly planar) or split at their midpoints (new vertices without ids); contour
  /// vertices, their ids and the slices' contour edges stay (docs/reconstruction.md, "Face quality").
  /// Default.
  Interpolated,
  /// Every one-to-one pair is one band of the minimum-area tiling, however thin its triangles, and no
  /// face is flipped or split afterwards.
  None,
};

struct TilingOptions {
  EndCaps end_caps = EndCaps::HalfSpacing;
  CapRefinement cap_refinement = CapRefinement::Interior;
  Branching branching = Branching::Interpolated;
  /// How many times a slab that changes topology is halved, >= 0 (0: a composite at the mid-plane).
  int max_branching_depth = 3;
  BandRefinement band_refinement = BandRefinement::Interpolated;
  /// A band is refined when faces with a minimum angle under 10 degrees hold more than this share of its
  /// area, in [0, 1].
  double max_band_sliver_share = 0.01;
  /// Intermediate contours are inserted so that the longest edge across each band is at most this many
  /// contour spacings, > 0.
  double max_band_aspect = 3.0;
  /// At most this many intermediate contours per band, >= 1.
  int max_intermediate_contours = 15;
  /// Grid of the signed distance fields, as a fraction of the contour spacing, in (0, 1].
  double interpolation_grid = 0.5;
  /// Threads tiling slabs at once (0: available_threads(), which a ThreadLimit caps). The mesh does not
  /// depend on it.
  int threads = 0;
  /// Two contours of adjacent slices correspond when the area of overlap of their regions exceeds this
  /// fraction of the smaller region (outer contours: the filled outline; holes: the hole). In (0, 1].
  double min_overlap_fraction = 0.05;
  /// ... and this fraction of the larger, in [0, 1): a speck inside a large contour (a pocket in a thin
  /// wall next to a large cavity, what is left of a bone in a slice where thresholding lost it) does not
  /// continue it.
  double min_overlap_of_larger = 0.01;
  /// One-to-one pairs are tiled by the minimum-area dynamic programme of Fuchs, Kedem and Uselton
  /// (1977) over the grid of m x n point pairs. Pairs of over 90 000 point pairs whose contours both have
  /// at least 32 points are solved coarse to fine, whatever their size: first on every k-th point (about
  /// 40 000 pairs), then at full resolution in a corridor of about 2 k points either side of that path
  /// (docs/reconstruction.md, "Tiling"). The other pairs (a contour of under 32 points) use the full grid
  /// while m * n is at most `full_dp_limit`, and above it a band of +/- `band_fraction` of the points
  /// around the arc-length diagonal; the full grid is the last resort when a corridor or band cannot
  /// reach the end.
  std::size_t full_dp_limit = 4'000'000;
  double band_fraction = 0.15;
  /// Vertex cap of the tiled mesh and memory budget of each contour pair's dynamic programme
  /// (LimitError, before allocating, when exceeded).
  ResourceLimits limits;
};

/// What the tiler did, for reports.
struct TilingStats {
  std::size_t one_to_one = 0;        ///< contour pairs of adjacent slices tiled directly by one band
  std::size_t branchings =
      0;  ///< groups of adjacent slices whose topology changes (split, merge, hole opening or closing)
  std::size_t refined_bands = 0;     ///< groups of adjacent slices tiled through intermediate contours for band quality
  std::size_t intermediate_contours = 0;  ///< contours inserted between slices by shape-based interpolation
  std::size_t composites = 0;        ///< mid-plane composite contours (Meyers), each with flat bridges
  std::size_t partings = 0;          ///< pieces capped on both sides of a slab instead of joined (see tile_contours)
  std::size_t caps = 0;              ///< capped contour ends (outer ends and hole ends, at slices or between them)
  std::size_t dropped_contours = 0;  ///< contours with no partner above or below (a single slice): not meshed
  std::size_t hole_contours = 0;     ///< hole contours meshed

  TilingStats& operator+=(const TilingStats& o);
};

/// What happens to a contour with no partner in either adjacent slice, which tile_contours leaves out (it
/// would be a sheet of no thickness): a structure drawn on one slice, or one thinner than the slice
/// spacing that a CT stack catches on one slice only (a small fragment, a cavity between two slices).
/// reconstruct() and reconstruct_from_contours() apply it after tiling (docs/reconstruction.md,
/// "Contours on one slice").
enum class SingleSliceContours {
  /// A slab reaching half-way to the adjacent slice planes (the radiotherapy convention for a structure
  /// drawn on one slice, and the voxel route's one voxel of thickness), closed with the tiler's caps; a
  /// hole inside material that continues becomes a hollow slab, thinner where the full one would meet
  /// the surface around it. With EndCaps::AtEndSlice the slab would have no thickness: dropped. Default.
  Slab,
  /// Dropped.
  Drop,
};

/// What a face of a tiled mesh closes or joins, for quality reports and renders.
enum class FaceRole : std::uint8_t {
  Band,    ///< between two contour levels (slice contours, intermediate contours or end copies)
  Bridge,  ///< flat faces where pieces join or part at a change of topology left unresolved by interpolation:
           ///< the fill under a composite's bridge, a nested fill, the caps of a parting
  Cap,     ///< closes a contour that ends (an object's end, a cavity's roof or floor): flat by construction
};

struct TilingResult {
  Mesh mesh;
  std::vector<FaceRole> face_roles;  ///< one per face of `mesh`
  TilingStats stats;
};

/// Tiles a contour stack into a closed, consistently outward-oriented, edge-manifold mesh per object.
///
/// - Correspondence: by overlap of regions between adjacent slices (outer with outer, hole with hole,
///   a hole only with holes of corresponding outers); the connected groups of this relation are tiled
///   together.
/// - One-to-one groups: Fuchs-Kedem-Uselton minimum total triangle area, by dynamic programming,
///   starting from the pair of nearest points.
/// - Branching groups (one-to-many, many-to-one, many-to-many): after Meyers, Skinner and Sloan
///   (1992), the contours of the side with several are copied onto an intermediate plane (the
///   mid-plane; thirds for many-to-many), joined into one composite contour by bridges between nearest
///   points, tiled one-to-one to the other side, each copy joined to its original by a straight band,
///   and the gap under each bridge closed by two triangles.
/// - Ends: a contour with no partner on one side is capped by ear clipping that respects its holes,
///   half a spacing beyond its slice (default) or in its own slice plane (EndCaps::AtEndSlice); a hole
///   that ends inside a continuing outer is closed the same way by a cap facing into the cavity.
///   Contours present in one slice only (no partner on either side) would make a zero-thickness sheet
///   and are dropped (counted in the stats).
///
/// Vertex ids: a vertex of contour c of slice s has slice id s and contour id c. Vertices of the
/// copies made for branching and for half-spacing end caps lie off the slice planes and have slice id
/// and contour id kNoId. Repeated consecutive points (and a last point equal to the first) are dropped
/// first. Throws InvalidInputError for a stack whose slices are not ordered by increasing w, a contour
/// with fewer than 3 distinct points, a non-finite point, a contour that intersects itself (naming the
/// two edges and where they meet), two contours of a slice that meet (naming both and where), a hole
/// inside another hole, or a hole in no outer contour of its slice (a hole's parent that does not
/// contain it is ignored, like a missing one); LimitError when the mesh
/// would exceed `options.limits.max_vertices` or a contour pair's programme the memory budget.
[[nodiscard]] TilingResult tile_contours(const ContourStack& stack, const TilingOptions& options = {},
                                         const ProgressCallback& progress = {});

}  // namespace contourmesh
