// SPDX-License-Identifier: BSD-3-Clause
// The contour-stack file: a documented JSON form of a ContourStack, so that contours from any tool,
// or written by hand, can be tiled, and the contours the image route found can be inspected. The
// format is specified in docs/contours.md.
#pragma once

#include <contourmesh/reconstruct/contours.h>

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace contourmesh {

/// A contour stack as stored in a file, with the optional description fields.
struct ContourStackFile {
  ContourStack stack;
  std::string name;                          ///< "name": what the contours outline (optional)
  std::optional<std::array<int, 3>> color;   ///< "color": display colour, RGB 0-255 (optional)
  /// Per slice and contour, the "hole" flag as written in the file, when present (read only).
  std::vector<std::vector<std::optional<bool>>> declared_holes;
};

/// True when `path` ends in .json (case-insensitive): the contour-stack file.
[[nodiscard]] bool is_contour_stack_path(const std::filesystem::path& path);

/// Reads a contour-stack file. The stack is returned as stored: points in slice coordinates, slices
/// in file order, orientation and holes as given (normalize_contour_stack recomputes them). Throws
/// InvalidInputError naming the file and the JSON location ("slices[3].contours[1].points[7]") for:
/// unreadable or malformed JSON, a wrong "format" or a "version" other than 1, missing or mistyped
/// fields, non-finite numbers, a frame whose axes are not orthonormal and right-handed, a contour with
/// fewer than 3 points, slices not ordered by increasing "w".
[[nodiscard]] ContourStackFile read_contour_stack(const std::filesystem::path& path);

/// Writes a contour-stack file atomically (the frame, every slice, empty ones too, and for each
/// contour its points, "hole" and "parent"). Coordinates are written with enough digits to read back
/// the same doubles. Throws InvalidInputError naming the file when it cannot be written.
void write_contour_stack(const ContourStackFile& file, const std::filesystem::path& path);

/// The JSON text write_contour_stack writes.
[[nodiscard]] std::string contour_stack_json(const ContourStackFile& file);

}  // namespace contourmesh
