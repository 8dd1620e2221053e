// SPDX-License-Identifier: BSD-3-Clause
// Typed exceptions thrown by libsmooth. The CLI maps them to exit codes (InvalidInputError and its
// subclasses -> 2 "bad input", CancelledError -> 2, or 128 + the signal when a signal cancelled the
// run, anything else -> 3 "internal"; docs/cli.md).
#pragma once

#include <exception>
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

/// A computation left the range where its result means anything: a coordinate became NaN or infinite,
/// or moved far beyond the input's extent (an iterative smoother run for too many iterations, or with
/// too large a step). Raised instead of returning the result, so nothing diverged is reported as
/// success. The message names the stage, the iteration when known, and a vertex.
class DivergenceError : public InvalidInputError {
 public:
  using InvalidInputError::InvalidInputError;
};

/// Rethrows the exception being handled with `context + ": "` in front of its message, keeping its type
/// (LimitError, DivergenceError, TopologyError, InvalidInputError); a message that already starts with
/// the context is rethrown as it is, as is any other exception. Call only inside a catch block.
[[noreturn]] inline void rethrow_with_context(const std::string& context) {
  auto with = [&](const std::exception& e) {
    const std::string what = e.what();
    return what.rfind(context + ": ", 0) == 0 ? what : context + ": " + what;
  };
  try {
    throw;
  } catch (const LimitError& e) {
    throw LimitError(with(e));
  } catch (const DivergenceError& e) {
    throw DivergenceError(with(e));
  } catch (const TopologyError& e) {
    throw TopologyError(with(e));
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(with(e));
  }
}

/// A progress callback asked to stop. Nothing the operation would have returned is valid.
class CancelledError : public std::runtime_error {
 public:
  CancelledError() : std::runtime_error("operation cancelled") {}
  explicit CancelledError(const std::string& stage) : std::runtime_error("operation cancelled during " + stage) {}
};

}  // namespace contourmesh
