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
