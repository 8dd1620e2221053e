// SPDX-License-Identifier: BSD-3-Clause
// vtkContourFeatureSmoothingFilter: every smoothing method of libsmooth as a VTK filter (cross-slice
// smoothing, the paper's feature-preserving smoothing of Xu et al. 2006, the baselines), through the
// library's one entry point smooth(mesh, method, options), for use inside larger VTK applications. Gives
// the same result as the library call and as `contourmesh smooth` with the same method and options.
#pragma once

#include <vtkPolyDataAlgorithm.h>

/// Smooths a triangle mesh whose points carry contour ids: the slice index c(i) in the point
/// array ContourIdArrayName (default "ContourId") and the contour within that slice in
/// ContourIndexArrayName (default "ContourIndex"; absent means one contour per slice), the arrays
/// vtkCtImageToContourSurfaceFilter and the contourmesh CLI write.
///
/// Input: vtkPolyData; polygons are triangulated, strips converted, vertices and lines dropped.
/// Output: the smoothed triangles, with double-precision points, the id arrays (as vtkIntArray, kNoId =
/// -1 off the slices), and with GenerateLabels the per-vertex vtkIntArray "FeatureLabel" (0 smooth,
/// 1 edge, 2 corner, 3 noise; -1 for vertices that the adaptive mesh adds, see KeepAdaptiveMesh). At the
/// original resolution the other point arrays of the input are passed through, except the normals
/// attribute (stale after smoothing); cell data is not passed (triangulation may renumber cells).
///
/// Presets: SetPreset (SetPresetToDefault, SetPresetToXu2006) sets Method and every option the preset
/// fixes, as `contourmesh smooth --preset` does; options set afterwards override it. A new filter holds
/// the default preset: cross-slice smoothing with its defaults.
///
/// Option values that "mean automatic" (NumberOfIterations -1, Lambda 0, Gamma and Delta < 0) take the
/// method's default, as the library's unset std::optional does. Setters clamp to the valid closed range;
/// values at an open end of a range (Mu 0, GammaFactor 0, DeltaFactor 0, Anisotropy 1, Delta 0, an even
/// Window) are rejected when the filter runs, like every other error: vtkErrorMacro naming the problem,
/// an empty output, RequestData returns 0.
///
/// Contour ids are needed by cross-slice smoothing (always) and by the paper's detection (Method Paper,
/// or GenerateLabels with a baseline). The detection options (Gamma, Window, ...) are the paper's;
/// cross-slice smoothing labels the creases of its result with its own defaults.
/// The input goes through libsmooth's prepare_input_mesh, the CLI's input policy (refusals, repairs
/// with one vtkWarningMacro each, orientation, ids made usable), so that the filter and `contourmesh
/// smooth` give the same result on the same dirty mesh. When the ids are missing or unusable: with
/// SliceAxis set they are recovered by binning the vertices along that axis (an error when they do not
/// lie on planes); otherwise cross-slice smoothing is an error, and for the paper's detection
/// DetectionMode decides: ContourContinuity (default) is an error, Automatic falls back to the
/// curvature-only detection with a warning (what the CLI does), CurvatureOnly never needs ids. A run
/// that diverges (coordinates that turn non-finite or run away) is an error, as in the library.
///
/// Progress: UpdateProgress with detection in [0, 0.3], subdivision in [0.3, 0.4] and smoothing in
/// [0.4, 1] for the paper's method, smoothing in [0, 0.8] and its crease labels in [0.8, 1] for
/// cross-slice smoothing (smoothing alone spans [0, 1] for a baseline), at most once per iteration. Cancellation:
/// setting AbortExecute (for example from a vtkCommand::ProgressEvent observer) makes the library stop at its next
/// progress report (vtkAlgorithm::CheckAbort on VTK >= 9.3). An aborted run is not an error: the output is left empty
/// and RequestData returns 1, as VTK filters do when they abort. The pipeline then considers the (empty) output up to
/// date: call Modified() before the next Update() to run again.
class vtkContourFeatureSmoothingFilter : public vtkPolyDataAlgorithm {
 public:
  static vtkContourFeatureSmoothingFilter* New();
  vtkTypeMacro(vtkContourFeatureSmoothingFilter,
               vtkPolyDataAlgorithm)  // no ";": the macro ends with "public:" (-Wpedantic)
      void PrintSelf(ostream& os, vtkIndent indent) override;

