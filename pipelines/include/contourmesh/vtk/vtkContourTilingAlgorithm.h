// SPDX-License-Identifier: BSD-3-Clause
// vtkContourTilingAlgorithm: the base of the two VTK filters that tile contours into a closed surface
// (vtkCtImageToContourSurfaceFilter, vtkContourPolylinesToSurfaceFilter). It holds what they share:
// the tiler's options (libreconstruct's TilingOptions, docs/reconstruction.md "Tiling") under one set
// of names and enumerators, the names of the output's id arrays, and their printing, so that an
// option of the tiler reaches both filters through one place.
#pragma once

#include <vtkPolyDataAlgorithm.h>

/// Abstract: the tiling options and output array names of the contour-tiling filters. Setters clamp to
/// the valid closed range; MinOverlapFraction 0 (the range is (0, 1]) is rejected when a filter runs.
class vtkContourTilingAlgorithm : public vtkPolyDataAlgorithm {
 public:
  vtkTypeMacro(vtkContourTilingAlgorithm,
               vtkPolyDataAlgorithm)  // no ";": the macro ends with "public:" (-Wpedantic)
      void PrintSelf(ostream& os, vtkIndent indent) override;

  enum EndCapsType {
    END_CAPS_HALF_SPACING = 0,  ///< half a slice spacing beyond the last contour (default)
    END_CAPS_AT_END_SLICE = 1,  ///< in the plane of the last contour
  };
  enum CapRefinementType {
    CAP_REFINEMENT_INTERIOR = 0,      ///< constrained Delaunay with interior vertices (default)
    CAP_REFINEMENT_EAR_CLIPPING = 1,  ///< ear clipping only
  };
  enum BranchingType {
    BRANCHING_INTERPOLATED = 0,  ///< shape-based interpolation, composites only at the finest level (default)
    BRANCHING_MID_PLANE = 1,     ///< mid-plane composites only
  };
  enum BandRefinementType {
    BAND_REFINEMENT_INTERPOLATED = 0,  ///< bands of slivers tiled again through interpolated contours (default)
    BAND_REFINEMENT_NONE = 1,          ///< every one-to-one pair is one minimum-area band
  };

  ///@{
  /// Where objects end (default half a spacing beyond the last contour).
  vtkSetClampMacro(EndCaps, int, END_CAPS_HALF_SPACING, END_CAPS_AT_END_SLICE);
  vtkGetMacro(EndCaps, int);
  void SetEndCapsToHalfSpacing() { this->SetEndCaps(END_CAPS_HALF_SPACING); }
  void SetEndCapsToAtEndSlice() { this->SetEndCaps(END_CAPS_AT_END_SLICE); }
  ///@}

  ///@{
  /// How caps are triangulated (default interior vertices, refined).
  vtkSetClampMacro(CapRefinement, int, CAP_REFINEMENT_INTERIOR, CAP_REFINEMENT_EAR_CLIPPING);
  vtkGetMacro(CapRefinement, int);
  void SetCapRefinementToInterior() { this->SetCapRefinement(CAP_REFINEMENT_INTERIOR); }
  void SetCapRefinementToEarClipping() { this->SetCapRefinement(CAP_REFINEMENT_EAR_CLIPPING); }
  ///@}

  ///@{
  /// Contours of adjacent slices correspond when their regions overlap by more than this fraction of
  /// the smaller one, in (0, 1] (default 0.05).
  vtkSetClampMacro(MinOverlapFraction, double, 0.0, 1.0);
  vtkGetMacro(MinOverlapFraction, double);
  ///@}

  ///@{
  /// ... and by more than this fraction of the larger one, in [0, 1) (default 0.01): a speck inside a
  /// large contour does not continue it.
  vtkSetClampMacro(MinOverlapOfLarger, double, 0.0, 1.0);
  vtkGetMacro(MinOverlapOfLarger, double);
  ///@}

