// SPDX-License-Identifier: BSD-3-Clause
// contourmesh: the command-line front end of ContourMesh.
#include "cli_common.h"

#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"ContourMesh: feature-preserving smoothing of meshes reconstructed from CT contours"};
  app.set_version_flag("--version", std::string("contourmesh ") + CONTOURMESH_VERSION);
  app.require_subcommand(1);
  app.fallthrough(false);
  contourmesh::cli::add_phantom_command(app);
  contourmesh::cli::add_contours_command(app);
  contourmesh::cli::add_reconstruct_command(app);
  contourmesh::cli::add_detect_command(app);
  contourmesh::cli::add_smooth_command(app);
  contourmesh::cli::add_run_command(app);
  contourmesh::cli::add_compare_command(app);
  contourmesh::cli::install_signal_handlers();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help/version on stdout, errors on stderr
    return code == 0 ? contourmesh::cli::kOk : contourmesh::cli::kUsage;
  }
  // The selected subcommand's callback ran inside parse() and stored its exit code.
  return contourmesh::cli::last_exit_code();
}
