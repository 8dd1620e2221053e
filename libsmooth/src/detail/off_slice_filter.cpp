// SPDX-License-Identifier: BSD-3-Clause
#include "detail/off_slice_filter.h"

#include "contourmesh/internal/huge_pages.h"
#include "contourmesh/internal/union_find.h"
#include "detail/guidance_patches.h"
#include "detail/off_slice_workspace.h"
#include "detail/parallel.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace contourmesh::detail {

namespace {

// The filtered faces that take the rim iterations (OffSliceFilterOptions::rim_iterations): those whose
// neighbourhood holds two faces whose `normals` are more than the rim angle apart, and `rim_rings` rings of
// filtered faces around them.
std::vector<std::uint8_t> rim_faces(const Workspace& w, const OffSliceFilterOptions& options,
                                    const Eigen::Matrix3Xd& normals) {
  const std::size_t nk = w.filtered.size();
  const double rim_cos = std::cos(options.rim_angle_degrees * M_PI / 180.0);
  std::vector<std::uint8_t> rim;
  detail::assign_huge(rim, nk, 0);
  parallel_chunks(nk, 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const Index f = w.filtered[k];
      for (Index r = w.ring_offsets[k]; r < w.ring_offsets[k + 1] && !rim[k]; ++r) {
        rim[k] = normals.col(f).dot(normals.col(w.ring[static_cast<std::size_t>(r)])) < rim_cos ? 1 : 0;
      }
    }
  });
  std::vector<std::uint8_t> grown;
  detail::assign_huge(grown, nk, 0);
  for (int round = 0; round < options.rim_rings; ++round) {
    parallel_chunks(nk, 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        grown[k] = rim[k];
        for (Index r = w.ring_offsets[k]; r < w.ring_offsets[k + 1] && !grown[k]; ++r) {
          const Index kg = w.filtered_of[static_cast<std::size_t>(w.ring[static_cast<std::size_t>(r)])];
          grown[k] = kg >= 0 && rim[static_cast<std::size_t>(kg)] ? 1 : 0;
        }
      }
    });
    rim.swap(grown);
  }
  return rim;
}

