// SPDX-License-Identifier: BSD-3-Clause
// Cross-slice smoothing's last stage: the vertices between the slices follow the bilaterally filtered
// normals of their faces (OffSliceFilterOptions).
#include "contourmesh/smooth/cross_slice.h"
#include "contourmesh/smooth/errors.h"
#include "contourmesh/smooth/metrics.h"
#include "contourmesh/smooth/shapes.h"
#include "smooth/test_meshes.h"
#include "contourmesh/smooth/surface_metrics.h"
#include "detail/off_slice_filter.h"
#include "detail/parallel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace contourmesh {
namespace {

using std::numbers::pi;

struct Accuracy {
  double rms = 0.0;           ///< of the distance of surface samples to the truth, mm
  double normal_error = 0.0;  ///< area-weighted mean angle of face normals to the true normal, degrees
};

Accuracy measure(const Mesh& mesh, const ScalarField& sdf) {
  // One sample per mm^2 and one-sided differences: the truth's distance (a polygon distance per slice
  // it spans) is nearly all of the test's time, most of all under the sanitizers.
  const SurfaceSamples s = sample_mesh_surface(mesh.positions, mesh.triangles, 1.0, 7);
  double w = 0.0, d2 = 0.0, angle = 0.0;
  constexpr double h = 1e-5;
  for (Index k = 0; k < s.size(); ++k) {
    const Eigen::Vector3d p = s.points.col(k);
    const Triangle& t = mesh.triangles[static_cast<std::size_t>(s.faces[k])];
    const Eigen::Vector3d n = (mesh.positions.col(t[1]) - mesh.positions.col(t[0]))
                                  .cross(mesh.positions.col(t[2]) - mesh.positions.col(t[0]))
                                  .normalized();
    const double d = sdf(p);
    Eigen::Vector3d g;
    for (int a = 0; a < 3; ++a) g[a] = (sdf(p + Eigen::Vector3d::Unit(a) * h) - d) / h;
    w += s.weights[k];
    d2 += s.weights[k] * d * d;
    angle += s.weights[k] * std::acos(std::clamp(n.dot(g.normalized()), -1.0, 1.0)) * 180.0 / pi;
  }
  return {std::sqrt(d2 / w), angle / w};
}

// A cylinder whose odd slices are intermediate contours (vertices without ids, as a tiler's refined bands
// have), with caps half a spacing beyond the end slices; the vertices without ids carry noise, the
// contours are exact (so the cross-slice stages leave them in place).
Mesh noisy_off_slice_cylinder(const ContourStackSpec& spec) {
  Mesh mesh = make_contour_stack(spec);
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.slice_ids[i] < 0) continue;
    if (mesh.slice_ids[i] % 2 == 1) {
      mesh.slice_ids[i] = mesh.contour_ids[i] = kNoId;
    } else {
      mesh.slice_ids[i] /= 2;
    }
  }
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 0.15);
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.slice_ids[i] >= 0) continue;
    for (int a = 0; a < 3; ++a) mesh.positions(a, i) += noise(rng);
  }
  return mesh;
}

TEST(CrossSliceOffSlice, FilteredNormalsLowerTheNormalErrorWithoutRaisingTheDistance) {
  const ContourStackSpec spec = test::cylinder_spec(10.0, 21);
  const ScalarField sdf = contour_stack_sdf(spec);
  const Mesh mesh = noisy_off_slice_cylinder(spec);
  CrossSliceOptions without;
  without.off_slice.filter = OffSliceFilter::None;
  const CrossSliceResult before = cross_slice_smooth(mesh, without);
  const CrossSliceResult after = cross_slice_smooth(mesh);  // the default filters
  const Accuracy a = measure(before.mesh, sdf), b = measure(after.mesh, sdf);
  EXPECT_EQ(before.off_slice_moved, 0u);
  EXPECT_GT(after.off_slice_moved, 0u);
  EXPECT_LT(b.normal_error, 0.7 * a.normal_error) << a.normal_error << " -> " << b.normal_error;
  EXPECT_LE(b.rms, a.rms) << a.rms << " -> " << b.rms;
}

