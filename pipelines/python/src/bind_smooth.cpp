// SPDX-License-Identifier: BSD-3-Clause
// Python bindings: smoothing (every method, through libsmooth's one entry point smooth()) and the paper's
// feature detection.
#include "bindings.h"
#include "bridge.h"

#include <contourmesh/reconstruct/threads.h>
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/contour_structure.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/feature_detection.h>
#include <contourmesh/smooth/limits.h>
#include <contourmesh/smooth/smooth.h>

#include <pybind11/stl.h>

#include <map>

namespace contourmesh::python {

namespace {

// The default method: the default preset's, as on the command line.
std::string default_method() { return std::string(to_string(preset(Preset::Default).method)); }

// Keyword options, consumed one by one; what is left at the end is an error naming it.
class Options {
 public:
  Options(const py::dict& kwargs, std::string method) : method_(std::move(method)) {
    for (const auto& [key, value] : kwargs) {
      std::string name = py::str(key);
      if (name == "lambda_") name = "lambda";
      values_[name] = py::reinterpret_borrow<py::object>(value);
    }
  }
  template <class Apply>
  void take(const std::string& name, Apply&& apply) {
    const auto it = values_.find(name);
    if (it == values_.end()) return;
    if (!it->second.is_none()) apply(it->second);
    values_.erase(it);
  }
  void take_double(const std::string& name, double& target) {
    take(name, [&](const py::object& v) { target = as_double(v, name); });
  }
  void take_double(const std::string& name, std::optional<double>& target) {
    take(name, [&](const py::object& v) { target = as_double(v, name); });
  }
  void take_int(const std::string& name, int& target) {
    take(name, [&](const py::object& v) { target = as_int(v, name); });
  }
  void take_int(const std::string& name, std::optional<int>& target) {
    take(name, [&](const py::object& v) { target = as_int(v, name); });
  }
  /// The method named in the error of finish(), once it is known.
  void set_method(std::string method) { method_ = std::move(method); }
  void finish() const {
    if (values_.empty()) return;
    std::string names;
    for (const auto& [name, value] : values_) names += (names.empty() ? "" : ", ") + name;
    throw InvalidInputError("option" + std::string(values_.size() == 1 ? " " : "s ") + names +
                            " not known to method '" + method_ + "'");
  }