// Bilateral filtering of the normals of the filtered faces (Zheng et al. 2011, eq. 4), Jacobi style; the
// other local faces' normals are read as they are. `normals` holds every local face's normal. The range
// kernel compares the normals themselves or, with `patches`, guidance normals.
void filter_normals(const Workspace& w, const OffSliceFilterOptions& options, const GuidancePatches* patches,
                    Eigen::Matrix3Xd& normals) {
  const double sigma_r = 2.0 * std::sin(0.5 * options.sigma_angle_degrees * M_PI / 180.0);  // as |n_i - n_j|
  const double inv_r = 1.0 / (2.0 * sigma_r * sigma_r);
  // Where a sum vanishes, a face keeps the normal of two iterations before (that of `next`).
  Eigen::Matrix3Xd next = normals;
  // The sums read single-precision copies of the normals, padded to four floats (16 bytes a face against
  // 24, one aligned load each) and weighted by single-precision coefficients: the sums are memory-bound,
  // and the result moves by a micrometre at most (head-and-neck mesh: 1.2 um, mean 2e-8 mm; every
  // phantom's distances in compare within 1e-7 mm of the double sums, labels the same). The normals
  // themselves, their lengths and the guidance stay in double.
  Eigen::Matrix4Xf nf(4, normals.cols()), nextf(4, normals.cols());
  parallel_chunks(static_cast<std::size_t>(normals.cols()), 8192, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t l = begin; l < end; ++l) {
      const auto ll = static_cast<Index>(l);
      nf.col(ll) << normals.col(ll).cast<float>(), 0.0f;
    }
  });
  nextf = nf;
  FillVector<float> range;  // every slot is computed in the first iteration
  detail::resize_huge(range, w.slot_a.size());
  // Only what changed is recomputed. A face's sum reads the normals of its neighbourhood only (the face's
  // own included) and each pair's range kernel, which reads the pair's two compared normals: where none of
  // them changed bit for bit in the last iteration, the sum and its normal are those of the last iteration,
  // and so is a kernel whose two faces kept their compared normals. The filtered normals start moving near
  // the region's features and spread a ring per iteration; flat caps keep theirs. Guidance normals read
  // two rings of normals: where they are computed, they are compared bit for bit with the last ones, which
  // widens the set of faces recomputed to what they reach.
  const std::size_t nl = w.faces.size(), nk = w.filtered.size();
  const bool full = full_recompute();
  // Per local face: its normal changed in the last iteration (never, for the faces not filtered); the first
  // iteration computes everything.
  std::vector<std::uint8_t> changed, changes;
  detail::assign_huge(changed, nl, 0);
  detail::assign_huge(changes, nl, 0);
  std::vector<std::uint8_t> summed;  // per filtered face: its last sum was not zero (its normal set)
  detail::assign_huge(summed, nk, 0);
  // Per neighbourhood entry: its spatial weight times its pair's range kernel (in single precision),
  // kept from the iteration that last summed the face (the kernels change only where the guidance is
  // computed): the iterations in between stream it instead of looking up each pair's slot.
  FillVector<float> coefficient;
  detail::resize_huge(coefficient, w.ring.size());
  // Guidance: per local face, the compared normal and whether it changed since it was last computed. It
  // is computed every `guidance_interval` iterations; in between, it and the range kernels stay.
  const double min_cos = std::cos(options.sigma_angle_degrees * M_PI / 180.0);
  Eigen::Matrix3Xd guidance, last_guidance;
  GuidanceState state;
  std::vector<std::uint8_t> guided_changed;
  detail::assign_huge(guided_changed, nl, 0);
  // Per local face: its normal changed since the guidance was last computed (the patches it is in are
  // computed again); the faces not filtered never change.
  std::vector<std::uint8_t> changed_since;
  detail::assign_huge(changed_since, nl, 0);
  if (patches) {
    guidance = normals;
    state.mean = detail::huge_matrix<Eigen::Matrix3Xd>(3, static_cast<Index>(nl));
    detail::assign_huge(state.consistency, nl, 0.0);
    detail::assign_huge(state.recomputed, nl, 0);
  }
  const int interval = std::max(options.guidance_interval, 1);
  // After the normal iterations, the rim iterations update the rim faces only (the others' normals stay).
  const bool rims = options.normal_iterations > 0 && options.rim_iterations > 0;
  const std::vector<std::uint8_t> rim = rims ? rim_faces(w, options, normals) : std::vector<std::uint8_t>{};
  // The rim faces' indices among the filtered faces: from the third rim iteration on, only they are visited
  // (the first sets the other faces' next normals and change flags, the second the other buffers').
  std::vector<Index> rim_list;
  for (std::size_t k = 0; k < rim.size(); ++k) {
    if (rim[k]) rim_list.push_back(static_cast<Index>(k));
  }
  const int iterations = options.normal_iterations + (rims ? options.rim_iterations : 0);
  for (int it = 0; it < iterations; ++it) {
    const bool all = it == 0 || full;
    const bool rim_only = it >= options.normal_iterations;
    const bool refresh = !patches || it % interval == 0;  // the guidance (and so the range kernels) recomputed
    if (!refresh) {
      std::fill(guided_changed.begin(), guided_changed.end(), 0);
    } else if (patches) {
      last_guidance.swap(guidance);
      // From the second computation on, the buffer of two computations before: its columns of the faces
      // not filtered hold their normals, which never change, and guidance_normals writes every filtered one.
      if (it == 0) guidance = normals;
      // The faces not filtered: their guidance is their normal, new in the first iteration only.
      if (all || it == interval) std::fill(guided_changed.begin(), guided_changed.end(), all ? 1 : 0);
      // A patch is computed again where one of its normals changed since it was last computed (in any
      // iteration since then: on a real scan nearly every patch in the normal iterations, and in the rim
      // iterations only those reaching a rim face).
      guidance_normals(w, *patches, normals, changed_since, all, min_cos, state, last_guidance, guidance,
                       guided_changed);
      std::fill(changed_since.begin(), changed_since.end(), 0);
    }
    const Eigen::Matrix3Xd& compared = patches ? guidance : normals;
    const std::vector<std::uint8_t>& compared_changed = patches ? guided_changed : changed;
    // The range kernel of every pair, from |n_b - n_a|^2 of unit normals, in single precision (the hot
    // spot). The dot product is symmetric, bit for bit.
    parallel_chunks(refresh ? range.size() : 0, 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t s = begin; s < end; ++s) {
        const auto a = static_cast<std::size_t>(w.slot_a[s]), b = static_cast<std::size_t>(w.slot_b[s]);
        if (!all && !compared_changed[a] && !compared_changed[b]) continue;
        const double dr = 2.0 - 2.0 * compared.col(w.slot_b[s]).dot(compared.col(w.slot_a[s]));
        range[s] = std::exp(static_cast<float>(-dr * inv_r));
      }
    });
    const bool rim_faces_only = !full && it >= options.normal_iterations + 2;
    parallel_chunks(rim_faces_only ? rim_list.size() : nk, 1024, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t q = begin; q < end; ++q) {
        const std::size_t k = rim_faces_only ? static_cast<std::size_t>(rim_list[q]) : q;
        const Index f = w.filtered[k];
        if (rim_only && !rim[k]) {  // not a rim face: its normal stays
          next.col(f) = normals.col(f);
          nextf.col(f) = nf.col(f);
          changes[static_cast<std::size_t>(f)] = 0;
          continue;
        }
        bool stale = all || summed[k] == 0;  // a face whose last sum vanished is summed again
        for (Index r = w.ring_offsets[k]; r < w.ring_offsets[k + 1] && !stale; ++r) {
          const auto g = static_cast<std::size_t>(w.ring[static_cast<std::size_t>(r)]);
          stale = changed[g] != 0 || (patches && guided_changed[g] != 0);
        }
        if (!stale) {  // the last sum again: the normal stays
          next.col(f) = normals.col(f);
          nextf.col(f) = nf.col(f);
          changes[static_cast<std::size_t>(f)] = 0;
          continue;
        }
        Eigen::Vector4f accf = Eigen::Vector4f::Zero();
        if (refresh) {  // new kernels: the coefficients of the face's neighbourhood again
          for (Index r = w.ring_offsets[k]; r < w.ring_offsets[k + 1]; ++r) {
            const auto ru = static_cast<std::size_t>(r);
            const auto kernel = static_cast<double>(range[static_cast<std::size_t>(w.ring_slot[ru])]);
            coefficient[ru] = static_cast<float>(w.ring_weights[ru] * kernel);
            accf += coefficient[ru] * nf.col(w.ring[ru]);
          }
        } else {
          for (Index r = w.ring_offsets[k]; r < w.ring_offsets[k + 1]; ++r) {
            const auto ru = static_cast<std::size_t>(r);
            accf += coefficient[ru] * nf.col(w.ring[ru]);
          }
        }
        const Eigen::Vector3d acc = accf.head<3>().cast<double>();
        const double len = acc.norm();
        summed[k] = len > 0.0 ? 1 : 0;
        if (len > 0.0) {
          next.col(f) = acc / len;
          nextf.col(f) << next.col(f).cast<float>(), 0.0f;
        }
        changes[static_cast<std::size_t>(f)] = same_bits(next.col(f), normals.col(f)) ? 0 : 1;
        changed_since[static_cast<std::size_t>(f)] |= changes[static_cast<std::size_t>(f)];
      }
    });
    normals.swap(next);
    nf.swap(nextf);
    changed.swap(changes);
  }
}