TEST(CrossSliceOffSlice, LeavesContourVerticesAndKeepsTheOthersInTheirSlabs) {
  const ContourStackSpec spec = test::cylinder_spec(10.0, 21);
  const Mesh mesh = noisy_off_slice_cylinder(spec);
  const CrossSliceResult r = cross_slice_smooth(mesh);
  CrossSliceOptions without;
  without.off_slice.filter = OffSliceFilter::None;
  const CrossSliceResult unfiltered = cross_slice_smooth(mesh, without);
  // The contour slices are 4 mm apart here; a vertex without ids moves at most max_move spacings.
  const double reach = CrossSliceOptions{}.off_slice.max_move * 4.0;
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::Vector3d moved = r.mesh.positions.col(i) - unfiltered.mesh.positions.col(i);
    if (mesh.slice_ids[i] >= 0) {
      // The filter leaves contour vertices where the cross-slice stages put them.
      EXPECT_EQ(moved.norm(), 0.0) << "contour vertex " << i;
      continue;
    }
    EXPECT_LE(moved.norm(), reach + 1e-9) << "vertex " << i;
    // An intermediate contour (z near 4k + 2) stays strictly inside its slab (4k, 4k + 4).
    const double z0 = mesh.positions(2, i), z = r.mesh.positions(2, i);
    if (z0 > 0.0 && z0 < 40.0) {
      const double bottom = 4.0 * std::floor(z0 / 4.0);
      EXPECT_GT(z, bottom) << "vertex " << i;
      EXPECT_LT(z, bottom + 4.0) << "vertex " << i;
    }
  }
}

// The filter's loops run in fixed chunks, Jacobi style: the result is the same, bit for bit, on one thread
// and on many. The cylinder is long enough for several chunks of every loop (faces, face pairs, moving
// vertices).
TEST(CrossSliceOffSlice, SameResultOnOneThreadAndOnSeveral) {
  const Mesh mesh = noisy_off_slice_cylinder(test::cylinder_spec(10.0, 51));
  CrossSliceResult one, several;
  {
    const detail::ScopedWorkerCount threads(1);
    one = cross_slice_smooth(mesh);
  }
  {
    const detail::ScopedWorkerCount threads(5);
    several = cross_slice_smooth(mesh);
  }
  EXPECT_GT(one.off_slice_moved, 2048u);
  EXPECT_EQ(one.off_slice_moved, several.off_slice_moved);
  EXPECT_TRUE(one.mesh.positions == several.mesh.positions);
  EXPECT_EQ(one.labels, several.labels);
}

// Every stage of the default (adjacency, contour frame, vertex normals, noise estimates, next cuts,
// profiles, extension, off-slice filter, creases) runs in fixed chunks: on a mesh of several chunks of
// each (about 40k vertices, contours with noise and a ridge, vertices between them with noise) the whole
// result is the same, bit for bit, on one thread and on several.
TEST(CrossSlice, WholeDefaultSameOnOneThreadAndOnSeveral) {
  ContourStackSpec spec = test::cylinder_spec(20.0, 101);
  spec.curve = ridge_circle_curve(20.0, 4.0, 0.4);
  spec.points_per_contour = 400;
  Mesh mesh = noisy_off_slice_cylinder(spec);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 0.1);
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.slice_ids[i] < 0) continue;
    for (int a = 0; a < 2; ++a) mesh.positions(a, i) += noise(rng);  // within the slice plane
  }
  ASSERT_GT(mesh.num_vertices(), 2 * 16384);
  CrossSliceResult one, several;
  {
    const detail::ScopedWorkerCount threads(1);
    one = cross_slice_smooth(mesh);
  }
  {
    const detail::ScopedWorkerCount threads(3);
    several = cross_slice_smooth(mesh);
  }
  EXPECT_GT(one.profiles, 16384u);
  EXPECT_GT(one.off_slice_moved, 4096u);
  EXPECT_EQ(one.noise_across, several.noise_across);
  EXPECT_EQ(one.noise_along, several.noise_along);
  EXPECT_EQ(one.profiles, several.profiles);
  EXPECT_EQ(one.off_slice_moved, several.off_slice_moved);
  EXPECT_TRUE(one.mesh.positions == several.mesh.positions);
  EXPECT_EQ(one.labels, several.labels);
  EXPECT_EQ(one.features.edge_strength, several.features.edge_strength);
}

