// SPDX-License-Identifier: BSD-3-Clause
// Contours drawn elsewhere (radiotherapy structure sets, contour files, VTK polylines) turned into the
// ordered, oriented contour stack the tiler takes: slice axis, slice grouping, nesting, orientation,
// checks with messages that name the contour. See docs/contours.md.
#pragma once

#include "contourmesh/reconstruct/contours.h"

#include <Eigen/Core>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace contourmesh {

/// One closed planar contour in physical space (mm), as drawn: either orientation, the closing point
/// may repeat the first. `name` says where it came from in messages ("contour 12"); `slice_id`, when
/// given for every contour, groups the contours into slices instead of their positions along the axis.
struct PlanarContour {
  std::vector<Eigen::Vector3d> points;
  std::string name;
  std::optional<long long> slice_id;
};

struct PlanarStackOptions {
  /// The slice axis (any length > 0). Default: the common normal of the contours, from their area
  /// vectors (a normal within 1e-6 rad of a coordinate axis is snapped to it).
  std::optional<Eigen::Vector3d> slice_axis;
  /// Largest distance (mm) of a contour's points from its slice plane, > 0. Larger: the contour is
  /// refused as non-planar (or tilted). DICOM stores coordinates as decimal strings of at most 16
  /// characters, so exact planarity cannot be expected.
  double planarity_tolerance = 0.05;
  /// Contours whose mean positions along the axis differ by less than this (mm) share a slice, > 0.
  /// Ignored when every contour has a slice id.
  double slice_tolerance = 0.1;
  /// A gap between consecutive slices larger than this times the typical spacing (the lower median of
  /// the gaps) is reported as a warning (the slices are tiled across it anyway); > 1.
  double gap_factor = 1.5;
  /// Contours enclosing less than this area (mm^2) are dropped with a warning (points or lines drawn
  /// by accident), >= 0.
  double min_area = 1e-6;
};

/// What building the stack found and did.
struct PlanarStackReport {
  std::size_t input_contours = 0;
  std::size_t contours = 0;        ///< contours in the stack
  std::size_t hole_contours = 0;   ///< of which holes (contours inside an odd number of others)
  std::size_t slices = 0;
  std::size_t reversed = 0;        ///< contours whose orientation was reversed
  std::size_t repeated_points = 0; ///< consecutive repeated points dropped (and closing points)
  std::size_t dropped_contours = 0;///< degenerate contours dropped (fewer than 3 distinct points, no area)
  double typical_spacing = 0.0;    ///< lower median distance between consecutive slices, mm (0 with one slice)
  double largest_gap = 0.0;        ///< largest distance between consecutive slices, mm
  std::vector<std::string> warnings;  ///< one line each, naming the contours or slices
  /// source[s][c]: index in the input of contour c of slice s of the stack.
  std::vector<std::vector<std::size_t>> source;
};

struct PlanarStack {
  ContourStack stack;
  PlanarStackReport report;
};

/// Builds an ordered contour stack from planar contours in physical space.
///
/// - Slice axis w: `options.slice_axis` or the contours' common normal, pointing so that its largest
///   component is positive (+z for axial contours). The in-plane axes are the next two coordinate axes
///   when w is one (x, y for z), else any right-handed orthonormal pair; the frame's origin is 0, so
///   stack coordinates are the physical ones (for axial contours u = x, v = y, w = z).
/// - Slices: contours grouped by slice id, or by position along w (`slice_tolerance`), ordered by w.
///   Every point must lie within `planarity_tolerance` of its slice plane.
/// - Each contour: consecutive repeated points and a closing point equal to the first are dropped
///   (counted, one warning); fewer than 3 distinct points or less than `min_area`: dropped with a
///   warning. A contour that intersects itself, or two contours of a slice that meet, are errors.
/// - Nesting: a contour inside an odd number of others of its slice is a hole of the smallest one that
///   contains it (`parent`), otherwise an outer contour (islands inside holes included). Outer contours
///   are made counter-clockwise and holes clockwise seen from +w.
/// - Slice spacing: a gap above `gap_factor` times the typical spacing is a warning.
///
/// `what` prefixes every message (for example "ROI 5 'Heart'"). Throws InvalidInputError, naming
/// `what` and the contour, for: no contour, a non-finite point, a non-planar or tilted contour, a
/// self-intersection, contours of one slice that meet, two slice ids in one plane, options out of range.
[[nodiscard]] PlanarStack build_contour_stack(const std::vector<PlanarContour>& contours, const std::string& what,
                                              const PlanarStackOptions& options = {});

/// Normalises a stack whose contours are already in slice coordinates: the per-contour cleaning,
/// nesting and orientation of build_contour_stack, slices kept as they are (they must be ordered by
/// increasing w). `is_hole` and `parent` are recomputed from the nesting. Returns the report (its
/// `source` maps to the input positions within each slice).
PlanarStackReport normalize_contour_stack(ContourStack& stack, const std::string& what,
                                          const PlanarStackOptions& options = {});

/// The volume the radiotherapy convention gives a contour stack, mm^3: each slice is a slab reaching
/// half-way to its neighbours, the end slices half a spacing beyond themselves (the spacing to their
/// one neighbour), its area the outer contours' minus the holes'. A one-slice stack has volume 0.
[[nodiscard]] double slicewise_volume(const ContourStack& stack);

/// The slab thickness slicewise_volume gives each slice of `stack`, mm.
[[nodiscard]] std::vector<double> slice_thicknesses(const ContourStack& stack);

}  // namespace contourmesh
