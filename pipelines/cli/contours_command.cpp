// SPDX-License-Identifier: BSD-3-Clause
// contourmesh contours IN: what an RT Structure Set or a contour file holds (--list), and its contour
// stacks written as contour files (--roi NAME|all -o OUT.json).
#include "cli_common.h"
#include "contour_input.h"
#include "progress_display.h"

#include <contourmesh/vtk/atomic_file.h>
#include <contourmesh/vtk/contour_stack_io.h>
#include <contourmesh/reconstruct/planar_contours.h>
#include <contourmesh/reconstruct/rtstruct.h>
#include <contourmesh/smooth/errors.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>

namespace contourmesh::cli {

namespace {

struct ContoursArgs {
  std::string input;
  std::string output;
  bool list = false;
  bool json = false;
  ContourArgs contour;
  CommonArgs common;
};

std::string color_text(const std::optional<std::array<int, 3>>& c) {
  if (!c) return "-";
  return std::to_string((*c)[0]) + "," + std::to_string((*c)[1]) + "," + std::to_string((*c)[2]);
}

int list_structure_set(const ContoursArgs& a) {
  const RtStructureSet set = read_rt_structure_set(a.input);
  print_warnings("contours", set.warnings);
  nlohmann::json rois = nlohmann::json::array();
  for (const RtRoi& roi : set.rois) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const RtContour& c : roi.contours) {
      for (const Eigen::Vector3d& p : c.points) {
        lo = std::min(lo, p.z());
        hi = std::max(hi, p.z());
      }
    }
    nlohmann::json j;
    j["number"] = roi.number;
    j["name"] = roi.name;
    j["color"] = roi.color ? nlohmann::json(*roi.color) : nlohmann::json(nullptr);
    j["interpreted_type"] = roi.interpreted_type;
    j["contours"] = roi.contours.size();
    j["closed_contours"] = roi.closed_contours();
    j["slices"] = roi.slices();
    j["points"] = roi.points();
    j["z_min"] = roi.points() > 0 ? nlohmann::json(lo) : nlohmann::json(nullptr);
    j["z_max"] = roi.points() > 0 ? nlohmann::json(hi) : nlohmann::json(nullptr);
    if (!roi.error.empty()) {
      j["error"] = roi.error;
      print_warnings("contours", {a.input + ": " + roi.error});
    }
    rois.push_back(j);
  }
  const auto spacing = structure_set_slice_spacing(set);
  if (a.json) {
    nlohmann::json j;
    j["command"] = "contours";
    j["input"] = a.input;
    j["kind"] = "rtstruct";
    j["label"] = set.label;
    j["slice_spacing"] = spacing ? nlohmann::json(*spacing) : nlohmann::json(nullptr);
    j["rois"] = rois;
    print_json(j);
    return kOk;
  }
  std::cout << a.input << ": RT Structure Set '" << set.label << "', " << set.rois.size() << " ROI"
            << (set.rois.size() == 1 ? "" : "s");
  if (spacing) std::cout << ", slices " << std::fixed << std::setprecision(2) << *spacing << " mm apart";
  std::cout << "\n";
  std::size_t width = 4;
  for (const RtRoi& roi : set.rois) width = std::max(width, roi.name.size());
  std::cout << std::left << "  " << std::setw(4) << "#" << std::setw(static_cast<int>(width) + 2) << "name"
            << std::setw(13) << "colour" << std::setw(12) << "type" << std::right << std::setw(9) << "contours"
            << std::setw(8) << "slices" << std::setw(9) << "points" << "  z range, mm\n";
  std::size_t other = 0;
  for (std::size_t i = 0; i < set.rois.size(); ++i) {
    const RtRoi& roi = set.rois[i];
    const nlohmann::json& j = rois[i];
    std::cout << std::left << "  " << std::setw(4) << roi.number << std::setw(static_cast<int>(width) + 2) << roi.name
              << std::setw(13) << color_text(roi.color) << std::setw(12)
              << (roi.interpreted_type.empty() ? "-" : roi.interpreted_type) << std::right << std::setw(9)
              << roi.contours.size() << std::setw(8) << roi.slices() << std::setw(9) << roi.points() << "  ";
    if (roi.points() == 0) {
      std::cout << "(no contours)\n";
    } else {
      std::cout << std::fixed << std::setprecision(2) << j["z_min"].get<double>() << " .. " << j["z_max"].get<double>()
                << "\n";
    }
    other += roi.contours.size() - roi.closed_contours();
  }
  if (other > 0) {
    std::cout << "  (" << other << " contour" << (other == 1 ? " is" : "s are")
              << " not CLOSED_PLANAR: POINT or OPEN contours bound no volume and are skipped)\n";
  }
  return kOk;
}

