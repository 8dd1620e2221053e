// SPDX-License-Identifier: BSD-3-Clause
// The compiled part of the `contourmesh` Python package (_contourmesh): the library's exceptions as
// Python exceptions, and the bindings. The public functions and their documentation are in
// contourmesh/__init__.py, which wraps these.
#include "bindings.h"

#include <contourmesh/smooth/errors.h>

#include <filesystem>

namespace py = pybind11;

PYBIND11_MODULE(_contourmesh, m) {
  m.doc() = "ContourMesh bindings (use the contourmesh package)";
  // The hierarchy of contourmesh/smooth/errors.h: InvalidInputError is a ValueError, TopologyError and LimitError
  // are InvalidInputErrors, CancelledError is a RuntimeError. The objects live as long as the module.
  static py::handle invalid = PyErr_NewExceptionWithDoc(
      "contourmesh.InvalidInputError", "The input violates a documented precondition (a ValueError).",
      PyExc_ValueError, nullptr);
  static py::handle topology = PyErr_NewExceptionWithDoc(
      "contourmesh.TopologyError", "The mesh connectivity is unusable for the operation.", invalid.ptr(), nullptr);
  static py::handle limit = PyErr_NewExceptionWithDoc(
      "contourmesh.LimitError", "The input exceeds a vertex or memory limit.", invalid.ptr(), nullptr);
  static py::handle cancelled = PyErr_NewExceptionWithDoc(
      "contourmesh.CancelledError", "The progress callback asked to stop.", PyExc_RuntimeError, nullptr);
  m.attr("InvalidInputError") = invalid;
  m.attr("TopologyError") = topology;
  m.attr("LimitError") = limit;
  m.attr("CancelledError") = cancelled;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const contourmesh::LimitError& e) {
      PyErr_SetString(limit.ptr(), e.what());
    } catch (const contourmesh::TopologyError& e) {
      PyErr_SetString(topology.ptr(), e.what());
    } catch (const contourmesh::InvalidInputError& e) {
      PyErr_SetString(invalid.ptr(), e.what());
    } catch (const contourmesh::CancelledError& e) {
      PyErr_SetString(cancelled.ptr(), e.what());
    } catch (const std::filesystem::filesystem_error& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });
  contourmesh::python::bind_reconstruct(m);
  contourmesh::python::bind_smooth(m);
}
