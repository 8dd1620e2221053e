// SPDX-License-Identifier: BSD-3-Clause
// Private: checking a contour stack and normalising it for tiling.
#pragma once

#include "contourmesh/reconstruct/contours.h"

#include <vector>

namespace contourmesh::detail {

/// The contours of each slice, checked and normalised: repeated consecutive points (and a last point
/// equal to the first) dropped, outer contours counter-clockwise and holes clockwise, each hole's
/// parent the smallest outer contour that contains it (a given parent is kept when it contains the
/// hole). Throws InvalidInputError, naming the slice and contour, for slices not ordered by increasing
/// w, a contour with fewer than 3 distinct points or a non-finite point, a contour that intersects
/// itself, two contours of a slice that meet, a hole inside another hole, or a hole in no outer contour.
[[nodiscard]] std::vector<std::vector<Contour>> prepare_stack(const ContourStack& stack);

}  // namespace contourmesh::detail