// A cone (radius 10 + 1.5 z: walls 34 degrees off the slice planes) sampled every half millimetre, whose
// slices at multiples of 2 mm are contours and the three between each pair are rows of vertices without
// ids, with their heights pulled towards the middle of their slab by `compression` (0: exact, 1: all at
// the middle), as off-slice heights read from an image by linear interpolation between two slices are:
// the faces between the slices form terraces. Plus isotropic noise of `noise_mm` on those vertices. The
// cone's true normal is known in closed form.
Mesh terraced_cone(double compression, double noise_mm) {
  ContourStackSpec spec = test::cylinder_spec(10.0, 41);
  spec.slice_spacing = 0.5;
  Mesh mesh = make_contour_stack(spec);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, noise_mm);
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    const double z = mesh.positions(2, i);
    const double scale = (10.0 + 1.5 * z) / 10.0;
    mesh.positions(0, i) *= scale;
    mesh.positions(1, i) *= scale;
    if (mesh.slice_ids[i] < 0) continue;
    if (mesh.slice_ids[i] % 4 == 0) {
      mesh.slice_ids[i] /= 4;
      continue;
    }
    mesh.slice_ids[i] = mesh.contour_ids[i] = kNoId;
    const double bottom = 2.0 * std::floor(z / 2.0);
    mesh.positions(2, i) = bottom + 1.0 + (1.0 - compression) * (z - bottom - 1.0);
    for (int a = 0; a < 3; ++a) mesh.positions(a, i) += noise(rng);
  }
  return mesh;
}

// Area-weighted mean angle between the face normals of the cone's wall (faces off the caps) and the
// cone's normal, degrees.
double cone_wall_normal_error(const Mesh& mesh) {
  double w = 0.0, angle = 0.0;
  for (const Triangle& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.positions.col(t[0]), b = mesh.positions.col(t[1]), c = mesh.positions.col(t[2]);
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const Eigen::Vector3d centre = (a + b + c) / 3.0;
    if (std::abs(cross.normalized().z()) > 0.9) continue;  // a cap
    const Eigen::Vector3d radial = Eigen::Vector3d(centre.x(), centre.y(), 0.0).normalized();
    const Eigen::Vector3d truth = (radial - 1.5 * Eigen::Vector3d::UnitZ()).normalized();
    const double area = 0.5 * cross.norm();
    w += area;
    angle += area * std::acos(std::clamp(cross.normalized().dot(truth), -1.0, 1.0)) * 180.0 / pi;
  }
  return angle / w;
}

TEST(CrossSliceOffSlice, PatchGuidanceFlattensTerracesBetweenTheSlices) {
  const Mesh mesh = terraced_cone(0.7, 0.1);
  CrossSliceOptions faces, patches, none;
  faces.off_slice.range = OffSliceRange::FaceNormals;
  patches.off_slice.range = OffSliceRange::PatchGuidance;
  none.off_slice.filter = OffSliceFilter::None;
  const double before = cone_wall_normal_error(cross_slice_smooth(mesh, none).mesh);
  const double by_faces = cone_wall_normal_error(cross_slice_smooth(mesh, faces).mesh);
  const double by_patches = cone_wall_normal_error(cross_slice_smooth(mesh, patches).mesh);
  EXPECT_GT(before, 10.0);
  // The faces' own normals read the terraces' steps as creases and keep some of them; guidance does not.
  EXPECT_LT(by_patches, 0.1 * before) << before << " -> " << by_patches;
  EXPECT_LT(by_patches, 0.7 * by_faces) << by_faces << " against " << by_patches;
}