  ///@{
  /// Contour pairs of over 90,000 point pairs, both contours of 32 points or more, are tiled by the
  /// minimum-area dynamic programme coarse to fine, whatever their size. Other pairs with m * n points
  /// up to FullDynamicProgrammingLimit use the full programme, larger ones a band of +/- BandFraction
  /// of the contour length around the diagonal (defaults 4,000,000 and 0.15).
  vtkSetClampMacro(FullDynamicProgrammingLimit, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(FullDynamicProgrammingLimit, vtkIdType);
  vtkSetClampMacro(BandFraction, double, 0.0, 1.0);
  vtkGetMacro(BandFraction, double);
  ///@}

  ///@{
  /// Where contours split, merge or a hole opens or closes between slices: shape-based interpolation
  /// (default) or mid-plane composites only; and how many times such a slab is halved, >= 0 (default 3).
  vtkSetClampMacro(Branching, int, BRANCHING_INTERPOLATED, BRANCHING_MID_PLANE);
  vtkGetMacro(Branching, int);
  void SetBranchingToInterpolated() { this->SetBranching(BRANCHING_INTERPOLATED); }
  void SetBranchingToMidPlane() { this->SetBranching(BRANCHING_MID_PLANE); }
  vtkSetClampMacro(MaxBranchingDepth, int, 0, VTK_INT_MAX);
  vtkGetMacro(MaxBranchingDepth, int);
  ///@}

  ///@{
  /// Whether a band whose faces under 10 degrees hold more than MaxBandSliverShare of its area (in
  /// [0, 1], default 0.01) is tiled again through intermediate contours (default) or kept; the
  /// intermediate contours are at most MaxBandAspect contour spacings apart across the band (> 0,
  /// default 3), MaxIntermediateContours of them at most (>= 1, default 15), interpolated on a grid of
  /// InterpolationGrid contour spacings (in (0, 1], default 0.5).
  vtkSetClampMacro(BandRefinement, int, BAND_REFINEMENT_INTERPOLATED, BAND_REFINEMENT_NONE);
  vtkGetMacro(BandRefinement, int);
  void SetBandRefinementToInterpolated() { this->SetBandRefinement(BAND_REFINEMENT_INTERPOLATED); }
  void SetBandRefinementToNone() { this->SetBandRefinement(BAND_REFINEMENT_NONE); }
  vtkSetClampMacro(MaxBandSliverShare, double, 0.0, 1.0);
  vtkGetMacro(MaxBandSliverShare, double);
  vtkSetClampMacro(MaxBandAspect, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaxBandAspect, double);
  vtkSetClampMacro(MaxIntermediateContours, int, 1, VTK_INT_MAX);
  vtkGetMacro(MaxIntermediateContours, int);
  vtkSetClampMacro(InterpolationGrid, double, 0.0, 1.0);
  vtkGetMacro(InterpolationGrid, double);
  ///@}

  ///@{
  /// Names of the id point arrays of the output.
  vtkSetStringMacro(ContourIdArrayName);
  vtkGetStringMacro(ContourIdArrayName);
  vtkSetStringMacro(ContourIndexArrayName);
  vtkGetStringMacro(ContourIndexArrayName);
  ///@}

 protected:
  vtkContourTilingAlgorithm();
  ~vtkContourTilingAlgorithm() override;

  /// Whether the pipeline asked this run to stop (CheckAbort on VTK >= 9.3, AbortExecute before).
  bool AbortRequested();

  int EndCaps = END_CAPS_HALF_SPACING;
  int CapRefinement = CAP_REFINEMENT_INTERIOR;
  double MinOverlapFraction = 0.05;
  vtkIdType FullDynamicProgrammingLimit = 4'000'000;
  double BandFraction = 0.15;
  int Branching = BRANCHING_INTERPOLATED;
  int MaxBranchingDepth = 3;
  int BandRefinement = BAND_REFINEMENT_INTERPOLATED;
  double MaxBandSliverShare = 0.01;
  double MaxBandAspect = 3.0;
  int MaxIntermediateContours = 15;
  double InterpolationGrid = 0.5;
  double MinOverlapOfLarger = 0.01;
  char* ContourIdArrayName = nullptr;
  char* ContourIndexArrayName = nullptr;

 private:
  vtkContourTilingAlgorithm(const vtkContourTilingAlgorithm&) = delete;
  void operator=(const vtkContourTilingAlgorithm&) = delete;
};
