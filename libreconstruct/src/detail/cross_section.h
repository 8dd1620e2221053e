// SPDX-License-Identifier: BSD-3-Clause
// Private: the cross-section of some of a mesh's faces (contour_deviation.h's cross_section over a subset).
#pragma once

#include "contourmesh/reconstruct/contour_deviation.h"

#include <vector>

namespace contourmesh::detail {

/// cross_section(mesh, frame, w, just_above) restricted to the listed faces (all of them when `faces` is
/// null): the same segments, in the order of the list.
[[nodiscard]] std::vector<SectionSegment> cross_section_of(const Mesh& mesh, const std::vector<Index>* faces,
                                                           const ContourStack& frame, double w, bool just_above);

}  // namespace contourmesh::detail
