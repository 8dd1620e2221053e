// SPDX-License-Identifier: BSD-3-Clause
// Options every subcommand shares (--quiet, --threads) and the progress display on stderr.
#pragma once

#include <contourmesh/smooth/progress.h>

#include <chrono>
#include <string>
#include <string_view>

namespace CLI {
class App;
}

namespace contourmesh::cli {

struct CommonArgs {
  bool quiet = false;
  bool verbose = false;  ///< let ITK, GDCM, MetaIO, NIfTI and VTK print their own messages
  int threads = 0;       ///< 0: every core
  std::string command;   ///< the subcommand's name, set by add_common_options
};

/// Registers --quiet / -q, --verbose and --threads on a subcommand.
void add_common_options(CLI::App* command, CommonArgs& args);

/// Validates --threads (>= 0, at most ITK's maximum, and a stack per thread within the memory
/// available: InvalidInputError or LimitError otherwise) and caps every parallel stage at that many
/// threads for the rest of the process (ThreadLimit: TBB loops, ITK filters, VTK's SMP tools; and
/// vtkMultiThreader, which VTK's image filters use).
/// Without --verbose, the messages of ITK, GDCM and VTK are turned into one line each
/// ("contourmesh COMMAND: warning: ITK: ..."), or dropped where the command reports the problem itself.
void apply_common_options(const CommonArgs& args);

/// Whether --verbose was given to the running command.
[[nodiscard]] bool verbose();

/// Stage-by-stage progress on stderr. On a terminal: one line redrawn in place with the stage name, a
/// bar and the elapsed time. Otherwise (a pipe, a log file): one line per finished stage. Nothing with
/// --quiet. Stages come from stage() or from the library's progress callback.
class ProgressDisplay {
 public:
  ProgressDisplay(std::string command, bool quiet);
  ~ProgressDisplay();
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

  /// Ends the current stage (if any) and starts `name`; throws CancelledError instead once SIGINT or
  /// SIGTERM arrived.
  void stage(std::string_view name);
  /// A callback for library calls: switches stage when the name changes, draws the fraction. Returns
  /// false (cancel) once SIGINT or SIGTERM arrived (cancel_requested()).
  [[nodiscard]] ProgressCallback callback();
  /// Ends the current stage.
  void finish();

 private:
  void draw(double fraction, bool force);

  std::string command_;
  bool quiet_;
  bool terminal_;
  std::string stage_;
  std::chrono::steady_clock::time_point stage_start_{};
  std::chrono::steady_clock::time_point last_draw_{};
};

}  // namespace contourmesh::cli
