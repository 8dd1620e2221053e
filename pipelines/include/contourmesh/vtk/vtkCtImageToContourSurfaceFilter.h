// SPDX-License-Identifier: BSD-3-Clause
// vtkCtImageToContourSurfaceFilter: libreconstruct's chain (segmentation -> contours -> tiling,
// reconstruct()) as a VTK filter: a CT volume in, a closed tiled surface with contour ids out. Gives
// the same mesh as reconstruct() and as `contourmesh reconstruct` with the same options.
#pragma once

#include <vtkPolyDataAlgorithm.h>

/// Segments a CT volume slice by slice (index axis k is the slice axis) and tiles the contours of
/// adjacent slices into a closed, outward-oriented triangle mesh.
///
/// Input: vtkImageData with one-component point scalars in HU (any numeric type; the array is chosen
/// with SetInputArrayToProcess, default the active scalars), its spacing, origin and direction matrix
/// (VTK >= 9). The whole extent is requested. Output: vtkPolyData with double-precision points,
/// triangles and the vtkIntArray point arrays ContourIdArrayName (default "ContourId", the slice index)
/// and ContourIndexArrayName (default "ContourIndex", the contour within the slice); vertices off the
/// slice planes (end caps, branching copies) have -1 in both. vtkContourFeatureSmoothingFilter reads
/// these arrays, so image -> surface -> smoothing is a plain VTK chain.
///
/// Setters clamp to the valid closed range; MinOverlapFraction 0 (the range is (0, 1]) is rejected
/// when the filter runs. Errors (no scalars, NaN or infinite scalars, a spacing that is not finite and
/// > 0, a direction matrix that is singular or not orthonormal, no bone above the threshold, contours in
/// fewer than two slices, options out of range): vtkErrorMacro naming the problem, an empty output,
/// RequestData returns 0.
///
/// Progress: segmentation in [0, 0.7], tiling in [0.7, 1], once per slice. Cancellation through
/// AbortExecute (vtkAlgorithm::CheckAbort on VTK >= 9.3), checked once per slice: an aborted run
/// leaves the output empty and returns 1 (not an error); call Modified() before the next Update() to
/// run again.
class vtkCtImageToContourSurfaceFilter : public vtkPolyDataAlgorithm {
 public:
  static vtkCtImageToContourSurfaceFilter* New();
  vtkTypeMacro(vtkCtImageToContourSurfaceFilter,
               vtkPolyDataAlgorithm)  // no ";": the macro ends with "public:" (-Wpedantic)
      void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ThresholdMethodType {
    THRESHOLD_FIXED = 0,  ///< voxels >= Threshold are foreground (default)
    THRESHOLD_OTSU = 1,   ///< Otsu's threshold of the (denoised) volume's histogram
  };
  enum DenoisingType {
    DENOISING_NONE = 0,                   ///< default
    DENOISING_MEDIAN = 1,                 ///< 3 x 3 median in each slice plane
    DENOISING_CURVATURE_ANISOTROPIC = 2,  ///< 5 steps of curvature anisotropic diffusion, 3-D
  };
  enum EndCapsType {
    END_CAPS_HALF_SPACING = 0,  ///< half a slice spacing beyond the last contour (default)
    END_CAPS_AT_END_SLICE = 1,  ///< in the plane of the last contour
  };
  enum OffSlicePlacementType {
    OFF_SLICE_IMAGE_CROSSING = 0,  ///< vertices between the slices where the image crosses the threshold (default)
    OFF_SLICE_TILED = 1,           ///< where the tiler put them (caps half a spacing beyond the last contour)
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
  /// Fixed threshold (default) or Otsu's.
  vtkSetClampMacro(ThresholdMethod, int, THRESHOLD_FIXED, THRESHOLD_OTSU);
  vtkGetMacro(ThresholdMethod, int);
  void SetThresholdMethodToFixed() { this->SetThresholdMethod(THRESHOLD_FIXED); }
  void SetThresholdMethodToOtsu() { this->SetThresholdMethod(THRESHOLD_OTSU); }
  ///@}

  ///@{
  /// Foreground threshold in the image's units, HU for CT (default 300: cortical and most trabecular
  /// bone). Finite (infinities clamp to the largest double).
  vtkSetClampMacro(Threshold, double, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX);
  vtkGetMacro(Threshold, double);
  ///@}

  /// The threshold used by the last run (the Otsu value when chosen); NaN before a run and after a failed
  /// or aborted one.
  vtkGetMacro(ThresholdUsed, double);

