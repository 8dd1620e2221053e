// Typed exceptions thrown by libsmooth. The CLI maps them to exit codes (InvalidInputError and its
// subclasses -> 2 "bad input", CancelledError -> 130-style cancel, anything else -> 3 "internal").
#pragma once

#include <stdexcept>
#include <string>

namespace contourmesh {

/// The input violates a documented precondition (sizes, NaN/Inf, indices out of range, options out of
/// range). The message names what and where (for a mesh: the vertex or triangle index).
class InvalidInputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// The mesh connectivity is unusable for the requested operation: degenerate or duplicate triangles,
/// non-manifold edges or vertices, an open mesh where a closed one is required.
class TopologyError : public InvalidInputError {
 public:
  using InvalidInputError::InvalidInputError;
};

/// The input is too large for a configured limit: a mesh with more vertices than allowed, or a step
/// whose estimated memory exceeds the budget (see limits.h). Raised before the big allocation, so the
/// process fails with a message instead of running out of memory.
class LimitError : public InvalidInputError {
 public:
  using InvalidInputError::InvalidInputError;
};

/// A progress callback asked to stop. Nothing the operation would have returned is valid.
class CancelledError : public std::runtime_error {
 public:
  CancelledError() : std::runtime_error("operation cancelled") {}
  explicit CancelledError(const std::string& stage) : std::runtime_error("operation cancelled during " + stage) {}
};

}  // namespace contourmesh