// Guidance computed once, from the unfiltered normals, with the range kernels kept from then on: the
// terraces still average out within the patches.
TEST(CrossSliceOffSlice, PatchGuidanceComputedOnceFlattensTerraces) {
  const Mesh mesh = terraced_cone(0.7, 0.1);
  CrossSliceOptions once, none;
  once.off_slice.guidance_interval = once.off_slice.normal_iterations;
  once.off_slice.rim_iterations = 0;
  none.off_slice.filter = OffSliceFilter::None;
  const double before = cone_wall_normal_error(cross_slice_smooth(mesh, none).mesh);
  const double after = cone_wall_normal_error(cross_slice_smooth(mesh, once).mesh);
  EXPECT_LT(after, 0.1 * before) << before << " -> " << after;
}

// The first iteration always computes the guidance: with one iteration any interval gives the same
// result; with more, a longer interval keeps an older guidance and changes the result.
TEST(CrossSliceOffSlice, GuidanceIntervalStartsWithTheFirstIteration) {
  const Mesh mesh = noisy_off_slice_cylinder(test::cylinder_spec(10.0, 21));
  CrossSliceOptions every, sparse;
  every.off_slice.guidance_interval = 1;
  sparse.off_slice.guidance_interval = 7;
  every.off_slice.rim_iterations = sparse.off_slice.rim_iterations = 0;
  every.off_slice.normal_iterations = sparse.off_slice.normal_iterations = 1;
  EXPECT_TRUE(cross_slice_smooth(mesh, every).mesh.positions == cross_slice_smooth(mesh, sparse).mesh.positions);
  every.off_slice.normal_iterations = sparse.off_slice.normal_iterations = 20;
  EXPECT_FALSE(cross_slice_smooth(mesh, every).mesh.positions == cross_slice_smooth(mesh, sparse).mesh.positions);
}

TEST(CrossSliceOffSlice, PatchGuidanceLeavesContourVertices) {
  const Mesh mesh = terraced_cone(0.7, 0.1);
  CrossSliceOptions patches, none;
  patches.off_slice.range = OffSliceRange::PatchGuidance;
  none.off_slice.filter = OffSliceFilter::None;
  const CrossSliceResult r = cross_slice_smooth(mesh, patches), unfiltered = cross_slice_smooth(mesh, none);
  EXPECT_GT(r.off_slice_moved, 0u);
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.slice_ids[i] < 0) continue;
    EXPECT_EQ((r.mesh.positions.col(i) - unfiltered.mesh.positions.col(i)).norm(), 0.0) << "contour vertex " << i;
  }
}

TEST(CrossSliceOffSlice, PatchGuidanceSameResultOnOneThreadAndOnSeveral) {
  const Mesh mesh = noisy_off_slice_cylinder(test::cylinder_spec(10.0, 51));
  CrossSliceOptions o;
  o.off_slice.range = OffSliceRange::PatchGuidance;
  CrossSliceResult one, several;
  {
    const detail::ScopedWorkerCount threads(1);
    one = cross_slice_smooth(mesh, o);
  }
  {
    const detail::ScopedWorkerCount threads(5);
    several = cross_slice_smooth(mesh, o);
  }
  EXPECT_GT(one.off_slice_moved, 2048u);
  EXPECT_TRUE(one.mesh.positions == several.mesh.positions);
}

// Guidance keeps an exact polygonal cylinder's cap rims where they are, as the faces' own normals do: the
// wall faces along a rim take the patch of the band below (all wall), not one straddling the rim.
TEST(CrossSliceOffSlice, PatchGuidanceLeavesAnExactCylinderInPlace) {
  const Mesh mesh = make_contour_stack(test::cylinder_spec(10.0, 20));
  CrossSliceOptions o;
  o.off_slice.range = OffSliceRange::PatchGuidance;
  const CrossSliceResult r = cross_slice_smooth(mesh, o);
  EXPECT_LT((r.mesh.positions - mesh.positions).cwiseAbs().maxCoeff(), 0.02);
}

