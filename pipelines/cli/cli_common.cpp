// SPDX-License-Identifier: BSD-3-Clause
#include "cli_common.h"

#include <contourmesh/reconstruct/phantom.h>
#include <contourmesh/smooth/atomic_file.h>
#include <contourmesh/smooth/errors.h>

#include <CLI/CLI.hpp>

#include <unistd.h>

#include <csignal>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <new>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace contourmesh::cli {

namespace {

int run_guarded_body(const std::string& command, const std::function<int()>& body);

volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_cancel_signal(int signal) {
  if (g_signal != 0) {  // the second one: stop now, without leaving temporaries behind
    remove_pending_temporaries();
    ::_exit(kSignalBase + signal);
  }
  g_signal = signal;
}

const char* signal_name(int signal) { return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal"; }

}  // namespace

void install_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_cancel_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: a blocking read returns, and the next progress report cancels
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
}

bool cancel_requested() { return g_signal != 0; }
int cancel_signal() { return static_cast<int>(g_signal); }

void check_distinct_outputs(const std::vector<std::pair<std::string, std::string>>& outputs) {
  std::vector<std::pair<std::string, std::filesystem::path>> paths;
  for (const auto& [label, path] : outputs) paths.emplace_back(label, path);
  contourmesh::check_distinct_outputs(paths);
}

int run_guarded(const std::string& command, const std::function<int()>& body) {
  const int code = run_guarded_body(command, body);
  if (cancel_requested()) {
    if (code == kOk) {
      std::cerr << "contourmesh " << command << ": interrupted by " << signal_name(cancel_signal())
                << " after the outputs were complete\n";
    }
    return kSignalBase + cancel_signal();
  }
  return code;
}

namespace {

int run_guarded_body(const std::string& command, const std::function<int()>& body) {
  try {
    return body();
  } catch (const UsageError& e) {
    std::cerr << "contourmesh " << command << ": error: " << e.what() << "\n";
    return kUsage;
  } catch (const LimitError& e) {
    const std::string what = e.what();
    std::cerr << "contourmesh " << command << ": error: " << cli_wording(what)
              << (what.find("limit of") != std::string::npos ? "; raise it with --max-vertices" : "") << "\n";
    return kBadInput;
  } catch (const InvalidInputError& e) {
    std::cerr << "contourmesh " << command << ": error: " << cli_wording(e.what()) << "\n";
    return kBadInput;
  } catch (const CancelledError& e) {
    if (cancel_requested()) {
      std::cerr << "contourmesh " << command << ": cancelled by " << signal_name(cancel_signal())
                << "; no partial file was left\n";
    } else {
      std::cerr << "contourmesh " << command << ": " << e.what() << "\n";
    }
    return kBadInput;
  } catch (const std::filesystem::filesystem_error& e) {
    // Creating an output directory, and the like: the path the user gave is unusable.
    std::cerr << "contourmesh " << command << ": error: " << e.path1().string() << ": " << e.code().message() << "\n";
    return kBadInput;
  } catch (const std::bad_alloc&) {
    std::cerr << "contourmesh " << command
              << ": error: out of memory (the input is too large for this machine; lower --max-vertices to fail "
                 "earlier, or use a coarser sampling)\n";
    return kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "contourmesh " << command << ": internal error: " << e.what() << "\n";
    return kInternal;
  }
}

}  // namespace

namespace {
int g_exit_code = kOk;
}  // namespace

std::string fixed(double v, int digits) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

std::string cli_wording(std::string text) {
  static const std::pair<const char*, const char*> kPhrases[] = {
      {"give the slice axis", "give --slice-axis"},
      {"allow uneven slices", "give --allow-uneven-slices"},
      {"treat non-finite voxels as air", "give --non-finite-as-air"},
  };
  for (const auto& [library, cli] : kPhrases) {
    if (const auto at = text.find(library); at != std::string::npos) text.replace(at, std::strlen(library), cli);
  }
  return text;
}

void set_exit_code(int code) { g_exit_code = code; }
int last_exit_code() { return g_exit_code; }

void print_json(const nlohmann::json& json) { std::cout << json.dump() << std::endl; }

void add_max_vertices_option(CLI::App* command, Index& max_vertices) {
  command
      ->add_option("--max-vertices", max_vertices,
                   "Refuse meshes (read or produced) with more vertices than this, before allocating them")
      ->check(CLI::Range(1, std::numeric_limits<Index>::max()))
      ->capture_default_str();
}

CLI::Option* add_contour_noise_option(CLI::App* command, double& contour_noise) {
  return command
      ->add_option("--contour-noise", contour_noise,
                   "Phantom contour noise: RMS in mm of each slice's own random displacement of its contours "
                   "(waves of centimetres plus bumps of a few mm; the paper's noise model), 0 to 10")
      ->capture_default_str();
}

void check_contour_noise(double contour_noise) {
  if (!std::isfinite(contour_noise) || contour_noise < 0.0 || contour_noise > kMaxContourNoise) {
    throw InvalidInputError("--contour-noise must be an RMS in [0, " +
                            std::to_string(static_cast<int>(kMaxContourNoise)) + "] mm");
  }
}

std::string phantom_shape_names(const std::string& separator) {
  std::string names;
  for (PhantomShape s : all_phantom_shapes()) names += (names.empty() ? "" : separator) + std::string(to_string(s));
  for (PhantomShape s : extra_phantom_shapes()) names += separator + std::string(to_string(s));
  return names;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace contourmesh::cli
