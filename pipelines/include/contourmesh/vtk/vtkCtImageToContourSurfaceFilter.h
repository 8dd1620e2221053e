// SPDX-License-Identifier: BSD-3-Clause
// vtkCtImageToContourSurfaceFilter: libreconstruct's chain (segmentation -> contours -> tiling,
// reconstruct()) as a VTK filter: a CT volume in, a closed tiled surface with contour ids out. Gives
// the same mesh as reconstruct() and as `contourmesh reconstruct` with the same options.
#pragma once

#include "contourmesh/vtk/vtkContourTilingAlgorithm.h"

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
class vtkCtImageToContourSurfaceFilter : public vtkContourTilingAlgorithm {
 public:
  static vtkCtImageToContourSurfaceFilter* New();
  vtkTypeMacro(vtkCtImageToContourSurfaceFilter,
               vtkContourTilingAlgorithm)  // no ";": the macro ends with "public:" (-Wpedantic)
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
  enum FlatCrossingsType {
    FLAT_CROSSINGS_PATCHES = 0,    ///< a flat patch of half-inside pixels (an end face on a slice) decided whole
                                   ///< (default)
    FLAT_CROSSINGS_PER_PIXEL = 1,  ///< each pixel by its own value
  };
  enum SingleSliceContoursType {
    SINGLE_SLICE_SLAB = 0,  ///< a slab half-way to the adjacent slices, hollow for a hole (default)
    SINGLE_SLICE_DROP = 1,
  };
  enum OffSlicePlacementType {
    OFF_SLICE_IMAGE_CROSSING = 0,  ///< vertices between the slices where the image crosses the threshold (default)
    OFF_SLICE_TILED = 1,           ///< where the tiler put them (caps half a spacing beyond the last contour)
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
  /// Pixels whose column the boundary crosses near the slice's centre (a surface lying in a slice, such
  /// as an end face on a slice centre): decided per flat patch (default) or each by its own value
  /// (docs/reconstruction.md, "Surfaces that lie in a slice").
  vtkSetClampMacro(FlatCrossings, int, FLAT_CROSSINGS_PATCHES, FLAT_CROSSINGS_PER_PIXEL);
  vtkGetMacro(FlatCrossings, int);
  void SetFlatCrossingsToPatches() { this->SetFlatCrossings(FLAT_CROSSINGS_PATCHES); }
  void SetFlatCrossingsToPerPixel() { this->SetFlatCrossings(FLAT_CROSSINGS_PER_PIXEL); }
  ///@}

  ///@{
  /// Contours found on one slice only (a fragment or cavity thinner than the slice spacing): slabs reaching
  /// half-way to the adjacent slices, hollow for holes (default), or dropped (docs/reconstruction.md,
  /// "Contours on one slice").
  vtkSetClampMacro(SingleSliceContours, int, SINGLE_SLICE_SLAB, SINGLE_SLICE_DROP);
  vtkGetMacro(SingleSliceContours, int);
  void SetSingleSliceContoursToSlab() { this->SetSingleSliceContours(SINGLE_SLICE_SLAB); }
  void SetSingleSliceContoursToDrop() { this->SetSingleSliceContours(SINGLE_SLICE_DROP); }
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
  /// Mesh components enclosing less than this many voxel volumes are dropped, >= 0 (default 4; 0 keeps
  /// everything).
  vtkSetClampMacro(MinComponentVoxels, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MinComponentVoxels, double);
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
  int FlatCrossings = FLAT_CROSSINGS_PATCHES;
  int SingleSliceContours = SINGLE_SLICE_SLAB;
  int OffSlicePlacement = OFF_SLICE_IMAGE_CROSSING;
  double MinComponentVoxels = 4.0;

 private:
  vtkCtImageToContourSurfaceFilter(const vtkCtImageToContourSurfaceFilter&) = delete;
  void operator=(const vtkCtImageToContourSurfaceFilter&) = delete;
};