  enum MethodType {
    METHOD_NONE = 0,                 ///< positions unchanged (with GenerateLabels: detection only)
    METHOD_LAPLACIAN = 1,            ///< paper eq. 5
    METHOD_TAUBIN = 2,               ///< Taubin lambda|mu, paper eq. 6
    METHOD_MEAN_CURVATURE_FLOW = 3,  ///< explicit cotangent flow (Desbrun et al. 1999)
    METHOD_MIN_DIST_FLOW = 4,        ///< Zhang & Fiume 2002
    METHOD_PAPER = 5,                ///< Xu et al. 2006, Algorithm 1
    METHOD_CROSS_SLICE = 6,          ///< cross-slice smoothing, the project's default (the default preset)
  };
  enum PresetType {
    PRESET_DEFAULT = 0,  ///< cross-slice smoothing with its defaults
    PRESET_XU2006 = 1,   ///< the paper's literal configuration (libsmooth's Preset::Xu2006)
  };
  enum DetectionModeType {
    DETECTION_CONTOUR_CONTINUITY = 0,  ///< the paper's Algorithm 2; needs contour ids (default)
    DETECTION_CURVATURE_ONLY = 1,      ///< anisotropy of the principal curvatures; needs no ids
    DETECTION_AUTOMATIC = 2,           ///< contour continuity when ids are available, else curvature-only
  };
  enum UmbrellaMeasureType {
    UMBRELLA_LENGTH = 0,            ///< |U|, the paper's choice (default)
    UMBRELLA_NORMAL_COMPONENT = 1,  ///< |U . n|
  };
  enum InSliceFeaturesType {
    IN_SLICE_NOISE = 0,         ///< the paper's rule: no continuity across contours, noise (default)
    IN_SLICE_ALONG_LINE = 1,    ///< extension: continuity along the feature line itself
  };
  enum TimeStepType {
    TIME_STEP_RELATIVE_TO_MEAN_EDGE = 0,  ///< mean curvature flow: dt = lambda h^2 / 4 (default)
    TIME_STEP_ABSOLUTE = 1,               ///< dt = lambda in squared length units
  };
  enum CreaseRestorationType {
    CREASE_RESTORATION_NONE = 0,       ///< the input's connectivity (default)
    CREASE_RESTORATION_SUBDIVIDE = 1,  ///< cross-slice: creases restored on a refined mesh
  };
  enum OffSliceVolumeType {
    OFF_SLICE_VOLUME_FREE = 0,      ///< cross-slice: the off-slice filter's fit stands (default)
    OFF_SLICE_VOLUME_PRESERVE = 1,  ///< cross-slice: the volume the off-slice filter takes is given back
  };
  enum SliceAxisType {
    SLICE_AXIS_NONE = -1,  ///< never recover missing ids (default)
    SLICE_AXIS_X = 0,
    SLICE_AXIS_Y = 1,
    SLICE_AXIS_Z = 2,
  };

  ///@{
  /// Applies a preset: Method and the options the preset fixes (the paper's method, its iterations,
  /// steps and detection rules for PRESET_XU2006); the other options return to their defaults. Values
  /// outside the enum are clamped. GetPreset gives the preset last applied (PRESET_DEFAULT for a new
  /// filter), whatever was set afterwards.
  void SetPreset(int preset);
  vtkGetMacro(Preset, int);
  void SetPresetToDefault() { this->SetPreset(PRESET_DEFAULT); }
  void SetPresetToXu2006() { this->SetPreset(PRESET_XU2006); }
  const char* GetPresetAsString();
  ///@}

