// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/cross_slice.h"

#include "contourmesh/internal/huge_pages.h"
#include "detail/contour_profiles.h"
#include "detail/lpa_ici.h"
#include "detail/off_slice_filter.h"
#include "detail/parallel.h"
#include "detail/stopwatch.h"
#include "contourmesh/smooth/errors.h"
#include "contourmesh/smooth/normals.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

namespace contourmesh {

namespace {

void check_options(const CrossSliceOptions& o) {
  const auto fail = [](const std::string& what) { throw InvalidInputError("cross-slice smoothing: " + what); };
  if (o.reach && (*o.reach < 1 || *o.reach > 30)) fail("reach must be in [1, 30], got " + std::to_string(*o.reach));
  if (o.along_reach < 1 || o.along_reach > 30) {
    fail("along reach must be in [1, 30], got " + std::to_string(o.along_reach));
  }
  if (!(o.gamma > 0.0 && std::isfinite(o.gamma))) fail("gamma must be a finite number > 0");
  if (!(o.precise_noise >= 0.0 && std::isfinite(o.precise_noise))) fail("precise noise must be a finite number >= 0");
  if (!(o.noisy_reach_length >= 0.0 && std::isfinite(o.noisy_reach_length))) {
    fail("noisy reach length must be a finite number >= 0 (mm)");
  }
  for (const auto& noise : {o.noise_across, o.noise_along}) {
    if (noise && !(*noise >= 0.0 && std::isfinite(*noise))) fail("a noise level must be a finite number >= 0 mm");
  }
  if (!(o.min_profile_share >= 0.0 && o.min_profile_share <= 1.0)) fail("the min profile share must be in [0, 1]");
  if (o.extension_iterations < 0) fail("extension iterations must be >= 0");
  if (o.across_model != ProfileModel::Parabola && o.across_model != ProfileModel::Circle) {
    fail("unknown profile model " + std::to_string(static_cast<int>(o.across_model)));
  }
  if (o.across_kinks != ProfileKinks::Ignore && o.across_kinks != ProfileKinks::Bound) {
    fail("unknown kink handling " + std::to_string(static_cast<int>(o.across_kinks)));
  }
  if (o.kink_sides != KinkSides::Curves && o.kink_sides != KinkSides::Lines) {
    fail("unknown kink side model " + std::to_string(static_cast<int>(o.kink_sides)));
  }
  if (!(o.kink_false_rate > 0.0 && o.kink_false_rate < 1.0)) fail("the kink false rate must be in (0, 1)");
  const OffSliceFilterOptions& f = o.off_slice;
  if (f.normal_iterations < 0 || f.vertex_iterations < 0 || f.rim_iterations < 0) {
    fail("off-slice filter iterations must be >= 0");
  }
  if (!(f.vertex_step > 0.0 && f.vertex_step <= 2.0)) fail("the vertex step must be in (0, 2]");
  if (!(f.rim_angle_degrees > 0.0 && f.rim_angle_degrees < 180.0)) fail("the rim angle must be in (0, 180) degrees");
  if (f.rim_rings < 0) fail("the rim rings must be >= 0");
  if (f.guidance_interval < 1) fail("the guidance interval must be >= 1");
  if (!(f.sigma_angle_degrees > 0.0 && f.sigma_angle_degrees <= 90.0)) {
    fail("off-slice filter angle must be in (0, 90] degrees");
  }
  if (!(f.max_move >= 0.0 && std::isfinite(f.max_move))) fail("off-slice filter max move must be a finite number >= 0");
}

// The reach on noisy contours: at least 8 slices, about `length` mm, at most 30 slices.
int noisy_reach(double length, double spacing) {
  constexpr int kShortest = 8, kLongest = 30;
  if (!(spacing > 0.0)) return kShortest;
  const double slices = std::round(length / spacing);
  return static_cast<int>(std::clamp(slices, static_cast<double>(kShortest), static_cast<double>(kLongest)));
}

// The noise level across the slices: given, estimated from the profiles across the slices, or, where too
// few contour vertices have one (CrossSliceOptions::min_profile_share), from those along the contours.
double noise_across(const detail::ContourFrame& frame, const Eigen::Matrix3Xd& positions,
                    const Eigen::Matrix3Xd& normals, const CrossSliceOptions& options, NoiseSource& source) {
  if (options.noise_across) {
    source = NoiseSource::Given;
    return *options.noise_across;
  }
  const detail::NoiseEstimate across = detail::profile_noise(frame, positions, normals, true);
  if (across.share() >= options.min_profile_share && across.profiles > 0) {
    source = NoiseSource::AcrossProfiles;
    return across.sigma;
  }
  source = NoiseSource::AlongProfiles;
  return detail::profile_noise(frame, positions, normals, false).sigma;
}

// How a stage reads a profile.
enum class ProfileFrame {
  InSlice,  ///< offsets along the in-slice normal m against the profile parameter (along contours)
  Tangent,  ///< rotated into the surface's own frame in the profile plane (across slices)
};

// Rotates a cross-slice profile (height in slice spacings, offset along m) into the frame of the surface
// at the vertex: the abscissa along the surface's tangent in the profile plane, the ordinate along its
// normal there. On a sloped surface a(z) bends with 1 / sin^3 of the slope; in this frame a sphere's
// profile is the same parabola at every latitude. Returns the normal's in-slice component (the factor
// from an ordinate to an in-slice offset), or 0 when the surface is too flat in the plane for it.
double to_tangent_frame(detail::Profile& p, double spacing) {
  // The surface's slope in the plane: a least-squares line through the samples within three slices
  // (the vertex normal itself carries the per-slice noise being removed).
  double s0 = 0, s1 = 0, s2 = 0, t0 = 0, t1 = 0;
  for (int k = 0; k < p.size; ++k) {
    const double x = p.x[static_cast<std::size_t>(k)], y = p.y[static_cast<std::size_t>(k)];
    if (std::abs(x) > 3.5) continue;
    s0 += 1;
    s1 += x;
    s2 += x * x;
    t0 += y;
    t1 += x * y;
  }
  const double det = s0 * s2 - s1 * s1;
  if (!(s0 >= 3.0 && det > 0.0)) return 0.0;
  double slope = (s0 * t1 - s1 * t0) / det / spacing;  // mm of offset per mm of height
  // A wall within about 27 degrees of the slice axis is read as it is: there a(z) bends little, its
  // fitted slope is partly the noise itself, and tilting by it would bias the flat-profile estimates
  // (the mean over a window clipped at a profile's end). Measured: rotating every profile cost 25 % on
  // the ridge-box with contour noise; rotating from 15 degrees on, 4 % on the femur.
  if (std::abs(slope) < 0.5) slope = 0.0;
  const double len = std::hypot(slope, 1.0);
  const double nz = -slope / len, na = 1.0 / len;
  // Below 0.2 (the surface within 12 degrees of the slice plane) an ordinate would need a five-fold
  // in-slice move: leave such vertices to the along-contour stage.
  if (na < 0.2) return 0.0;
  for (int k = 0; k < p.size; ++k) {
    const double z = p.x[static_cast<std::size_t>(k)] * spacing, a = p.y[static_cast<std::size_t>(k)];
    p.x[static_cast<std::size_t>(k)] = (z * na - a * nz) / spacing;
    p.y[static_cast<std::size_t>(k)] = z * nz + a * na;
  }
  p.sort();
  return na;
}

// One stage: every contour vertex's offset along its in-slice normal, re-estimated from its profile on
// `positions`. Returns the number of vertices whose profile gave an estimate.
template <typename MakeProfile>
std::size_t smooth_profiles(const detail::ContourFrame& frame, const Eigen::Matrix3Xd& positions,
                            const Eigen::Matrix3Xd& normals, const detail::LpaIciOptions& lpa, ProfileFrame read,
                            Eigen::Matrix3Xd& displacement, MakeProfile make_profile) {
  const Index n = static_cast<Index>(positions.cols());
  constexpr std::size_t kChunk = 2048;
  const std::size_t count = static_cast<std::size_t>(n);
  const std::vector<std::size_t> counts =
      detail::map_chunks<std::size_t>(count, kChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
        detail::Profile profile;
        Eigen::Vector3d m;
        std::size_t estimated = 0;
        for (std::size_t k = begin; k < end; ++k) {
          const Index i = static_cast<Index>(k);
          if (!frame.is_contour_vertex(i) || !detail::in_slice_normal(frame, normals.col(i), m)) continue;
          make_profile(positions, normals, i, m, profile);
          detail::LpaIciOptions local = lpa;
          double scale = 1.0;  // in-slice offset per unit of the fitted ordinate
          if (read == ProfileFrame::Tangent) {
            const double na = to_tangent_frame(profile, frame.slice_spacing);
            if (na == 0.0) continue;
            local.sigma = lpa.sigma * na;  // in-slice noise seen along the normal
            scale = 1.0 / na;
          }
          const detail::LpaIciResult r = detail::lpa_ici(profile, local);
          if (!r.valid) continue;
          displacement.col(i) += scale * r.value * m;
          ++estimated;
        }
        return estimated;
      });
  std::size_t total = 0;
  for (std::size_t c : counts) total += c;
  return total;
}

// Spreads the contour vertices' displacements to the other vertices (Jacobi iterations of the
// umbrella average with the contour vertices held).
void extend_displacements(const detail::ContourFrame& frame, int iterations, Eigen::Matrix3Xd& displacement) {
  const Index n = static_cast<Index>(displacement.cols());
  std::vector<Index> free;
  for (Index i = 0; i < n; ++i) {
    if (!frame.is_contour_vertex(i) && frame.adjacency.valence(i) > 0) free.push_back(i);
  }
  if (free.empty()) return;
  // Each iteration's averages, for the free vertices only (the others are held), then written back:
  // Jacobi steps, each vertex independent, in fixed chunks on every core.
  auto next = detail::huge_matrix<Eigen::Matrix3Xd>(3, static_cast<Index>(free.size()));
  constexpr std::size_t kChunk = 4096;
  for (int it = 0; it < iterations; ++it) {
    detail::parallel_chunks(free.size(), kChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        const auto ring = frame.adjacency.ring(free[k]);
        for (Index j : ring) sum += displacement.col(j);
        next.col(static_cast<Index>(k)) = sum / static_cast<double>(ring.size());
      }
    });
    detail::parallel_chunks(free.size(), kChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) displacement.col(free[k]) = next.col(static_cast<Index>(k));
    });
  }
}

