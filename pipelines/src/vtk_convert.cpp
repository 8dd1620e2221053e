// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/vtk/vtk_convert.h"

#include <contourmesh/smooth/errors.h>

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTriangleFilter.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace contourmesh {

vtkSmartPointer<vtkPolyData> to_polydata(const Mesh& mesh, const ContourIdArrayNames& arrays,
                                         const std::vector<PointScalars>& extra) {
  const Index n = mesh.num_vertices();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  for (Index i = 0; i < n; ++i) points->SetPoint(i, mesh.positions.col(i).data());

  vtkNew<vtkIdTypeArray> offsets;
  vtkNew<vtkIdTypeArray> connectivity;
  offsets->SetNumberOfValues(static_cast<vtkIdType>(mesh.triangles.size()) + 1);
  connectivity->SetNumberOfValues(static_cast<vtkIdType>(mesh.triangles.size()) * 3);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    offsets->SetValue(static_cast<vtkIdType>(f), static_cast<vtkIdType>(3 * f));
    for (int c = 0; c < 3; ++c) connectivity->SetValue(static_cast<vtkIdType>(3 * f + c), mesh.triangles[f][c]);
  }
  offsets->SetValue(static_cast<vtkIdType>(mesh.triangles.size()), static_cast<vtkIdType>(3 * mesh.triangles.size()));
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);

  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(polys);
  if (mesh.has_contour_ids()) {
    for (int which = 0; which < 2; ++which) {
      const auto& ids = which == 0 ? mesh.slice_ids : mesh.contour_ids;
      vtkNew<vtkIntArray> array;
      array->SetName(which == 0 ? arrays.slice.c_str() : arrays.contour.c_str());
      array->SetNumberOfValues(n);
      for (Index i = 0; i < n; ++i) array->SetValue(i, ids[i]);
      poly->GetPointData()->AddArray(array);
    }
  }
  for (const PointScalars& scalars : extra) {
    if (scalars.values.size() != static_cast<std::size_t>(n)) {
      throw InvalidInputError("point array '" + scalars.name + "' has " + std::to_string(scalars.values.size()) +
                              " values for " + std::to_string(n) + " vertices");
    }
    vtkSmartPointer<vtkDataArray> array;
    if (scalars.type == ScalarType::Int32) array = vtkSmartPointer<vtkIntArray>::New();
    else array = vtkSmartPointer<vtkDoubleArray>::New();
    array->SetName(scalars.name.c_str());
    array->SetNumberOfTuples(n);
    for (Index i = 0; i < n; ++i) array->SetComponent(i, 0, scalars.values[i]);
    poly->GetPointData()->AddArray(array);
  }
  return poly;
}

namespace {

std::vector<std::int32_t> read_id_array(vtkDataArray* array, Index n) {
  if (array->GetNumberOfComponents() != 1 || array->GetNumberOfTuples() != n) {
    throw InvalidInputError(std::string("point array '") + array->GetName() + "' has " +
                            std::to_string(array->GetNumberOfTuples()) + " x " +
                            std::to_string(array->GetNumberOfComponents()) + " values, expected " + std::to_string(n) +
                            " x 1");
  }
  std::vector<std::int32_t> ids(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) {
    // Any array type may carry the ids: a value that is no 32-bit integer (NaN, 1e300, 2.5) has no
    // meaning as an id, and converting it to int would be undefined.
    const double value = array->GetComponent(i, 0);
    if (!(value >= std::numeric_limits<std::int32_t>::min() && value <= std::numeric_limits<std::int32_t>::max()) ||
        value != std::floor(value)) {
      std::ostringstream msg;
      msg << "point " << i << " has " << array->GetName() << " = " << value << ", not a 32-bit integer";
      throw InvalidInputError(msg.str());
    }
    ids[i] = static_cast<std::int32_t>(value);
  }
  return ids;
}

}  // namespace

Mesh from_polydata(vtkPolyData* input, const ContourIdArrayNames& arrays) {
  if (input == nullptr) throw InvalidInputError("no polydata");
  vtkSmartPointer<vtkPolyData> poly = input;
  // Out-of-range point ids would make the triangle filter read out of bounds: check them first.
  {
    const vtkIdType points = input->GetNumberOfPoints();
    vtkIdType cell = 0;
    for (vtkCellArray* cells : {input->GetPolys(), input->GetStrips()}) {
      if (cells == nullptr) continue;
      vtkIdType npts = 0;
      const vtkIdType* ids = nullptr;
      for (cells->InitTraversal(); cells->GetNextCell(npts, ids); ++cell) {
        for (vtkIdType k = 0; k < npts; ++k) {
          if (ids[k] < 0 || ids[k] >= points) {
            throw InvalidInputError("polygon " + std::to_string(cell) + " references point " + std::to_string(ids[k]) +
                                    " but the file has " + std::to_string(points) + " points");
          }
        }
      }
    }
  }
  const bool triangles_only = input->GetNumberOfStrips() == 0 &&
                              (input->GetPolys()->GetNumberOfCells() == 0 || input->GetPolys()->IsHomogeneous() == 3);
  if (!triangles_only) {
    vtkNew<vtkTriangleFilter> triangulate;
    triangulate->SetInputData(input);
    triangulate->PassVertsOff();
    triangulate->PassLinesOff();
    triangulate->Update();
    poly = triangulate->GetOutput();
  }
  Mesh mesh;
  const auto n = static_cast<Index>(poly->GetNumberOfPoints());
  mesh.positions.resize(3, n);
  for (Index i = 0; i < n; ++i) poly->GetPoint(i, mesh.positions.col(i).data());
  vtkCellArray* polys = poly->GetPolys();
  mesh.triangles.reserve(static_cast<std::size_t>(polys->GetNumberOfCells()));
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  for (polys->InitTraversal(); polys->GetNextCell(npts, pts);) {
    if (npts != 3) continue;  // vtkTriangleFilter leaves only triangles; degenerate cells are dropped
    mesh.triangles.push_back({static_cast<Index>(pts[0]), static_cast<Index>(pts[1]), static_cast<Index>(pts[2])});
  }
  vtkDataArray* slice = poly->GetPointData()->GetArray(arrays.slice.c_str());
  vtkDataArray* contour = poly->GetPointData()->GetArray(arrays.contour.c_str());
  if (slice != nullptr) {
    mesh.slice_ids = read_id_array(slice, n);
    // A file with slice ids but no contour index: every slice holds one contour.
    mesh.contour_ids = contour != nullptr ? read_id_array(contour, n) : std::vector<std::int32_t>(n, 0);
  }
  return mesh;
}

}  // namespace contourmesh