  ///@{
  /// The smoother. Default METHOD_CROSS_SLICE (the default preset).
  vtkSetClampMacro(Method, int, METHOD_NONE, METHOD_CROSS_SLICE);
  vtkGetMacro(Method, int);
  void SetMethodToNone() { this->SetMethod(METHOD_NONE); }
  void SetMethodToLaplacian() { this->SetMethod(METHOD_LAPLACIAN); }
  void SetMethodToTaubin() { this->SetMethod(METHOD_TAUBIN); }
  void SetMethodToMeanCurvatureFlow() { this->SetMethod(METHOD_MEAN_CURVATURE_FLOW); }
  void SetMethodToMinDistFlow() { this->SetMethod(METHOD_MIN_DIST_FLOW); }
  void SetMethodToPaper() { this->SetMethod(METHOD_PAPER); }
  void SetMethodToCrossSlice() { this->SetMethod(METHOD_CROSS_SLICE); }
  const char* GetMethodAsString();
  ///@}

  ///@{
  /// Iterations, >= 0; -1 (default) = automatic: the method's own count (libsmooth's default_iterations:
  /// 40 for the paper's method, 20 for a baseline). Cross-slice smoothing has no iteration count.
  vtkSetClampMacro(NumberOfIterations, int, -1, VTK_INT_MAX);
  vtkGetMacro(NumberOfIterations, int);
  ///@}

  ///@{
  /// Step factor in (0, 1]; 0 (default) = the paper's value for the method (paper and Taubin 0.6307,
  /// Laplacian 0.3, mean curvature flow 0.3, MIN-DIST 0.5; the paper's method with Laplacian diffusion
  /// 0.3).
  vtkSetClampMacro(Lambda, double, 0.0, 1.0);
  vtkGetMacro(Lambda, double);
  ///@}

  ///@{
  /// Taubin's shrink-compensating factor in [-1, 0) (default -0.6732; 0 is rejected when run). Used by
  /// METHOD_TAUBIN and by the paper's method with Taubin diffusion.
  vtkSetClampMacro(Mu, double, -1.0, 0.0);
  vtkGetMacro(Mu, double);
  ///@}

  ///@{
  /// MIN-DIST flow crease threshold on 1 - cos(dihedral angle), in [0, 2] (default 0.03).
  vtkSetClampMacro(Beta, double, 0.0, 2.0);
  vtkGetMacro(Beta, double);
  ///@}

  ///@{
  /// Whether boundary vertices of an open mesh move (default Off: they stay fixed).
  vtkSetMacro(BoundarySmoothing, vtkTypeBool);
  vtkGetMacro(BoundarySmoothing, vtkTypeBool);
  vtkBooleanMacro(BoundarySmoothing, vtkTypeBool);
  ///@}

  ///@{
  /// How mean curvature flow turns Lambda into a time step (default relative to the mean edge).
  vtkSetClampMacro(TimeStepMode, int, TIME_STEP_RELATIVE_TO_MEAN_EDGE, TIME_STEP_ABSOLUTE);
  vtkGetMacro(TimeStepMode, int);
  void SetTimeStepModeToRelativeToMeanEdge() { this->SetTimeStepMode(TIME_STEP_RELATIVE_TO_MEAN_EDGE); }
  void SetTimeStepModeToAbsolute() { this->SetTimeStepMode(TIME_STEP_ABSOLUTE); }
  ///@}