 private:
  std::map<std::string, py::object> values_;
  std::string method_;
};

BoundaryPolicy parse_boundary(const std::string& s) {
  if (s == "fixed") return BoundaryPolicy::Fixed;
  if (s == "free") return BoundaryPolicy::Free;
  throw InvalidInputError("boundary must be 'fixed' or 'free', got '" + s + "'");
}

// The detection options of the paper's method and of detect(): the CLI's --gamma ... --corner-spread.
void take_detection(Options& o, DetectionOptions& d) {
  o.take_double("gamma", d.gamma);
  o.take_double("delta", d.delta);
  o.take("measure", [&](const py::object& v) {
    const std::string s = as_string(v, "measure");
    if (s == "length") d.measure = UmbrellaMeasure::Length;
    else if (s == "normal") d.measure = UmbrellaMeasure::NormalComponent;
    else throw InvalidInputError("measure must be 'length' or 'normal', got '" + s + "'");
  });
  o.take("in_slice", [&](const py::object& v) {
    const std::string s = as_string(v, "in_slice");
    if (s == "noise") d.in_slice = InSliceFeatures::Noise;
    else if (s == "along-line") d.in_slice = InSliceFeatures::AlongFeatureLine;
    else throw InvalidInputError("in_slice must be 'noise' or 'along-line', got '" + s + "'");
  });
  o.take_int("prefilter", d.prefilter_iterations);
  o.take_int("window", d.window);
  o.take_double("corner_spread", d.corner_spread);
}

// slice_axis="x"|"y"|"z": ids recovered from the slice planes for a mesh given without them.
void take_slice_axis(Options& o, Mesh& mesh) {
  o.take("slice_axis", [&](const py::object& v) {
    const std::string s = as_string(v, "slice_axis");
    Eigen::Vector3d axis;
    if (s == "x") axis = Eigen::Vector3d::UnitX();
    else if (s == "y") axis = Eigen::Vector3d::UnitY();
    else if (s == "z") axis = Eigen::Vector3d::UnitZ();
    else throw InvalidInputError("slice_axis must be 'x', 'y' or 'z', got '" + s + "'");
    if (mesh.has_contour_ids()) return;
    if (!assign_ids_by_slice_planes(mesh, build_adjacency(mesh), axis)) {
      throw InvalidInputError("slice_axis='" + s + "': the points do not lie on planes normal to that axis");
    }
  });
}

py::array_t<std::uint8_t> labels_array(const std::vector<VertexLabel>& labels) {
  py::array_t<std::uint8_t> a(static_cast<py::ssize_t>(labels.size()));
  for (std::size_t i = 0; i < labels.size(); ++i)
    a.mutable_at(static_cast<py::ssize_t>(i)) = static_cast<std::uint8_t>(labels[i]);
  return a;
}

py::array_t<double> vector_array(const Eigen::VectorXd& v) {
  py::array_t<double> a(v.size());
  std::copy(v.data(), v.data() + v.size(), a.mutable_data());
  return a;
}

py::dict detection_dict(const FeatureDetection& d) {
  py::dict out;
  out["labels"] = labels_array(d.labels);
  out["umbrella"] = vector_array(d.umbrella);
  out["kappa_min"] = vector_array(d.curvature.kappa_min);
  out["kappa_max"] = vector_array(d.curvature.kappa_max);
  out["k_below"] = vector_array(d.k_below);
  out["k0"] = vector_array(d.k0);
  out["k_above"] = vector_array(d.k_above);
  out["psi"] = vector_array(d.psi);
  out["gamma"] = d.gamma;
  out["candidates"] = d.candidates;
  out["edges"] = d.edges;
  out["corners"] = d.corners;
  out["noise"] = d.noise;
  return out;
}

// The method and its options: `method`, else the preset given as the option `preset` (default: the
// default preset), then the options the method knows; an option it does not know is an error.
MethodConfig method_config(const py::object& method_arg, Options& o, Mesh& mesh) {
  std::optional<std::string> preset_name;
  o.take("preset", [&](const py::object& v) { preset_name = as_string(v, "preset"); });
  MethodConfig c;
  if (!method_arg.is_none()) {
    if (preset_name) throw InvalidInputError("give a method or a preset, not both");
    c.method = parse_smoothing_method(as_string(method_arg, "method"));
  } else {
    c = preset(preset_name ? parse_preset(*preset_name) : Preset::Default);
  }
  SmoothOptions& so = c.options;
  const SmoothingMethod m = c.method;
  o.set_method(std::string(to_string(m)));
  if (m == SmoothingMethod::FeaturePreserving || m == SmoothingMethod::CrossSlice) take_slice_axis(o, mesh);
  if (m != SmoothingMethod::None && m != SmoothingMethod::CrossSlice) {
    o.take_int("iterations", so.iterations);
  }
  if (m == SmoothingMethod::FeaturePreserving) {
    FeatureSmoothingOptions& fo = so.paper;
    take_detection(o, fo.detection);
    o.take_double("lambda", fo.lambda);
    o.take_double("mu", fo.mu);
    o.take_int("max_levels", fo.max_levels);
    o.take("diffusion", [&](const py::object& v) {
      const std::string s = as_string(v, "diffusion");
      if (s != "taubin" && s != "laplacian")
        throw InvalidInputError("diffusion must be 'taubin' or 'laplacian', got '" + s + "'");
      fo.diffusion = parse_smoothing_method(s);
    });
    o.take("keep_adaptive", [&](const py::object& v) {
      fo.output = v.cast<bool>() ? OutputResolution::Adaptive : OutputResolution::Original;
    });
    o.take("boundary", [&](const py::object& v) { fo.boundary = parse_boundary(as_string(v, "boundary")); });
  } else if (m == SmoothingMethod::CrossSlice) {
    CrossSliceOptions& co = so.cross_slice;
    o.take_int("reach", co.reach);
    o.take_int("along_reach", co.along_reach);
    o.take_double("gamma", co.gamma);
    o.take_double("precise_noise", co.precise_noise);
    o.take_double("noisy_reach_length", co.noisy_reach_length);
    o.take_double("noise_across", co.noise_across);
    o.take_double("noise_along", co.noise_along);
    o.take_double("min_profile_share", co.min_profile_share);
    o.take_int("extension_iterations", co.extension_iterations);
    o.take("creases", [&](const py::object& v) {
      const std::string s = as_string(v, "creases");
      if (s == "none") co.crease_restoration = CreaseRestoration::None;
      else if (s == "restore") co.crease_restoration = CreaseRestoration::Subdivide;
      else throw InvalidInputError("creases must be 'none' or 'restore', got '" + s + "'");
    });
    o.take("profile_model", [&](const py::object& v) {
      const std::string s = as_string(v, "profile_model");
      if (s == "parabola") co.across_model = ProfileModel::Parabola;
      else if (s == "circle") co.across_model = ProfileModel::Circle;
      else throw InvalidInputError("profile_model must be 'parabola' or 'circle', got '" + s + "'");
    });
    o.take("kinks", [&](const py::object& v) {
      const std::string s = as_string(v, "kinks");
      if (s == "ignore") co.across_kinks = ProfileKinks::Ignore;
      else if (s == "bound") co.across_kinks = ProfileKinks::Bound;
      else throw InvalidInputError("kinks must be 'ignore' or 'bound', got '" + s + "'");
    });
    o.take_double("kink_rate", co.kink_false_rate);
    o.take("kink_sides", [&](const py::object& v) {
      const std::string s = as_string(v, "kink_sides");
      if (s == "curves") co.kink_sides = KinkSides::Curves;
      else if (s == "lines") co.kink_sides = KinkSides::Lines;
      else throw InvalidInputError("kink_sides must be 'curves' or 'lines', got '" + s + "'");
    });
    o.take("stages", [&](const py::object& v) {
      const std::string s = as_string(v, "stages");
      if (s == "across-then-along") co.stages = CrossSliceStages::AcrossThenAlong;
      else if (s == "across-only") co.stages = CrossSliceStages::AcrossOnly;
      else throw InvalidInputError("stages must be 'across-then-along' or 'across-only', got '" + s + "'");
    });
    OffSliceFilterOptions& fo = co.off_slice;
    o.take("off_slice_filter", [&](const py::object& v) {
      const std::string s = as_string(v, "off_slice_filter");
      if (s == "bilateral") fo.filter = OffSliceFilter::BilateralNormals;
      else if (s == "none") fo.filter = OffSliceFilter::None;
      else throw InvalidInputError("off_slice_filter must be 'bilateral' or 'none', got '" + s + "'");
    });
    o.take("off_slice_motion", [&](const py::object& v) {
      const std::string s = as_string(v, "off_slice_motion");
      if (s == "free") fo.motion = OffSliceMotion::Free;
      else if (s == "axis") fo.motion = OffSliceMotion::AlongAxis;
      else throw InvalidInputError("off_slice_motion must be 'free' or 'axis', got '" + s + "'");
    });
    o.take("off_slice_range", [&](const py::object& v) {
      const std::string s = as_string(v, "off_slice_range");
      if (s == "faces") fo.range = OffSliceRange::FaceNormals;
      else if (s == "patches") fo.range = OffSliceRange::PatchGuidance;
      else throw InvalidInputError("off_slice_range must be 'faces' or 'patches', got '" + s + "'");
    });
    o.take("off_slice_volume", [&](const py::object& v) {
      const std::string s = as_string(v, "off_slice_volume");
      if (s == "free") fo.volume = OffSliceVolume::Free;
      else if (s == "preserve") fo.volume = OffSliceVolume::Preserve;
      else throw InvalidInputError("off_slice_volume must be 'free' or 'preserve', got '" + s + "'");
    });
    o.take_int("normal_iterations", fo.normal_iterations);
    o.take_double("normal_sigma", fo.sigma_angle_degrees);
    o.take_int("guidance_interval", fo.guidance_interval);
    o.take_int("rim_iterations", fo.rim_iterations);
    o.take_double("rim_angle", fo.rim_angle_degrees);
    o.take_int("rim_rings", fo.rim_rings);
    o.take_int("vertex_iterations", fo.vertex_iterations);
    o.take_double("vertex_step", fo.vertex_step);
    o.take_double("max_move", fo.max_move);
    o.take_double("contour_max_move", fo.contour_max_move);
  } else if (m != SmoothingMethod::None) {
    SmoothingOptions& bo = so.baseline;
    o.take_double("lambda", bo.lambda);
    o.take("boundary", [&](const py::object& v) { bo.boundary = parse_boundary(as_string(v, "boundary")); });
    if (m == SmoothingMethod::Taubin) o.take_double("mu", bo.mu);
    if (m == SmoothingMethod::MinDistFlow) o.take_double("beta", bo.beta);
  }
  o.finish();
  return c;
}

// What the method did, by name (the keys docs/python.md lists for each method).
py::dict smooth_report(const SmoothResult& r, const MethodConfig& c) {
  py::dict d;
  d["method"] = std::string(to_string(r.method));
  if (default_iterations(r.method) > 0) d["iterations"] = r.iterations;
  if (is_baseline(r.method) && r.method != SmoothingMethod::None) {
    d["lambda"] = c.options.baseline.lambda.value_or(default_lambda(r.method));
  }
  if (!r.labels.empty()) {
    std::size_t edges = 0, corners = 0, noise = 0;
    for (VertexLabel l : r.labels) {
      edges += l == VertexLabel::Edge;
      corners += l == VertexLabel::Corner;
      noise += l == VertexLabel::Noise;
    }
    d["edges"] = edges;
    d["corners"] = corners;
    d["noise"] = noise;
    d["seconds_detect"] = r.seconds.detect;
    d["seconds_smooth"] = r.seconds.smooth;
  }
  if (r.detection) d["gamma"] = r.detection->gamma;
  if (r.method == SmoothingMethod::FeaturePreserving) {
    d["subdivided_vertices"] = r.subdivided_vertices;
    d["adaptive_vertices"] = r.adaptive_vertices;
    d["seconds_subdivide"] = r.seconds.subdivide;
  }
  if (r.method == SmoothingMethod::CrossSlice) {
    d["noise_across"] = r.noise_across;
    d["noise_along"] = r.noise_along;
    d["noise_across_from"] = std::string(to_string(r.noise_across_source));
    d["profiles"] = r.profiles;
  }
  d["seconds"] = r.seconds.total;
  return d;
}

py::tuple smooth_py(const py::object& points, const py::object& triangles, const py::object& slice_ids,
                    const py::object& contour_ids, const py::object& method_arg, const py::object& progress,
                    int threads, Index max_vertices, const py::dict& kwargs) {
  Mesh mesh = mesh_from_arrays(points, triangles, slice_ids, contour_ids);
  if (max_vertices < 1) throw InvalidInputError("max_vertices must be >= 1");
  Options o(kwargs, "");
  MethodConfig config = method_config(method_arg, o, mesh);
  config.options.limits.max_vertices = max_vertices;
  if (mesh.num_vertices() > max_vertices) {
    throw LimitError("the mesh has " + std::to_string(mesh.num_vertices()) + " vertices, over the limit of " +
                     std::to_string(max_vertices) + " (max_vertices)");
  }
  ProgressBridge bridge(progress);
  config.options.progress = bridge.callback();
  SmoothResult result;
  {
    const ThreadLimit limit(threads);
    bridge.run([&] { result = smooth(mesh, config.method, config.options); });
  }
  py::tuple arrays = mesh_to_arrays(result.mesh);
  return py::make_tuple(arrays[0], arrays[1], arrays[2], arrays[3],
                        result.labels.empty() ? py::object(py::none()) : py::object(labels_array(result.labels)),
                        smooth_report(result, config));
}

py::dict detect_py(const py::object& points, const py::object& triangles, const py::object& slice_ids,
                   const py::object& contour_ids, const py::object& progress, const py::dict& kwargs) {
  Mesh mesh = mesh_from_arrays(points, triangles, slice_ids, contour_ids);
  Options o(kwargs, "detect");
  DetectionOptions d;
  take_slice_axis(o, mesh);
  take_detection(o, d);
  o.take("mode", [&](const py::object& v) {
    const std::string s = as_string(v, "mode");
    if (s == "contour-continuity") d.mode = DetectionMode::ContourContinuity;
    else if (s == "curvature-only") d.mode = DetectionMode::CurvatureOnly;
    else throw InvalidInputError("mode must be 'contour-continuity' or 'curvature-only', got '" + s + "'");
  });
  o.finish();
  ProgressBridge bridge(progress);
  const ProgressCallback callback = bridge.callback();
  const FeatureDetection result = bridge.run([&] {
    if (callback && !callback("detect", 0.0)) throw CancelledError("detect");
    const MeshAdjacency adjacency = build_adjacency(mesh);
    FeatureDetection r = detect_features(mesh, adjacency, d);
    if (callback && !callback("detect", 1.0)) throw CancelledError("detect");
    return r;
  });
  return detection_dict(result);
}

}  // namespace

void bind_smooth(py::module_& m) {
  m.attr("DEFAULT_METHOD") = default_method();
  m.def("_smooth", &smooth_py, py::arg("points"), py::arg("triangles"), py::arg("slice_ids"), py::arg("contour_ids"),
        py::arg("method"), py::arg("progress"), py::arg("threads"), py::arg("max_vertices"), py::arg("options"));
  m.def("_detect", &detect_py, py::arg("points"), py::arg("triangles"), py::arg("slice_ids"), py::arg("contour_ids"),
        py::arg("progress"), py::arg("options"));
}

}  // namespace contourmesh::python
