// SPDX-License-Identifier: BSD-3-Clause
// Python bindings: volumes, label maps, reconstruction, phantoms.
#include "bindings.h"
#include "bridge.h"

#include <contourmesh/reconstruct/label_map.h>
#include <contourmesh/reconstruct/phantom.h>
#include <contourmesh/reconstruct/reconstruction.h>
#include <contourmesh/reconstruct/threads.h>
#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/limits.h>

#include <pybind11/stl.h>

#include <memory>

namespace contourmesh::python {

namespace {

ImageSmoothing parse_image_smoothing(const std::string& s) {
  if (s == "none") return ImageSmoothing::None;
  if (s == "median") return ImageSmoothing::Median;
  if (s == "anisotropic") return ImageSmoothing::CurvatureAnisotropic;
  throw InvalidInputError("smoothing must be 'none', 'median' or 'anisotropic', got '" + s + "'");
}

py::dict report_dict(const ReconstructionReport& r) {
  py::dict d;
  d["slices"] = r.slices;
  d["slices_with_contours"] = r.slices_with_contours;
  d["contours"] = r.contours;
  d["hole_contours"] = r.hole_contours;
  d["threshold"] = r.threshold;
  d["dropped_regions"] = r.dropped_regions;
  d["dropped_components"] = r.dropped_components;
  d["one_to_one"] = r.tiling.one_to_one;
  d["branchings"] = r.tiling.branchings;
  d["caps"] = r.tiling.caps;
  d["dropped_contours"] = r.tiling.dropped_contours;
  d["single_slice_slabs"] = r.single_slice_slabs;
  d["single_slice_cavities"] = r.single_slice_cavities;
  d["single_slice_thinned"] = r.single_slice_thinned;
  d["single_slice_filled"] = r.single_slice_filled;
  d["single_slice_left_out"] = r.single_slice_left_out;
  d["seconds_segment"] = r.seconds_segment;
  d["seconds_tile"] = r.seconds_tile;
  return d;
}

py::tuple reconstruction_tuple(const Reconstruction& r) {
  py::tuple arrays = mesh_to_arrays(r.mesh);
  return py::make_tuple(arrays[0], arrays[1], arrays[2], arrays[3], report_dict(r.report));
}

py::tuple reconstruct_py(const py::object& volume, const py::object& spacing, const py::object& origin,
                         const py::object& direction, double threshold, bool otsu, const py::object& label,
                         double sampling, const std::string& smoothing, const std::string& keep, double min_area,
                         bool fill_holes, const std::string& end_caps, const std::string& flat_crossings,
                         const std::string& single_slice, Index max_vertices, int threads,
                         const py::object& progress) {
  const CtImage::Pointer image = image_from_array(volume, spacing, origin, direction);
  ReconstructionOptions options;
  auto& seg = options.segmentation;
  seg.threshold = threshold;
  seg.threshold_method = otsu ? ThresholdMethod::Otsu : ThresholdMethod::Fixed;
  seg.sampling = sampling;
  seg.smoothing = parse_image_smoothing(smoothing);
  if (keep == "all") seg.components = ComponentSelection::KeepAll;
  else if (keep == "largest") seg.components = ComponentSelection::KeepLargest;
  else throw InvalidInputError("keep must be 'all' or 'largest', got '" + keep + "'");
  seg.min_region_area = min_area;
  seg.fill_holes = fill_holes;
  if (end_caps == "half-spacing") options.tiling.end_caps = EndCaps::HalfSpacing;
  else if (end_caps == "end-slice") options.tiling.end_caps = EndCaps::AtEndSlice;
  else throw InvalidInputError("end_caps must be 'half-spacing' or 'end-slice', got '" + end_caps + "'");
  if (flat_crossings == "patches") seg.flat_crossings = FlatCrossings::Patches;
  else if (flat_crossings == "per-pixel") seg.flat_crossings = FlatCrossings::PerPixel;
  else throw InvalidInputError("flat_crossings must be 'patches' or 'per-pixel', got '" + flat_crossings + "'");
  if (single_slice == "slab") options.single_slice = SingleSliceContours::Slab;
  else if (single_slice == "drop") options.single_slice = SingleSliceContours::Drop;
  else throw InvalidInputError("single_slice must be 'slab' or 'drop', got '" + single_slice + "'");
  if (max_vertices < 1) throw InvalidInputError("max_vertices must be >= 1");
  options.tiling.limits.max_vertices = max_vertices;
  std::optional<std::string> label_spec;
  if (!label.is_none()) {
    if (otsu) throw InvalidInputError("label and otsu exclude each other (a label map is not thresholded)");
    label_spec = py::isinstance<py::str>(label) ? label.cast<std::string>() : std::to_string(as_int(label, "label"));
  }
  ProgressBridge bridge(progress);
  const ThreadLimit limit(threads);
  const Reconstruction r = bridge.run([&] {
    if (!label_spec) return reconstruct(*image, options, bridge.callback());
    const LabelMap map = label_map_from_image(image);
    const std::vector<Label> labels = select_labels(map, *label_spec);
    if (labels.size() != 1) throw InvalidInputError("label: give one label value");
    return reconstruct_label(map, labels.front(), options, bridge.callback());
  });
  return reconstruction_tuple(r);
}

py::list label_list(const LabelMap& map) {
  py::list labels;
  for (const Label& l : map.labels) {
    py::dict d;
    d["value"] = l.value;
    d["layer"] = l.layer;
    d["name"] = l.name;
    d["id"] = l.id;
    d["voxels"] = l.voxels;
    labels.append(d);
  }
  return labels;
}

}  // namespace

void bind_reconstruct(py::module_& m) {
  m.def("_reconstruct", &reconstruct_py, py::arg("volume"), py::arg("spacing"), py::arg("origin"),
        py::arg("direction"), py::arg("threshold"), py::arg("otsu"), py::arg("label"), py::arg("sampling"),
        py::arg("smoothing"), py::arg("keep"), py::arg("min_area"), py::arg("fill_holes"), py::arg("end_caps"),
        py::arg("flat_crossings"), py::arg("single_slice"), py::arg("max_vertices"), py::arg("threads"),
        py::arg("progress"));

  m.def(
      "_read_volume",
      [](const std::string& path, const std::string& series) {
        VolumeReadOptions o;
        o.series_uid = series;
        CtImage::Pointer image;
        {
          py::gil_scoped_release release;
          image = read_volume(path, o);
        }
        return image_to_arrays(*image);
      },
      py::arg("path"), py::arg("series"));

  m.def(
      "_list_series",
      [](const std::string& path) {
        std::vector<DicomSeries> series;
        {
          py::gil_scoped_release release;
          series = list_dicom_series(path);
        }
        py::list out;
        for (const DicomSeries& s : series) {
          py::dict d;
          d["uid"] = s.uid;
          d["number"] = s.number;
          d["modality"] = s.modality;
          d["description"] = s.description;
          d["files"] = s.files;
          out.append(d);
        }
        return out;
      },
      py::arg("path"));

  m.def(
      "_read_label_map",
      [](const std::string& path) {
        LabelMap map;
        {
          py::gil_scoped_release release;
          map = read_label_map(path);
        }
        py::list layers;
        py::tuple geometry;
        for (const CtImage::Pointer& layer : map.layers) {
          py::tuple t = image_to_arrays(*layer);
          layers.append(t[0]);
          geometry = t;
        }
        return py::make_tuple(layers, geometry[1], geometry[2], geometry[3], label_list(map));
      },
      py::arg("path"));

  m.def("phantom_shapes", [] {
    std::vector<std::string> names;
    for (PhantomShape s : all_phantom_shapes()) names.emplace_back(to_string(s));
    for (PhantomShape s : extra_phantom_shapes()) names.emplace_back(to_string(s));
    return names;
  }, "The names of the built-in phantoms, in the order of `contourmesh phantom --shape` (the ten of "
     "`--phantom all`, then the extra ones).");

  m.def(
      "_render_phantom",
      [](const std::string& name, const py::object& spacing, double noise, double blur, double contour_noise,
         std::uint64_t seed, double margin, int threads) {
        const Phantom phantom = make_phantom(parse_phantom_shape(name));
        PhantomVolumeOptions o;
        o.spacing = vector3(spacing, "spacing");
        o.noise = noise;
        o.blur = blur;
        o.contour_noise = contour_noise;
        o.seed = seed;
        o.margin = margin;
        CtImage::Pointer image;
        {
          py::gil_scoped_release release;
          const ThreadLimit limit(threads);
          image = render_phantom(phantom, o);
        }
        return image_to_arrays(*image);
      },
      py::arg("name"), py::arg("spacing"), py::arg("noise"), py::arg("blur"), py::arg("contour_noise"),
      py::arg("seed"), py::arg("margin"), py::arg("threads"));

  py::class_<Phantom, std::shared_ptr<Phantom>>(m, "Phantom", R"doc(
The analytic truth of a built-in phantom (millimetres, slice axis z).

Phantom(name): name is one of phantom_shapes(). sdf(points) and normal(points) evaluate the signed
distance (negative inside) and the outward unit normal at an (n, 3) array of points.)doc")
      .def(py::init([](const std::string& name) {
             return std::make_shared<Phantom>(make_phantom(parse_phantom_shape(name)));
           }),
           py::arg("name"))
      .def_property_readonly("name", [](const Phantom& p) { return std::string(to_string(p.shape)); })
      .def_property_readonly(
          "volume", [](const Phantom& p) { return p.volume; }, "Exact volume of the solid, mm^3.")
      .def_property_readonly("surface_components", [](const Phantom& p) { return p.surface_components; })
      .def_property_readonly("euler_characteristic", [](const Phantom& p) { return p.euler_characteristic; })
      .def_property_readonly(
          "bounds",
          [](const Phantom& p) {
            py::array_t<double> b({py::ssize_t{2}, py::ssize_t{3}});
            for (int d = 0; d < 3; ++d) {
              b.mutable_at(0, d) = p.bounds.min()[d];
              b.mutable_at(1, d) = p.bounds.max()[d];
            }
            return b;
          },
          "Bounding box of the solid: [[xmin, ymin, zmin], [xmax, ymax, zmax]], mm.")
      .def_property_readonly(
          "feature_points",
          [](const Phantom& p) {
            py::array_t<double> a({static_cast<py::ssize_t>(p.feature_points.size()), py::ssize_t{3}});
            for (std::size_t i = 0; i < p.feature_points.size(); ++i) {
              for (int d = 0; d < 3; ++d) a.mutable_at(static_cast<py::ssize_t>(i), d) = p.feature_points[i][d];
            }
            return a;
          },
          "Points along the sharp edges and at the corners, (k, 3).")
      .def(
          "sdf",
          [](const Phantom& p, const py::object& points) {
            const Eigen::Matrix3Xd x = points_from_array(points, "points");
            py::array_t<double> out(x.cols());
            double* o = out.mutable_data();
            {
              py::gil_scoped_release release;
              for (Eigen::Index i = 0; i < x.cols(); ++i) o[i] = p.sdf(x.col(i));
            }
            return out;
          },
          py::arg("points"), "Signed distance (mm, negative inside) at each of the (n, 3) points.")
      .def(
          "__call__", [](const py::object& self, const py::object& points) { return self.attr("sdf")(points); },
          py::arg("points"))
      .def(
          "normal",
          [](const Phantom& p, const py::object& points) {
            const Eigen::Matrix3Xd x = points_from_array(points, "points");
            py::array_t<double> out({static_cast<py::ssize_t>(x.cols()), py::ssize_t{3}});
            double* o = out.mutable_data();
            {
              py::gil_scoped_release release;
              for (Eigen::Index i = 0; i < x.cols(); ++i) {
                const Eigen::Vector3d nrm = p.normal(x.col(i));
                for (int d = 0; d < 3; ++d) o[3 * i + d] = nrm[d];
              }
            }
            return out;
          },
          py::arg("points"), "Outward unit normal at each of the (n, 3) points.")
      .def("__repr__", [](const Phantom& p) { return "Phantom('" + std::string(to_string(p.shape)) + "')"; });
}

}  // namespace contourmesh::python
