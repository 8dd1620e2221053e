// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/vtk/vtkContourFeatureSmoothingFilter.h"

#include "contourmesh/vtk/vtk_convert.h"
#include "vtk_progress.h"

#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/feature_detection.h>
#include <contourmesh/smooth/input_policy.h>
#include <contourmesh/smooth/smooth.h>

#include <vtkAbstractArray.h>
#include <vtkDataArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkContourFeatureSmoothingFilter);

vtkContourFeatureSmoothingFilter::vtkContourFeatureSmoothingFilter() {
  this->SetContourIdArrayName("ContourId");
  this->SetContourIndexArrayName("ContourIndex");
  this->SetPreset(PRESET_DEFAULT);
}

vtkContourFeatureSmoothingFilter::~vtkContourFeatureSmoothingFilter() {
  this->SetContourIdArrayName(nullptr);
  this->SetContourIndexArrayName(nullptr);
  this->SetLockedArrayName(nullptr);
}

namespace {

using contourmesh::InvalidInputError;

using Filter = vtkContourFeatureSmoothingFilter;
using contourmesh::SmoothingMethod;

SmoothingMethod to_library(int method) {
  switch (method) {
    case Filter::METHOD_LAPLACIAN: return SmoothingMethod::Laplacian;
    case Filter::METHOD_TAUBIN: return SmoothingMethod::Taubin;
    case Filter::METHOD_MEAN_CURVATURE_FLOW: return SmoothingMethod::MeanCurvatureFlow;
    case Filter::METHOD_MIN_DIST_FLOW: return SmoothingMethod::MinDistFlow;
    case Filter::METHOD_PAPER: return SmoothingMethod::FeaturePreserving;
    case Filter::METHOD_CROSS_SLICE: return SmoothingMethod::CrossSlice;
    default: return SmoothingMethod::None;
  }
}

int from_library(SmoothingMethod method) {
  switch (method) {
    case SmoothingMethod::None: return Filter::METHOD_NONE;
    case SmoothingMethod::Laplacian: return Filter::METHOD_LAPLACIAN;
    case SmoothingMethod::Taubin: return Filter::METHOD_TAUBIN;
    case SmoothingMethod::MeanCurvatureFlow: return Filter::METHOD_MEAN_CURVATURE_FLOW;
    case SmoothingMethod::MinDistFlow: return Filter::METHOD_MIN_DIST_FLOW;
    case SmoothingMethod::FeaturePreserving: return Filter::METHOD_PAPER;
    case SmoothingMethod::CrossSlice: return Filter::METHOD_CROSS_SLICE;
  }
  return Filter::METHOD_NONE;
}

// The filter's properties for a method and its options (a preset). Options the filter has no property
// for (cross-slice's own) keep the library's defaults when the filter runs.
void set_properties(Filter* f, const contourmesh::MethodConfig& config) {
  using namespace contourmesh;
  SmoothOptions o = config.options;
  const SmoothingMethod m = config.method;
  const bool paper = m == SmoothingMethod::FeaturePreserving;
  f->SetMethod(from_library(m));
  f->SetNumberOfIterations(default_iterations(m) > 0 ? iterations_of(m, o) : -1);
  const std::optional<double> lambda = paper ? o.paper.lambda : o.baseline.lambda;
  f->SetLambda(lambda.value_or(0.0));
  f->SetMu(paper ? o.paper.mu : o.baseline.mu);
  f->SetBeta(o.baseline.beta);
  f->SetBoundarySmoothing((paper ? o.paper.boundary : o.baseline.boundary) == BoundaryPolicy::Free);
  f->SetTimeStepMode(o.baseline.time_step == TimeStep::Absolute ? Filter::TIME_STEP_ABSOLUTE
                                                                 : Filter::TIME_STEP_RELATIVE_TO_MEAN_EDGE);
  const DetectionOptions* chosen = detection_options_of(m, o);
  const DetectionOptions d = chosen != nullptr ? *chosen : DetectionOptions{};
  f->SetDetectionMode(d.mode == DetectionMode::CurvatureOnly ? Filter::DETECTION_CURVATURE_ONLY
                                                             : Filter::DETECTION_CONTOUR_CONTINUITY);
  f->SetAnisotropy(d.anisotropy);
  f->SetGamma(d.gamma.value_or(-1.0));
  f->SetGammaFactor(d.gamma_factor);
  f->SetUmbrellaMeasure(d.measure == UmbrellaMeasure::NormalComponent ? Filter::UMBRELLA_NORMAL_COMPONENT
                                                                      : Filter::UMBRELLA_LENGTH);
  f->SetDelta(d.delta.value_or(-1.0));
  f->SetDeltaFactor(d.delta_factor);
  f->SetWindow(d.window);
  f->SetCornerSpread(d.corner_spread);
  f->SetInSliceFeatures(d.in_slice == InSliceFeatures::AlongFeatureLine ? Filter::IN_SLICE_ALONG_LINE
                                                                        : Filter::IN_SLICE_NOISE);
  f->SetPrefilterIterations(d.prefilter_iterations);
  f->SetUmbilicTolerance(d.curvature.umbilic_tolerance);
  f->SetMinReciprocalCondition(d.curvature.min_reciprocal_condition);
  f->SetMaxLevels(o.paper.max_levels);
  f->SetDiffusionMethod(o.paper.diffusion == SmoothingMethod::Laplacian ? Filter::METHOD_LAPLACIAN
                                                                        : Filter::METHOD_TAUBIN);
  f->SetKeepAdaptiveMesh(o.paper.output == OutputResolution::Adaptive);
  f->SetCreaseRestoration(o.cross_slice.crease_restoration == CreaseRestoration::Subdivide
                              ? Filter::CREASE_RESTORATION_SUBDIVIDE
                              : Filter::CREASE_RESTORATION_NONE);
  f->SetOffSliceVolume(o.cross_slice.off_slice.volume == OffSliceVolume::Preserve ? Filter::OFF_SLICE_VOLUME_PRESERVE
                                                                                  : Filter::OFF_SLICE_VOLUME_FREE);
}

// The input's point arrays for the prepared mesh's vertices: the first input point merged into each.
std::vector<vtkIdType> representatives(const std::vector<contourmesh::Index>& vertex_map, contourmesh::Index count) {
  std::vector<vtkIdType> first(static_cast<std::size_t>(count), -1);
  for (std::size_t i = vertex_map.size(); i-- > 0;) first[vertex_map[i]] = static_cast<vtkIdType>(i);
  return first;
}

}  // namespace

