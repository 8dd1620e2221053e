// SPDX-License-Identifier: BSD-3-Clause
// Sharp features of a (smoothed) mesh: creases found from the spread of face normals around each vertex,
// kept when they extend along a line, and widened to a band. The cross-slice smoother labels its
// result with it (docs/smoothing.md, "Feature labels (crease detection)").
//
// 1. Candidates: the normal tensor T = sum_f A_f n_f n_f^T / 3 over the faces of the vertex and of
//    its ring neighbours within `radius` (faces counted once per such vertex they touch) has eigenvalues
//    l1 >= l2 >= l3. Its normals spread in two directions
//    (a crease) when l2 / trace >= `edge_threshold`: two planes meeting at a dihedral angle theta give
//    l2 / trace = sin^2(theta / 2) / ... up to the split of areas, about 0.07 at 30 degrees and 0.25 at
//    60; a smooth patch of curvature kappa gives about (radius kappa)^2 / 4. In three directions (a
//    corner) when l3 / trace >= `corner_threshold`.
// 2. Non-maximum suppression, then confirmation at the feature's scale (CreaseConfirmation::Ball). A
//    candidate crease is a ridge maximum when no ring neighbour lying across its crease direction (the
//    eigenvector of l3, along which the normals vary least), rather than along it, has a larger
//    l2 / trace. Ridge maxima and the ring's corners are examined with the same tensor over every vertex
//    within `confirm_radius` connected to them through such vertices; the other candidates cannot become
//    core vertices, and are not examined (on a real scan, half of the candidates). A crease keeps
//    l2 / trace >= `confirm_threshold` there; a step or fold of a few tenths of a millimetre (a cap's
//    rim on a contour stack, a jagged end face), whose faces fill little of the ball, does not. A
//    corner keeps l3 / trace >= `confirm_corner_threshold` (three faces meeting: up to 1/3); otherwise
//    it is examined as an edge. With CreaseSampling::SliceAware the crease threshold is
//    `steep_confirm_threshold` / sin^2(psi), at most `confirm_threshold`, psi the angle between the
//    ball's mean normal and the slice planes: a contour stack samples a surface nearly parallel to its
//    slices coarsely, and a smooth surface folds there between two contours. Examined vertices not
//    confirmed are labelled noise. docs/smoothing.md, "Feature labels (crease detection)".
// 3. Core vertices: the confirmed corners and ridge maxima. Lines, not specks: groups of core vertices
//    spanning less than `min_extent` are noise. A group is connected through shared edges and, between
//    adjacent slices, through links of up to `link_radius` along the crease direction of both ends (a
//    crease oblique to the slices meets adjacent contours at vertices that share no edge).
// 4. Band: every vertex within `band` of a kept core vertex (along the mesh's edges) takes its label,
//    edge or corner (corner wins), as the evaluation's feature region counts vertices near a feature.
#pragma once

#include "contourmesh/smooth/adjacency.h"
#include "contourmesh/smooth/feature_detection.h"
#include "contourmesh/smooth/mesh.h"

#include <Eigen/Core>

#include <optional>
#include <vector>

namespace contourmesh {

/// Whether a crease found on the ring must persist at a larger scale.
enum class CreaseConfirmation {
  None,  ///< the ring's tensor alone
  Ball,  ///< also the tensor over every vertex within `confirm_radius` connected to it (default)
};

/// How the confirming threshold depends on the slices.
enum class CreaseSampling {
  Isotropic,   ///< `confirm_threshold` everywhere
  /// `steep_confirm_threshold` / sin^2 of the angle between the ball's mean normal and the slice axis,
  /// at most `confirm_threshold` (default); meshes without contour ids, or whose slices do not span
  /// planes, are examined isotropically
  SliceAware,
};

struct CreaseOptions {
  double radius = 1.0;            ///< mm (input units) around each vertex for its normal tensor, > 0
  double edge_threshold = 0.05;   ///< l2 / trace of a crease, in (0, 0.5]
  double corner_threshold = 0.08; ///< l3 / trace of a corner, in (0, 1/3]
  CreaseConfirmation confirm = CreaseConfirmation::Ball;
  /// mm: the ball of the confirming tensor, > 0; more than a slice spacing, so that it holds faces
  /// on both sides of a crease that runs between two contours (2.5 suits 2 mm slices).
  double confirm_radius = 2.5;
  /// l2 / trace of a crease over the ball, in (0, 0.5]: the threshold where the surface lies in the
  /// slice planes, and everywhere with CreaseSampling::Isotropic. 0.25 is two planes 60 degrees apart
  /// with the ball centred on their line.
  double confirm_threshold = 0.25;
  /// l3 / trace of a corner over the ball, in (0, 1/3]: three planes meeting at right angles give
  /// 1/3 with the ball centred on the corner.
  double confirm_corner_threshold = 0.3;
  CreaseSampling sampling = CreaseSampling::SliceAware;
  /// l2 / trace of a crease over the ball where the surface crosses the slices at right angles, in
  /// (0, confirm_threshold] (CreaseSampling::SliceAware): 0.1 is two planes about 37 degrees apart.
  double steep_confirm_threshold = 0.1;
  double min_extent = 3.0;        ///< mm: groups of core vertices shorter than this are noise, >= 0
  /// mm, >= 0: core vertices on adjacent slices this close (through vertices as close) are one group
  /// when the segment joining them runs along the crease at both ends, within `link_angle_degrees`;
  /// 0, or a mesh without contour ids, groups core vertices that share an edge only. A crease oblique
  /// to the slices meets adjacent contours at vertices a slice spacing / sin(angle to the slices) apart,
  /// which share no edge: 4 (two 2 mm slice spacings) links creases down to 30 degrees to such slices.
  double link_radius = 4.0;
  double link_angle_degrees = 30.0;  ///< in [0, 90]
  double band = 1.5;              ///< mm: labels reach vertices this far from a core vertex, >= 0
  /// Standard deviation of the noise of the positions, mm, >= 0; unset is 0 (cross_slice_smooth sets
  /// its estimate across the slices). The confirming crease threshold rises by
  /// noise_factor (noise / confirm_radius)^2, the spread of the normals over the ball that noise of
  /// that size leaves.
  std::optional<double> noise;
  double noise_factor = 2.0;      ///< >= 0
};

struct CreaseDetection {
  /// Smooth, Edge, Corner, or Noise (a vertex examined over the ball and not confirmed, or a core vertex
  /// of a group shorter than `min_extent`)
  std::vector<VertexLabel> labels;
  Eigen::VectorXd edge_strength;    ///< l2 / trace per vertex
  Eigen::VectorXd corner_strength;  ///< l3 / trace per vertex
  /// l2 / trace and l3 / trace over the ball, per vertex examined over it (the ring's corners and the
  /// ridge maxima; 0 elsewhere and without confirmation)
  Eigen::VectorXd confirm_strength, confirm_corner_strength;
  std::size_t core_vertices = 0;    ///< core vertices kept
  std::size_t edges = 0, corners = 0, noise = 0;
};

/// Runs on every core. Throws InvalidInputError for options out of range or an adjacency of another
/// mesh.
[[nodiscard]] CreaseDetection detect_creases(const Mesh& mesh, const MeshAdjacency& adjacency,
                                             const CreaseOptions& options = {});

}  // namespace contourmesh
