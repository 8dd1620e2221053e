#include "smooth/cross_slice.h"

#include "detail/parallel.h"
#include "smooth/adjacency.h"
#include "smooth/contour_structure.h"
#include "smooth/errors.h"
#include "smooth/normals.h"
#include "smooth/slice_neighbors.h"

#include <Eigen/Dense>

#include <chrono>
#include <cmath>

namespace contourmesh {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

struct Frame {
  const Mesh& mesh;
  const MeshAdjacency& adjacency;
  const ContourNeighbours& contour;
  const SliceRings& rings;
  Eigen::Vector3d axis;  // slice axis, towards increasing slice ids
};

// The contour vertices of the next slice (upward or downward) adjacent to `from`.
void next_slice_vertices(const Frame& f, Index from, bool upward, std::vector<Index>& out) {
  for (Index j : upward ? f.rings.above(from) : f.rings.below(from)) {
    if (f.contour.of[j][0] >= 0) out.push_back(j);
  }
}

// Where the plane {x : (x - origin) . plane_normal = 0} cuts the contour through the `start` vertices:
// walking at most `max_steps` edges each way from each start vertex, the crossing nearest to the
// origin's slice-axis line. Returns false when there is none.
bool cut_contour(const Frame& f, const std::vector<Index>& start, const Eigen::Vector3d& origin,
                 const Eigen::Vector3d& plane_normal, Eigen::Vector3d& cut, Index& edge_a, Index& edge_b) {
  constexpr int kMaxSteps = 24;
  const Eigen::Matrix3Xd& x = f.mesh.positions;
  double best = std::numeric_limits<double>::infinity();
  for (Index j0 : start) {
    for (int side = 0; side < 2; ++side) {
      Index prev = j0, cur = f.contour.of[j0][static_cast<std::size_t>(side)];
      for (int step = 0; step < kMaxSteps && cur >= 0; ++step) {
        const double sp = (x.col(prev) - origin).dot(plane_normal), sc = (x.col(cur) - origin).dot(plane_normal);
        if ((sp <= 0.0) != (sc <= 0.0)) {
          const double t = sp / (sp - sc);
          const Eigen::Vector3d q = x.col(prev) + t * (x.col(cur) - x.col(prev));
          const Eigen::Vector3d r = q - origin;
          const double off_axis = (r - r.dot(f.axis) * f.axis).norm();
          if (off_axis < best) {
            best = off_axis;
            cut = q;
            edge_a = prev;
            edge_b = cur;
          }
          break;
        }
        const auto& nb = f.contour.of[cur];
        const Index next = nb[0] == prev ? nb[1] : nb[0];
        prev = cur;
        cur = next;
      }
    }
  }
  return std::isfinite(best);
}

// The profile of contour vertex i: (height along the axis, offset along m) of the cuts of the plane
// through v_i with normal `tangent`, over up to `reach` slices each way; (0, 0) is the vertex itself.
void profile(const Frame& f, Index i, const Eigen::Vector3d& m, const Eigen::Vector3d& tangent, int reach,
             double max_offset, std::vector<Eigen::Vector2d>& out) {
  out.assign(1, Eigen::Vector2d::Zero());
  const Eigen::Vector3d v = f.mesh.positions.col(i);
  std::vector<Index> start;
  for (const bool upward : {true, false}) {
    start.clear();
    next_slice_vertices(f, i, upward, start);
    for (int k = 1; k <= reach && !start.empty(); ++k) {
      Eigen::Vector3d cut = Eigen::Vector3d::Zero();
      Index a = -1, b = -1;
      if (!cut_contour(f, start, v, tangent, cut, a, b)) break;
      const Eigen::Vector3d r = cut - v;
      if ((r - r.dot(f.axis) * f.axis).norm() > max_offset) break;
      out.emplace_back(r.dot(f.axis), r.dot(m));
      start.clear();
      next_slice_vertices(f, a, upward, start);
      next_slice_vertices(f, b, upward, start);
    }
  }
}

// The weighted least-squares polynomial of the profile, evaluated at height 0; false when the profile
// cannot support a fit (one-sided, or too few points).
bool fit_at_zero(const std::vector<Eigen::Vector2d>& prof, double spacing, int reach, int degree, double& value) {
  int up = 0, down = 0;
  for (const Eigen::Vector2d& p : prof) {
    up += p.x() > 0.1 * spacing ? 1 : 0;
    down += p.x() < -0.1 * spacing ? 1 : 0;
  }
  if (up == 0 || down == 0) return false;
  const int n = static_cast<int>(prof.size());
  degree = std::min(degree, n - 2);
  if (degree < 0) return false;
  const double bandwidth = reach + 1.0;
  Eigen::MatrixXd a(n, degree + 1);
  Eigen::VectorXd b(n), w(n);
  for (int k = 0; k < n; ++k) {
    const double z = prof[static_cast<std::size_t>(k)].x() / spacing;
    const double u = std::min(1.0, std::abs(z) / bandwidth);
    w[k] = std::pow(1.0 - u * u * u, 3);
    double power = 1.0;
    for (int d = 0; d <= degree; ++d, power *= z) a(k, d) = power;
    b[k] = prof[static_cast<std::size_t>(k)].y();
  }
  const Eigen::MatrixXd atw = a.transpose() * w.asDiagonal();
  const Eigen::VectorXd c = (atw * a).ldlt().solve(atw * b);
  value = c[0];
  return std::isfinite(value);
}

}  // namespace

