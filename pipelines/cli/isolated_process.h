// SPDX-License-Identifier: BSD-3-Clause
// Process control of the CLI (never of a library): run work that may abort the process in a child.
#pragma once

#include <functional>
#include <string>

namespace contourmesh::cli {

/// Runs `work` in a forked child process and waits for it. Returns "" when the child exits normally
/// after `work` returned; otherwise why it did not (an exception's message goes to stderr, then "failed
/// (exit code N, ...)"; a signal, e.g. VTK aborting when the X display goes away: "failed (signal N...)").
/// The child exits without running destructors or atexit handlers of the parent's state.
[[nodiscard]] std::string run_isolated(const std::string& what, const std::function<void()>& work);

}  // namespace contourmesh::cli
