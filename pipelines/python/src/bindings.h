// SPDX-License-Identifier: BSD-3-Clause
// Private to the Python module: the binding groups module.cpp registers.
#pragma once

#include <pybind11/pybind11.h>

namespace contourmesh::python {

void bind_reconstruct(pybind11::module_& m);  ///< volumes, label maps, reconstruction, phantoms
void bind_smooth(pybind11::module_& m);       ///< smoothing and feature detection

}  // namespace contourmesh::python
