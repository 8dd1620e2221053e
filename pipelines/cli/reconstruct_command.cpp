// contourmesh reconstruct: CT volume -> contours -> tiled mesh. (Being implemented.)
#include "cli_common.h"

#include <CLI/CLI.hpp>

namespace contourmesh::cli {

void add_reconstruct_command(CLI::App& app) { (void)app; }

}  // namespace contourmesh::cli
