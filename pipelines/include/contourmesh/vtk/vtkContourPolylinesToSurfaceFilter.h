// SPDX-License-Identifier: BSD-3-Clause
// vtkContourPolylinesToSurfaceFilter: planar contours held as vtkPolyData polylines (the form in which
// SlicerRT and VTK applications keep radiotherapy structures) in, the closed tiled surface with
// contour ids out. Gives the same mesh as build_contour_stack() + reconstruct_from_contours() and as
// `contourmesh reconstruct CONTOURS -o MESH` with the same options.
#pragma once

#include <vtkPolyDataAlgorithm.h>

/// Tiles planar contours given as polylines into a closed, outward-oriented triangle mesh.
///
/// Input: vtkPolyData whose line cells are the contours, one closed polyline each (either
/// orientation; the closing point may repeat the first). Loose two-point segments are refused: join
/// them with vtkStripper first. Slices come from the integer array SliceIdArrayName (default "SliceId"),
/// looked up in the cell data, then in the point data (every point of a contour must carry the same
/// id); without it, from the contours' positions along the slice axis (their common normal, or
/// SliceAxis), contours closer than SliceTolerance sharing a slice. Holes are the contours inside an
/// odd number of others of their slice; orientation is normalised. Contours are resampled (Sampling,
/// SamplingTolerance), a drifting single contour is tiled in centroid-aligned slices (DriftAlignment),
/// contours with no partner on an adjacent slice become slabs (SingleSliceContours); see
/// docs/contours.md.
///
/// Output: vtkPolyData with double-precision points, triangles and the vtkIntArray point arrays
/// ContourIdArrayName (default "ContourId": the slice index, 0 for the lowest slice along the axis) and
/// ContourIndexArrayName (default "ContourIndex": the contour within its slice, in input order among
/// the slice's contours); -1 off the contours. vtkContourFeatureSmoothingFilter reads these arrays.
///
/// Setters clamp to the valid closed range; PlanarityTolerance and SliceTolerance 0 (their range is
/// (0, inf)) are rejected when the filter runs. Errors (no lines, a contour with fewer than 3 points,
/// non-planar or self-intersecting contours, contours of a slice that meet, contours in one slice with
/// no SlabThickness): vtkErrorMacro naming the contour (by cell id), an empty output, RequestData
/// returns 0. What was repaired or reported (repeated points, gaps between slices, slabs) is one
/// vtkWarningMacro.
///
/// Progress: tiling in [0, 1]. Cancellation through AbortExecute (vtkAlgorithm::CheckAbort on VTK >=
/// 9.3): an aborted run leaves the output empty and returns 1; call Modified() before the next Update().
class vtkContourPolylinesToSurfaceFilter : public vtkPolyDataAlgorithm {
 public:
  static vtkContourPolylinesToSurfaceFilter* New();
  vtkTypeMacro(vtkContourPolylinesToSurfaceFilter,
               vtkPolyDataAlgorithm)  // no ";": the macro ends with "public:" (-Wpedantic)
      void PrintSelf(ostream& os, vtkIndent indent) override;

  enum DriftAlignmentType {
    DRIFT_ALIGNMENT_CENTROIDS = 0,  ///< tile a drifting single contour in centroid-aligned slices (default)
    DRIFT_ALIGNMENT_NONE = 1,
  };
  enum SingleSliceContoursType {
    SINGLE_SLICE_SLAB = 0,  ///< a slab reaching half-way to the adjacent slices (default)
    SINGLE_SLICE_DROP = 1,
  };
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
  /// Name of the integer slice-id array, in the cell or point data (default "SliceId"). When the input
  /// has no array of that name (or the name is empty), slices come from the contours' positions.
  vtkSetStringMacro(SliceIdArrayName);
  vtkGetStringMacro(SliceIdArrayName);
  ///@}

  ///@{
  /// The slice axis (any length); (0, 0, 0), the default, takes the contours' common normal.
  vtkSetVector3Macro(SliceAxis, double);
  vtkGetVector3Macro(SliceAxis, double);
  ///@}

  ///@{
  /// Largest distance of a contour point from its slice plane, mm, > 0 (default 0.05).
  vtkSetClampMacro(PlanarityTolerance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(PlanarityTolerance, double);
  ///@}

  ///@{
  /// Without slice ids: contours closer than this along the axis share a slice, mm, > 0 (default 0.1).
  vtkSetClampMacro(SliceTolerance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SliceTolerance, double);
  ///@}

  ///@{
  /// Largest distance between contour points after resampling, mm, >= 0 (default 1; 0: as drawn).
  vtkSetClampMacro(Sampling, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Sampling, double);
  ///@}

  ///@{
  /// Largest distance a resampled contour departs from the drawn one, mm, >= 0 (default 0.05).
  vtkSetClampMacro(SamplingTolerance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SamplingTolerance, double);
  ///@}

  ///@{
  /// Centroid alignment of drifting single contours while tiling (default Centroids).
  vtkSetClampMacro(DriftAlignment, int, DRIFT_ALIGNMENT_CENTROIDS, DRIFT_ALIGNMENT_NONE);
  vtkGetMacro(DriftAlignment, int);
  void SetDriftAlignmentToCentroids() { this->SetDriftAlignment(DRIFT_ALIGNMENT_CENTROIDS); }
  void SetDriftAlignmentToNone() { this->SetDriftAlignment(DRIFT_ALIGNMENT_NONE); }
  ///@}

  ///@{
  /// Contours with no partner on an adjacent slice: slabs (default) or dropped.
  vtkSetClampMacro(SingleSliceContours, int, SINGLE_SLICE_SLAB, SINGLE_SLICE_DROP);
  vtkGetMacro(SingleSliceContours, int);
  void SetSingleSliceContoursToSlab() { this->SetSingleSliceContours(SINGLE_SLICE_SLAB); }
  void SetSingleSliceContoursToDrop() { this->SetSingleSliceContours(SINGLE_SLICE_DROP); }
  ///@}

  ///@{
  /// Thickness of the slab made when every contour lies in one slice, mm, >= 0 (default 0: refuse).
  vtkSetClampMacro(SlabThickness, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SlabThickness, double);
  ///@}

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

  /// Slice-wise volume of the contours of the last run (the radiotherapy convention: each slice a slab
  /// reaching half-way to its neighbours), mm^3; NaN before a run and after a failed or aborted one.
  vtkGetMacro(SlicewiseVolume, double);

 protected:
  vtkContourPolylinesToSurfaceFilter();
  ~vtkContourPolylinesToSurfaceFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
                  vtkInformationVector* outputVector) override;

  char* SliceIdArrayName = nullptr;
  double SliceAxis[3] = {0.0, 0.0, 0.0};
  double PlanarityTolerance = 0.05;
  double SliceTolerance = 0.1;
  double Sampling = 1.0;
  double SamplingTolerance = 0.05;
  int DriftAlignment = DRIFT_ALIGNMENT_CENTROIDS;
  int SingleSliceContours = SINGLE_SLICE_SLAB;
  double SlabThickness = 0.0;
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
  double SlicewiseVolume;

 private:
  vtkContourPolylinesToSurfaceFilter(const vtkContourPolylinesToSurfaceFilter&) = delete;
  void operator=(const vtkContourPolylinesToSurfaceFilter&) = delete;

  bool AbortRequested();
};
