// SPDX-License-Identifier: BSD-3-Clause
// Private: the builders of the phantoms' analytic truth, one per PhantomShape.
#pragma once

#include "detail/phantom_geometry.h"

#include <optional>
#include <vector>

namespace contourmesh::detail {

/// What a builder produces: the sdf, bounds, topology, features and (when known) the analytic volume.
struct ShapeBuild {
  ScalarField sdf;
  Box3 bounds;
  std::optional<double> volume;
  int surface_components = 1;
  int euler_characteristic = 2;
  std::vector<Vec3> features;
};

/// The skull phantom's shell and orbits (build_skull), shared with the skull with a diploe, whose cavities
/// must keep clear of the same surfaces.
struct SkullGeometry {
  static constexpr double kCut = -35.0;  ///< the shell is cut open below the plane z = kCut
  /// The orbits: cylinders of radius kOrbitRadius along y about (+-kOrbitX, kOrbitZ), y in kOrbitYMid
  /// +- kOrbitHalf ([-75, -20]: through the front, ending inside the cranial cavity).
  static constexpr double kOrbitRadius = 9.0, kOrbitZ = -5.0, kOrbitX = 22.0;
  static constexpr double kOrbitYMid = -47.5, kOrbitHalf = 27.5;
  /// The outer and inner surfaces: a 6 mm ellipsoidal shell.
  [[nodiscard]] static Ellipsoid outer() { return {Vec3(0.0, 0.0, -15.0), Vec3(54.0, 60.0, 56.0)}; }
  [[nodiscard]] static Ellipsoid inner() { return {Vec3(0.0, 0.0, -15.0), Vec3(48.0, 54.0, 50.0)}; }
};

// The original seven (phantom_shapes.cpp).
ShapeBuild build_ridge_box();
ShapeBuild build_femur();
ShapeBuild build_pelvis();
ShapeBuild build_skull();
ShapeBuild build_branch();
ShapeBuild build_two_objects();
ShapeBuild build_cavity();

// The failure classes of contour stacks (phantom_slice_shapes.cpp).
ShapeBuild build_tilted_box();
ShapeBuild build_in_slice_ridge();
ShapeBuild build_end_face_on_slice();

// The skull with a diploe (phantom_diploe.cpp).
ShapeBuild build_skull_diploe();

}  // namespace contourmesh::detail
