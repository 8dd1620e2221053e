// SPDX-License-Identifier: BSD-3-Clause
// Conventions shared by the contourmesh subcommands: exit codes, error reporting, JSON output.
#pragma once

#include "spacing.h"

#include <contourmesh/smooth/mesh.h>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <chrono>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace CLI {
class App;
class Option;
}

namespace contourmesh::cli {

/// Documented exit codes (docs/cli.md).
enum ExitCode : int {
  kOk = 0,
  kUsage = 1,     ///< bad command line
  kBadInput = 2,  ///< unreadable or invalid input, or an output that cannot be written
  kInternal = 3,  ///< a bug or an unexpected failure
  kSignalBase = 128,  ///< + the signal number: cancelled by SIGINT (130) or SIGTERM (143)
};

/// A command line that does not fit its input (an option of the image route given for contours, a
/// structure set without --roi): exit code 1, like CLI11's own usage errors.
class UsageError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Runs a subcommand body, mapping exceptions to exit codes and one-line messages on stderr:
/// UsageError -> 1, InvalidInputError (LimitError with a hint at --max-vertices) -> 2, CancelledError -> 2, or
/// 128 + the signal when SIGINT or SIGTERM cancelled the run, a filesystem error -> 2,
/// std::bad_alloc -> 2 (out of memory), anything else -> 3.
int run_guarded(const std::string& command, const std::function<int()>& body);

/// Installs the SIGINT and SIGTERM handlers. The first signal asks the running command to stop:
/// cancel_requested() turns true, the progress callbacks return false, the library throws
/// CancelledError at its next progress report, every temporary output file is removed on the way out,
/// and run_guarded exits with 128 + the signal. A second signal removes the temporaries still being
/// written and ends the process at once, with the same code.
void install_signal_handlers();
/// True once SIGINT or SIGTERM arrived.
[[nodiscard]] bool cancel_requested();
/// The signal that asked to cancel, 0 if none.
[[nodiscard]] int cancel_signal();

/// Throws InvalidInputError when two outputs of one run name the same file (check_distinct_outputs),
/// e.g. --labels-out equal to -o.
void check_distinct_outputs(const std::vector<std::pair<std::string, std::string>>& outputs);

/// The exit code of the subcommand that ran (subcommand callbacks cannot return one).
void set_exit_code(int code);
int last_exit_code();

/// The library's wording turned into the command line's: "give the slice axis" -> "give --slice-axis",
/// "allow uneven slices" -> "give --allow-uneven-slices", "treat non-finite voxels as air" -> "give
/// --non-finite-as-air". Applied to every error and warning the commands print.
[[nodiscard]] std::string cli_wording(std::string text);

/// `v` with `digits` digits after the point, or "-" when it is not finite (a region without samples).
[[nodiscard]] std::string fixed(double v, int digits);

/// Prints `json` as one line on stdout.
void print_json(const nlohmann::json& json);

/// Registers --max-vertices N on `command`: meshes read or produced with more vertices are refused
/// (exit 2) before the memory is allocated. Default kDefaultMaxVertices.
void add_max_vertices_option(CLI::App* command, Index& max_vertices);

/// Registers --contour-noise MM on `command` (per-slice contour noise of a phantom, default 0).
CLI::Option* add_contour_noise_option(CLI::App* command, double& contour_noise);

/// Throws InvalidInputError unless `contour_noise` is a finite RMS in [0, kMaxContourNoise] mm.
void check_contour_noise(double contour_noise);

/// The built-in phantoms' names joined by `separator`, in PhantomShape order.
[[nodiscard]] std::string phantom_shape_names(const std::string& separator);

/// Seconds since `start`.
double seconds_since(std::chrono::steady_clock::time_point start);

/// Registers the subcommands on `app`.
void add_smooth_command(CLI::App& app);
void add_detect_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_phantom_command(CLI::App& app);
void add_reconstruct_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_contours_command(CLI::App& app);

}  // namespace contourmesh::cli