void vtkContourFeatureSmoothingFilter::SetPreset(int preset) {
  const int clamped = preset < PRESET_DEFAULT ? PRESET_DEFAULT : (preset > PRESET_XU2006 ? PRESET_XU2006 : preset);
  set_properties(this, contourmesh::preset(clamped == PRESET_XU2006 ? contourmesh::Preset::Xu2006
                                                                    : contourmesh::Preset::Default));
  if (this->Preset != clamped) {
    this->Preset = clamped;
    this->Modified();
  }
}

const char* vtkContourFeatureSmoothingFilter::GetPresetAsString() {
  return this->Preset == PRESET_XU2006 ? "Xu2006" : "Default";
}

const char* vtkContourFeatureSmoothingFilter::GetMethodAsString() {
  switch (this->Method) {
    case METHOD_NONE: return "None";
    case METHOD_LAPLACIAN: return "Laplacian";
    case METHOD_TAUBIN: return "Taubin";
    case METHOD_MEAN_CURVATURE_FLOW: return "MeanCurvatureFlow";
    case METHOD_MIN_DIST_FLOW: return "MinDistFlow";
    case METHOD_PAPER: return "Paper";
    default: return "CrossSlice";
  }
}

const char* vtkContourFeatureSmoothingFilter::GetDetectionModeAsString() {
  switch (this->DetectionMode) {
    case DETECTION_CURVATURE_ONLY: return "CurvatureOnly";
    case DETECTION_AUTOMATIC: return "Automatic";
    default: return "ContourContinuity";
  }
}