// The normal filter and the vertex update recompute only what changed in the last iteration (guidance
// normals read two rings, so more is recomputed with them): the same output, bit for bit, as recomputing
// everything.
// Two meshes: noise everywhere (everything changes at once), and one vertex pushed off a square prism
// whose flat walls are a fixed point of the filter, bit for bit (the changes spread from the bump and the
// corners a ring per iteration, and guidance changes a ring ahead of the normals).
TEST(CrossSliceOffSlice, SkippingUnchangedWorkGivesTheFullRecomputation) {
  ContourStackSpec spec;
  spec.curve = [](double t) {  // a square of side 20 mm, 16 samples a side, corners included
    const double u = 4.0 * t - std::floor(4.0 * t), s = -10.0 + 20.0 * u;
    switch (static_cast<int>(std::floor(4.0 * t)) % 4) {
      case 0: return Eigen::Vector2d(10.0, s);
      case 1: return Eigen::Vector2d(-s, 10.0);
      case 2: return Eigen::Vector2d(-10.0, -s);
      default: return Eigen::Vector2d(s, -10.0);
    }
  };
  spec.slices = 21;
  spec.points_per_contour = 64;
  Mesh bump = make_contour_stack(spec);
  Index pushed = -1;
  for (Index i = 0; i < bump.num_vertices(); ++i) {
    if (bump.slice_ids[i] < 0) continue;
    if (bump.slice_ids[i] % 2 == 1) {
      if (pushed < 0 && bump.slice_ids[i] == 9 && std::abs(bump.positions(1, i)) < 3.0) pushed = i;
      bump.slice_ids[i] = bump.contour_ids[i] = kNoId;
    } else {
      bump.slice_ids[i] /= 2;
    }
  }
  ASSERT_GE(pushed, 0);
  bump.positions.col(pushed).head<2>() *= 10.4 / 10.0;
  for (const Mesh& mesh : {terraced_cone(0.7, 0.1), bump}) {
    // Face normals; guidance in every iteration; guidance in every third, with rim iterations after the
    // 20 normal ones: the guidance of iteration 21 must see the changes of iteration 19, made by faces
    // that the rim iterations then leave.
    for (const int interval : {0, 1, 3}) {
      CrossSliceOptions o;
      o.off_slice.range = interval == 0 ? OffSliceRange::FaceNormals : OffSliceRange::PatchGuidance;
      o.off_slice.guidance_interval = std::max(interval, 1);
      if (interval == 3) o.off_slice.rim_iterations = 6;
      const CrossSliceResult skipping = cross_slice_smooth(mesh, o);
      CrossSliceResult full;
      {
        const detail::ScopedFullRecompute everything;
        full = cross_slice_smooth(mesh, o);
      }
      EXPECT_GT(skipping.off_slice_moved, 10u);
      EXPECT_TRUE(skipping.mesh.positions == full.mesh.positions) << interval;
    }
  }
}

// The rim iterations update the rim faces only: with no two faces sharp enough apart to make a rim they
// change nothing; at the caps' rims (90 degrees) they move vertices, the same whether the filter skips
// unchanged work or not; with every face a rim they are more normal iterations.
TEST(CrossSliceOffSlice, RimIterationsWithoutRimsChangeNothing) {
  const Mesh mesh = noisy_off_slice_cylinder(test::cylinder_spec(10.0, 21));
  CrossSliceOptions o;
  o.off_slice.rim_iterations = 0;
  const CrossSliceResult plain = cross_slice_smooth(mesh, o);
  o.off_slice.rim_iterations = 30;
  o.off_slice.rim_angle_degrees = 179.9;
  EXPECT_TRUE(cross_slice_smooth(mesh, o).mesh.positions == plain.mesh.positions);
  o.off_slice.rim_angle_degrees = 70.0;
  const CrossSliceResult rims = cross_slice_smooth(mesh, o);
  EXPECT_FALSE(rims.mesh.positions == plain.mesh.positions);
  const detail::ScopedFullRecompute everything;
  EXPECT_TRUE(cross_slice_smooth(mesh, o).mesh.positions == rims.mesh.positions);
}

TEST(CrossSliceOffSlice, RimIterationsOnEveryFaceAreMoreNormalIterations) {
  const Mesh mesh = noisy_off_slice_cylinder(test::cylinder_spec(10.0, 21));
  CrossSliceOptions rims;
  rims.off_slice.rim_iterations = 15;
  rims.off_slice.rim_angle_degrees = 1e-3;  // a seed wherever two neighbouring normals differ at all
  rims.off_slice.rim_rings = 100;           // and every face connected to one
  CrossSliceOptions more;
  more.off_slice.normal_iterations = rims.off_slice.normal_iterations + 15;
  more.off_slice.rim_iterations = 0;
  EXPECT_TRUE(cross_slice_smooth(mesh, rims).mesh.positions == cross_slice_smooth(mesh, more).mesh.positions);
}

