// SPDX-License-Identifier: BSD-3-Clause
// Conversion between contourmesh::Mesh and vtkPolyData.
#pragma once

#include "contourmesh/vtk/mesh_io.h"

#include <contourmesh/smooth/mesh.h>

#include <vtkSmartPointer.h>

class vtkPolyData;

namespace contourmesh {

/// Points (double precision), triangles, the two contour-id point arrays (vtkIntArray) when the mesh
/// has ids, and the extra arrays (vtkDoubleArray or vtkIntArray; sizes must match, InvalidInputError).
[[nodiscard]] vtkSmartPointer<vtkPolyData> to_polydata(const Mesh& mesh, const ContourIdArrayNames& arrays = {},
                                                      const std::vector<PointScalars>& extra = {});

/// Triangles of the polydata's polygons (larger polygons are triangulated, strips are converted) and
/// contour ids from the named point arrays when both are present. Throws InvalidInputError when an id
/// array has the wrong size or component count.
[[nodiscard]] Mesh from_polydata(vtkPolyData* polydata, const ContourIdArrayNames& arrays = {});

}  // namespace contourmesh
