// SPDX-License-Identifier: BSD-3-Clause
#include "progress_display.h"

#include "cli_common.h"
#include "library_messages.h"

#include <contourmesh/reconstruct/threads.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/limits.h>

#include <CLI/CLI.hpp>
#include <itkMultiThreaderBase.h>
#include <vtkMultiThreader.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <optional>

namespace contourmesh::cli {

namespace {
bool g_verbose = false;
// Stack and per-thread buffers reserved for each worker thread, for the memory check of --threads.
constexpr double kBytesPerThread = 2.0 * 1024 * 1024;
}  // namespace

void add_common_options(CLI::App* command, CommonArgs& args) {
  args.command = command->get_name();
  command->add_flag("-q,--quiet", args.quiet, "No progress and no summary; errors are still printed");
  command->add_flag("--verbose", args.verbose,
                    "Let ITK, GDCM, MetaIO and VTK print their own (multi-line) messages on stderr");
  command->add_option("--threads", args.threads,
                      "Threads for every parallel stage (segmentation, tiling, smoothing, ITK and VTK filters; "
                      "0: every core)")
      ->capture_default_str();
}

void apply_common_options(const CommonArgs& args) {
  g_verbose = args.verbose;
  configure_library_messages(args.command, args.verbose);
  if (args.threads < 0) throw InvalidInputError("--threads must be >= 0, got " + std::to_string(args.threads));
  if (args.threads > 0) {
    const auto most = itk::MultiThreaderBase::GetGlobalMaximumNumberOfThreads();
    if (static_cast<unsigned long>(args.threads) > most) {
      throw InvalidInputError("--threads " + std::to_string(args.threads) + ": more than the " + std::to_string(most) +
                              " worker threads ITK can run");
    }
    check_allocation("--threads " + std::to_string(args.threads), 0.0, args.threads * kBytesPerThread,
                     ResourceLimits{});
  }
  // One subcommand runs per process: the limit lasts until the process exits. VTK's image filters
  // thread with their own vtkMultiThreader (0: no cap), not with TBB.
  static std::optional<ThreadLimit> limit;
  limit.reset();
  limit.emplace(args.threads);
  vtkMultiThreader::SetGlobalMaximumNumberOfThreads(args.threads);
}

bool verbose() { return g_verbose; }

ProgressDisplay::ProgressDisplay(std::string command, bool quiet)
    : command_(std::move(command)), quiet_(quiet), terminal_(isatty(fileno(stderr)) != 0) {}

ProgressDisplay::~ProgressDisplay() {
  // A stage interrupted by an error is left without its "done" line; the error message follows.
  if (terminal_ && !quiet_ && !stage_.empty()) std::cerr << "\n";
}

void ProgressDisplay::stage(std::string_view name) {
  if (cancel_requested()) throw CancelledError(std::string(name));
  finish();
  stage_ = name;
  stage_start_ = std::chrono::steady_clock::now();
  last_draw_ = {};
  draw(0.0, true);
}

ProgressCallback ProgressDisplay::callback() {
  return [this](std::string_view name, double fraction) {
    if (cancel_requested()) return false;
    if (name != stage_) stage(name);
    draw(fraction, false);
    return true;
  };
}

void ProgressDisplay::finish() {
  if (stage_.empty()) return;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - stage_start_).count();
  if (!quiet_) {
    char line[160];
    std::snprintf(line, sizeof line, "%-12s done in %.2f s", stage_.c_str(), seconds);
    if (terminal_) {
      std::cerr << "\r" << line << "\x1b[K\n";
    } else {
      std::cerr << "contourmesh " << command_ << ": " << line << "\n";
    }
  }
  stage_.clear();
}

void ProgressDisplay::draw(double fraction, bool force) {
  if (quiet_ || !terminal_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  constexpr int kWidth = 30;
  const double f = std::clamp(fraction, 0.0, 1.0);
  const int filled = static_cast<int>(f * kWidth + 0.5);
  const double seconds = std::chrono::duration<double>(now - stage_start_).count();
  char line[200];
  std::snprintf(line, sizeof line, "%-12s [%s%s] %3d%%  %.1f s", stage_.c_str(), std::string(filled, '#').c_str(),
                std::string(kWidth - filled, '.').c_str(), static_cast<int>(100 * f + 0.5), seconds);
  std::cerr << "\r" << line << "\x1b[K" << std::flush;
}

}  // namespace contourmesh::cli
