// SPDX-License-Identifier: BSD-3-Clause
// Guidance normals of the off-slice normal filter (docs/smoothing.md, "Terraces between the slices"):
// the patches of faces around each face of the workspace, and the most consistent patch's mean normal per
// filtered face, recomputed where the normals changed. Private to libsmooth.
#pragma once

#include "detail/off_slice_workspace.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace contourmesh::detail {

// Patches for guidance normals (OffSliceRange::PatchGuidance), per local face: the faces sharing a vertex
// with it, weighted as the filter weighs a neighbourhood (area x spatial kernel). A filtered face's patch
// is its neighbourhood; the other local faces' patches reach one ring further, to faces outside the
// workspace ("outer" faces: no moving corner, so their normals are fixed, as the other local faces' are).
struct GuidancePatches {
  std::vector<Index> offsets;           ///< per local face, CSR into entries
  FillVector<Index> entries;            ///< local faces; an entry >= the local faces' count is outer
  FillVector<float> weights;            ///< per entry (single precision, as the filter's own weights)
  Eigen::Matrix3Xd outer_normals;       ///< per outer face
};

// Guidance normals (after Zhang, Deng, Zhang, Bouaziz, Liu, "Guided mesh normal filtering", Pacific
// Graphics 2015): a patch's consistency is the length of its weighted mean normal over its weights (1 when
// its normals agree). Each filtered face takes the mean normal of the most consistent patch that holds it,
// among its own and the patches of the faces sharing a vertex with it whose mean normal lies within
// `min_cos` of its own normal (next to a crease, not a patch of the other side); the other local faces keep
// their own normals (in `guidance` already). `normals` holds the local faces' normals.
struct GuidanceState {
  Eigen::Matrix3Xd mean;                 ///< per local face: its patch's mean normal
  std::vector<double> consistency;       ///< per local face
  std::vector<std::uint8_t> recomputed;  ///< per local face: its patch was recomputed this time
};

/// The patches of every local face of `w`, their weights and the normals of the faces outside the
/// workspace that they reach, from the mesh's `positions` and the local faces' `centroids` and `areas`.
GuidancePatches make_patches(const ContourFrame& frame, const std::vector<Triangle>& triangles,
                             const Eigen::Matrix3Xd& positions, const Workspace& w, const Eigen::Matrix3Xd& centroids,
                             const Eigen::VectorXd& areas);

// Only what changed is recomputed: a patch none of whose normals changed since the last computation
// (`changed`, per local face) keeps its mean and consistency; `first`: every patch and guidance normal is
// computed, and counts as changed. Otherwise a filtered face whose own normal and candidate patches all
// stayed keeps its guidance, copied from `last_guidance` (that of the last computation); `guided_changed`
// gets, per filtered face, whether its guidance differs from the last, bit for bit.
void guidance_normals(const Workspace& w, const GuidancePatches& p, const Eigen::Matrix3Xd& normals,
                      const std::vector<std::uint8_t>& changed, bool first, double min_cos,
                      GuidanceState& state, const Eigen::Matrix3Xd& last_guidance, Eigen::Matrix3Xd& guidance,
                      std::vector<std::uint8_t>& guided_changed);

}  // namespace contourmesh::detail
