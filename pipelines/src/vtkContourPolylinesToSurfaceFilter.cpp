// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/vtk/vtkContourPolylinesToSurfaceFilter.h"

#include "contourmesh/vtk/vtk_convert.h"
#include "vtk_progress.h"
#include "vtk_tiling_properties.h"

#include <contourmesh/reconstruct/contour_reconstruction.h>
#include <contourmesh/reconstruct/planar_contours.h>
#include <contourmesh/smooth/errors.h>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkContourPolylinesToSurfaceFilter);

vtkContourPolylinesToSurfaceFilter::vtkContourPolylinesToSurfaceFilter()
    : SlicewiseVolume(std::numeric_limits<double>::quiet_NaN()) {
  this->SetSliceIdArrayName("SliceId");
}

vtkContourPolylinesToSurfaceFilter::~vtkContourPolylinesToSurfaceFilter() {
  this->SetSliceIdArrayName(nullptr);
}

int vtkContourPolylinesToSurfaceFilter::FillInputPortInformation(int, vtkInformation* info) {
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

namespace {

// A slice id read from an integer-valued array; throws when the value is not an integer.
long long slice_id(vtkDataArray* array, vtkIdType index, const std::string& where) {
  const double v = array->GetComponent(index, 0);
  if (!std::isfinite(v) || v != std::floor(v) || std::abs(v) > 9e15) {
    throw contourmesh::InvalidInputError(where + ": slice id " + std::to_string(v) + " is not an integer");
  }
  return static_cast<long long>(v);
}

// The contours of the input's line cells, with slice ids when the array is there.
std::vector<contourmesh::PlanarContour> polylines(vtkPolyData* input, const char* array_name) {
  using contourmesh::InvalidInputError;
  vtkCellArray* lines = input->GetLines();
  if (lines == nullptr || lines->GetNumberOfCells() == 0) {
    throw InvalidInputError("the input has no lines (contours are line cells: closed polylines)");
  }
  vtkDataArray* cell_ids = nullptr;
  vtkDataArray* point_ids = nullptr;
  if (array_name != nullptr && *array_name != '\0') {
    cell_ids = input->GetCellData()->GetArray(array_name);
    if (cell_ids == nullptr) point_ids = input->GetPointData()->GetArray(array_name);
  }
  vtkPoints* points = input->GetPoints();
  const vtkIdType first_line = input->GetNumberOfVerts();  // cell ids run over verts, lines, polys, strips
  std::vector<contourmesh::PlanarContour> out;
  vtkNew<vtkIdList> ids;
  lines->InitTraversal();
  for (vtkIdType k = 0; lines->GetNextCell(ids); ++k) {
    const vtkIdType cell = first_line + k;
    contourmesh::PlanarContour c;
    c.name = "cell " + std::to_string(cell);
    if (ids->GetNumberOfIds() < 3) {
      throw InvalidInputError(c.name + " has " + std::to_string(ids->GetNumberOfIds()) +
                              " points: a contour is one closed polyline of at least 3 points (join loose segments "
                              "with vtkStripper)");
    }
    for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i) {
      double p[3];
      points->GetPoint(ids->GetId(i), p);
      c.points.emplace_back(p[0], p[1], p[2]);
    }
    if (cell_ids != nullptr) {
      c.slice_id = slice_id(cell_ids, cell, c.name);
    } else if (point_ids != nullptr) {
      c.slice_id = slice_id(point_ids, ids->GetId(0), c.name);
      for (vtkIdType i = 1; i < ids->GetNumberOfIds(); ++i) {
        if (slice_id(point_ids, ids->GetId(i), c.name) != *c.slice_id) {
          throw InvalidInputError(c.name + ": its points carry different slice ids (" + std::to_string(*c.slice_id) +
                                  " and " + std::to_string(slice_id(point_ids, ids->GetId(i), c.name)) + ")");
        }
      }
    }
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace

int vtkContourPolylinesToSurfaceFilter::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                                    vtkInformationVector* outputVector) {
  using namespace contourmesh;
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (output == nullptr) {
    vtkErrorMacro(<< "no output polydata");
    return 0;
  }
  output->Initialize();
  this->SlicewiseVolume = std::numeric_limits<double>::quiet_NaN();
  if (input == nullptr) {
    vtkErrorMacro(<< "no input polydata");
    return 0;
  }
  try {
    if (this->ContourIdArrayName == nullptr || this->ContourIndexArrayName == nullptr) {
      throw InvalidInputError("ContourIdArrayName and ContourIndexArrayName must be set");
    }
    if (this->AbortRequested()) throw CancelledError("start");
    PlanarStackOptions planar;
    planar.planarity_tolerance = this->PlanarityTolerance;
    planar.slice_tolerance = this->SliceTolerance;
    const Eigen::Vector3d axis(this->SliceAxis[0], this->SliceAxis[1], this->SliceAxis[2]);
    if (axis.squaredNorm() > 0.0) planar.slice_axis = axis;
    const PlanarStack built = build_contour_stack(polylines(input, this->SliceIdArrayName), "input", planar);

    ContourReconstructionOptions o;
    o.sampling = this->Sampling;
    o.sampling_tolerance = this->SamplingTolerance;
    o.alignment = this->DriftAlignment == DRIFT_ALIGNMENT_NONE ? contourmesh::DriftAlignment::None
                                                               : contourmesh::DriftAlignment::Centroids;
    o.single_slice = this->SingleSliceContours == SINGLE_SLICE_DROP ? contourmesh::SingleSliceContours::Drop
                                                                    : contourmesh::SingleSliceContours::Slab;
    o.slab_thickness = this->SlabThickness;
    o.tiling = filter_detail::tiling_options(*this);

    filter_detail::StageProgress stages(
        this, [](vtkAlgorithm* a) { return static_cast<vtkContourPolylinesToSurfaceFilter*>(a)->AbortRequested(); });
    stages.add("tile", 0.0, 1.0);
    const ContourReconstruction r = reconstruct_from_contours(built.stack, "input", o, stages.callback());
    if (this->AbortRequested()) throw CancelledError("output");
    std::string warnings;
    for (const auto* list : {&built.report.warnings, &r.report.warnings}) {
      for (const std::string& w : *list) warnings += (warnings.empty() ? "" : "\n") + w;
    }
    if (!warnings.empty()) vtkWarningMacro(<< warnings);
    output->ShallowCopy(
        to_polydata(r.mesh, ContourIdArrayNames{this->ContourIdArrayName, this->ContourIndexArrayName}));
    this->SlicewiseVolume = r.report.slicewise_volume;
    return 1;
  } catch (const CancelledError&) {
    output->Initialize();
    vtkDebugMacro(<< "aborted: the output is empty");
    return 1;
  } catch (const std::exception& e) {
    output->Initialize();
    vtkErrorMacro(<< e.what());
    return 0;
  }
}

void vtkContourPolylinesToSurfaceFilter::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  auto str = [](const char* s) { return s != nullptr ? s : "(none)"; };
  os << indent << "SliceIdArrayName: " << str(this->SliceIdArrayName) << "\n";
  os << indent << "SliceAxis: (" << this->SliceAxis[0] << ", " << this->SliceAxis[1] << ", " << this->SliceAxis[2]
     << ")"
     << (this->SliceAxis[0] == 0.0 && this->SliceAxis[1] == 0.0 && this->SliceAxis[2] == 0.0 ? " (common normal)" : "")
     << "\n";
  os << indent << "PlanarityTolerance: " << this->PlanarityTolerance << "\n";
  os << indent << "SliceTolerance: " << this->SliceTolerance << "\n";
  os << indent << "Sampling: " << this->Sampling << (this->Sampling > 0.0 ? "" : " (as drawn)") << "\n";
  os << indent << "SamplingTolerance: " << this->SamplingTolerance << "\n";
  os << indent << "DriftAlignment: " << (this->DriftAlignment == DRIFT_ALIGNMENT_NONE ? "None" : "Centroids") << "\n";
  os << indent << "SingleSliceContours: " << (this->SingleSliceContours == SINGLE_SLICE_DROP ? "Drop" : "Slab") << "\n";
  os << indent << "SlabThickness: " << this->SlabThickness << "\n";
  os << indent << "SlicewiseVolume: " << this->SlicewiseVolume << "\n";
}