int list_contour_file(const ContoursArgs& a) {
  const ContourInputs loaded = load_contour_inputs(a.input, InputKind::ContourFile, a.contour);
  const ContourInput& in = loaded.inputs.at(0);
  print_warnings("contours", in.warnings);
  std::size_t contours = 0, holes = 0, points = 0, occupied = 0;
  for (const SliceContours& s : in.stack.slices) {
    occupied += s.contours.empty() ? 0 : 1;
    for (const Contour& c : s.contours) {
      ++contours;
      holes += c.is_hole ? 1 : 0;
      points += c.points.size();
    }
  }
  const double volume = slicewise_volume(in.stack);
  const auto& sl = in.stack.slices;
  if (a.json) {
    nlohmann::json j;
    j["command"] = "contours";
    j["input"] = a.input;
    j["kind"] = "contour-file";
    describe_input(j, in);
    j["slices"] = sl.size();
    j["slices_with_contours"] = occupied;
    j["contours"] = contours;
    j["hole_contours"] = holes;
    j["points"] = points;
    j["w_min"] = sl.empty() ? nlohmann::json(nullptr) : nlohmann::json(sl.front().w);
    j["w_max"] = sl.empty() ? nlohmann::json(nullptr) : nlohmann::json(sl.back().w);
    j["slicewise_volume"] = volume;
    print_json(j);
    return kOk;
  }
  std::cout << a.input << ": contour stack" << (in.name.empty() ? "" : " '" + in.name + "'") << "\n"
            << "  " << contours << " contours (" << holes << (holes == 1 ? " hole), " : " holes), ") << points
            << " points, on " << occupied << " of " << sl.size() << " slices";
  if (!sl.empty())
    std::cout << std::fixed << std::setprecision(2) << ", w " << sl.front().w << " .. " << sl.back().w << " mm";
  std::cout << "\n  slice-wise volume " << std::setprecision(1) << volume << " mm^3\n";
  return kOk;
}

int write_stacks(const ContoursArgs& a, InputKind kind) {
  const auto start = std::chrono::steady_clock::now();
  const ContourInputs loaded = load_contour_inputs(a.input, kind, a.contour);
  print_warnings("contours", loaded.warnings);
  print_warnings("contours", loaded.skipped);
  const auto outputs = roi_outputs(a.output, loaded, ".json", true);
  std::size_t failed = 0;
  nlohmann::json written = for_each_roi(
      "contours", a.input, loaded,
      [&](const ContourInput& in, std::size_t i) {
        write_input_contours(in, outputs[i]);
        if (!a.json && !a.common.quiet) std::cout << "wrote " << outputs[i].string() << " (" << in.what << ")\n";
        nlohmann::json j;
        j["status"] = "ok";
        describe_input(j, in);
        j["output"] = outputs[i].string();
        j["slices"] = in.stack.slices.size();
        j["contours"] = in.stack.num_contours();
        return j;
      },
      failed);
  if (a.json) print_json(roi_results_json("contours", a.input, loaded, std::move(written), failed, start));
  return failed > 0 ? kBadInput : kOk;
}

int run_contours_command(const ContoursArgs& a) {
  const InputKind kind = input_kind(a.input);
  if (kind == InputKind::Volume) {
    std::error_code ec;
    if (!std::filesystem::exists(a.input, ec)) throw InvalidInputError(a.input + ": no such file");
    throw InvalidInputError(a.input + ": not an RT Structure Set (DICOM) or a contour file (.json)");
  }
  if (a.output.empty()) {
    if (!a.contour.roi.empty()) throw UsageError("--roi needs -o FILE.json (or use --list to see the ROIs)");
    return kind == InputKind::StructureSet ? list_structure_set(a) : list_contour_file(a);
  }
  if (a.list) throw UsageError("--list and -o do not go together");
  return write_stacks(a, kind);
}

}  // namespace

void add_contours_command(CLI::App& app) {
  auto args = std::make_shared<ContoursArgs>();
  CLI::App* cmd = app.add_subcommand(
      "contours", "List the ROIs of an RT Structure Set (or a contour file), or write them as contour files");
  cmd->add_option("input", args->input, "RT Structure Set (DICOM) or contour file (.json)")->required();
  cmd->add_flag("--list", args->list, "List the ROIs (the default without -o)");
  cmd->add_option("-o,--output", args->output,
                  "Write the --roi contours, normalised, as a contour file (.json); with --roi all a directory, or "
                  "a path with {roi}");
  cmd->add_option("--roi", args->contour.roi, "The ROI to write, by name or number, or 'all'");
  cmd->add_option("--planarity-tolerance", args->contour.planarity_tolerance,
                  "Largest distance of a contour point from its slice plane, mm")
      ->capture_default_str();
  cmd->add_flag("--json", args->json, "Print one JSON object on stdout instead of the table");
  add_common_options(cmd, args->common);
  cmd->callback([args] { set_exit_code(run_guarded("contours", [&] { return run_contours_command(*args); })); });
}

}  // namespace contourmesh::cli