// The move d of moving vertex m (off the contours) from its start x0, within `reach` of it and in its slab.
Eigen::Vector3d within_bounds(const Workspace& w, std::size_t m, const Eigen::Vector3d& axis, double reach,
                              const Eigen::Vector3d& x0, Eigen::Vector3d d) {
  if (d.norm() > reach) d *= reach / d.norm();
  const double h0 = axis.dot(x0);
  const double h = std::clamp(h0 + axis.dot(d), w.low[m], w.high[m]);
  d += axis * (h - h0 - axis.dot(d));
  return d;
}

// The vertex update (eq. 6, with a step: OffSliceFilterOptions::vertex_step), Jacobi style: each moving
// vertex goes towards the planes of its faces with the filtered normals `normals` (per filtered face),
// within its bounds (see filter_off_slice_normals).
// `x` and `start` hold the local vertices.
void update_vertices(const ContourFrame& frame, const Workspace& w, const Eigen::Matrix3Xd& normals,
                     const OffSliceFilterOptions& options, const Eigen::Matrix3Xd& start, Eigen::Matrix3Xd& x) {
  const double reach = options.max_move * frame.slice_spacing;
  const Eigen::Vector3d& axis = frame.axis;
  const std::size_t nk = w.filtered.size(), nm = w.moving.size();
  Eigen::Matrix3Xd centroids = detail::huge_matrix<Eigen::Matrix3Xd>(3, static_cast<Index>(nk));
  // Jacobi steps into a second buffer, swapped with x after each iteration: the vertices that do not move
  // are the same in both.
  Eigen::Matrix3Xd other = x;
  // Only what changed is recomputed: a vertex's update reads the corners of its faces (through their
  // centroids) and fixed data. Where none of them moved, bit for bit, in the last iteration, the update is
  // the last one again, which is where the vertex is; a centroid whose corners stayed is the same too.
  std::vector<std::uint8_t> moved;  // per local vertex, last iteration
  detail::assign_huge(moved, static_cast<std::size_t>(x.cols()), 0);
  std::vector<std::uint8_t> face_moved;  // per filtered face: a corner moved (its centroid is new)
  detail::assign_huge(face_moved, nk, 0);
  const bool full = full_recompute();
  for (int it = 0; it < options.vertex_iterations; ++it) {
    const bool all = it == 0 || full;
    parallel_chunks(nk, 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        const Triangle& t = w.corners[k];
        const auto c0 = static_cast<std::size_t>(t[0]), c1 = static_cast<std::size_t>(t[1]),
                   c2 = static_cast<std::size_t>(t[2]);
        face_moved[k] = all || moved[c0] || moved[c1] || moved[c2] ? 1 : 0;
        if (face_moved[k]) centroids.col(static_cast<Index>(k)) = (x.col(t[0]) + x.col(t[1]) + x.col(t[2])) / 3.0;
      }
    });
    parallel_chunks(nm, 2048, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t m = begin; m < end; ++m) {
        const Index i = w.moving[m];
        const Index first = w.incident_offsets[m], last = w.incident_offsets[m + 1];
        bool stale = false;
        for (Index r = first; r < last && !stale; ++r) {
          stale = face_moved[static_cast<std::size_t>(w.incident[static_cast<std::size_t>(r)])] != 0;
        }
        if (!stale) {  // the last update again
          other.col(i) = x.col(i);
          moved[static_cast<std::size_t>(i)] = 0;
          continue;
        }
        Eigen::Vector3d step = Eigen::Vector3d::Zero();
        for (Index r = first; r < last; ++r) {
          const Index f = w.incident[static_cast<std::size_t>(r)];
          step += normals.col(f) * normals.col(f).dot(centroids.col(f) - x.col(i));
        }
        step *= options.vertex_step / static_cast<double>(last - first);
        const Eigen::Vector3d x0 = start.col(i);
        Eigen::Vector3d d;
        if (w.on_contour[m]) {
          // A contour vertex stays in its slice plane, within the fidelity bound of where it was.
          step -= axis * axis.dot(step);
          d = x.col(i) + step - x0;
          if (d.norm() > options.contour_max_move) d *= options.contour_max_move / d.norm();
        } else {
          if (options.motion == OffSliceMotion::AlongAxis) step = axis * axis.dot(step);
          d = within_bounds(w, m, axis, reach, x0, x.col(i) + step - x0);
        }
        other.col(i) = x0 + d;
        moved[static_cast<std::size_t>(i)] = same_bits(other.col(i), x.col(i)) ? 0 : 1;
      }
    });
    x.swap(other);
  }
}

