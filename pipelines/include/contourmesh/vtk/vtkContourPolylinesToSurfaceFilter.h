// SPDX-License-Identifier: BSD-3-Clause
// vtkContourPolylinesToSurfaceFilter: planar contours held as vtkPolyData polylines (the form in which
// SlicerRT and VTK applications keep radiotherapy structures) in, the closed tiled surface with
// contour ids out. Gives the same mesh as build_contour_stack() + reconstruct_from_contours() and as
// `contourmesh reconstruct CONTOURS -o MESH` with the same options.
#pragma once

#include "contourmesh/vtk/vtkContourTilingAlgorithm.h"

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
class vtkContourPolylinesToSurfaceFilter : public vtkContourTilingAlgorithm {
 public:
  static vtkContourPolylinesToSurfaceFilter* New();
  vtkTypeMacro(vtkContourPolylinesToSurfaceFilter,
               vtkContourTilingAlgorithm)  // no ";": the macro ends with "public:" (-Wpedantic)
      void PrintSelf(ostream& os, vtkIndent indent) override;

  enum DriftAlignmentType {
    DRIFT_ALIGNMENT_CENTROIDS = 0,  ///< tile a drifting single contour in centroid-aligned slices (default)
    DRIFT_ALIGNMENT_NONE = 1,
  };
  enum SingleSliceContoursType {
    SINGLE_SLICE_SLAB = 0,  ///< a slab reaching half-way to the adjacent slices (default)
    SINGLE_SLICE_DROP = 1,
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
  double SlicewiseVolume;

 private:
  vtkContourPolylinesToSurfaceFilter(const vtkContourPolylinesToSurfaceFilter&) = delete;
  void operator=(const vtkContourPolylinesToSurfaceFilter&) = delete;
};
