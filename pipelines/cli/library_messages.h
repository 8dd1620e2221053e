// SPDX-License-Identifier: BSD-3-Clause
// The messages ITK, GDCM and VTK print on their own: multi-line, with source file names and object
// addresses. Without --verbose each becomes one line of the tool's own ("contourmesh COMMAND: warning:
// ITK: ..."), or nothing where the command reports the problem itself; with --verbose they pass as
// they are.
#pragma once

#include <string>

namespace contourmesh::cli {

/// Installs ITK's and VTK's output windows and GDCM's trace setting for the running command.
void configure_library_messages(const std::string& command, bool verbose);

/// One line from a library's message: without "WARNING: In file, line N" preambles, "Class (0x...): "
/// prefixes and blank lines; lines joined with "; ", at most 300 characters, printable.
[[nodiscard]] std::string one_line(const std::string& text);

}  // namespace contourmesh::cli
