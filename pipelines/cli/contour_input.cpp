// SPDX-License-Identifier: BSD-3-Clause
#include "contour_input.h"

#include "cli_common.h"

#include <contourmesh/vtk/atomic_file.h>
#include <contourmesh/vtk/contour_stack_io.h>
#include <contourmesh/reconstruct/rtstruct.h>
#include <contourmesh/smooth/errors.h>

#include <CLI/CLI.hpp>

#include <iostream>
#include <utility>
#include <sstream>

namespace contourmesh::cli {

namespace {

PlanarStackOptions planar_options(const ContourArgs& args) {
  PlanarStackOptions o;
  if (!(args.planarity_tolerance > 0.0)) throw InvalidInputError("--planarity-tolerance must be > 0 mm");
  o.planarity_tolerance = args.planarity_tolerance;
  return o;
}

// One ROI of a structure set as a contour input; conversion errors go to `error` when `keep_errors`.
ContourInput roi_input(const RtStructureSet& set, const RtRoi& roi, const std::string& stem, const ContourArgs& args,
                       bool keep_errors) {
  ContourInput in;
  in.what = roi.label();
  in.stem = stem;
  in.name = roi.name;
  in.roi_number = roi.number;
  in.color = roi.color;
  in.default_slab_thickness = structure_set_slice_spacing(set).value_or(0.0);
  try {
    RoiStack rs = roi_contour_stack(roi, planar_options(args));
    in.stack = std::move(rs.planar.stack);
    in.warnings = std::move(rs.planar.report.warnings);
  } catch (const InvalidInputError& e) {
    if (!keep_errors) throw InvalidInputError(set.file.string() + ": " + e.what());
    in.error = e.what();
  }
  return in;
}

}  // namespace

InputKind input_kind(const std::string& path) {
  if (is_contour_stack_path(path)) return InputKind::ContourFile;
  if (is_rt_structure_set(path)) return InputKind::StructureSet;
  return InputKind::Volume;
}

void add_contour_options(CLI::App* cmd, ContourArgs& args) {
  cmd->add_option("--roi", args.roi,
                  "RT Structure Set: the ROI to reconstruct, by name or number, or 'all' (one mesh per ROI; "
                  "`contourmesh contours FILE --list` lists them)");
  cmd->add_option("--sampling-tolerance", args.sampling_tolerance,
                  "Contours: largest distance resampled contours may depart from the drawn ones, mm")
      ->capture_default_str();
  cmd->add_option("--align", args.align,
                  "Contours: centroids (tile a drifting single contour in centroid-aligned slices) | none")
      ->capture_default_str();
  cmd->add_option("--single-slice", args.single_slice,
                  "A contour with no partner on an adjacent slice (drawn on one slice, or an object or cavity "
                  "thinner than the slice spacing): slab (half-way to the adjacent slices; hollow for a hole) | "
                  "drop")
      ->capture_default_str();
  cmd->add_option("--slab-thickness", args.slab_thickness,
                  "Contours all in one slice: slab thickness, mm (default for a structure set: its slice spacing)");
  cmd->add_option("--planarity-tolerance", args.planarity_tolerance,
                  "Contours: largest distance of a contour point from its slice plane, mm")
      ->capture_default_str();
}

SingleSliceContours parse_single_slice(const std::string& name) {
  if (name == "slab") return SingleSliceContours::Slab;
  if (name == "drop") return SingleSliceContours::Drop;
  throw InvalidInputError("--single-slice must be slab or drop, got '" + name + "'");
}

void reject_options(const CLI::App* command, const std::vector<std::string>& names, const std::string& why) {
  for (const std::string& name : names) {
    if (command->count(name) > 0) throw UsageError(name + " " + why);
  }
}

ContourInputs load_contour_inputs(const std::string& path, InputKind kind, const ContourArgs& args) {
  ContourInputs out;
  if (kind == InputKind::ContourFile) {
    if (!args.roi.empty()) throw UsageError("--roi applies to RT Structure Sets, not to a contour file (" + path + ")");
    ContourStackFile file = read_contour_stack(path);
    ContourInput in;
    in.what = path;
    in.stem = std::filesystem::path(path).stem().string();
    in.name = file.name;
    in.color = file.color;
    in.stack = std::move(file.stack);
    const PlanarStackReport report = normalize_contour_stack(in.stack, path, planar_options(args));
    in.warnings = report.warnings;
    // A "hole" flag that disagrees with the nesting: the nesting wins.
    std::size_t disagree = 0;
    std::string first;
    for (std::size_t s = 0; s < in.stack.slices.size(); ++s) {
      for (std::size_t k = 0; k < in.stack.slices[s].contours.size(); ++k) {
        const std::size_t c = report.source[s][k];
        const auto& declared = file.declared_holes[s][c];
        if (declared && *declared != in.stack.slices[s].contours[k].is_hole) {
          if (disagree++ == 0) first = "contour " + std::to_string(c) + " of slice " + std::to_string(s);
        }
      }
    }
    if (disagree > 0) {
      in.warnings.push_back(path + ": " + std::to_string(disagree) + " contour" + (disagree == 1 ? "'s" : "s'") +
                            " \"hole\" flag disagrees with the nesting (first: " + first +
                            "); holes are the contours inside an odd number of others");
    }
    out.inputs.push_back(std::move(in));
    return out;
  }
  if (kind != InputKind::StructureSet) throw InvalidInputError(path + ": not an RT Structure Set or a contour file");
  const RtStructureSet set = read_rt_structure_set(path);
  out.warnings = set.warnings;
  if (args.roi.empty()) {
    std::string names;
    for (const RtRoi& roi : set.rois) names += (names.empty() ? "'" : ", '") + roi.name + "'";
    throw UsageError(path + " is an RT Structure Set: choose the structure with --roi NAME or --roi all (" +
                            (names.empty() ? "it has no ROI" : "its ROIs: " + names) + ")");
  }
  const std::vector<std::string> stems = roi_file_stems(set);
  if (args.roi == "all") {
    out.all = true;
    for (std::size_t i = 0; i < set.rois.size(); ++i) {
      const RtRoi& roi = set.rois[i];
      if (roi.contours.empty()) {
        out.skipped.push_back(roi.label() + " has no contours: skipped");
        continue;
      }
      out.inputs.push_back(roi_input(set, roi, stems[i], args, true));
    }
    if (out.inputs.empty()) throw InvalidInputError(path + ": no ROI has contours");
    return out;
  }
  const RtRoi& roi = find_roi(set, args.roi);
  const auto index = static_cast<std::size_t>(&roi - set.rois.data());
  if (roi.contours.empty()) {
    throw InvalidInputError(path + ": " + roi.label() + " has no contours: there is nothing to reconstruct");
  }
  out.inputs.push_back(roi_input(set, roi, stems[index], args, false));
  return out;
}

ContourReconstructionOptions contour_options(const ContourArgs& args, const ContourInput& input,
                                             std::optional<double> sampling, const TilingOptions& tiling,
                                             Index max_vertices) {
  ContourReconstructionOptions o;
  if (sampling) {
    if (!(*sampling >= 0.0)) throw InvalidInputError("--sampling must be >= 0 mm (0: the contours as drawn)");
    o.sampling = *sampling;
  }
  if (!(args.sampling_tolerance >= 0.0)) throw InvalidInputError("--sampling-tolerance must be >= 0 mm");
  o.sampling_tolerance = args.sampling_tolerance;
  if (args.align == "centroids") o.alignment = DriftAlignment::Centroids;
  else if (args.align == "none") o.alignment = DriftAlignment::None;
  else throw InvalidInputError("--align must be centroids or none, got '" + args.align + "'");
  o.single_slice = parse_single_slice(args.single_slice);
  if (args.slab_thickness && !(*args.slab_thickness > 0.0)) throw InvalidInputError("--slab-thickness must be > 0 mm");
  o.slab_thickness = args.slab_thickness.value_or(input.default_slab_thickness);
  o.tiling = tiling;
  o.tiling.limits.max_vertices = max_vertices;
  return o;
}

std::filesystem::path roi_output_path(const std::string& output, const ContourInput& input, bool all,
                                      const std::string& extension) {
  if (!all) return output;
  const std::string key = "{roi}";
  if (const auto at = output.find(key); at != std::string::npos) {
    std::string p = output;
    p.replace(at, key.size(), input.stem);
    return p;
  }
  return std::filesystem::path(output) / (input.stem + extension);
}

std::vector<std::filesystem::path> roi_outputs(const std::string& output, const ContourInputs& loaded,
                                               const std::string& extension, bool json_only) {
  if (loaded.all && !output.empty() && output.find("{roi}") == std::string::npos &&
      std::filesystem::path(output).has_extension()) {
    throw UsageError("with --roi all, an output is a directory or a path containing {roi} (one file per ROI), not '" +
                     output + "'");
  }
  std::vector<std::filesystem::path> paths;
  for (const ContourInput& in : loaded.inputs) {
    if (output.empty()) {
      paths.emplace_back();
      continue;
    }
    paths.push_back(roi_output_path(output, in, loaded.all, extension));
    if (json_only && !is_contour_stack_path(paths.back())) {
      throw InvalidInputError(paths.back().string() + ": contour files end in .json");
    }
    ensure_parent_directory(paths.back());
    check_output_path(paths.back());
  }
  return paths;
}

nlohmann::json for_each_roi(const std::string& command, const std::string& path, const ContourInputs& loaded,
                            const std::function<nlohmann::json(const ContourInput&, std::size_t)>& body,
                            std::size_t& failed) {
  nlohmann::json rois = nlohmann::json::array();
  failed = 0;
  for (std::size_t i = 0; i < loaded.inputs.size(); ++i) {
    const ContourInput& in = loaded.inputs[i];
    auto fail = [&](const std::string& message) {
      std::cerr << "contourmesh " << command << ": error: " << path << ": " << message << "\n";
      ++failed;
      nlohmann::json j{{"status", "failed"}, {"error", message}};
      describe_input(j, in);
      rois.push_back(j);
    };
    if (!in.error.empty()) {
      if (!loaded.all) throw InvalidInputError(path + ": " + in.error);
      fail(in.error);
      continue;
    }
    print_warnings(command, in.warnings);
    try {
      rois.push_back(body(in, i));
    } catch (const LimitError& e) {
      if (!loaded.all) throw LimitError(path + ": " + e.what());
      fail(e.what());
    } catch (const InvalidInputError& e) {
      if (!loaded.all) throw InvalidInputError(path + ": " + e.what());
      fail(e.what());
    }
  }
  return rois;
}

nlohmann::json roi_results_json(const std::string& command, const std::string& path, const ContourInputs& loaded,
                                nlohmann::json rois, std::size_t failed, std::chrono::steady_clock::time_point start) {
  nlohmann::json j;
  if (loaded.all) {
    j["rois"] = std::move(rois);
    j["skipped"] = loaded.skipped;
    j["failed"] = failed;
  } else {
    j = rois.at(0);
  }
  j["command"] = command;
  j["input"] = path;
  j["seconds"] = seconds_since(start);
  return j;
}

void ensure_parent_directory(const std::filesystem::path& path) {
  const std::filesystem::path dir = path.parent_path();
  if (dir.empty() || std::filesystem::exists(dir)) return;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec)
    throw InvalidInputError(path.string() + ": cannot create the directory '" + dir.string() + "': " + ec.message());
}

void print_warnings(const std::string& command, const std::vector<std::string>& lines) {
  for (const std::string& line : lines) std::cerr << "contourmesh " << command << ": warning: " << line << "\n";
}

void describe_input(nlohmann::json& j, const ContourInput& input) {
  if (input.roi_number >= 0) j["roi"] = {{"number", input.roi_number}, {"name", input.name}};
  else if (!input.name.empty()) j["name"] = input.name;
  if (input.color) j["color"] = *input.color;
}

void write_input_contours(const ContourInput& input, const std::filesystem::path& path) {
  ContourStackFile file;
  file.stack = input.stack;
  file.name = input.name;
  file.color = input.color;
  write_contour_stack(file, path);
}

}  // namespace contourmesh::cli
