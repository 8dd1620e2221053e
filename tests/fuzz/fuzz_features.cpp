// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target: feature detection and the paper's smoothing (contourmesh/smooth/feature_detection.h,
// contourmesh/smooth/feature_smoothing.h) on random valid meshes. The bytes choose a shape (mostly a contour stack
// over a random star-shaped curve, else an icosphere or a cube), perturb it (Gaussian noise, vertices
// pushed off their place, vertices collapsed onto a neighbour: zero-area triangles), scale it by
// 10^-6 .. 10^6, optionally damage or drop the contour ids (then recovered as the CLI does), and pick
// the options. detect_features and feature_preserving_smooth must return labels in range and finite
// numbers and positions, or throw a typed exception with a one-line message; never crash or hang.
#include "fuzz_support.h"

#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/contour_structure.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/feature_detection.h>
#include <contourmesh/smooth/feature_smoothing.h>
#include <contourmesh/smooth/input_policy.h>
#include <contourmesh/smooth/shapes.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <new>
#include <numbers>
#include <string>
#include <vector>

namespace contourmesh::fuzz {
namespace {

// r(t) = R (1 + sum_k a_k cos(2 pi k t + phi_k)) with sum |a_k| <= 0.8: star-shaped, so simple.
PlanarCurve fourier_curve(ByteReader& in, double radius) {
  const int harmonics = in.integer(0, 4);
  std::vector<double> amplitude, phase;
  double budget = 0.8;
  for (int k = 0; k < harmonics; ++k) {
    amplitude.push_back(budget * in.unit());
    budget -= amplitude.back();
    phase.push_back(in.real(0.0, 2.0 * std::numbers::pi));
  }
  return [=](double t) {
    double r = 1.0;
    for (std::size_t k = 0; k < amplitude.size(); ++k) {
      r += amplitude[k] * std::cos(2.0 * std::numbers::pi * static_cast<double>(k + 2) * t + phase[k]);
    }
    const double a = 2.0 * std::numbers::pi * t;
    return Eigen::Vector2d(radius * r * std::cos(a), radius * r * std::sin(a));
  };
}

Mesh decode_mesh(ByteReader& in, double& feature_size) {
  const int shape = in.integer(0, 7);
  if (shape == 6) {
    feature_size = in.real(0.5, 20.0);
    return make_icosphere(in.integer(0, 3), feature_size);  // umbilic everywhere
  }
  if (shape == 7) {
    feature_size = in.real(0.5, 20.0);
    return make_cube(in.integer(1, 6), feature_size);  // flat faces, valence-3 corners
  }
  ContourStackSpec spec;
  const double radius = in.real(0.5, 30.0);
  if (shape <= 3) spec.curve = fourier_curve(in, radius);
  else {
    const double height = radius * in.real(0.0, 0.5);
    spec.curve = ridge_circle_curve(radius, height, in.real(0.05, 1.5));
  }
  spec.slices = in.integer(2, 12);
  spec.points_per_contour = in.integer(3, 48);
  spec.slice_spacing = in.real(0.05, 6.0);
  spec.z0 = in.real(-50.0, 50.0);
  spec.end_caps = in.flag() ? EndCaps::AtEndSlice : EndCaps::HalfSpacing;
  feature_size = std::min(spec.slice_spacing, 2.0 * std::numbers::pi * radius / spec.points_per_contour);
  return make_contour_stack(spec);
}

void perturb(ByteReader& in, Mesh& mesh, double feature_size) {
  const Index n = mesh.num_vertices();
  if (n == 0) return;
  const std::uint8_t what = in.byte();
  if (what & 1) {
    const NoiseDirection dir = (what & 2) ? NoiseDirection::Normal : NoiseDirection::InPlane;
    add_noise(mesh, {feature_size * in.real(0.0, 0.3), in.byte(), dir});  // braces: read in order
  }
  const int pushes = in.integer(0, 6);
  for (int k = 0; k < pushes; ++k) {  // a spike: one vertex moved by up to 3 features in any direction
    const Index v = in.integer(0, n - 1);
    mesh.positions.col(v) += 3.0 * feature_size * in.symmetric3();
  }
  const int collapses = in.integer(0, 3);
  for (int k = 0; k < collapses; ++k) {  // vertex onto a triangle neighbour: zero-area triangles, collinear rings
    const Triangle& t = mesh.triangles[static_cast<std::size_t>(in.integer(0, mesh.num_faces() - 1))];
    const int a = in.integer(0, 2);
    const double along = in.flag() ? 1.0 : 0.5;  // onto the neighbour, or onto the edge's midpoint
    mesh.positions.col(t[a]) += along * (mesh.positions.col(t[(a + 1) % 3]) - mesh.positions.col(t[a]));
  }
}

// Damages the ids (or drops them), then runs the input policy the CLI and the VTK filter share
// (prepare_input_mesh: repairs, orientation, ids compacted, checked, repaired or recovered, or the
// curvature-only fallback). Returns false when the policy refuses the mesh (with a one-line error).
bool damage_and_recover_ids(ByteReader& in, Mesh& mesh, DetectionOptions& detection) {
  const std::uint8_t what = in.byte();
  if (!mesh.has_contour_ids()) {
    detection.mode = DetectionMode::CurvatureOnly;
    return true;
  }
  const Index n = mesh.num_vertices();
  if (what & 1) {
    const int damaged = in.integer(1, 4);
    for (int k = 0; k < damaged; ++k) {
      const Index v = in.integer(0, n - 1);
      mesh.slice_ids[v] = in.integer(-3, 14);
      if (in.flag()) mesh.contour_ids[v] = in.integer(-2, 2);
    }
  }
  if (what & 2) {  // ids dropped: recovered from the slice planes, as with --slice-axis z
    mesh.slice_ids.clear();
    mesh.contour_ids.clear();
    if (!assign_ids_by_slice_planes(mesh, build_adjacency(mesh), Eigen::Vector3d::UnitZ())) {
      detection.mode = DetectionMode::CurvatureOnly;
    }
    return true;
  }
  if (what & 4) return true;  // detection on the ids as they are, consistent or not
  InputPolicyOptions policy;
  policy.ids = ContourIdUse::Detection;
  if (what & 8) policy.slice_axis = Eigen::Vector3d::UnitZ();
  try {
    PreparedMesh prepared = prepare_input_mesh(std::move(mesh), policy);
    mesh = std::move(prepared.mesh);
    if (prepared.detection_mode == DetectionMode::CurvatureOnly) detection.mode = DetectionMode::CurvatureOnly;
  } catch (const InvalidInputError& e) {
    check_message_is_one_line(e.what(), "prepare_input_mesh");
    if (verbose()) std::fprintf(stderr, "input refused: %s\n", e.what());
    return false;
  }
  return true;
}

DetectionOptions decode_detection(ByteReader& in) {
  DetectionOptions o;
  const std::uint8_t what = in.byte();
  if (what & 1) o.mode = DetectionMode::CurvatureOnly;
  if (what & 2) o.measure = UmbrellaMeasure::NormalComponent;
  if (what & 4) o.in_slice = InSliceFeatures::AlongFeatureLine;
  if (what & 8) o.gamma_factor = in.real(0.0, 4.0);
  if (what & 16) o.delta_factor = in.real(0.0, 2.0);
  if (what & 32) o.anisotropy = in.real(1.01, 10.0);
  if (what & 64) o.window = 5 + 2 * in.integer(0, 3);
  if (what & 128) o.prefilter_iterations = in.integer(0, 3);
  return o;
}

void check_detection(const FeatureDetection& d, Index n, std::string_view context) {
  const std::string where(context);
  if (d.labels.size() != static_cast<std::size_t>(n)) fail(where + ": one label per vertex expected");
  std::size_t counts[4] = {0, 0, 0, 0};
  for (Index i = 0; i < n; ++i) {
    const auto label = static_cast<unsigned>(d.labels[i]);
    if (label > 3) fail(where + ": vertex " + std::to_string(i) + " has label " + std::to_string(label));
    ++counts[label];
  }
  if (counts[1] != d.edges || counts[2] != d.corners || counts[3] != d.noise) fail(where + ": label counts disagree");
  if (d.edges + d.corners + d.noise != d.candidates) fail(where + ": candidates != edges + corners + noise");
  if (d.umbrella.size() != n || !d.umbrella.allFinite()) fail(where + ": umbrella measure not finite");
  if (!std::isfinite(d.gamma) || d.gamma < 0.0 || !std::isfinite(d.mean_umbrella)) fail(where + ": gamma not finite");
  if (!d.curvature.kappa_min.allFinite() || !d.curvature.kappa_max.allFinite()) fail(where + ": curvature not finite");
}

}  // namespace
}  // namespace contourmesh::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace contourmesh;
  fuzz::ByteReader in(data, size);
  double feature_size = 1.0;
  Mesh mesh = fuzz::decode_mesh(in, feature_size);
  fuzz::perturb(in, mesh, feature_size);
  const double scale = std::pow(10.0, in.integer(-6, 6));
  mesh.positions *= scale;
  FeatureSmoothingOptions options;
  options.detection = fuzz::decode_detection(in);
  if (!fuzz::damage_and_recover_ids(in, mesh, options.detection)) return 0;
  const std::uint8_t what = in.byte();
  options.max_levels = in.integer(0, 3);
  options.iterations = in.integer(0, 12);
  if (what & 1) options.diffusion = SmoothingMethod::Laplacian;
  if (what & 2) options.output = OutputResolution::Adaptive;
  if (what & 4) options.boundary = BoundaryPolicy::Free;
  options.limits.max_vertices = 200'000;
  options.limits.max_memory_bytes = std::size_t{512} << 20;
  fuzz::check_mesh_is_sane(mesh, "the generated mesh");

  const Index n = mesh.num_vertices();
  try {
    const FeatureDetection detection = detect_features(mesh, build_adjacency(mesh), options.detection);
    fuzz::check_detection(detection, n, "detect_features");
    if (fuzz::verbose()) {
      std::fprintf(stderr, "mesh: %d vertices, %s; labels: %zu candidates, %zu edges, %zu corners, %zu noise\n", n,
                   options.detection.mode == DetectionMode::CurvatureOnly ? "curvature-only" : "contour ids",
                   detection.candidates, detection.edges, detection.corners, detection.noise);
    }
    const FeatureSmoothingResult result = feature_preserving_smooth(mesh, options);
    fuzz::check_detection(result.detection, n, "feature_preserving_smooth");
    if (result.detection.labels != detection.labels)
      fuzz::fail("feature_preserving_smooth labels differ from detect_features");
    fuzz::check_mesh_is_sane(result.mesh, "feature_preserving_smooth");
    if (options.output == OutputResolution::Original &&
        (result.mesh.num_vertices() != n || result.mesh.triangles != mesh.triangles)) {
      fuzz::fail("feature_preserving_smooth changed the connectivity at the original resolution");
    }
  } catch (const InvalidInputError& e) {
    fuzz::check_message_is_one_line(e.what(), "feature detection");
    if (fuzz::verbose()) std::fprintf(stderr, "rejected: %s\n", e.what());
  } catch (const std::bad_alloc&) {
    fuzz::fail("feature detection ran out of memory (a limit check is missing)");
  } catch (const std::exception& e) {
    fuzz::fail(std::string("feature detection threw an untyped exception: ") + e.what());
  }
  return 0;
}
