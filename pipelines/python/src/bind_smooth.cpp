// Python bindings: smoothing (every method) and the paper's feature detection.
#include "bindings.h"
#include "bridge.h"

#include <reconstruct/threads.h>
#include <smooth/adjacency.h>
#include <smooth/contour_structure.h>
#include <smooth/cross_slice.h>
#include <smooth/errors.h>
#include <smooth/feature_detection.h>
#include <smooth/feature_smoothing.h>
#include <smooth/limits.h>
#include <smooth/smoothing.h>

#include <pybind11/stl.h>

#include <chrono>
#include <functional>
#include <map>
#include <set>
#include <type_traits>
#include <variant>

namespace contourmesh::python {

namespace {

// The methods by their command-line names. kDefaultMethod is the command line's default.
enum class Method { Paper, CrossSlice, None, Laplacian, Taubin, Mcf, MinDist };
constexpr const char* kDefaultMethod = "paper";

Method parse_method(const std::string& name) {
  static const std::map<std::string, Method> names{
      {"paper", Method::Paper},     {"cross-slice", Method::CrossSlice}, {"none", Method::None},
      {"laplacian", Method::Laplacian}, {"taubin", Method::Taubin},      {"mcf", Method::Mcf},
      {"mindist", Method::MinDist}};
  const auto it = names.find(name);
  if (it == names.end()) {
    throw InvalidInputError("method must be paper, cross-slice, none, laplacian, taubin, mcf or mindist, got '" + name +
                            "'");
  }
  return it->second;
}

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
  void finish() const {
    if (values_.empty()) return;
    std::string names;
    for (const auto& [name, value] : values_) names += (names.empty() ? "" : ", ") + name;
    throw InvalidInputError("option" + std::string(values_.size() == 1 ? " " : "s ") + names + " not known to method '" +
                            method_ + "'");
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
  for (std::size_t i = 0; i < labels.size(); ++i) a.mutable_at(static_cast<py::ssize_t>(i)) = static_cast<std::uint8_t>(labels[i]);
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

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

py::tuple smooth_py(const py::object& points, const py::object& triangles, const py::object& slice_ids,
                    const py::object& contour_ids, const py::object& method_arg, const py::object& progress,
                    int threads, Index max_vertices, const py::dict& kwargs) {
  const std::string method_name = method_arg.is_none() ? kDefaultMethod : as_string(method_arg, "method");
  const Method method = parse_method(method_name);
  Mesh mesh = mesh_from_arrays(points, triangles, slice_ids, contour_ids);
  if (max_vertices < 1) throw InvalidInputError("max_vertices must be >= 1");
  if (mesh.num_vertices() > max_vertices) {
    throw LimitError("the mesh has " + std::to_string(mesh.num_vertices()) + " vertices, over the limit of " +
                     std::to_string(max_vertices) + " (max_vertices)");
  }
  Options o(kwargs, method_name);
  // What the method did, filled while the GIL is released and turned into a dict afterwards.
  std::vector<std::pair<std::string, std::variant<double, long long>>> facts;
  const auto fact = [&facts](const char* name, auto value) {
    if constexpr (std::is_floating_point_v<decltype(value)>) facts.emplace_back(name, static_cast<double>(value));
    else facts.emplace_back(name, static_cast<long long>(value));
  };
  ProgressBridge bridge(progress);
  std::function<void()> work;
  Mesh result;
  std::optional<std::vector<VertexLabel>> labels;
  switch (method) {
    case Method::Paper: {
      auto fo = std::make_shared<FeatureSmoothingOptions>();
      take_slice_axis(o, mesh);
      take_detection(o, fo->detection);
      o.take_int("iterations", fo->iterations);
      o.take_double("lambda", fo->lambda);
      o.take_double("mu", fo->mu);
      o.take_int("max_levels", fo->max_levels);
      o.take("diffusion", [&](const py::object& v) {
        const std::string s = as_string(v, "diffusion");
        if (s != "taubin" && s != "laplacian") throw InvalidInputError("diffusion must be 'taubin' or 'laplacian', got '" + s + "'");
        fo->diffusion = parse_smoothing_method(s);
      });
      o.take("keep_adaptive", [&](const py::object& v) {
        fo->output = v.cast<bool>() ? OutputResolution::Adaptive : OutputResolution::Original;
      });
      o.take("boundary", [&](const py::object& v) { fo->boundary = parse_boundary(as_string(v, "boundary")); });
      o.finish();
      fo->progress = bridge.callback();
      fo->limits.max_vertices = max_vertices;
      work = [&, fo] {
        FeatureSmoothingResult r = feature_preserving_smooth(mesh, *fo);
        result = std::move(r.mesh);
        labels = r.detection.labels;
        fact("iterations", fo->iterations);
        fact("edges", r.detection.edges);
        fact("corners", r.detection.corners);
        fact("noise", r.detection.noise);
        fact("gamma", r.detection.gamma);
        fact("subdivided_vertices", r.subdivided_vertices);
        fact("adaptive_vertices", r.adaptive_vertices);
        fact("seconds_detect", r.seconds.detect);
        fact("seconds_subdivide", r.seconds.subdivide);
        fact("seconds_smooth", r.seconds.smooth);
        fact("seconds", r.seconds.total);
      };
      break;
    }
    case Method::CrossSlice: {
      auto co = std::make_shared<CrossSliceOptions>();
      take_slice_axis(o, mesh);
      o.take_int("reach", co->reach);
      o.take_int("along_reach", co->along_reach);
      o.take_double("gamma", co->gamma);
      o.take_double("noise_across", co->noise_across);
      o.take_double("noise_along", co->noise_along);
      o.take_int("extension_iterations", co->extension_iterations);
      o.take("stages", [&](const py::object& v) {
        const std::string s = as_string(v, "stages");
        if (s == "across-then-along") co->stages = CrossSliceStages::AcrossThenAlong;
        else if (s == "across-only") co->stages = CrossSliceStages::AcrossOnly;
        else throw InvalidInputError("stages must be 'across-then-along' or 'across-only', got '" + s + "'");
      });
      o.finish();
      co->progress = bridge.callback();
      work = [&, co] {
        CrossSliceResult r = cross_slice_smooth(mesh, *co);
        result = std::move(r.mesh);
        labels = std::move(r.labels);
        fact("noise_across", r.noise_across);
        fact("noise_along", r.noise_along);
        fact("profiles", r.profiles);
        fact("seconds_detect", r.seconds_detect);
        fact("seconds_smooth", r.seconds_smooth);
        fact("seconds", r.seconds_total);
      };
      break;
    }
    default: {
      auto so = std::make_shared<SmoothingOptions>();
      switch (method) {
        case Method::None: so->method = SmoothingMethod::None; break;
        case Method::Laplacian: so->method = SmoothingMethod::Laplacian; break;
        case Method::Taubin: so->method = SmoothingMethod::Taubin; break;
        case Method::Mcf: so->method = SmoothingMethod::MeanCurvatureFlow; break;
        default: so->method = SmoothingMethod::MinDistFlow; break;
      }
      if (method != Method::None) {
        o.take_int("iterations", so->iterations);
        o.take_double("lambda", so->lambda);
        o.take("boundary", [&](const py::object& v) { so->boundary = parse_boundary(as_string(v, "boundary")); });
      }
      if (method == Method::Taubin) o.take_double("mu", so->mu);
      if (method == Method::MinDist) o.take_double("beta", so->beta);
      o.finish();
      so->progress = bridge.callback();
      work = [&, so] {
        const auto t = std::chrono::steady_clock::now();
        result = mesh;
        result.positions = smooth(mesh, *so);
        fact("iterations", so->method == SmoothingMethod::None ? 0 : so->iterations);
        fact("lambda", so->lambda.value_or(default_lambda(so->method)));
        fact("seconds", seconds_since(t));
      };
      break;
    }
  }
  {
    const ThreadLimit limit(threads);
    bridge.run([&] { work(); });
  }
  py::dict report;
  report["method"] = method_name;
  for (const auto& [name, value] : facts) {
    std::visit([&, &key = name](auto v) { report[py::str(key)] = v; }, value);
  }
  py::tuple arrays = mesh_to_arrays(result);
  return py::make_tuple(arrays[0], arrays[1], arrays[2], arrays[3],
                        labels ? py::object(labels_array(*labels)) : py::object(py::none()), report);
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
  m.attr("DEFAULT_METHOD") = kDefaultMethod;
  m.def("_smooth", &smooth_py, py::arg("points"), py::arg("triangles"), py::arg("slice_ids"), py::arg("contour_ids"),
        py::arg("method"), py::arg("progress"), py::arg("threads"), py::arg("max_vertices"), py::arg("options"));
  m.def("_detect", &detect_py, py::arg("points"), py::arg("triangles"), py::arg("slice_ids"), py::arg("contour_ids"),
        py::arg("progress"), py::arg("options"));
}

}  // namespace contourmesh::python
