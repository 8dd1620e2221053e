// SPDX-License-Identifier: BSD-3-Clause
#include "bridge.h"

#include <contourmesh/smooth/errors.h>

#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace contourmesh::python {

namespace {

std::string shape_of(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> as_array(const py::handle& h, const std::string& name) {
  try {
    return py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(h);
  } catch (const py::error_already_set&) {
    throw InvalidInputError(name + ": not convertible to a numeric array");
  }
}

template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> checked(const py::handle& h, const std::string& name) {
  auto a = as_array<T>(h, name);
  if (!a) throw InvalidInputError(name + ": not convertible to a numeric array");
  return a;
}

std::vector<std::int32_t> ids_of(const py::handle& h, const std::string& name, py::ssize_t n) {
  auto a = checked<std::int64_t>(h, name);
  if (a.ndim() != 1 || a.shape(0) != n) {
    throw InvalidInputError(name + ": expected shape (" + std::to_string(n) + ",), one id per point, got " +
                            shape_of(a));
  }
  std::vector<std::int32_t> ids(static_cast<std::size_t>(n));
  const std::int64_t* p = a.data();
  for (py::ssize_t i = 0; i < n; ++i) {
    if (p[i] < kNoId || p[i] > std::numeric_limits<std::int32_t>::max()) {
      throw InvalidInputError(name + "[" + std::to_string(i) + "] = " + std::to_string(p[i]) +
                              " is out of range (ids are >= -1)");
    }
    ids[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(p[i]);
  }
  return ids;
}

}  // namespace

Eigen::Vector3d vector3(const py::handle& h, const std::string& name) {
  auto a = checked<double>(h, name);
  if (a.size() != 3) throw InvalidInputError(name + ": expected 3 numbers (x, y, z), got shape " + shape_of(a));
  return {a.data()[0], a.data()[1], a.data()[2]};
}

Eigen::Matrix3Xd points_from_array(const py::handle& points, const std::string& name) {
  auto p = checked<double>(points, name);
  if (p.ndim() != 2 || p.shape(1) != 3) throw InvalidInputError(name + ": expected shape (n, 3), got " + shape_of(p));
  Eigen::Matrix3Xd m(3, p.shape(0));
  std::memcpy(m.data(), p.data(), sizeof(double) * static_cast<std::size_t>(p.size()));
  return m;
}

Mesh mesh_from_arrays(const py::handle& points, const py::handle& triangles, const py::handle& slice_ids,
                      const py::handle& contour_ids) {
  Mesh mesh;
  mesh.positions = points_from_array(points, "points");
  auto t = checked<std::int64_t>(triangles, "triangles");
  if (t.ndim() != 2 || t.shape(1) != 3) throw InvalidInputError("triangles: expected shape (m, 3), got " + shape_of(t));
  const py::ssize_t n = mesh.positions.cols();
  if (n > std::numeric_limits<Index>::max()) throw LimitError("points: more than 2^31 vertices");
  mesh.triangles.resize(static_cast<std::size_t>(t.shape(0)));
  const std::int64_t* tp = t.data();
  for (py::ssize_t f = 0; f < t.shape(0); ++f) {
    for (int c = 0; c < 3; ++c) {
      const std::int64_t v = tp[3 * f + c];
      if (v < 0 || v >= n) {
        throw InvalidInputError("triangles[" + std::to_string(f) + "] references point " + std::to_string(v) +
                                " but there are " + std::to_string(n) + " points");
      }
      mesh.triangles[static_cast<std::size_t>(f)][c] = static_cast<Index>(v);
    }
  }
  if (slice_ids.is_none() != contour_ids.is_none()) {
    throw InvalidInputError("slice_ids and contour_ids: give both or neither");
  }
  if (!slice_ids.is_none()) {
    mesh.slice_ids = ids_of(slice_ids, "slice_ids", n);
    mesh.contour_ids = ids_of(contour_ids, "contour_ids", n);
  }
  return mesh;
}

py::tuple mesh_to_arrays(const Mesh& mesh) {
  const py::ssize_t n = mesh.num_vertices();
  py::array_t<double> points({n, py::ssize_t{3}});
  std::memcpy(points.mutable_data(), mesh.positions.data(), sizeof(double) * 3 * static_cast<std::size_t>(n));
  py::array_t<std::int32_t> triangles({static_cast<py::ssize_t>(mesh.triangles.size()), py::ssize_t{3}});
  if (!mesh.triangles.empty()) {
    std::memcpy(triangles.mutable_data(), mesh.triangles.data(), sizeof(Triangle) * mesh.triangles.size());
  }
  if (!mesh.has_contour_ids()) return py::make_tuple(points, triangles, py::none(), py::none());
  py::array_t<std::int32_t> slice(n), contour(n);
  std::copy(mesh.slice_ids.begin(), mesh.slice_ids.end(), slice.mutable_data());
  std::copy(mesh.contour_ids.begin(), mesh.contour_ids.end(), contour.mutable_data());
  return py::make_tuple(points, triangles, slice, contour);
}

CtImage::Pointer image_from_array(const py::handle& volume, const py::handle& spacing, const py::handle& origin,
                                  const py::handle& direction) {
  auto v = checked<float>(volume, "volume");
  if (v.ndim() != 3)
    throw InvalidInputError("volume: expected a 3-D array indexed [slice, row, column], got shape " + shape_of(v));
  const Eigen::Vector3d s = vector3(spacing, "spacing");
  const Eigen::Vector3d o = vector3(origin, "origin");
  if (!s.allFinite() || (s.array() <= 0.0).any())
    throw InvalidInputError("spacing: every value must be finite and > 0 mm");
  if (!o.allFinite()) throw InvalidInputError("origin: every value must be finite");
  auto image = CtImage::New();
  CtImage::RegionType region;
  CtImage::SizeType size;
  size[0] = static_cast<CtImage::SizeValueType>(v.shape(2));
  size[1] = static_cast<CtImage::SizeValueType>(v.shape(1));
  size[2] = static_cast<CtImage::SizeValueType>(v.shape(0));
  if (size[0] == 0 || size[1] == 0 || size[2] == 0)
    throw InvalidInputError("volume: empty (shape " + shape_of(v) + ")");
  region.SetSize(size);
  image->SetRegions(region);
  image->SetSpacing(s.data());
  image->SetOrigin(o.data());
  if (!direction.is_none()) {
    auto d = checked<double>(direction, "direction");
    if (d.ndim() != 2 || d.shape(0) != 3 || d.shape(1) != 3) {
      throw InvalidInputError("direction: expected a 3 x 3 matrix, got shape " + shape_of(d));
    }
    CtImage::DirectionType m;
    Eigen::Matrix3d e;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) m(r, c) = e(r, c) = d.at(r, c);
    }
    if (!e.allFinite() || !(e.transpose() * e).isApprox(Eigen::Matrix3d::Identity(), 1e-6)) {
      throw InvalidInputError("direction: not an orthonormal matrix");
    }
    image->SetDirection(m);
  }
  image->Allocate();
  std::memcpy(image->GetBufferPointer(), v.data(), sizeof(float) * static_cast<std::size_t>(v.size()));
  return image;
}

