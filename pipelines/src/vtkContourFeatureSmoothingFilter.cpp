#include "pipelines/vtkContourFeatureSmoothingFilter.h"

#include "pipelines/vtk_convert.h"
#include "vtk_progress.h"

#include <smooth/adjacency.h>
#include <smooth/divergence.h>
#include <smooth/errors.h>
#include <smooth/feature_detection.h>
#include <smooth/feature_smoothing.h>
#include <smooth/input_policy.h>
#include <smooth/smoothing.h>

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
}

vtkContourFeatureSmoothingFilter::~vtkContourFeatureSmoothingFilter() {
  this->SetContourIdArrayName(nullptr);
  this->SetContourIndexArrayName(nullptr);
  this->SetLockedArrayName(nullptr);
}

namespace {

using contourmesh::InvalidInputError;

contourmesh::SmoothingMethod to_library(int method) {
  switch (method) {
    case vtkContourFeatureSmoothingFilter::METHOD_LAPLACIAN: return contourmesh::SmoothingMethod::Laplacian;
    case vtkContourFeatureSmoothingFilter::METHOD_TAUBIN: return contourmesh::SmoothingMethod::Taubin;
    case vtkContourFeatureSmoothingFilter::METHOD_MEAN_CURVATURE_FLOW:
      return contourmesh::SmoothingMethod::MeanCurvatureFlow;
    case vtkContourFeatureSmoothingFilter::METHOD_MIN_DIST_FLOW: return contourmesh::SmoothingMethod::MinDistFlow;
    default: return contourmesh::SmoothingMethod::None;
  }
}

// The input's point arrays for the prepared mesh's vertices: the first input point merged into each.
std::vector<vtkIdType> representatives(const std::vector<contourmesh::Index>& vertex_map, contourmesh::Index count) {
  std::vector<vtkIdType> first(static_cast<std::size_t>(count), -1);
  for (std::size_t i = vertex_map.size(); i-- > 0;) first[vertex_map[i]] = static_cast<vtkIdType>(i);
  return first;
}

}  // namespace

const char* vtkContourFeatureSmoothingFilter::GetMethodAsString() {
  switch (this->Method) {
    case METHOD_NONE: return "None";
    case METHOD_LAPLACIAN: return "Laplacian";
    case METHOD_TAUBIN: return "Taubin";
    case METHOD_MEAN_CURVATURE_FLOW: return "MeanCurvatureFlow";
    case METHOD_MIN_DIST_FLOW: return "MinDistFlow";
    default: return "Paper";
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

  const bool paper = this->Method == METHOD_PAPER;
  const bool detect = paper || this->GenerateLabels;

  // The one input policy, as `contourmesh smooth` runs it (smooth/input_policy.h): refusals, repairs,
  // orientation, and contour ids made usable for the detection.
  InputPolicyOptions policy;
  policy.ids = detect && this->DetectionMode != DETECTION_CURVATURE_ONLY ? ContourIdUse::Detection
                                                                         : ContourIdUse::PassThrough;
  if (this->SliceAxis != SLICE_AXIS_NONE) policy.slice_axis = Eigen::Vector3d::Unit(this->SliceAxis);
  policy.slice_tolerance = this->SliceTolerance;
  policy.missing_ids = this->DetectionMode == DETECTION_AUTOMATIC ? MissingIds::CurvatureOnly : MissingIds::Refuse;
  if (policy.ids == ContourIdUse::Detection && !mesh.has_contour_ids() && !policy.slice_axis &&
      policy.missing_ids == MissingIds::Refuse) {
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

  const MeshAdjacency adjacency = build_adjacency(mesh);

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
  if (this->DetectionMode == DETECTION_CURVATURE_ONLY || prepared.detection_mode == contourmesh::DetectionMode::CurvatureOnly) {
    detection.mode = contourmesh::DetectionMode::CurvatureOnly;
  }

  filter_detail::StageProgress stages(
      this, [](vtkAlgorithm* a) { return static_cast<vtkContourFeatureSmoothingFilter*>(a)->AbortRequested(); });
  Mesh result;
  std::vector<VertexLabel> labels;
  if (paper) {
    stages.add("detect", 0.0, 0.3);
    stages.add("subdivide", 0.3, 0.1);
    stages.add("smooth", 0.4, 0.6);
    FeatureSmoothingOptions o;
    o.detection = detection;
    o.max_levels = this->MaxLevels;
    o.diffusion = this->DiffusionMethod == METHOD_LAPLACIAN ? SmoothingMethod::Laplacian : SmoothingMethod::Taubin;
    o.iterations = this->NumberOfIterations >= 0 ? this->NumberOfIterations : 40;
    if (this->Lambda > 0.0) o.lambda = this->Lambda;
    o.mu = this->Mu;
    o.boundary = this->BoundarySmoothing ? BoundaryPolicy::Free : BoundaryPolicy::Fixed;
    o.output = this->KeepAdaptiveMesh ? OutputResolution::Adaptive : OutputResolution::Original;
    o.locked = locked;
    o.progress = stages.callback();
    o.on_iteration = divergence_guard(mesh.positions, "smoothing");
    FeatureSmoothingResult r = feature_preserving_smooth(mesh, o);
    result = std::move(r.mesh);
    labels = std::move(r.detection.labels);
  } else {
    if (this->GenerateLabels) {
      stages.add("detect", 0.0, 0.3);
      stages.add("smooth", 0.3, 0.7);
      detection.progress = stages.callback();
      labels = detect_features(mesh, adjacency, detection).labels;
    } else {
      stages.add("smooth", 0.0, 1.0);
    }
    SmoothingOptions o;
    o.method = to_library(this->Method);
    o.iterations = this->NumberOfIterations >= 0 ? this->NumberOfIterations : 20;
    if (this->Lambda > 0.0) o.lambda = this->Lambda;
    o.mu = this->Mu;
    o.beta = this->Beta;
    o.time_step = this->TimeStepMode == TIME_STEP_ABSOLUTE ? TimeStep::Absolute : TimeStep::RelativeToMeanEdge;
    o.boundary = this->BoundarySmoothing ? BoundaryPolicy::Free : BoundaryPolicy::Fixed;
    o.locked = locked;
    o.progress = stages.callback();
    o.on_iteration = divergence_guard(mesh.positions, "smoothing");
    result = mesh;
    result.positions = smooth(mesh, adjacency, o);
  }
  check_not_diverged(result.positions, DivergenceBounds::of(mesh.positions), "smoothing");
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
  os << indent << "Method: " << this->GetMethodAsString() << "\n";
  os << indent << "NumberOfIterations: " << this->NumberOfIterations << (this->NumberOfIterations < 0 ? " (automatic)" : "")
     << "\n";
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
  os << indent << "UmbrellaMeasure: " << (this->UmbrellaMeasure == UMBRELLA_NORMAL_COMPONENT ? "NormalComponent" : "Length")
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
  os << indent << "GenerateLabels: " << (this->GenerateLabels ? "On" : "Off") << "\n";
  os << indent << "SliceAxis: " << (this->SliceAxis == SLICE_AXIS_NONE ? "None" : std::string(1, "XYZ"[this->SliceAxis]))
     << "\n";
  os << indent << "SliceTolerance: " << this->SliceTolerance << (this->SliceTolerance > 0.0 ? "" : " (automatic)") << "\n";
  os << indent << "ContourIdArrayName: " << str(this->ContourIdArrayName) << "\n";
  os << indent << "ContourIndexArrayName: " << str(this->ContourIndexArrayName) << "\n";
  os << indent << "LockedArrayName: " << str(this->LockedArrayName) << "\n";
}