bool vtkContourFeatureSmoothingFilter::AbortRequested() {
#if VTK_MAJOR_VERSION > 9 || (VTK_MAJOR_VERSION == 9 && VTK_MINOR_VERSION >= 3)
  return this->CheckAbort();
#else
  return this->GetAbortExecute() != 0;  // vtkAlgorithm::CheckAbort arrived in VTK 9.3
#endif
}

int vtkContourFeatureSmoothingFilter::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                                  vtkInformationVector* outputVector) {
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (output == nullptr) {
    vtkErrorMacro(<< "no output polydata");
    return 0;
  }
  output->Initialize();
  if (input == nullptr) {
    vtkErrorMacro(<< "no input polydata");
    return 0;
  }
  try {
    return this->Execute(input, output);
  } catch (const contourmesh::CancelledError&) {
    output->Initialize();
    vtkDebugMacro(<< "aborted: the output is empty");
    return 1;
  } catch (const std::exception& e) {
    output->Initialize();
    vtkErrorMacro(<< e.what());
    return 0;
  }
}

int vtkContourFeatureSmoothingFilter::Execute(vtkPolyData* input, vtkPolyData* output) {
  using namespace contourmesh;
  if (this->ContourIdArrayName == nullptr || this->ContourIndexArrayName == nullptr) {
    throw InvalidInputError("ContourIdArrayName and ContourIndexArrayName must be set");
  }
  if (input->GetNumberOfPoints() == 0) return 1;  // empty in, empty out
  if (this->AbortRequested()) throw CancelledError("start");

  const ContourIdArrayNames names{this->ContourIdArrayName, this->ContourIndexArrayName};
  Mesh mesh = from_polydata(input, names);
  if (mesh.triangles.empty()) throw InvalidInputError("input has no triangles");
  const Index n_input = mesh.num_vertices();

  const SmoothingMethod method = to_library(this->Method);
  const bool cross_slice = method == SmoothingMethod::CrossSlice;
  // The paper's detection runs for its method, and for labels of a method that has none of its own.
  const bool detect =
      method == SmoothingMethod::FeaturePreserving || (this->GenerateLabels && !produces_labels(method));

  // The one input policy, as `contourmesh smooth` runs it (contourmesh/smooth/input_policy.h): refusals, repairs,
  // orientation, and contour ids made usable for the detection or for cross-slice smoothing, which
  // cannot do without them.
  InputPolicyOptions policy;
  policy.ids = cross_slice || (detect && this->DetectionMode != DETECTION_CURVATURE_ONLY) ? ContourIdUse::Detection
                                                                                         : ContourIdUse::PassThrough;
  if (this->SliceAxis != SLICE_AXIS_NONE) policy.slice_axis = Eigen::Vector3d::Unit(this->SliceAxis);
  policy.slice_tolerance = this->SliceTolerance;
  policy.missing_ids =
      this->DetectionMode == DETECTION_AUTOMATIC && !cross_slice ? MissingIds::CurvatureOnly : MissingIds::Refuse;
  if (policy.ids == ContourIdUse::Detection && !mesh.has_contour_ids() && !policy.slice_axis &&
      policy.missing_ids == MissingIds::Refuse) {
    if (cross_slice) {
      throw InvalidInputError(std::string("input has no contour-id point array '") + this->ContourIdArrayName +
                              "', which cross-slice smoothing needs: set SliceAxis to recover the ids by binning "
                              "the vertices along the slice axis, or choose another Method");
    }
    throw InvalidInputError(std::string("input has no contour-id point array '") + this->ContourIdArrayName +
                            "': set SliceAxis to recover the ids by binning the vertices along the slice axis, "
                            "or SetDetectionModeToCurvatureOnly()");
  }
  PreparedMesh prepared;
  try {
    prepared = prepare_input_mesh(std::move(mesh), policy);
  } catch (const InvalidInputError&) {
    rethrow_with_context("input");
  }
  for (const std::string& warning : prepared.warnings) vtkWarningMacro(<< "input: " << warning);
  mesh = std::move(prepared.mesh);
  const Index n = mesh.num_vertices();
  const std::vector<Index>& vertex_map = prepared.repair.vertex_map;  // empty: input point i is vertex i

  std::vector<std::uint8_t> locked;
  if (this->LockedArrayName != nullptr && this->LockedArrayName[0] != '\0') {
    if (cross_slice) {
      throw InvalidInputError(
          "cross-slice smoothing cannot lock vertices: unset LockedArrayName or choose another Method");
    }
    vtkDataArray* array = input->GetPointData()->GetArray(this->LockedArrayName);
    if (array == nullptr) {
      throw InvalidInputError(std::string("input has no point array '") + this->LockedArrayName +
                              "' (LockedArrayName)");
    }
    if (array->GetNumberOfComponents() != 1 || array->GetNumberOfTuples() != n_input) {
      throw InvalidInputError(std::string("locked array '") + this->LockedArrayName + "' is not one value per point");
    }
    locked.assign(static_cast<std::size_t>(n), 0);
    for (Index i = 0; i < n_input; ++i) {
      if (array->GetComponent(i, 0) != 0.0) locked[vertex_map.empty() ? i : vertex_map[i]] = 1;
    }
  }

  // Detection options.
  DetectionOptions detection;
  detection.anisotropy = this->Anisotropy;
  if (this->Gamma >= 0.0) detection.gamma = this->Gamma;
  detection.gamma_factor = this->GammaFactor;
  detection.measure =
      this->UmbrellaMeasure == UMBRELLA_NORMAL_COMPONENT ? UmbrellaMeasure::NormalComponent : UmbrellaMeasure::Length;
  if (this->Delta >= 0.0) detection.delta = this->Delta;
  detection.delta_factor = this->DeltaFactor;
  detection.window = this->Window;
  detection.corner_spread = this->CornerSpread;
  detection.in_slice = this->InSliceFeatures == IN_SLICE_ALONG_LINE ? contourmesh::InSliceFeatures::AlongFeatureLine
                                                                    : contourmesh::InSliceFeatures::Noise;
  detection.prefilter_iterations = this->PrefilterIterations;
  detection.curvature.umbilic_tolerance = this->UmbilicTolerance;
  detection.curvature.min_reciprocal_condition = this->MinReciprocalCondition;
  if (this->DetectionMode == DETECTION_CURVATURE_ONLY ||
      prepared.detection_mode == contourmesh::DetectionMode::CurvatureOnly) {
    detection.mode = contourmesh::DetectionMode::CurvatureOnly;
  }

  // The library's options from the properties (as `contourmesh smooth` builds them from its flags).
  SmoothOptions o;
  if (this->NumberOfIterations >= 0 && default_iterations(method) > 0) o.iterations = this->NumberOfIterations;
  const std::optional<double> lambda = this->Lambda > 0.0 ? std::optional<double>(this->Lambda) : std::nullopt;
  const BoundaryPolicy boundary = this->BoundarySmoothing ? BoundaryPolicy::Free : BoundaryPolicy::Fixed;
  o.baseline.lambda = lambda;
  o.baseline.mu = this->Mu;
  o.baseline.beta = this->Beta;
  o.baseline.time_step = this->TimeStepMode == TIME_STEP_ABSOLUTE ? TimeStep::Absolute : TimeStep::RelativeToMeanEdge;
  o.baseline.boundary = boundary;
  o.baseline.locked = locked;
  o.paper.detection = detection;
  o.paper.max_levels = this->MaxLevels;
  o.paper.diffusion = this->DiffusionMethod == METHOD_LAPLACIAN ? SmoothingMethod::Laplacian : SmoothingMethod::Taubin;
  o.paper.lambda = lambda;
  o.paper.mu = this->Mu;
  o.paper.boundary = boundary;
  o.paper.output = this->KeepAdaptiveMesh ? OutputResolution::Adaptive : OutputResolution::Original;
  o.paper.locked = locked;
  // A cross-slice property set away from its default with another method is an error, not ignored.
  const auto needs_cross_slice = [cross_slice](const std::string& what, const std::string& property,
                                               const std::string& default_value) {
    if (!cross_slice) {
      throw InvalidInputError(what + " (" + property + ") needs cross-slice smoothing: set " + property + " to " +
                              default_value + " or choose SetMethodToCrossSlice()");
    }
  };
  if (this->CreaseRestoration == CREASE_RESTORATION_SUBDIVIDE) {
    needs_cross_slice("crease restoration", "CreaseRestoration", "None");
    o.cross_slice.crease_restoration = contourmesh::CreaseRestoration::Subdivide;
  }
  if (this->OffSliceVolume == OFF_SLICE_VOLUME_PRESERVE) {
    needs_cross_slice("keeping the off-slice volume", "OffSliceVolume", "Free");
    o.cross_slice.off_slice.volume = contourmesh::OffSliceVolume::Preserve;
  }

  filter_detail::StageProgress stages(
      this, [](vtkAlgorithm* a) { return static_cast<vtkContourFeatureSmoothingFilter*>(a)->AbortRequested(); });
  std::vector<VertexLabel> labels;
  if (method == SmoothingMethod::FeaturePreserving) {
    stages.add("detect", 0.0, 0.3);
    stages.add("subdivide", 0.3, 0.1);
    stages.add("smooth", 0.4, 0.6);
  } else if (cross_slice) {
    stages.add("smooth", 0.0, 0.8);
    stages.add("detect", 0.8, 0.2);
  } else if (detect) {
    stages.add("detect", 0.0, 0.3);
    stages.add("smooth", 0.3, 0.7);
  } else {
    stages.add("smooth", 0.0, 1.0);
  }
  o.progress = stages.callback();
  if (this->GenerateLabels && !produces_labels(method)) {
    detection.progress = o.progress;
    labels = detect_features(mesh, build_adjacency(mesh), detection).labels;
  }
  // smooth() also stops a diverging run (DivergenceError), as `contourmesh smooth` does.
  SmoothResult smoothed = smooth(mesh, method, o);
  if (produces_labels(method)) labels = std::move(smoothed.labels);
  const Mesh& result = smoothed.mesh;
  if (this->AbortRequested()) throw CancelledError("output");

  std::vector<PointScalars> extra;
  if (this->GenerateLabels) {
    PointScalars array{"FeatureLabel", std::vector<double>(static_cast<std::size_t>(result.num_vertices()), -1.0),
                       ScalarType::Int32};
    for (std::size_t i = 0; i < labels.size(); ++i) array.values[i] = static_cast<double>(labels[i]);
    extra.push_back(std::move(array));
  }
  vtkSmartPointer<vtkPolyData> poly = to_polydata(result, names, extra);
  // At the input's resolution, pass the input's other point arrays (not its now stale normals); where
  // coincident input points were merged, each vertex takes the values of the first of them.
  if (result.num_vertices() == n) {
    const std::vector<vtkIdType> source =
        vertex_map.empty() ? std::vector<vtkIdType>() : representatives(vertex_map, n);
    vtkPointData* in = input->GetPointData();
    vtkPointData* out = poly->GetPointData();
    for (int a = 0; a < in->GetNumberOfArrays(); ++a) {
      vtkAbstractArray* array = in->GetAbstractArray(a);
      if (array == nullptr || array->GetName() == nullptr || array == in->GetNormals()) continue;
      if (array->GetNumberOfTuples() != n_input || out->GetAbstractArray(array->GetName()) != nullptr) continue;
      if (source.empty()) {
        out->AddArray(array);
        continue;
      }
      vtkSmartPointer<vtkAbstractArray> copy = vtkSmartPointer<vtkAbstractArray>::Take(array->NewInstance());
      copy->SetName(array->GetName());
      copy->SetNumberOfComponents(array->GetNumberOfComponents());
      copy->SetNumberOfTuples(n);
      for (Index j = 0; j < n; ++j) copy->SetTuple(j, source[j], array);
      out->AddArray(copy);
    }
    if (vtkDataArray* scalars = in->GetScalars(); scalars != nullptr && scalars->GetName() != nullptr) {
      out->SetActiveScalars(scalars->GetName());
    }
  }
  output->ShallowCopy(poly);
  return 1;
}

