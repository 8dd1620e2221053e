// SPDX-License-Identifier: BSD-3-Clause
// Private helper of the two surface filters (CT image, contour polylines): their common base
// vtkContourTilingAlgorithm carries the tiler's properties; this turns them into the library's
// TilingOptions, so that an option added to the tiler reaches both filters through one place.
#pragma once

#include "contourmesh/vtk/vtkContourTilingAlgorithm.h"

#include <contourmesh/reconstruct/tiling.h>

#include <cstddef>

namespace contourmesh::filter_detail {

/// The TilingOptions that `filter`'s tiling properties select (VTK's getters are not const).
[[nodiscard]] inline TilingOptions tiling_options(vtkContourTilingAlgorithm& filter) {
  using Filter = vtkContourTilingAlgorithm;
  TilingOptions t;
  t.end_caps = filter.GetEndCaps() == Filter::END_CAPS_AT_END_SLICE ? EndCaps::AtEndSlice : EndCaps::HalfSpacing;
  t.cap_refinement = filter.GetCapRefinement() == Filter::CAP_REFINEMENT_EAR_CLIPPING ? CapRefinement::EarClipping
                                                                                        : CapRefinement::Interior;
  t.min_overlap_fraction = filter.GetMinOverlapFraction();
  t.full_dp_limit = static_cast<std::size_t>(filter.GetFullDynamicProgrammingLimit());
  t.band_fraction = filter.GetBandFraction();
  t.branching =
      filter.GetBranching() == Filter::BRANCHING_MID_PLANE ? Branching::MidPlaneComposite : Branching::Interpolated;
  t.max_branching_depth = filter.GetMaxBranchingDepth();
  t.band_refinement = filter.GetBandRefinement() == Filter::BAND_REFINEMENT_NONE ? BandRefinement::None
                                                                                  : BandRefinement::Interpolated;
  t.max_band_sliver_share = filter.GetMaxBandSliverShare();
  t.max_band_aspect = filter.GetMaxBandAspect();
  t.max_intermediate_contours = filter.GetMaxIntermediateContours();
  t.interpolation_grid = filter.GetInterpolationGrid();
  t.min_overlap_of_larger = filter.GetMinOverlapOfLarger();
  return t;
}

}  // namespace contourmesh::filter_detail
