// Atomic output files: write to a temporary sibling, then rename over the destination.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace contourmesh {

/// Checks, before any work, that a file can be created at `path`: it names a file, its directory
/// exists and is a directory, `path` itself is not a directory, and the directory is writable (access
/// with W_OK: also catches a read-only file system; root passes permission bits, as writing would).
/// Throws InvalidInputError naming `path` and the reason.
void check_output_path(const std::filesystem::path& path);

/// Calls `write(temporary_path)`, which must create the file at that path, then renames it to `path`.
/// The temporary lives in the same directory (same file system, so the rename is atomic) and keeps the
/// extension of `path`. If `write` throws or the rename fails, the temporary is removed and `path` is
/// left untouched. Throws InvalidInputError naming `path` when check_output_path fails or the rename
/// fails; exceptions from `write` propagate.
void write_atomically(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write);

/// Writes `text` atomically to `path` (used for JSON and CSV outputs).
void write_text_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace contourmesh