// Six times the signed volume of the cone from `origin` over the triangle (a, b, c).
double cone_volume6(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& origin) {
  return (a - origin).dot((b - origin).cross(c - origin));
}

// The regions of OffSliceVolume::Preserve: the moving vertices off the contours joined through the filtered
// faces they share (not through contour vertices). Per filtered face and per moving vertex, its region (the
// smallest moving index in it), or -1 (a face with no such corner, a contour vertex); per region (at its
// index), six times the volume its faces enclose at `start` seen from its first vertex's start.
struct Regions {
  std::vector<Index> of_face, of_moving;
  std::vector<double> start_volume6;
};

// The cone volumes of the filtered faces of each region at the positions x, six times, from the region's
// first vertex's start, added into `volume6` (per region, at its index).
void region_volumes6(const Workspace& w, const Regions& regions, const Eigen::Matrix3Xd& start,
                     const Eigen::Matrix3Xd& x, std::vector<double>& volume6) {
  for (std::size_t k = 0; k < w.filtered.size(); ++k) {
    const Index r = regions.of_face[k];
    if (r < 0) continue;
    const Triangle& t = w.corners[k];
    volume6[static_cast<std::size_t>(r)] +=
        cone_volume6(x.col(t[0]), x.col(t[1]), x.col(t[2]), start.col(w.moving[static_cast<std::size_t>(r)]));
  }
}

