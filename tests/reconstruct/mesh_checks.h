// SPDX-License-Identifier: BSD-3-Clause
// Topology checks shared by the reconstruction tests.
#pragma once

#include <contourmesh/smooth/topology.h>

namespace contourmesh::test {

struct Topology {
  bool closed = false;
  bool manifold = false;
  long euler = 0;
  int components = 0;
  std::string problems;
};

inline Topology topology_of(const Mesh& mesh) {
  const TopologySummary s = summarize_topology(mesh);
  return {s.closed, s.manifold, s.euler_characteristic, s.components, s.first_problems};
}

}  // namespace contourmesh::test
