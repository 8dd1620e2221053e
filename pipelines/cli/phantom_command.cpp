// contourmesh phantom: writes a synthetic CT volume of a built-in phantom. (Being implemented.)
#include "cli_common.h"

#include <CLI/CLI.hpp>

namespace contourmesh::cli {

void add_phantom_command(CLI::App& app) { (void)app; }

}  // namespace contourmesh::cli
