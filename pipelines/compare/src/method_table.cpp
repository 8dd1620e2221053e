// SPDX-License-Identifier: BSD-3-Clause
#include "compare/method_table.h"

#include "timing.h"
#include "vtk_methods.h"

#include <contourmesh/vtk/vtk_convert.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/metrics.h>

#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace contourmesh {

using namespace compare_detail;

std::string_view to_string(ExternalMethod method) {
  switch (method) {
    case ExternalMethod::VtkWindowedSinc: return "vtk-windowed-sinc";
    case ExternalMethod::VtkSmoothFeatureEdges: return "vtk-smooth-feature-edges";
    case ExternalMethod::VoxelFlyingEdges: return "voxel-flying-edges";
    case ExternalMethod::VoxelWindowedSinc: return "voxel-windowed-sinc";
  }
  return "unknown";
}

std::string_view to_string(Route route) { return route == Route::Voxel ? "voxel" : "contour"; }

namespace {

// Stage records of a libsmooth result, in the order the method runs them.
void record_stages(SmoothingMethod method, const SmoothResult& r, const StageRecorder& record) {
  switch (method) {
    case SmoothingMethod::FeaturePreserving:
      record("detect", r.seconds.detect);
      record("subdivide", r.seconds.subdivide);
      record("smooth", r.seconds.smooth);
      break;
    case SmoothingMethod::CrossSlice:
      record("smooth", r.seconds.smooth);
      record("detect", r.seconds.detect);
      break;
    default:
      record("smooth", r.seconds.total);  // with the adjacency, part of the cost as inside VTK's filters
  }
}

MethodOutput run_library(SmoothingMethod method, const SmoothOptions& base, const MethodContext& ctx) {
  const Mesh& mesh = ctx.contour_mesh;
  SmoothOptions o = base;
  o.limits = ctx.limits;
  o.progress = ctx.progress;
  MethodOutput out;
  out.volume_input = enclosed_volume(mesh);
  SmoothResult r;
  out.seconds = timed(ctx.timing_repeats, [&](const StageRecorder& record) {
    r = smooth(mesh, method, o);
    record_stages(method, r, record);
  });
  out.iterations = r.iterations;
  if (!r.labels.empty()) out.labels = FeatureLabels{r.labels, r.detection, r.creases, r.seconds.detect};
  out.subdivided_vertices = r.subdivided_vertices;
  out.adaptive_vertices = r.adaptive_vertices;
  const bool iterative = r.iterations > 0 && (is_baseline(method) || method == SmoothingMethod::FeaturePreserving);
  if (ctx.volume_curves && iterative) {
    // A rerun with an observer, untimed: the rate after every iteration (the input's vertices only).
    const double v0 = out.volume_input;
    out.volume_curve = {0.0};
    const IterationObserver observe = [&](int, const Eigen::Matrix3Xd& positions) {
      out.volume_curve.push_back(
          volume_shrinking_rate(v0, enclosed_volume(positions.leftCols(mesh.num_vertices()), mesh.triangles)));
    };
    SmoothOptions curve = o;
    curve.progress = {};
    curve.baseline.on_iteration = observe;
    curve.paper.on_iteration = observe;
    (void)smooth(mesh, method, curve);
  }
  out.mesh = std::move(r.mesh);
  return out;
}

MethodOutput run_vtk_windowed_sinc(const MethodContext& ctx, int iterations, double passband) {
  MethodOutput out;
  const vtkSmartPointer<vtkPolyData> poly = to_polydata(ctx.contour_mesh);
  vtkSmartPointer<vtkPolyData> result;
  out.seconds = timed(ctx.timing_repeats, [&](const StageRecorder& record) {
    const auto t = Clock::now();
    result = windowed_sinc(poly, iterations, passband);
    record("smooth", seconds_since(t));
  });
  out.mesh = ctx.contour_mesh;
  out.mesh.positions = positions_of(result);
  out.volume_input = enclosed_volume(ctx.contour_mesh);
  out.iterations = iterations;
  return out;
}

MethodOutput run_vtk_smooth(const MethodContext& ctx, int iterations, const MethodTableOptions& o) {
  MethodOutput out;
  const vtkSmartPointer<vtkPolyData> poly = to_polydata(ctx.contour_mesh);
  const auto filter = [&](int k) {
    return smooth_polydata(poly, k, o.laplace_relaxation, o.laplace_feature_angle, o.laplace_edge_angle);
  };
  vtkSmartPointer<vtkPolyData> result;
  out.seconds = timed(ctx.timing_repeats, [&](const StageRecorder& record) {
    const auto t = Clock::now();
    result = filter(iterations);
    record("smooth", seconds_since(t));
  });
  out.mesh = ctx.contour_mesh;
  out.mesh.positions = positions_of(result);
  out.volume_input = enclosed_volume(ctx.contour_mesh);
  out.iterations = iterations;
  if (ctx.volume_curves) {
    // VTK's filter has no observer: one run per iteration count.
    out.volume_curve = {0.0};
    for (int k = 1; k <= iterations; ++k) {
      out.volume_curve.push_back(volume_shrinking_rate(
          out.volume_input, enclosed_volume(positions_of(filter(k)), ctx.contour_mesh.triangles)));
    }
  }
  return out;
}

MethodOutput run_voxel(const MethodContext& ctx, bool smoothed, int iterations, double passband,
                       const std::string& id) {
  const VoxelSurface v = voxel_route(ctx.image, ctx.reconstruction.segmentation.threshold,
                                     ctx.reconstruction.min_component_voxels, iterations, passband, ctx.timing_repeats,
                                     ctx.progress, id);
  MethodOutput out;
  out.volume_input = enclosed_volume(v.raw);
  if (smoothed) {
    out.mesh = v.smoothed;
    out.seconds = v.seconds;
    out.iterations = iterations;
  } else {
    out.mesh = v.raw;
    double total = 0.0;
    for (const auto& [stage, seconds] : v.seconds) {
      if (stage == "threshold" || stage == "surface") {
        out.seconds.emplace_back(stage, seconds);
        total += seconds;
      }
    }
    out.seconds.emplace_back("total", total);
  }
  return out;
}

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string baseline_settings(SmoothingMethod m, const SmoothOptions& o) {
  if (m == SmoothingMethod::None) return "the reconstructed contour mesh, unsmoothed";
  std::ostringstream s;
  s << iterations_of(m, o) << " iterations, lambda " << o.baseline.lambda.value_or(default_lambda(m));
  if (m == SmoothingMethod::Taubin) s << ", mu " << o.baseline.mu;
  if (m == SmoothingMethod::MinDistFlow) s << ", beta " << o.baseline.beta;
  return s.str();
}

std::string paper_settings(const SmoothOptions& o) {
  const FeatureSmoothingOptions& p = o.paper;
  const DetectionOptions& d = p.detection;
  std::ostringstream s;
  s << "Algorithm 1: detection by " << (d.measure == UmbrellaMeasure::Length ? "|U|" : "|U.n|") << " > "
    << d.gamma_factor << " x its mean, window " << d.window << ", in-slice lines "
    << (d.in_slice == InSliceFeatures::Noise ? "noise (the paper's rule)" : "followed along the line")
    << (d.corner_spread > 1.0 / 3.0 ? ", corners by the umbilic vote only"
                                    : ", corner-spread rule " + number(d.corner_spread))
    << "; up to " << p.max_levels << " subdivision levels; " << to_string(p.diffusion) << " "
    << p.lambda.value_or(default_lambda(p.diffusion)) << " / " << p.mu << ", "
    << iterations_of(SmoothingMethod::FeaturePreserving, o) << " iterations";
  return s.str();
}

// The off-slice stage's part of the cross-slice description (empty when it is off).
std::string off_slice_settings(const OffSliceFilterOptions& f) {
  if (f.filter != OffSliceFilter::BilateralNormals) return {};
  std::string s = "; vertices between the slices fitted to bilaterally filtered normals (" +
                  std::to_string(f.normal_iterations) + " iterations, " + number(f.sigma_angle_degrees) + " degrees";
  if (f.range == OffSliceRange::PatchGuidance) {
    s += ", range on guidance normals";
    if (f.guidance_interval > 1) s += " computed every " + std::to_string(f.guidance_interval) + " iterations";
  }
  if (f.rim_iterations > 0) {
    s += ", " + std::to_string(f.rim_iterations) + " more at rims of " + number(f.rim_angle_degrees) + " degrees";
  }
  return s + "; " + std::to_string(f.vertex_iterations) + " vertex steps of " + number(f.vertex_step) + ")";
}

std::string cross_slice_settings(const SmoothOptions& o) {
  const CrossSliceOptions& c = o.cross_slice;
  std::ostringstream s;
  const std::string noisy_reach = c.noisy_reach_length > 0.0
                                      ? "about " + number(c.noisy_reach_length) + " mm (at least 8 slices)"
                                      : std::string("8 slices");
  s << "profiles across "
    << (c.reach ? std::to_string(*c.reach) + " slices each way"
                : "4 slices each way (noise below " + number(c.precise_noise) + " mm) or " + noisy_reach)
    << (c.stages == CrossSliceStages::AcrossThenAlong
            ? ", then along " + std::to_string(c.along_reach) + " contour vertices each way"
            : " only")
    << ", LPA-ICI windows (gamma " << c.gamma << ", "
    << (c.across_model == ProfileModel::Circle ? "circles" : "parabolas") << " across"
    << (c.across_kinks == ProfileKinks::Bound ? ", bounded at slope breaks, false rate " + number(c.kink_false_rate) +
                                                    (c.kink_sides == KinkSides::Lines ? ", lines beside them" : "")
                                              : std::string())
    << ") for a noise level "
    << (c.noise_across ? number(*c.noise_across) + " mm" : std::string("estimated from the mesh"))
    << off_slice_settings(c.off_slice) << "; labels: creases of the result (radius " << c.features.radius << " mm"
    << (c.features.confirm == CreaseConfirmation::Ball ? ", confirmed over " + number(c.features.confirm_radius) + " mm"
                                                       : std::string())
    << ", band " << c.features.band << " mm)"
    << (c.features.link_radius > 0.0
            ? ", lines linked across adjacent slices within " + number(c.features.link_radius) + " mm"
            : std::string());
  return s.str();
}

std::string settings_of(SmoothingMethod m, const SmoothOptions& o) {
  if (m == SmoothingMethod::FeaturePreserving) return paper_settings(o);
  if (m == SmoothingMethod::CrossSlice) return cross_slice_settings(o);
  return baseline_settings(m, o);
}

MethodSpec library_row(SmoothingMethod m, SmoothOptions options, std::string id, std::string title, std::string legend,
                       std::array<double, 3> colour, std::string preset) {
  MethodSpec s;
  s.key = m;
  s.id = std::move(id);
  s.title = std::move(title);
  s.legend = std::move(legend);
  s.colour = colour;
  s.route = Route::Contour;
  s.settings = settings_of(m, options);
  if (!preset.empty()) s.settings = "the " + preset + " preset: " + s.settings;
  s.options = options;
  s.preset = std::move(preset);
  s.run = [m, options](const MethodContext& ctx) { return run_library(m, options, ctx); };
  return s;
}

MethodSpec external_row(ExternalMethod m, std::string title, std::string legend, std::array<double, 3> colour,
                        Route route, std::string settings, std::function<MethodOutput(const MethodContext&)> run) {
  MethodSpec s;
  s.key = m;
  s.id = std::string(to_string(m));
  s.title = std::move(title);
  s.legend = std::move(legend);
  s.colour = colour;
  s.route = route;
  s.settings = std::move(settings);
  s.run = std::move(run);
  return s;
}

void check(const MethodTableOptions& o) {
  const auto fail = [](const std::string& what) { throw InvalidInputError("comparison: " + what); };
  if (o.iterations < 1) fail("the iteration count must be >= 1");
  if (o.voxel_sinc_iterations < 1) fail("the voxel route's windowed-sinc iterations must be >= 1");
  if (!(o.sinc_passband > 0.0 && o.sinc_passband <= 2.0)) fail("windowed-sinc passband must be in (0, 2]");
  if (!(o.laplace_relaxation > 0.0 && o.laplace_relaxation <= 1.0)) fail("relaxation factor must be in (0, 1]");
}

// Colours of the variants, in turn.
constexpr std::array<std::array<double, 3>, 6> kVariantColours = {{
    {0.55, 0.0, 0.55}, {0.0, 0.5, 0.5}, {0.6, 0.4, 0.0}, {0.3, 0.3, 0.8}, {0.8, 0.3, 0.3}, {0.3, 0.6, 0.2}}};

}  // namespace

