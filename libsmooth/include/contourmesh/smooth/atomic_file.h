// SPDX-License-Identifier: BSD-3-Clause
// Output files that are either complete or absent: written to a temporary sibling, flushed to disk and
// renamed over the destination. Shared by every writer of ContourMesh (meshes, volumes, reports), so
// that they all follow the same rules (docs/robustness.md, "Writes"):
// - only regular files are replaced, or new ones created: an existing device, FIFO or socket is
//   refused (`-o /dev/null` never replaces /dev/null, and nothing is written into a device);
// - a symbolic link is written through: its target is replaced, the link stays;
// - the temporary name fits the file system's NAME_MAX, however long the destination's name;
// - the data is fsync'ed before the rename, so a crash never leaves a renamed but empty file;
// - a failure or a cancellation removes the temporary and leaves an existing file byte for byte.
#pragma once

#include "contourmesh/smooth/progress.h"

#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace contourmesh {

/// The file a write to `path` replaces or creates: `path` with its symbolic links followed (a dangling
/// link gives the path it points to). Throws InvalidInputError naming `path` for a loop of links.
[[nodiscard]] std::filesystem::path resolve_output_path(const std::filesystem::path& path);

/// Checks, before any work, that a file can be written at `path`: it names a file; after following
/// symbolic links, its directory exists, is a directory and is writable (access with W_OK: also
/// catches a read-only file system; root passes permission bits, as writing would), and the file
/// either does not exist or is a regular file (not a directory, device, FIFO or socket). Throws
/// InvalidInputError naming `path` and the reason.
void check_output_path(const std::filesystem::path& path);

/// Throws InvalidInputError when two of the outputs of one run name the same file (after following
/// symbolic links and "." and ".."; hard links to one file included): the second write would silently
/// replace the first. Each entry is (what the caller calls it, e.g. "--labels-out", path); empty paths
/// are skipped.
void check_distinct_outputs(const std::vector<std::pair<std::string, std::filesystem::path>>& outputs);

/// Calls `write(temporary_path)`, which must write the whole file at that path (the name exists, empty,
/// when `write` is called), then flushes it to disk and renames it over the destination (`path` with
/// symbolic links followed; an existing file's permission bits are kept). The temporary lives in the
/// destination's directory (same file system, so the rename is atomic), is hidden (a leading dot), and
/// keeps the destination's extension. `progress`, when set, is called with ("write", 1) once the data
/// is on disk: returning false cancels (CancelledError) before the destination is touched. If anything
/// fails or cancels, the temporary is removed and the destination is left untouched. Throws
/// InvalidInputError naming `path` when check_output_path fails, or the flush or the rename fails
/// (a full disk is usually seen here); exceptions from `write` propagate.
void write_atomically(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write,
                      const ProgressCallback& progress = {});

/// Writes `text` atomically to `path` (used for JSON and CSV outputs); checks every write.
void write_text_atomically(const std::filesystem::path& path, const std::string& text,
                           const ProgressCallback& progress = {});

/// Removes the temporary files of the writes in progress in this process (at most 64 are tracked).
/// Async-signal-safe (it only calls unlink): for a signal handler that ends the process at once.
void remove_pending_temporaries() noexcept;

/// The temporary name write_atomically uses next to `destination`, for a given unique `tag`: a leading
/// dot, the destination's stem shortened (at a UTF-8 character boundary) so that the whole name fits in
/// `name_max` bytes, ".tmp-" and the tag, and the destination's extension. Exposed for tests.
[[nodiscard]] std::filesystem::path temporary_name(const std::filesystem::path& destination, const std::string& tag,
                                                   std::size_t name_max = 255);

}  // namespace contourmesh