py::tuple image_to_arrays(const CtImage& image) {
  const auto size = image.GetLargestPossibleRegion().GetSize();
  py::array_t<float> volume({static_cast<py::ssize_t>(size[2]), static_cast<py::ssize_t>(size[1]),
                             static_cast<py::ssize_t>(size[0])});
  std::memcpy(volume.mutable_data(), image.GetBufferPointer(), sizeof(float) * static_cast<std::size_t>(volume.size()));
  py::array_t<double> spacing(3), origin(3), direction({py::ssize_t{3}, py::ssize_t{3}});
  for (int d = 0; d < 3; ++d) {
    spacing.mutable_at(d) = image.GetSpacing()[d];
    origin.mutable_at(d) = image.GetOrigin()[d];
    for (int c = 0; c < 3; ++c) direction.mutable_at(d, c) = image.GetDirection()(d, c);
  }
  return py::make_tuple(volume, spacing, origin, direction);
}

ProgressBridge::ProgressBridge(py::object progress) : progress_(std::move(progress)) {
  if (!progress_.is_none() && !PyCallable_Check(progress_.ptr())) {
    throw InvalidInputError("progress: expected a callable progress(stage, fraction) or None");
  }
}

ProgressCallback ProgressBridge::callback() {
  return [this](std::string_view stage, double fraction) {
    if (error_) return false;
    py::gil_scoped_acquire gil;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // Ctrl-C
      if (progress_.is_none()) return true;
      const py::object result = progress_(std::string(stage), fraction);
      return result.is_none() || py::bool_(result);
    } catch (py::error_already_set& e) {
      error_.emplace(std::move(e));
      return false;
    }
  };
}

void ProgressBridge::rethrow_python_error() {
  if (!error_) return;
  py::error_already_set e = std::move(*error_);
  error_.reset();
  throw e;
}

double as_double(const py::handle& value, const std::string& name) {
  try {
    return value.cast<double>();
  } catch (const py::cast_error&) {
    throw InvalidInputError(name + ": expected a number, got " +
                            std::string(py::str(value.get_type().attr("__name__"))));
  }
}

int as_int(const py::handle& value, const std::string& name) {
  if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value)) {
    throw InvalidInputError(name + ": expected an integer, got " +
                            std::string(py::str(value.get_type().attr("__name__"))));
  }
  return value.cast<int>();
}

std::string as_string(const py::handle& value, const std::string& name) {
  if (!py::isinstance<py::str>(value)) {
    throw InvalidInputError(name + ": expected a string, got " +
                            std::string(py::str(value.get_type().attr("__name__"))));
  }
  return value.cast<std::string>();
}

}  // namespace contourmesh::python