std::vector<std::string> standard_method_ids() {
  std::vector<std::string> ids;
  for (const MethodSpec& s : method_table()) ids.push_back(s.id);
  return ids;
}

namespace {

// libsmooth's baselines at the shared iteration count, then the two presets: the paper's method as the
// paper configures it (its own 40 iterations, said in its title) and the default.
void add_library_rows(std::vector<MethodSpec>& rows, int n) {
  const auto baseline = [&](SmoothingMethod m, const char* title, std::array<double, 3> colour) {
    SmoothOptions options;
    if (m != SmoothingMethod::None) options.iterations = n;
    rows.push_back(library_row(m, options, std::string(to_string(m)), title, title, colour, ""));
  };
  baseline(SmoothingMethod::None, "none (the unsmoothed contour mesh)", {0.5, 0.5, 0.5});
  rows.back().legend = "none";
  baseline(SmoothingMethod::Laplacian, "Laplacian", {0.12, 0.47, 0.71});
  baseline(SmoothingMethod::Taubin, "Taubin", {0.17, 0.63, 0.17});
  baseline(SmoothingMethod::MeanCurvatureFlow, "mean curvature flow", {0.58, 0.40, 0.74});
  baseline(SmoothingMethod::MinDistFlow, "MIN-DIST flow", {0.55, 0.34, 0.29});
  const MethodConfig xu = preset(Preset::Xu2006);
  const int its = iterations_of(xu.method, xu.options);
  rows.push_back(library_row(xu.method, xu.options, std::string(to_string(xu.method)),
                             "the paper's method (xu2006 preset, " + std::to_string(its) + " iterations)",
                             "paper (xu2006, " + std::to_string(its) + " its)", {0.84, 0.15, 0.16}, "xu2006"));
  MethodConfig d = preset(Preset::Default);
  d.options.iterations = n;  // used only if the method has an iteration count
  const std::string name(to_string(d.method));
  rows.push_back(library_row(d.method, d.options, name, name + " smoothing (the default)", name + " (default)",
                             {0.80, 0.0, 0.80}, "default"));
}

// VTK's two filters on the contour mesh at the shared count, and 3D Slicer's voxel route.
void add_external_rows(std::vector<MethodSpec>& rows, const MethodTableOptions& o) {
  const int n = o.iterations;
  std::ostringstream sinc;
  sinc << "3D Slicer's settings: " << n << " iterations, passband " << o.sinc_passband
       << ", normalized coordinates, no boundary or feature-edge smoothing";
  rows.push_back(external_row(ExternalMethod::VtkWindowedSinc, "vtkWindowedSincPolyDataFilter", "vtkWindowedSinc",
                              {1.0, 0.5, 0.05}, Route::Contour, sinc.str(), [n, o](const MethodContext& ctx) {
                                return run_vtk_windowed_sinc(ctx, n, o.sinc_passband);
                              }));
  std::ostringstream laplace;
  laplace << n << " iterations, relaxation " << o.laplace_relaxation << ", feature-edge smoothing on (feature angle "
          << o.laplace_feature_angle << ", edge angle " << o.laplace_edge_angle << ")";
  rows.push_back(external_row(ExternalMethod::VtkSmoothFeatureEdges, "vtkSmoothPolyDataFilter + feature edges",
                              "vtkSmoothPolyData + features", {0.09, 0.75, 0.81}, Route::Contour, laplace.str(),
                              [n, o](const MethodContext& ctx) { return run_vtk_smooth(ctx, n, o); }));
  const auto voxel = [o](bool smoothed, ExternalMethod m) {
    return [o, smoothed, m](const MethodContext& ctx) {
      return run_voxel(ctx, smoothed, o.voxel_sinc_iterations, o.sinc_passband, std::string(to_string(m)));
    };
  };
  rows.push_back(external_row(ExternalMethod::VoxelFlyingEdges, "voxel route: flying edges", "voxel route, unsmoothed",
                              {0.3, 0.3, 0.3}, Route::Voxel,
                              "threshold (islands and holes under the contour route's speck size removed and filled), "
                              "vtkDiscreteFlyingEdges3D on the padded binary image, unsmoothed",
                              voxel(false, ExternalMethod::VoxelFlyingEdges)));
  std::ostringstream slicer;
  slicer << "3D Slicer's voxel route: threshold, islands and holes removed, vtkDiscreteFlyingEdges3D, "
         << "vtkWindowedSincPolyDataFilter (" << o.voxel_sinc_iterations << " iterations, passband " << o.sinc_passband
         << ")";
  rows.push_back(external_row(ExternalMethod::VoxelWindowedSinc,
                              "voxel route: flying edges + windowed sinc (3D Slicer)", "voxel route (3D Slicer)",
                              {0.74, 0.74, 0.13}, Route::Voxel, slicer.str(),
                              voxel(true, ExternalMethod::VoxelWindowedSinc)));
}

// Keeps the rows named in `only` (all when it is empty); throws for a name that is not a row's.
void keep_only(std::vector<MethodSpec>& rows, const std::vector<std::string>& only) {
  if (only.empty()) return;
  for (const std::string& id : only) {
    if (std::none_of(rows.begin(), rows.end(), [&](const MethodSpec& s) { return s.id == id; })) {
      std::string known;
      for (const MethodSpec& s : rows) known += (known.empty() ? "" : ", ") + s.id;
      throw InvalidInputError("comparison: unknown method '" + id + "' (the methods are " + known + ")");
    }
  }
  std::erase_if(rows, [&](const MethodSpec& s) { return std::find(only.begin(), only.end(), s.id) == only.end(); });
}

// The variants, after the standard rows; `taken` holds the ids in use.
void add_variant_rows(std::vector<MethodSpec>& rows, const MethodTableOptions& o, std::set<std::string> taken) {
  std::size_t colour = 0;
  for (const MethodVariant& v : o.variants) {
    if (!taken.insert(v.id).second) {
      throw InvalidInputError("comparison: the variant name '" + v.id + "' is already a method's or another variant's");
    }
    SmoothOptions options = v.options;
    if (v.preset != "xu2006" && !options.iterations) options.iterations = o.iterations;  // the shared count
    MethodSpec s = library_row(v.method, options, v.id, v.id, v.id, kVariantColours[colour++ % kVariantColours.size()],
                               v.preset);
    s.settings = std::string(to_string(v.method)) + (v.preset.empty() ? "" : " (" + v.preset + " preset)") + " with " +
                 v.changes + ": " + settings_of(v.method, options);
    s.variant = true;
    rows.push_back(std::move(s));
  }
}

}  // namespace

std::vector<MethodSpec> method_table(const MethodTableOptions& o) {
  check(o);
  std::vector<MethodSpec> rows;
  add_library_rows(rows, o.iterations);
  add_external_rows(rows, o);
  std::set<std::string> ids;  // every standard id, run or not: a variant may not take one
  for (const MethodSpec& s : rows) ids.insert(s.id);
  keep_only(rows, o.only);
  add_variant_rows(rows, o, std::move(ids));
  return rows;
}

}  // namespace contourmesh
