# SPDX-License-Identifier: BSD-3-Clause
"""numpy arrays -> vtkPolyData (VTK's Python package is imported only here)."""

import numpy as np
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData


def to_polydata(points, triangles=None, slice_ids=None, contour_ids=None, point_arrays=None):
    if hasattr(points, "_fields"):  # a Reconstruction or a Smoothed
        result = points
        points, triangles, slice_ids, contour_ids = result[:4]
        if point_arrays is None and getattr(result, "labels", None) is not None:
            point_arrays = {"FeatureLabel": result.labels}
    points = np.ascontiguousarray(points, dtype=np.float64)
    triangles = np.asarray(triangles)
    if points.ndim != 2 or points.shape[1] != 3:
        raise ValueError(f"points: expected shape (n, 3), got {points.shape}")
    if triangles.ndim != 2 or triangles.shape[1] != 3:
        raise ValueError(f"triangles: expected shape (m, 3), got {triangles.shape}")
    if triangles.size and (triangles.min() < 0 or triangles.max() >= len(points)):
        raise ValueError("triangles: an index is out of range of the points")
    vtk_points = vtkPoints()
    vtk_points.SetData(numpy_support.numpy_to_vtk(points, deep=True))
    cells = vtkCellArray()
    offsets = np.arange(0, 3 * len(triangles) + 1, 3, dtype=np.int64)
    connectivity = np.ascontiguousarray(triangles, dtype=np.int64).ravel()
    cells.SetData(numpy_support.numpy_to_vtkIdTypeArray(offsets, deep=True),
                  numpy_support.numpy_to_vtkIdTypeArray(connectivity, deep=True))
    poly = vtkPolyData()
    poly.SetPoints(vtk_points)
    poly.SetPolys(cells)
    arrays = {}
    if slice_ids is not None:
        arrays["ContourId"] = np.asarray(slice_ids, dtype=np.int32)
    if contour_ids is not None:
        arrays["ContourIndex"] = np.asarray(contour_ids, dtype=np.int32)
    arrays.update(point_arrays or {})
    for name, values in arrays.items():
        values = np.ascontiguousarray(values)
        if len(values) != len(points):
            raise ValueError(f"point array {name}: {len(values)} values for {len(points)} points")
        if values.dtype == np.uint8 or values.dtype == np.bool_:
            values = values.astype(np.int32)
        array = numpy_support.numpy_to_vtk(values, deep=True)
        array.SetName(name)
        poly.GetPointData().AddArray(array)
    return poly