  ///@{
  /// Image denoising before thresholding (default none).
  vtkSetClampMacro(Denoising, int, DENOISING_NONE, DENOISING_CURVATURE_ANISOTROPIC);
  vtkGetMacro(Denoising, int);
  void SetDenoisingToNone() { this->SetDenoising(DENOISING_NONE); }
  void SetDenoisingToMedian() { this->SetDenoising(DENOISING_MEDIAN); }
  void SetDenoisingToCurvatureAnisotropic() { this->SetDenoising(DENOISING_CURVATURE_ANISOTROPIC); }
  ///@}

  ///@{
  /// Keep only the largest 6-connected 3-D component (default Off: every region).
  vtkSetMacro(KeepLargestComponent, vtkTypeBool);
  vtkGetMacro(KeepLargestComponent, vtkTypeBool);
  vtkBooleanMacro(KeepLargestComponent, vtkTypeBool);
  ///@}

  ///@{
  /// Per slice, regions smaller than this (mm^2) are dropped and holes smaller than this filled, >= 0
  /// (default 2).
  vtkSetClampMacro(MinRegionArea, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MinRegionArea, double);
  ///@}

  ///@{
  /// Fill every hole of every region, per slice (default Off).
  vtkSetMacro(FillHoles, vtkTypeBool);
  vtkGetMacro(FillHoles, vtkTypeBool);
  vtkBooleanMacro(FillHoles, vtkTypeBool);
  ///@}

  ///@{
  /// Distance between contour points, mm, >= 0; 0 (default) = the smaller in-plane pixel spacing.
  vtkSetClampMacro(Sampling, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Sampling, double);
  ///@}

  ///@{
  /// Contours shorter than this (mm) are dropped with their holes, >= 0 (default 3).
  vtkSetClampMacro(MinContourLength, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MinContourLength, double);
  ///@}

  ///@{
  /// Where objects end (default half a spacing beyond the last contour).
  vtkSetClampMacro(EndCaps, int, END_CAPS_HALF_SPACING, END_CAPS_AT_END_SLICE);
  vtkGetMacro(EndCaps, int);
  void SetEndCapsToHalfSpacing() { this->SetEndCaps(END_CAPS_HALF_SPACING); }
  void SetEndCapsToAtEndSlice() { this->SetEndCaps(END_CAPS_AT_END_SLICE); }
  ///@}

  ///@{
  /// Heights of the vertices between the slices (end caps, intermediate contours): from the image
  /// (default) or as tiled.
  vtkSetClampMacro(OffSlicePlacement, int, OFF_SLICE_IMAGE_CROSSING, OFF_SLICE_TILED);
  vtkGetMacro(OffSlicePlacement, int);
  void SetOffSlicePlacementToImageCrossing() { this->SetOffSlicePlacement(OFF_SLICE_IMAGE_CROSSING); }
  void SetOffSlicePlacementToTiled() { this->SetOffSlicePlacement(OFF_SLICE_TILED); }
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
  /// Mesh components enclosing less than this many voxel volumes are dropped, >= 0 (default 4; 0 keeps
  /// everything).
  vtkSetClampMacro(MinComponentVoxels, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MinComponentVoxels, double);
  ///@}

  ///@{
  /// Names of the id point arrays of the output.
  vtkSetStringMacro(ContourIdArrayName);
  vtkGetStringMacro(ContourIdArrayName);
  vtkSetStringMacro(ContourIndexArrayName);
  vtkGetStringMacro(ContourIndexArrayName);
  ///@}

 protected:
  vtkCtImageToContourSurfaceFilter();
  ~vtkCtImageToContourSurfaceFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation* request, vtkInformationVector** inputVector,
                          vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
                  vtkInformationVector* outputVector) override;

  int ThresholdMethod = THRESHOLD_FIXED;
  double Threshold = 300.0;
  double ThresholdUsed;
  int Denoising = DENOISING_NONE;
  vtkTypeBool KeepLargestComponent = 0;
  double MinRegionArea = 2.0;
  vtkTypeBool FillHoles = 0;
  double Sampling = 0.0;
  double MinContourLength = 3.0;
  int EndCaps = END_CAPS_HALF_SPACING;
  int CapRefinement = CAP_REFINEMENT_INTERIOR;
  int OffSlicePlacement = OFF_SLICE_IMAGE_CROSSING;
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
  double MinComponentVoxels = 4.0;
  char* ContourIdArrayName = nullptr;
  char* ContourIndexArrayName = nullptr;

 private:
  vtkCtImageToContourSurfaceFilter(const vtkCtImageToContourSurfaceFilter&) = delete;
  void operator=(const vtkCtImageToContourSurfaceFilter&) = delete;

  bool AbortRequested();
};