Regions off_slice_regions(const Workspace& w, Index local_vertices, const Eigen::Matrix3Xd& start) {
  const std::size_t nk = w.filtered.size(), nm = w.moving.size();
  std::vector<Index> moving_of;
  detail::assign_huge(moving_of, static_cast<std::size_t>(local_vertices), -1);
  for (std::size_t m = 0; m < nm; ++m) {
    if (!w.on_contour[m]) moving_of[static_cast<std::size_t>(w.moving[m])] = static_cast<Index>(m);
  }
  UnionFind<Index> sets(nm);
  Regions r;
  detail::assign_huge(r.of_face, nk, -1);
  for (std::size_t k = 0; k < nk; ++k) {
    Index root = -1;
    for (Index v : w.corners[k]) {
      const Index m = moving_of[static_cast<std::size_t>(v)];
      if (m >= 0) root = root < 0 ? sets.find(m) : sets.unite(root, m);
    }
    r.of_face[k] = root;
  }
  for (Index& root : r.of_face) {
    if (root >= 0) root = sets.find(root);
  }
  detail::assign_huge(r.of_moving, nm, -1);
  for (std::size_t m = 0; m < nm; ++m) {
    if (!w.on_contour[m]) r.of_moving[m] = sets.find(static_cast<Index>(m));
  }
  r.start_volume6.assign(nm, 0.0);
  region_volumes6(w, r, start, start, r.start_volume6);
  return r;
}

