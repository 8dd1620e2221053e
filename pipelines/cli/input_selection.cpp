// SPDX-License-Identifier: BSD-3-Clause
#include "input_selection.h"

#include "cli_common.h"

#include <contourmesh/smooth/errors.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <iomanip>
#include <iostream>

namespace contourmesh::cli {

void add_input_selection_options(CLI::App* command, InputSelectionArgs& args,
                                 const std::vector<CLI::Option*>& threshold_options) {
  CLI::Option* label = command->add_option(
      "--label", args.label,
      "Label map or .seg.nrrd input: mesh the voxels of this label (a value, or a segment name) instead of "
      "thresholding; writes -o");
  CLI::Option* labels = command->add_option(
      "--labels", args.labels,
      "Label map or .seg.nrrd input: 'all' or a comma-separated list of values or segment names; one mesh per "
      "label, named <output stem>_<label name or value><ext> (or -o with {label} replaced)");
  label->excludes(labels);
  for (CLI::Option* t : threshold_options) {
    label->excludes(t);
    labels->excludes(t);
  }
  command->add_option("--series", args.series,
                      "DICOM directory holding several series: the Series Instance UID to read (--list-series)");
  command->add_flag("--list-series", args.list_series,
                    "List the DICOM series of the input directory (UID, number, modality, files, description) "
                    "and exit");
}

bool labels_requested(const InputSelectionArgs& args) { return !args.label.empty() || !args.labels.empty(); }

VolumeReadOptions read_options(const InputSelectionArgs& args) {
  VolumeReadOptions o;
  o.series_uid = args.series;
  return o;
}

SelectedLabels read_selected_labels(const std::string& input, const InputSelectionArgs& args) {
  if (!args.series.empty()) throw InvalidInputError("--series reads a DICOM series; label maps are files");
  SelectedLabels s;
  s.map = read_label_map(input);
  try {
    s.labels = select_labels(s.map, args.label.empty() ? args.labels : args.label);
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(input + ": " + e.what());
  }
  if (!args.label.empty() && s.labels.size() != 1) {
    throw InvalidInputError("--label takes one label; use --labels for several");
  }
  return s;
}

std::filesystem::path label_output_path(const std::string& output, const Label& label, const InputSelectionArgs& args) {
  if (!args.label.empty()) return output;
  const std::string tag = label_file_tag(label);
  std::string text = output;
  const std::size_t at = text.find("{label}");
  if (at != std::string::npos) return text.replace(at, 7, tag);
  const std::filesystem::path path(output);
  return path.parent_path() / (path.stem().string() + "_" + tag + path.extension().string());
}

int print_series_list(const std::string& input, bool json) {
  const std::vector<DicomSeries> series = list_dicom_series(input);
  if (series.empty()) throw InvalidInputError(input + ": a directory without a DICOM series");
  if (json) {
    nlohmann::json j;
    j["input"] = input;
    j["series"] = nlohmann::json::array();
    for (const DicomSeries& s : series) {
      j["series"].push_back({{"uid", s.uid}, {"number", s.number}, {"modality", s.modality},
                             {"description", s.description}, {"files", s.files}});
    }
    print_json(j);
    return kOk;
  }
  std::size_t width = 3;
  for (const DicomSeries& s : series) width = std::max(width, s.uid.size());
  std::cout << std::left << std::setw(static_cast<int>(width)) << "UID" << "  " << std::setw(6) << "number" << "  "
            << std::setw(8) << "modality" << "  " << std::right << std::setw(5) << "files" << "  description\n";
  for (const DicomSeries& s : series) {
    std::cout << std::left << std::setw(static_cast<int>(width)) << s.uid << "  " << std::setw(6) << s.number << "  "
              << std::setw(8) << s.modality << "  " << std::right << std::setw(5) << s.files << "  " << s.description
              << "\n";
  }
  return kOk;
}

}  // namespace contourmesh::cli
