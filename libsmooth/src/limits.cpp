// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/limits.h"

#include "contourmesh/smooth/errors.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

namespace contourmesh {

std::size_t available_memory_bytes() {
#if defined(__linux__)
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::size_t kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit) {
    if (key == "MemAvailable:") return kib * 1024;
  }
#endif
#if defined(_SC_PHYS_PAGES) && defined(_SC_PAGESIZE)
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page = ::sysconf(_SC_PAGESIZE);
  if (pages > 0 && page > 0) return static_cast<std::size_t>(pages) * static_cast<std::size_t>(page);
#endif
  return 0;
}

std::string format_bytes(double bytes) {
  char buf[32];
  if (bytes >= 1e9) std::snprintf(buf, sizeof buf, "%.1f GB", bytes / 1e9);
  else if (bytes >= 1e6) std::snprintf(buf, sizeof buf, "%.0f MB", bytes / 1e6);
  else if (bytes >= 1e3) std::snprintf(buf, sizeof buf, "%.0f kB", bytes / 1e3);
  else std::snprintf(buf, sizeof buf, "%.0f bytes", bytes);
  return buf;
}

void check_allocation(std::string_view what, double vertices, double bytes, const ResourceLimits& limits) {
  if (!(limits.max_vertices > 0)) throw InvalidInputError("the vertex limit must be > 0");
  if (vertices > static_cast<double>(limits.max_vertices)) {
    std::ostringstream msg;
    msg.precision(0);
    msg << std::fixed << what << ": " << vertices << " vertices exceed the limit of " << limits.max_vertices
        << " vertices";
    throw LimitError(msg.str());
  }
  const std::size_t budget = limits.max_memory_bytes > 0 ? limits.max_memory_bytes : available_memory_bytes();
  if (budget > 0 && bytes > static_cast<double>(budget)) {
    throw LimitError(std::string(what) + ": needs about " + format_bytes(bytes) + " of memory, more than the " +
                     format_bytes(static_cast<double>(budget)) +
                     (limits.max_memory_bytes > 0 ? " allowed" : " available"));
  }
}

}  // namespace contourmesh
