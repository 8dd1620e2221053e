// SPDX-License-Identifier: BSD-3-Clause
// Resource limits: a cap on the vertices of any mesh read or produced and a memory budget checked
// before the big allocations (tiling, adaptive subdivision), so oversized inputs fail with a clear
// LimitError instead of an out-of-memory crash.
#pragma once

#include "contourmesh/smooth/mesh.h"

#include <cstddef>
#include <string>
#include <string_view>

namespace contourmesh {

/// Default vertex cap: 50 million vertices, a few GB per copy of the mesh (the smoothing chain holds
/// several: positions, adjacency, curvatures, the adaptive mesh).
inline constexpr Index kDefaultMaxVertices = 50'000'000;

struct ResourceLimits {
  /// Meshes with more vertices than this are refused, > 0.
  Index max_vertices = kDefaultMaxVertices;
  /// Bytes one step may allocate. 0: the memory the system reports available when the check runs
  /// (MemAvailable on Linux; no limit where it cannot be queried).
  std::size_t max_memory_bytes = 0;
};

/// Memory the system can give this process now, in bytes (Linux: MemAvailable from /proc/meminfo;
/// elsewhere physical pages from sysconf when available); 0 when unknown.
[[nodiscard]] std::size_t available_memory_bytes();

/// "12.3 GB", "850 MB": a byte count for messages.
[[nodiscard]] std::string format_bytes(double bytes);

/// Throws LimitError naming `what` when `vertices` exceeds limits.max_vertices, or when `bytes` exceeds
/// limits.max_memory_bytes (or, when that is 0, the available memory). The message gives the count or
/// the estimate and the limit, e.g. "adaptive subdivision: 61000000 vertices exceed the limit of
/// 50000000 vertices".
void check_allocation(std::string_view what, double vertices, double bytes, const ResourceLimits& limits);

}  // namespace contourmesh
