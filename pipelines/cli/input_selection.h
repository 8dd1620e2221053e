// SPDX-License-Identifier: BSD-3-Clause
// Options of the commands that read a volume and may pick part of it: labels of a label map or a
// 3D Slicer segmentation (--label, --labels) instead of a threshold, and one DICOM series of a
// directory that holds several (--series, --list-series).
#pragma once

#include <contourmesh/reconstruct/label_map.h>
#include <contourmesh/reconstruct/volume.h>

#include <filesystem>
#include <string>

namespace CLI {
class App;
class Option;
}

namespace contourmesh::cli {

struct InputSelectionArgs {
  std::string label;   ///< --label: one label, by value or name
  std::string labels;  ///< --labels: "all" or a comma-separated list of values or names
  std::string series;  ///< --series UID
  bool list_series = false;
};

/// Registers --label, --labels, --series and --list-series on `command`. --label and --labels exclude
/// each other and every option in `threshold_options` (the threshold path's).
void add_input_selection_options(CLI::App* command, InputSelectionArgs& args,
                                 const std::vector<CLI::Option*>& threshold_options);

/// True when --label or --labels was given.
[[nodiscard]] bool labels_requested(const InputSelectionArgs& args);

/// The read options for --series.
[[nodiscard]] VolumeReadOptions read_options(const InputSelectionArgs& args);

/// The label map of `input` and the labels --label / --labels select (InvalidInputError naming `input`
/// when none matches).
struct SelectedLabels {
  LabelMap map;
  std::vector<Label> labels;
};
[[nodiscard]] SelectedLabels read_selected_labels(const std::string& input, const InputSelectionArgs& args);

/// Where the mesh of `label` goes: with --label, `output` itself; with --labels, `output` with
/// "{label}" replaced by the label's tag (label_file_tag), or when it has none, "<stem>_<tag><ext>".
[[nodiscard]] std::filesystem::path label_output_path(const std::string& output, const Label& label,
                                                      const InputSelectionArgs& args);

/// --list-series: prints the DICOM series of directory `input` (a table, or one JSON object with
/// `series`: [{uid, number, modality, description, files}]). Returns the exit code.
int print_series_list(const std::string& input, bool json);

}  // namespace contourmesh::cli
