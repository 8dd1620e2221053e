// SPDX-License-Identifier: BSD-3-Clause
// Balls of vertices for per-vertex neighbourhood work on every core (crease detection and crease
// restoration): the vertices within a radius of one vertex and connected to it through such vertices,
// gathered breadth-first into scratch space that each worker reuses. Private to libsmooth.
#pragma once

#include "contourmesh/internal/huge_pages.h"
#include "contourmesh/smooth/adjacency.h"
#include "contourmesh/smooth/mesh.h"

#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace contourmesh::detail {

/// Scratch space of one worker: the gathered vertices, and a stamp per mesh vertex (the ball's number
/// when it was gathered), so that membership is one look-up instead of a search.
struct BallScratch {
  std::vector<Index> ball;
  std::vector<std::uint32_t> stamp;
  std::uint32_t current = 0;

  explicit BallScratch(Index vertices) { assign_huge(stamp, static_cast<std::size_t>(vertices), std::uint32_t{0}); }

  /// Starts a new ball: no vertex is a member.
  void clear() {
    ball.clear();
    if (++current == 0) {  // after 2^32 balls: forget every stamp
      std::fill(stamp.begin(), stamp.end(), 0u);
      current = 1;
    }
  }
  /// Whether j is a member of the current ball.
  [[nodiscard]] bool has(Index j) const { return stamp[static_cast<std::size_t>(j)] == current; }
  /// Adds j unless it is a member; whether it was added.
  bool add(Index j) {
    std::uint32_t& s = stamp[static_cast<std::size_t>(j)];
    if (s == current) return false;
    s = current;
    ball.push_back(j);
    return true;
  }
};

/// Hands each chunk of a parallel loop a BallScratch no other chunk is using; builds one only when all
/// are taken (so as many as run at once, each of the mesh's size).
class BallScratchPool {
 public:
  explicit BallScratchPool(Index vertices) : vertices_(vertices) {}
  std::unique_ptr<BallScratch> take() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!free_.empty()) {
        std::unique_ptr<BallScratch> s = std::move(free_.back());
        free_.pop_back();
        return s;
      }
    }
    return std::make_unique<BallScratch>(vertices_);
  }
  void give_back(std::unique_ptr<BallScratch> s) {
    const std::lock_guard<std::mutex> lock(mutex_);
    free_.push_back(std::move(s));
  }

 private:
  Index vertices_;
  std::mutex mutex_;
  std::vector<std::unique_ptr<BallScratch>> free_;
};

/// Every vertex within `radius` of vertex i and connected to it through such vertices, gathered
/// breadth-first from i into scratch.ball; the search stops once `max_vertices` are gathered (a
/// safeguard against degenerate, very dense meshes; the last ring examined may add a few more).
inline void gather_ball(const Mesh& mesh, const MeshAdjacency& adjacency, Index i, double radius,
                        std::size_t max_vertices, BallScratch& scratch) {
  const Eigen::Vector3d centre = mesh.positions.col(i);
  const double r2 = radius * radius;
  scratch.clear();
  scratch.add(i);
  const std::vector<Index>& ball = scratch.ball;
  for (std::size_t b = 0; b < ball.size() && ball.size() < max_vertices; ++b) {
    for (Index j : adjacency.ring(ball[b])) {
      // A member already (most ring neighbours are, once the ball grows) before the distance.
      if (scratch.has(j) || (mesh.positions.col(j) - centre).squaredNorm() > r2) continue;
      scratch.add(j);
    }
  }
}

}  // namespace contourmesh::detail