// OffSliceVolume::Preserve: each region is offset along its vertex normals (those not `fixed`, per local
// vertex) by one distance, clamped to the bounds of update_vertices, so that the filtered faces touching
// it enclose what they enclosed at `start` (the other faces did not move, so on a closed mesh that is the
// enclosed volume). A few rounds, as clamping leaves a rest. Sequential and in mesh order: the sums do
// not depend on the thread count.
void restore_volume(const ContourFrame& frame, const Workspace& w, const OffSliceFilterOptions& options,
                    const Regions& regions, const Eigen::Matrix3Xd& start, const std::vector<std::uint8_t>& fixed,
                    Eigen::Matrix3Xd& x) {
  const std::size_t nm = w.moving.size();
  const double reach = options.max_move * frame.slice_spacing;
  const Eigen::Vector3d& axis = frame.axis;
  std::vector<double> change(nm), rate(nm);  // per region: 6 x the volume change; the change per mm of offset
  Eigen::Matrix3Xd normal = detail::huge_matrix<Eigen::Matrix3Xd>(3, static_cast<Index>(nm));
  for (int round = 0; round < 3; ++round) {
    for (std::size_t r = 0; r < nm; ++r) change[r] = -regions.start_volume6[r];
    std::fill(rate.begin(), rate.end(), 0.0);
    region_volumes6(w, regions, start, x, change);
    // Each vertex's normal: the sum of its faces' cross products (twice their areas). An offset d along
    // it changes the volume by d times a third of the faces' areas.
    normal.setZero();
    for (std::size_t m = 0; m < nm; ++m) {
      if (regions.of_moving[m] < 0 || fixed[static_cast<std::size_t>(w.moving[m])]) continue;
      for (Index q = w.incident_offsets[m]; q < w.incident_offsets[m + 1]; ++q) {
        const Triangle& t = w.corners[static_cast<std::size_t>(w.incident[static_cast<std::size_t>(q)])];
        normal.col(static_cast<Index>(m)) += (x.col(t[1]) - x.col(t[0])).cross(x.col(t[2]) - x.col(t[0]));
      }
      rate[static_cast<std::size_t>(regions.of_moving[m])] += normal.col(static_cast<Index>(m)).norm() / 6.0;
    }
    bool moved = false;
    for (std::size_t m = 0; m < nm; ++m) {
      const Index r = regions.of_moving[m];
      if (r < 0 || fixed[static_cast<std::size_t>(w.moving[m])]) continue;
      const auto ru = static_cast<std::size_t>(r);
      const double len = normal.col(static_cast<Index>(m)).norm();
      if (!(rate[ru] > 0.0) || !(len > 0.0)) continue;
      const double offset = -change[ru] / 6.0 / rate[ru];
      Eigen::Vector3d step = normal.col(static_cast<Index>(m)) * (offset / len);
      if (options.motion == OffSliceMotion::AlongAxis) step = axis * axis.dot(step);
      const Index i = w.moving[m];
      const Eigen::Vector3d x0 = start.col(i);
      const Eigen::Vector3d d = within_bounds(w, m, axis, reach, x0, x.col(i) + step - x0);
      moved = moved || x0 + d != x.col(i);
      x.col(i) = x0 + d;
    }
    if (!moved) break;
  }
}

// A face that turned over (its normal against its unfiltered one) gets its moving vertices back, until
// none does; they are marked in `undone` (per local vertex). Whether any vertex went back.
bool undo_turned_faces(const Workspace& w, const Eigen::Matrix3Xd& initial_normals, const Eigen::Matrix3Xd& start,
                       Eigen::Matrix3Xd& x, std::vector<std::uint8_t>& undone) {
  bool undid = false;
  for (int round = 0; round < 8; ++round) {
    bool any = false;
    for (std::size_t k = 0; k < w.filtered.size(); ++k) {
      const Triangle& t = w.corners[k];
      const auto kk = static_cast<Index>(k);
      if (initial_normals.col(kk).isZero() || face_normal(x, t).dot(initial_normals.col(kk)) > 0.0) continue;
      for (int c = 0; c < 3; ++c) {
        const Index v = t[static_cast<std::size_t>(c)];
        if (w.moves[static_cast<std::size_t>(v)] && x.col(v) != start.col(v)) {
          x.col(v) = start.col(v);
          undone[static_cast<std::size_t>(v)] = 1;
          any = true;
        }
      }
    }
    undid = undid || any;
    if (!any) break;
  }
  return undid;
}


}  // namespace

