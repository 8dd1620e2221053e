// SPDX-License-Identifier: BSD-3-Clause
// Private to the Python module: numpy <-> ContourMesh types, progress callbacks that call back into
// Python, and running library work without the GIL.
#pragma once

#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/mesh.h>
#include <contourmesh/smooth/progress.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <optional>
#include <string>

namespace contourmesh::python {

namespace py = pybind11;

/// (n, 3) float64 points and (m, 3) integer triangles, plus optional (n,) slice and contour ids (None or
/// both), into a Mesh. Throws InvalidInputError naming the argument for a wrong shape, or ids given for
/// only one of the two arrays.
[[nodiscard]] Mesh mesh_from_arrays(const py::handle& points, const py::handle& triangles, const py::handle& slice_ids,
                                    const py::handle& contour_ids);

/// (n, 3) points as a 3 x n matrix (InvalidInputError naming `name` for another shape).
[[nodiscard]] Eigen::Matrix3Xd points_from_array(const py::handle& points, const std::string& name);

/// Three numbers (x, y, z) as a vector (InvalidInputError naming `name` otherwise).
[[nodiscard]] Eigen::Vector3d vector3(const py::handle& value, const std::string& name);

/// (points, triangles, slice_ids, contour_ids): new numpy arrays (float64 (n, 3), int32 (m, 3), int32
/// (n,) twice, or None for a mesh without ids).
[[nodiscard]] py::tuple mesh_to_arrays(const Mesh& mesh);

/// A numpy volume indexed [k, j, i] (slice, row, column, as SimpleITK and ITK's GetArrayFromImage lay it
/// out) with spacing and origin in x, y, z order and an optional 3 x 3 direction (columns: the i, j, k
/// axes in physical space), into a CtImage. Values are converted to float32.
[[nodiscard]] CtImage::Pointer image_from_array(const py::handle& volume, const py::handle& spacing,
                                                const py::handle& origin, const py::handle& direction);

/// The inverse: (volume [k, j, i] float32, spacing (3,), origin (3,), direction (3, 3)).
[[nodiscard]] py::tuple image_to_arrays(const CtImage& image);

/// Runs library work without the GIL and with a progress callback that re-acquires it to call the
/// Python `progress(stage, fraction)` (None or a truthy result goes on; False cancels). A KeyboardInterrupt
/// (Ctrl-C) or an exception raised by the Python callback cancels the work and is re-raised as it was.
class ProgressBridge {
 public:
  explicit ProgressBridge(py::object progress);
  /// The callback to hand to the library (called from the thread that runs the work).
  [[nodiscard]] ProgressCallback callback();
  /// Runs `work` with the GIL released; rethrows a Python error the callback met.
  template <class Work>
  auto run(Work&& work) {
    try {
      py::gil_scoped_release release;
      return work();
    } catch (...) {
      rethrow_python_error();
      throw;
    }
  }

 private:
  void rethrow_python_error();
  py::object progress_;
  std::optional<py::error_already_set> error_;
};

/// A keyword option as a double / int / string, with the option's name in the error.
[[nodiscard]] double as_double(const py::handle& value, const std::string& name);
[[nodiscard]] int as_int(const py::handle& value, const std::string& name);
[[nodiscard]] std::string as_string(const py::handle& value, const std::string& name);

}  // namespace contourmesh::python