CrossSliceResult cross_slice_smooth(const Mesh& mesh, const CrossSliceOptions& options) {
  if (!mesh.has_contour_ids()) {
    throw InvalidInputError("cross-slice smoothing needs contour ids (recover them from the slice planes first)");
  }
  if (options.reach < 1) throw InvalidInputError("cross-slice smoothing: reach must be >= 1");
  if (options.degree < 1 || options.degree > 2) throw InvalidInputError("cross-slice smoothing: degree must be 1 or 2");
  if (options.extension_iterations < 0) {
    throw InvalidInputError("cross-slice smoothing: extension iterations must be >= 0");
  }
  const auto start = std::chrono::steady_clock::now();
  CrossSliceResult result;
  const MeshAdjacency adjacency = build_adjacency(mesh);

  auto t = std::chrono::steady_clock::now();
  DetectionOptions detection = options.detection;
  if (!detection.progress) detection.progress = options.progress;
  result.detection = detect_features(mesh, adjacency, detection);
  result.seconds_detect = seconds_since(t);

  t = std::chrono::steady_clock::now();
  const ContourNeighbours contour = contour_neighbours(mesh, adjacency);
  const SliceRings rings = split_rings_by_slice(mesh, adjacency);
  const Frame frame{mesh, adjacency, contour, rings, estimate_slice_axis(mesh)};
  const Eigen::Matrix3Xd normals = vertex_normals(mesh.positions, mesh.triangles);
  const Index n = mesh.num_vertices();

  // Slice spacing: the median height of the edges between adjacent slices.
  std::vector<double> heights;
  for (Index i = 0; i < n && heights.size() < 4096; ++i) {
    for (Index j : rings.above(i)) heights.push_back(std::abs((mesh.positions.col(j) - mesh.positions.col(i)).dot(frame.axis)));
  }
  if (heights.empty()) throw InvalidInputError("cross-slice smoothing: no edge joins two slices");
  std::nth_element(heights.begin(), heights.begin() + static_cast<std::ptrdiff_t>(heights.size() / 2), heights.end());
  const double spacing = heights[heights.size() / 2];
  if (!(spacing > 0.0)) throw InvalidInputError("cross-slice smoothing: the slices are not apart");

  Eigen::Matrix3Xd displacement = Eigen::Matrix3Xd::Zero(3, n);
  std::vector<std::uint8_t> on_contour(static_cast<std::size_t>(n), 0);
  std::vector<std::size_t> fitted(static_cast<std::size_t>((n + 1023) / 1024), 0);
  detail::parallel_chunks(static_cast<std::size_t>(n), 1024, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    std::vector<Eigen::Vector2d> prof;
    for (std::size_t ii = begin; ii < end; ++ii) {
      const Index i = static_cast<Index>(ii);
      if (mesh.slice_ids[ii] < 0 || contour.of[ii][0] < 0) continue;
      on_contour[ii] = 1;
      Eigen::Vector3d m = normals.col(i) - normals.col(i).dot(frame.axis) * frame.axis;
      if (m.norm() < 1e-3) continue;
      m.normalize();
      const Eigen::Vector3d tangent = frame.axis.cross(m);
      profile(frame, i, m, tangent, options.reach, 6.0 * spacing, prof);
      double offset = 0.0;
      if (!fit_at_zero(prof, spacing, options.reach, options.degree, offset)) continue;
      displacement.col(i) = offset * m;
      ++fitted[chunk];
    }
  });
  for (std::size_t c : fitted) result.profiles += c;
  if (options.progress && !options.progress("smooth", 0.8)) throw CancelledError("smoothing");

  // Harmonic extension of the displacements to the vertices off the contours.
  Eigen::Matrix3Xd next = displacement;
  for (int it = 0; it < options.extension_iterations; ++it) {
    for (Index i = 0; i < n; ++i) {
      if (on_contour[static_cast<std::size_t>(i)]) continue;
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      const auto ring = adjacency.ring(i);
      for (Index j : ring) sum += displacement.col(j);
      if (!ring.empty()) next.col(i) = sum / static_cast<double>(ring.size());
    }
    displacement.swap(next);
  }
  result.mesh = mesh;
  result.mesh.positions += displacement;
  result.seconds_smooth = seconds_since(t);
  result.seconds_total = seconds_since(start);
  if (options.progress && !options.progress("smooth", 1.0)) throw CancelledError("smoothing");
  return result;
}

}  // namespace contourmesh