// A copy of `mesh` whose large arrays are advised for huge pages before they are written.
Mesh copy_mesh(const Mesh& mesh) {
  Mesh copy;
  copy.positions = detail::huge_matrix<Eigen::Matrix3Xd>(3, mesh.positions.cols());
  copy.positions = mesh.positions;
  detail::reserve_huge(copy.triangles, mesh.triangles.size());
  copy.triangles = mesh.triangles;
  detail::reserve_huge(copy.slice_ids, mesh.slice_ids.size());
  copy.slice_ids = mesh.slice_ids;
  detail::reserve_huge(copy.contour_ids, mesh.contour_ids.size());
  copy.contour_ids = mesh.contour_ids;
  return copy;
}

}  // namespace

std::string_view to_string(NoiseSource source) {
  switch (source) {
    case NoiseSource::Given: return "given";
    case NoiseSource::AcrossProfiles: return "across";
    case NoiseSource::AlongProfiles: return "along";
  }
  return "unknown";
}

CrossSliceResult cross_slice_smooth(const Mesh& mesh, const CrossSliceOptions& options) {
  check_options(options);
  const auto start = std::chrono::steady_clock::now();
  CrossSliceResult result;
  const detail::ContourFrame frame = detail::make_contour_frame(mesh);

  auto t = std::chrono::steady_clock::now();
  const Index n = mesh.num_vertices();
  auto displacement = detail::huge_matrix<Eigen::Matrix3Xd>(3, n);
  displacement.setZero();
  detail::LpaIciOptions lpa;

  // 1. Across the slices.
  const Eigen::Matrix3Xd normals = vertex_normals(mesh.positions, mesh.triangles, frame.adjacency);
  result.noise_across = noise_across(frame, mesh.positions, normals, options, result.noise_across_source);
  // The reach: short where the contours are precise, long where they are noisy (precise_noise): there
  // at least 8 slices and about noisy_reach_length mm.
  result.reach = options.reach.value_or(
      result.noise_across < options.precise_noise ? 4 : noisy_reach(options.noisy_reach_length, frame.slice_spacing));
  lpa.gamma = options.gamma;
  lpa.sigma = result.noise_across;
  lpa.max_half_width = result.reach;
  lpa.circle = options.across_model == ProfileModel::Circle;
  lpa.x_unit = frame.slice_spacing;  // the tangent frame's abscissa is in slice spacings, its ordinate in mm
  lpa.kinks = options.across_kinks == ProfileKinks::Bound;
  lpa.kink_false_rate = options.kink_false_rate;
  lpa.kink_side_lines = options.kink_sides == KinkSides::Lines;
  const detail::NextCuts cuts = detail::next_cuts(frame, mesh.positions, normals);
  result.profiles = smooth_profiles(frame, mesh.positions, normals, lpa, ProfileFrame::Tangent, displacement,
                                    [&](const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd&, Index i,
                                        const Eigen::Vector3d& m, detail::Profile& p) {
                                      detail::chained_profile(frame, x, cuts, i, m, result.reach, p);
                                    });
  if (options.progress && !options.progress("smooth", 0.5)) throw CancelledError("smoothing");

  // 2. Along the contours, on the positions after step 1 (held in the result's positions, which take
  // the final ones below: no buffer of their own).
  result.mesh = copy_mesh(mesh);
  if (options.stages == CrossSliceStages::AcrossThenAlong) {
    Eigen::Matrix3Xd& across = result.mesh.positions;
    detail::parallel_chunks(static_cast<std::size_t>(n), 16384, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (auto i = static_cast<Index>(begin); i < static_cast<Index>(end); ++i) across.col(i) += displacement.col(i);
    });
    const Eigen::Matrix3Xd across_normals = vertex_normals(across, mesh.triangles, frame.adjacency);
    result.noise_along =
        options.noise_along.value_or(detail::profile_noise(frame, across, across_normals, false).sigma);
    lpa.sigma = result.noise_along;
    lpa.max_half_width = options.along_reach;
    lpa.circle = false;
    lpa.kinks = false;
    lpa.kink_side_lines = false;
    (void)smooth_profiles(frame, across, across_normals, lpa, ProfileFrame::InSlice, displacement,
                          [&](const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd&, Index i, const Eigen::Vector3d& m,
                              detail::Profile& p) {
                            detail::along_contour_profile(frame, x, i, m, options.along_reach, p);
                          });
  }

  // 3. Vertices off the slices follow.
  extend_displacements(frame, options.extension_iterations, displacement);
  detail::parallel_chunks(static_cast<std::size_t>(n), 16384, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (auto i = static_cast<Index>(begin); i < static_cast<Index>(end); ++i) {
      result.mesh.positions.col(i) = mesh.positions.col(i) + displacement.col(i);
    }
  });
  result.off_slice_moved =
      detail::filter_off_slice_normals(frame, mesh.triangles, options.off_slice, result.mesh.positions);
  result.seconds_smooth = detail::seconds_since(t);
  if (options.progress && !options.progress("smooth", 1.0)) throw CancelledError("smoothing");

  // 4. Labels.
  t = std::chrono::steady_clock::now();
  CreaseOptions features = options.features;
  if (!features.noise) features.noise = result.noise_across;  // the creases rise above the noise left
  result.features = detect_creases(result.mesh, frame.adjacency, features);
  result.labels = result.features.labels;
  if (options.crease_restoration == CreaseRestoration::Subdivide) {
    result.mesh = restore_creases(result.mesh, result.labels, options.restoration).mesh;
  }
  result.seconds_detect = detail::seconds_since(t);
  result.seconds_total = detail::seconds_since(start);
  if (options.progress && !options.progress("detect", 1.0)) throw CancelledError("feature detection");
  return result;
}

}  // namespace contourmesh