// Fitting to filtered normals rounds a thin structure's caps and intermediate contours inwards; with
// OffSliceVolume::Preserve the stage gives the volume back by a uniform offset, within the bounds.
TEST(CrossSliceOffSlice, PreserveKeepsTheVolumeTheFilterWouldTake) {
  const Mesh mesh = noisy_off_slice_cylinder(test::cylinder_spec(1.5, 9));
  CrossSliceOptions none, free, kept;
  none.off_slice.filter = OffSliceFilter::None;
  kept.off_slice.volume = OffSliceVolume::Preserve;
  const double v0 = enclosed_volume(cross_slice_smooth(mesh, none).mesh);
  const double v_free = enclosed_volume(cross_slice_smooth(mesh, free).mesh);
  const CrossSliceResult r = cross_slice_smooth(mesh, kept);
  EXPECT_GT(std::abs(v_free - v0), 0.005 * v0) << v0 << " -> " << v_free;
  EXPECT_NEAR(enclosed_volume(r.mesh), v0, 1e-6 * v0);
  EXPECT_GT(r.off_slice_moved, 0u);
}

TEST(CrossSliceOffSlice, RejectsOptionsOutOfRange) {
  const Mesh mesh = make_contour_stack(test::cylinder_spec(10.0, 6));
  CrossSliceOptions o;
  o.off_slice.sigma_angle_degrees = 0.0;
  EXPECT_THROW((void)cross_slice_smooth(mesh, o), InvalidInputError);
  o = {};
  o.off_slice.normal_iterations = -1;
  EXPECT_THROW((void)cross_slice_smooth(mesh, o), InvalidInputError);
  o = {};
  o.off_slice.max_move = -0.1;
  EXPECT_THROW((void)cross_slice_smooth(mesh, o), InvalidInputError);
  o = {};
  o.off_slice.rim_iterations = -1;
  EXPECT_THROW((void)cross_slice_smooth(mesh, o), InvalidInputError);
  o = {};
  o.off_slice.rim_angle_degrees = 180.0;
  EXPECT_THROW((void)cross_slice_smooth(mesh, o), InvalidInputError);
  o = {};
  o.off_slice.rim_rings = -1;
  EXPECT_THROW((void)cross_slice_smooth(mesh, o), InvalidInputError);
  o = {};
  o.off_slice.guidance_interval = 0;
  EXPECT_THROW((void)cross_slice_smooth(mesh, o), InvalidInputError);
  for (const double step : {0.0, -1.0, 2.01}) {
    o = {};
    o.off_slice.vertex_step = step;
    EXPECT_THROW((void)cross_slice_smooth(mesh, o), InvalidInputError) << step;
  }
}

// The vertex update has not converged after its iterations, so its step acts as a time step: half the
// iterations at twice the step end about where the iterations at the step do, and far from where half
// the iterations at the step end.
TEST(CrossSliceOffSlice, VertexStepScalesTheUpdateLikeMoreIterations) {
  const Mesh mesh = noisy_off_slice_cylinder(test::cylinder_spec(10.0, 21));
  const auto run = [&](int iterations, double step) {
    CrossSliceOptions o;
    o.off_slice.vertex_iterations = iterations;
    o.off_slice.vertex_step = step;
    return cross_slice_smooth(mesh, o).mesh.positions;
  };
  const Eigen::Matrix3Xd long_steps = run(20, 1.0), double_steps = run(10, 2.0), short_steps = run(10, 1.0);
  const double same = (double_steps - long_steps).colwise().norm().maxCoeff();
  const double fewer = (short_steps - long_steps).colwise().norm().maxCoeff();
  EXPECT_GT(fewer, 1e-3);
  EXPECT_LT(same, 0.25 * fewer) << same << " against " << fewer;
}

}  // namespace
}  // namespace contourmesh