void vtkContourFeatureSmoothingFilter::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  auto str = [](const char* s) { return s != nullptr ? s : "(none)"; };
  os << indent << "Preset: " << this->GetPresetAsString() << " (last applied)\n";
  os << indent << "Method: " << this->GetMethodAsString() << "\n";
  os << indent << "NumberOfIterations: " << this->NumberOfIterations
     << (this->NumberOfIterations < 0 ? " (automatic)" : "") << "\n";
  os << indent << "Lambda: " << this->Lambda << (this->Lambda > 0.0 ? "" : " (automatic)") << "\n";
  os << indent << "Mu: " << this->Mu << "\n";
  os << indent << "Beta: " << this->Beta << "\n";
  os << indent << "BoundarySmoothing: " << (this->BoundarySmoothing ? "On" : "Off") << "\n";
  os << indent << "TimeStepMode: " << (this->TimeStepMode == TIME_STEP_ABSOLUTE ? "Absolute" : "RelativeToMeanEdge")
     << "\n";
  os << indent << "DetectionMode: " << this->GetDetectionModeAsString() << "\n";
  os << indent << "Anisotropy: " << this->Anisotropy << "\n";
  os << indent << "Gamma: " << this->Gamma << (this->Gamma < 0.0 ? " (automatic)" : "") << "\n";
  os << indent << "GammaFactor: " << this->GammaFactor << "\n";
  os << indent
     << "UmbrellaMeasure: " << (this->UmbrellaMeasure == UMBRELLA_NORMAL_COMPONENT ? "NormalComponent" : "Length")
     << "\n";
  os << indent << "Delta: " << this->Delta << (this->Delta < 0.0 ? " (automatic)" : "") << "\n";
  os << indent << "DeltaFactor: " << this->DeltaFactor << "\n";
  os << indent << "Window: " << this->Window << "\n";
  os << indent << "CornerSpread: " << this->CornerSpread << "\n";
  os << indent << "InSliceFeatures: " << (this->InSliceFeatures == IN_SLICE_ALONG_LINE ? "AlongLine" : "Noise") << "\n";
  os << indent << "PrefilterIterations: " << this->PrefilterIterations << "\n";
  os << indent << "UmbilicTolerance: " << this->UmbilicTolerance << "\n";
  os << indent << "MinReciprocalCondition: " << this->MinReciprocalCondition << "\n";
  os << indent << "MaxLevels: " << this->MaxLevels << "\n";
  os << indent << "DiffusionMethod: " << (this->DiffusionMethod == METHOD_LAPLACIAN ? "Laplacian" : "Taubin") << "\n";
  os << indent << "KeepAdaptiveMesh: " << (this->KeepAdaptiveMesh ? "On" : "Off") << "\n";
  os << indent
     << "CreaseRestoration: " << (this->CreaseRestoration == CREASE_RESTORATION_SUBDIVIDE ? "Subdivide" : "None")
     << "\n";
  os << indent << "OffSliceVolume: " << (this->OffSliceVolume == OFF_SLICE_VOLUME_PRESERVE ? "Preserve" : "Free")
     << "\n";
  os << indent << "GenerateLabels: " << (this->GenerateLabels ? "On" : "Off") << "\n";
  os << indent
     << "SliceAxis: " << (this->SliceAxis == SLICE_AXIS_NONE ? "None" : std::string(1, "XYZ"[this->SliceAxis])) << "\n";
  os << indent << "SliceTolerance: " << this->SliceTolerance << (this->SliceTolerance > 0.0 ? "" : " (automatic)")
     << "\n";
  os << indent << "ContourIdArrayName: " << str(this->ContourIdArrayName) << "\n";
  os << indent << "ContourIndexArrayName: " << str(this->ContourIndexArrayName) << "\n";
  os << indent << "LockedArrayName: " << str(this->LockedArrayName) << "\n";
}
