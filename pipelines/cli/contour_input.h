// SPDX-License-Identifier: BSD-3-Clause
// The contour route of the CLI, shared by `reconstruct`, `run` and `contours`: what kind of input a
// path is, the options of drawn contours, loading one or all ROIs of an RT Structure Set or a
// contour-stack file, and naming one output per ROI.
#pragma once

#include <contourmesh/reconstruct/contour_reconstruction.h>
#include <contourmesh/reconstruct/contours.h>
#include <contourmesh/reconstruct/planar_contours.h>
#include <contourmesh/smooth/end_caps.h>
#include <contourmesh/smooth/mesh.h>

#include <nlohmann/json.hpp>

#include <array>
#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace contourmesh::cli {

enum class InputKind {
  Volume,        ///< a CT volume file or a DICOM series directory
  StructureSet,  ///< a DICOM RT Structure Set file
  ContourFile,   ///< a contour-stack file (.json)
};

/// The kind of `path`: .json is a contour file, a DICOM file whose header says RT Structure Set is a
/// structure set, anything else a volume.
[[nodiscard]] InputKind input_kind(const std::string& path);

/// Options of the contour route.
struct ContourArgs {
  std::string roi;                      ///< --roi NAME | NUMBER | all
  double sampling_tolerance = 0.05;     ///< --sampling-tolerance MM
  std::string align = "centroids";      ///< --align centroids | none
  std::string single_slice = "slab";    ///< --single-slice slab | drop
  std::optional<double> slab_thickness; ///< --slab-thickness MM
  double planarity_tolerance = 0.05;    ///< --planarity-tolerance MM
};

/// Registers --roi and the contour options on `command`.
void add_contour_options(CLI::App* command, ContourArgs& args);
/// --single-slice's value: slab | drop (InvalidInputError otherwise). It applies to volumes too.
[[nodiscard]] SingleSliceContours parse_single_slice(const std::string& name);

/// Throws InvalidInputError when an option of the image route was given for contour input (or the
/// reverse): `names` are the options of the other route, looked up on `command`.
void reject_options(const CLI::App* command, const std::vector<std::string>& names, const std::string& why);

/// One contour stack to reconstruct.
struct ContourInput {
  std::string what;                         ///< "ROI 5 'Heart'", or the file name
  std::string stem;                         ///< output file stem (sanitised ROI name)
  std::string name;                         ///< ROI or stack name ("" when none)
  int roi_number = -1;                      ///< -1 for a contour file
  std::optional<std::array<int, 3>> color;
  ContourStack stack;                       ///< normalised: oriented, holes from nesting, slices ordered
  double default_slab_thickness = 0.0;      ///< for a one-slice stack without --slab-thickness
  std::vector<std::string> warnings;
  std::string error;                        ///< set when this ROI cannot be reconstructed (with --roi all)
};

/// What load_contour_inputs found.
struct ContourInputs {
  std::vector<ContourInput> inputs;
  bool all = false;                         ///< --roi all
  std::vector<std::string> skipped;         ///< ROIs without contours (with --roi all): one line each
  std::vector<std::string> warnings;        ///< about the file as a whole
};

/// Loads the stacks to reconstruct: from a structure set the ROI named by --roi (required; "all": every
/// ROI, those without contours listed as skipped and those that fail with `error` set), from a contour
/// file its one stack (--roi must be empty). Throws InvalidInputError naming the file otherwise.
[[nodiscard]] ContourInputs load_contour_inputs(const std::string& path, InputKind kind, const ContourArgs& args);

/// Options of reconstruct_from_contours from the command line (`tiling` with its vertex limit set to
/// `max_vertices`).
[[nodiscard]] ContourReconstructionOptions contour_options(const ContourArgs& args, const ContourInput& input,
                                                           std::optional<double> sampling, const TilingOptions& tiling,
                                                           Index max_vertices);

/// Output of one ROI: `output` itself for a single ROI; with --roi all, `output` with "{roi}" replaced
/// by the stem, or else `output` as a directory holding "<stem><extension>".
[[nodiscard]] std::filesystem::path roi_output_path(const std::string& output, const ContourInput& input, bool all,
                                                    const std::string& extension);

/// The output path of every input (roi_output_path), each checked before any work: its directory is
/// created when missing, it must be writable, and with `json_only` end in .json. An empty `output`
/// gives empty paths (no such output).
[[nodiscard]] std::vector<std::filesystem::path> roi_outputs(const std::string& output, const ContourInputs& loaded,
                                                             const std::string& extension, bool json_only = false);

/// Runs `body` on every input, collecting the JSON object it returns for each. With --roi all, an
/// input whose conversion failed, or whose body throws InvalidInputError, is reported (one error line
/// on stderr, and {"status": "failed", "error": ...}) and the others go on; with one ROI the error
/// propagates, prefixed by the file. Returns the objects and sets `failed`.
[[nodiscard]] nlohmann::json for_each_roi(const std::string& command, const std::string& path,
                                          const ContourInputs& loaded,
                                          const std::function<nlohmann::json(const ContourInput&, std::size_t)>& body,
                                          std::size_t& failed);

/// The JSON a command prints: the one ROI's object, or (--roi all) `rois`, `skipped` and `failed`;
/// with `command`, `input` and `seconds` since `start`.
[[nodiscard]] nlohmann::json roi_results_json(const std::string& command, const std::string& path,
                                              const ContourInputs& loaded, nlohmann::json rois, std::size_t failed,
                                              std::chrono::steady_clock::time_point start);

/// Creates the directory of `path` when missing (InvalidInputError when it cannot).
void ensure_parent_directory(const std::filesystem::path& path);

/// Prints each line as "contourmesh COMMAND: warning: LINE" on stderr.
void print_warnings(const std::string& command, const std::vector<std::string>& lines);

/// JSON fields describing the input: "roi" {number, name} (structure sets), "name", "color".
void describe_input(nlohmann::json& j, const ContourInput& input);

/// Writes the normalised drawn stack of `input` as a contour-stack file.
void write_input_contours(const ContourInput& input, const std::filesystem::path& path);

}  // namespace contourmesh::cli
