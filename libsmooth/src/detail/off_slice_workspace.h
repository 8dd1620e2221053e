// SPDX-License-Identifier: BSD-3-Clause
// The off-slice normal filter's workspace (docs/smoothing.md, "Vertices between the slices"): the faces
// and vertices it touches, numbered compactly once, their neighbourhoods and pair slots, the slab bounds
// of the moving vertices and the spatial kernel. Private to libsmooth (detail/off_slice_filter.h is the
// filter).
#pragma once

#include "detail/contour_profiles.h"
#include "detail/parallel.h"
#include "contourmesh/smooth/cross_slice.h"

#include <Eigen/Core>

#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

namespace contourmesh::detail {

// The unit normal of triangle t of the positions x (zero where it is degenerate), its area into *area when
// given.
template <typename Positions>
Eigen::Vector3d face_normal(const Positions& x, const Triangle& t, double* area = nullptr) {
  const Eigen::Vector3d c = (x.col(t[1]) - x.col(t[0])).cross(x.col(t[2]) - x.col(t[0]));
  const double len = c.norm();
  if (area) *area = 0.5 * len;
  return len > 0.0 ? Eigen::Vector3d(c / len) : Eigen::Vector3d::Zero();
}

// Everything the filter touches, numbered compactly and built once: the work is proportional to the
// region around the vertices without ids, not to the mesh (a few per cent of a large bone's vertices).
//
// Faces: the filtered ones (touching a moving vertex), and the faces sharing a vertex with one (their
// neighbourhoods), numbered in ascending mesh order. Vertices: those of the filtered faces, ascending.
struct Workspace {
  // Faces of the neighbourhoods, in mesh order; the filtered ones among them.
  std::vector<Index> faces;     ///< local face -> mesh face
  std::vector<Index> filtered;  ///< filtered face k -> local face (ascending)
  // Per filtered face: the corners (local vertices), and its neighbourhood in CSR (local faces, the face
  // itself included, ascending) with area x spatial kernel per entry, in single precision: the filter's
  // sums run in single precision anyway, and on a real scan these are over ten million entries.
  std::vector<Triangle> corners;
  std::vector<Index> ring_offsets;
  FillVector<Index> ring;
  FillVector<float> ring_weights;
  // The range kernel is symmetric: each pair of faces (a, b) that meet in a neighbourhood has one slot,
  // computed once per iteration however many of the two neighbourhoods it is in.
  FillVector<Index> ring_slot;       ///< per neighbourhood entry
  FillVector<Index> slot_a, slot_b;  ///< per slot: the faces (local), as first met: face a, entry b
  std::vector<Index> filtered_of;     ///< local face -> filtered face, or -1
  std::vector<Index> face_map;        ///< mesh face -> local face, or -1
  double sigma_s = 1.0;               ///< width of the spatial kernel, mm
  // Vertices.
  std::vector<Index> vertices;  ///< local vertex -> mesh vertex
  std::vector<std::uint8_t> moves;  ///< per local vertex
  std::vector<Index> moving;    ///< local ids of the moving vertices, ascending
  // Per moving vertex: its faces (filtered face ids, in the adjacency's order) in CSR, whether it is a
  // contour vertex, and for the others the heights it may take.
  std::vector<Index> incident_offsets, incident;
  std::vector<std::uint8_t> on_contour;
  std::vector<double> low, high;
};

// Two 3-vectors equal bit for bit (-0 and 0 differ): what the filter's iterations test to skip the work
// whose inputs did not change.
template <typename A, typename B>
bool same_bits(const A& a, const B& b) {
  return std::memcmp(a.data(), b.data(), 3 * sizeof(double)) == 0;
}

// The axis coordinates of the slice planes, ascending (one per slice id of a contour vertex: the mean).
std::vector<double> slice_levels(const ContourFrame& frame, const Eigen::Matrix3Xd& positions);

// The heights a vertex starting at height h may take: its slab between two slice planes, a twentieth of
// a spacing inside, and within `reach` of h. Beyond the outer planes (end caps) only the plane bounds.
std::pair<double, double> height_bounds(const std::vector<double>& levels, double h, double spacing, double reach);

// Numbers the faces and vertices (see Workspace) and the neighbourhoods of the filtered faces.
Workspace make_workspace(const ContourFrame& frame, const std::vector<Triangle>& triangles,
                         const OffSliceFilterOptions& options);

// The spatial part of the neighbourhoods' weights: area of the neighbour x a Gaussian of the distance
// between centroids, whose width is the mean such distance (fixed while the normals are filtered: nothing
// moves then).
void spatial_weights(const Eigen::Matrix3Xd& centroids, const Eigen::VectorXd& areas, Workspace& w);

}  // namespace contourmesh::detail