  ///@{
  /// Feature detection mode (see the class comment). Default DETECTION_CONTOUR_CONTINUITY.
  vtkSetClampMacro(DetectionMode, int, DETECTION_CONTOUR_CONTINUITY, DETECTION_AUTOMATIC);
  vtkGetMacro(DetectionMode, int);
  void SetDetectionModeToContourContinuity() { this->SetDetectionMode(DETECTION_CONTOUR_CONTINUITY); }
  void SetDetectionModeToCurvatureOnly() { this->SetDetectionMode(DETECTION_CURVATURE_ONLY); }
  void SetDetectionModeToAutomatic() { this->SetDetectionMode(DETECTION_AUTOMATIC); }
  const char* GetDetectionModeAsString();
  ///@}

  ///@{
  /// Curvature-only detection: minimum ratio |kappa_large| / |kappa_small| of an edge, > 1 (default 3).
  vtkSetClampMacro(Anisotropy, double, 1.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Anisotropy, double);
  ///@}

  ///@{
  /// Threshold on the umbrella measure, length units, >= 0. Negative (default -1) = automatic:
  /// GammaFactor times its mean over the contour vertices.
  vtkSetClampMacro(Gamma, double, -1.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Gamma, double);
  void SetGammaToAutomatic() { this->SetGamma(-1.0); }
  vtkSetClampMacro(GammaFactor, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(GammaFactor, double);
  ///@}

  ///@{
  /// Which size of the umbrella U(v) is compared with Gamma (default UMBRELLA_LENGTH).
  vtkSetClampMacro(UmbrellaMeasure, int, UMBRELLA_LENGTH, UMBRELLA_NORMAL_COMPONENT);
  vtkGetMacro(UmbrellaMeasure, int);
  void SetUmbrellaMeasureToLength() { this->SetUmbrellaMeasure(UMBRELLA_LENGTH); }
  void SetUmbrellaMeasureToNormalComponent() { this->SetUmbrellaMeasure(UMBRELLA_NORMAL_COMPONENT); }
  ///@}

  ///@{
  /// Feature lines within a slice plane (cap rims, ridges parallel to the slices): the paper's blind
  /// spot. IN_SLICE_NOISE keeps the paper's rule (default); IN_SLICE_ALONG_LINE follows the line itself
  /// (libsmooth's InSliceFeatures::AlongFeatureLine, docs/smoothing.md).
  vtkSetClampMacro(InSliceFeatures, int, IN_SLICE_NOISE, IN_SLICE_ALONG_LINE);
  vtkGetMacro(InSliceFeatures, int);
  void SetInSliceFeaturesToNoise() { this->SetInSliceFeatures(IN_SLICE_NOISE); }
  void SetInSliceFeaturesToAlongLine() { this->SetInSliceFeatures(IN_SLICE_ALONG_LINE); }
  ///@}

  ///@{
  /// Contour curvatures agree when |k0 - k| < Delta (1 / length, > 0). Negative (default -1) =
  /// automatic: DeltaFactor times |k0|.
  vtkSetClampMacro(Delta, double, -1.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Delta, double);
  void SetDeltaToAutomatic() { this->SetDelta(-1.0); }
  vtkSetClampMacro(DeltaFactor, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(DeltaFactor, double);
  ///@}

  ///@{
  /// A candidate whose face normals spread in three directions (the smallest eigenvalue of the
  /// angle-weighted normal tensor over its trace: 1/3 at a box corner, 0 on an edge) above this value
  /// goes to the corner vote like an umbilic one. In [0, 1] (default 0.1); above 1/3 turns it off.
  vtkSetClampMacro(CornerSpread, double, 0.0, 1.0);
  vtkGetMacro(CornerSpread, double);
  ///@}

  ///@{
  /// Consecutive contour vertices per curve fit: odd, >= 5 (default 7).
  vtkSetClampMacro(Window, int, 5, VTK_INT_MAX);
  vtkGetMacro(Window, int);
  ///@}

  ///@{
  /// Taubin iterations on a copy used for detection only, >= 0 (default 0).
  vtkSetClampMacro(PrefilterIterations, int, 0, VTK_INT_MAX);
  vtkGetMacro(PrefilterIterations, int);
  ///@}

  ///@{
  /// Principal curvature fit: umbilic tolerance (>= 0, default 0.05) and the reciprocal condition
  /// number below which a fit widens to the 2-ring (in [0, 1), default 1e-6).
  vtkSetClampMacro(UmbilicTolerance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(UmbilicTolerance, double);
  vtkSetClampMacro(MinReciprocalCondition, double, 0.0, 1.0);
  vtkGetMacro(MinReciprocalCondition, double);
  ///@}

  ///@{
  /// Paper: at most this many subdivision levels around a feature vertex, >= 0 (default 3).
  vtkSetClampMacro(MaxLevels, int, 0, VTK_INT_MAX);
  vtkGetMacro(MaxLevels, int);
  ///@}

  ///@{
  /// Paper: the isotropic scheme on the adaptive mesh, METHOD_TAUBIN (default) or METHOD_LAPLACIAN.
  vtkSetClampMacro(DiffusionMethod, int, METHOD_LAPLACIAN, METHOD_TAUBIN);
  vtkGetMacro(DiffusionMethod, int);
  void SetDiffusionMethodToTaubin() { this->SetDiffusionMethod(METHOD_TAUBIN); }
  void SetDiffusionMethodToLaplacian() { this->SetDiffusionMethod(METHOD_LAPLACIAN); }
  ///@}

  ///@{
  /// Paper: output the smoothed adaptive mesh (denser around features) instead of the input's
  /// connectivity (default Off).
  vtkSetMacro(KeepAdaptiveMesh, vtkTypeBool);
  vtkGetMacro(KeepAdaptiveMesh, vtkTypeBool);
  vtkBooleanMacro(KeepAdaptiveMesh, vtkTypeBool);
  ///@}

  ///@{
  /// Cross-slice smoothing: CREASE_RESTORATION_NONE (default) keeps the input's connectivity;
  /// CREASE_RESTORATION_SUBDIVIDE restores the creases the image's blur rounded: the mesh is refined
  /// around the edge vertices whose neighbourhood fits two planes, and the vertices near each crease move
  /// onto its planes (contourmesh/smooth/crease_restoration.h). The output may then have more points, the
  /// input's first; FeatureLabel is -1 on the new ones, and the input's other point arrays are passed
  /// only when no point was added.
  vtkSetClampMacro(CreaseRestoration, int, CREASE_RESTORATION_NONE, CREASE_RESTORATION_SUBDIVIDE);
  vtkGetMacro(CreaseRestoration, int);
  void SetCreaseRestorationToNone() { this->SetCreaseRestoration(CREASE_RESTORATION_NONE); }
  void SetCreaseRestorationToSubdivide() { this->SetCreaseRestoration(CREASE_RESTORATION_SUBDIVIDE); }
  ///@}

  ///@{
  /// Cross-slice smoothing: OFF_SLICE_VOLUME_FREE (default) or OFF_SLICE_VOLUME_PRESERVE, which gives back
  /// the volume the normal filter of the vertices between the slices takes (contourmesh::OffSliceVolume).
  /// Use Preserve on meshes tiled from drawn contours (vtkContourPolylinesToSurfaceFilter), whose vertices
  /// between the slices are interpolated: `contourmesh run` does on such input (docs/contours.md).
  vtkSetClampMacro(OffSliceVolume, int, OFF_SLICE_VOLUME_FREE, OFF_SLICE_VOLUME_PRESERVE);
  vtkGetMacro(OffSliceVolume, int);
  void SetOffSliceVolumeToFree() { this->SetOffSliceVolume(OFF_SLICE_VOLUME_FREE); }
  void SetOffSliceVolumeToPreserve() { this->SetOffSliceVolume(OFF_SLICE_VOLUME_PRESERVE); }
  ///@}

  ///@{
  /// Add the per-vertex "FeatureLabel" array (default Off): the labels of the paper's method or of
  /// cross-slice smoothing; with a baseline method the paper's detection runs on the input just for them.
  vtkSetMacro(GenerateLabels, vtkTypeBool);
  vtkGetMacro(GenerateLabels, vtkTypeBool);
  vtkBooleanMacro(GenerateLabels, vtkTypeBool);
  ///@}

  ///@{
  /// Recover missing contour ids by binning the vertices along this axis (default SLICE_AXIS_NONE).
  /// SliceTolerance: coordinates closer than this share a slice plane; 0 (default) = 1e-4 of the extent.
  vtkSetClampMacro(SliceAxis, int, SLICE_AXIS_NONE, SLICE_AXIS_Z);
  vtkGetMacro(SliceAxis, int);
  void SetSliceAxisToNone() { this->SetSliceAxis(SLICE_AXIS_NONE); }
  void SetSliceAxisToX() { this->SetSliceAxis(SLICE_AXIS_X); }
  void SetSliceAxisToY() { this->SetSliceAxis(SLICE_AXIS_Y); }
  void SetSliceAxisToZ() { this->SetSliceAxis(SLICE_AXIS_Z); }
  vtkSetClampMacro(SliceTolerance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SliceTolerance, double);
  ///@}

  ///@{
  /// Names of the id point arrays, read from the input and written to the output.
  vtkSetStringMacro(ContourIdArrayName);
  vtkGetStringMacro(ContourIdArrayName);
  vtkSetStringMacro(ContourIndexArrayName);
  vtkGetStringMacro(ContourIndexArrayName);
  ///@}

  ///@{
  /// Optional point array (one component) whose non-zero values lock vertices in place. Default none.
  /// The baselines and the paper's method honour it; cross-slice smoothing cannot lock (an error).
  vtkSetStringMacro(LockedArrayName);
  vtkGetStringMacro(LockedArrayName);
  ///@}

 protected:
  vtkContourFeatureSmoothingFilter();
  ~vtkContourFeatureSmoothingFilter() override;

  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
                  vtkInformationVector* outputVector) override;

  int Preset = PRESET_DEFAULT;
  int Method = METHOD_CROSS_SLICE;
  int NumberOfIterations = -1;
  double Lambda = 0.0;
  double Mu = -0.6732;
  double Beta = 0.03;
  vtkTypeBool BoundarySmoothing = 0;
  int TimeStepMode = TIME_STEP_RELATIVE_TO_MEAN_EDGE;
  int DetectionMode = DETECTION_CONTOUR_CONTINUITY;
  double Anisotropy = 3.0;
  double Gamma = -1.0;
  double GammaFactor = 2.0;
  int UmbrellaMeasure = UMBRELLA_LENGTH;
  double Delta = -1.0;
  double DeltaFactor = 0.5;
  int Window = 7;
  double CornerSpread = 0.1;
  int InSliceFeatures = IN_SLICE_NOISE;
  int PrefilterIterations = 0;
  double UmbilicTolerance = 0.05;
  double MinReciprocalCondition = 1e-6;
  int MaxLevels = 3;
  int DiffusionMethod = METHOD_TAUBIN;
  vtkTypeBool KeepAdaptiveMesh = 0;
  int CreaseRestoration = CREASE_RESTORATION_NONE;
  int OffSliceVolume = OFF_SLICE_VOLUME_FREE;
  vtkTypeBool GenerateLabels = 0;
  int SliceAxis = SLICE_AXIS_NONE;
  double SliceTolerance = 0.0;
  char* ContourIdArrayName = nullptr;
  char* ContourIndexArrayName = nullptr;
  char* LockedArrayName = nullptr;

 private:
  vtkContourFeatureSmoothingFilter(const vtkContourFeatureSmoothingFilter&) = delete;
  void operator=(const vtkContourFeatureSmoothingFilter&) = delete;

  int Execute(vtkPolyData* input, vtkPolyData* output);
  bool AbortRequested();
};