std::size_t filter_off_slice_normals(const ContourFrame& frame, const std::vector<Triangle>& triangles,
                                     const OffSliceFilterOptions& options, Eigen::Matrix3Xd& positions) {
  if (options.filter == OffSliceFilter::None) return 0;
  Workspace w = make_workspace(frame, triangles, options);
  if (w.moving.empty()) return 0;

  // Normals, areas and centroids of the local faces, from the mesh's positions.
  const auto nl = static_cast<Index>(w.faces.size());
  Eigen::Matrix3Xd normals = detail::huge_matrix<Eigen::Matrix3Xd>(3, nl);
  Eigen::Matrix3Xd centroids = detail::huge_matrix<Eigen::Matrix3Xd>(3, nl);
  Eigen::VectorXd areas(nl);
  parallel_chunks(w.faces.size(), 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t l = begin; l < end; ++l) {
      const Triangle& t = triangles[static_cast<std::size_t>(w.faces[l])];
      const auto ll = static_cast<Index>(l);
      double a = 0.0;
      normals.col(ll) = face_normal(positions, t, &a);
      areas[ll] = a;
      centroids.col(ll) = (positions.col(t[0]) + positions.col(t[1]) + positions.col(t[2])) / 3.0;
    }
  });
  const auto nk = static_cast<Index>(w.filtered.size());
  Eigen::Matrix3Xd initial_normals = detail::huge_matrix<Eigen::Matrix3Xd>(3, nk);
  parallel_chunks(w.filtered.size(), 8192, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) initial_normals.col(static_cast<Index>(k)) = normals.col(w.filtered[k]);
  });

  // The local vertices where they start, and the heights each moving vertex off the contours may take.
  const auto nv = static_cast<Index>(w.vertices.size());
  Eigen::Matrix3Xd start = detail::huge_matrix<Eigen::Matrix3Xd>(3, nv);
  parallel_chunks(w.vertices.size(), 8192, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) start.col(static_cast<Index>(v)) = positions.col(w.vertices[v]);
  });
  {
    const std::vector<double> levels = slice_levels(frame, positions);
    const double reach = options.max_move * frame.slice_spacing;
    detail::assign_huge(w.low, w.moving.size(), 0.0);
    detail::assign_huge(w.high, w.moving.size(), 0.0);
    parallel_chunks(w.moving.size(), 8192, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t m = begin; m < end; ++m) {
        if (w.on_contour[m]) continue;
        const double h0 = frame.axis.dot(start.col(w.moving[m]));
        std::tie(w.low[m], w.high[m]) = height_bounds(levels, h0, frame.slice_spacing, reach);
      }
    });
  }

  spatial_weights(centroids, areas, w);
  GuidancePatches patches;
  const bool guided = options.range == OffSliceRange::PatchGuidance;
  if (guided) patches = make_patches(frame, triangles, positions, w, centroids, areas);
  filter_normals(w, options, guided ? &patches : nullptr, normals);
  Eigen::Matrix3Xd filtered_normals = detail::huge_matrix<Eigen::Matrix3Xd>(3, nk);
  for (Index k = 0; k < nk; ++k) filtered_normals.col(k) = normals.col(w.filtered[static_cast<std::size_t>(k)]);

  Eigen::Matrix3Xd x = start;
  update_vertices(frame, w, filtered_normals, options, start, x);
  std::vector<std::uint8_t> undone;
  detail::assign_huge(undone, w.vertices.size(), 0);
  undo_turned_faces(w, initial_normals, start, x, undone);
  // The volume after the undo, which may give back part of what the fit moved; the vertices it sent back
  // stay, and if the offsets turn a face, its vertices go back too and the rest try again.
  if (options.volume == OffSliceVolume::Preserve) {
    const Regions regions = off_slice_regions(w, x.cols(), start);
    for (int round = 0; round < 3; ++round) {
      restore_volume(frame, w, options, regions, start, undone, x);
      if (!undo_turned_faces(w, initial_normals, start, x, undone)) break;
    }
  }
  std::size_t moved = 0;
  for (Index v : w.moving) {
    if (x.col(v) == start.col(v)) continue;
    positions.col(w.vertices[static_cast<std::size_t>(v)]) = x.col(v);
    ++moved;
  }
  return moved;
}

}  // namespace contourmesh::detail
