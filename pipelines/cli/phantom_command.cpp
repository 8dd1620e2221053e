// SPDX-License-Identifier: BSD-3-Clause
// contourmesh phantom --shape NAME -o vol.mha: writes a synthetic CT volume of a built-in phantom
// (SPEC 4) with partial-volume effect, blur and noise.
#include "cli_common.h"
#include "progress_display.h"

#include <contourmesh/vtk/atomic_file.h>
#include <contourmesh/reconstruct/phantom.h>
#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/errors.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace contourmesh::cli {

namespace {

constexpr std::array<std::string_view, 4> kVolumeExtensions = {".mha", ".nrrd", ".nii", ".nii.gz"};

struct PhantomArgs {
  std::string shape;
  std::string output;
  std::string spacing = "0.7,0.7,2";
  double noise = 20.0;
  double contour_noise = 0.0;
  double blur = 0.5;
  std::uint64_t seed = 1;
  double margin = PhantomVolumeOptions{}.margin;
  bool json = false;
  CommonArgs common;
};

// Fails before the rendering work when the output cannot be written: the formats write_volume knows
// and an existing directory.
void check_output(const std::string& output) {
  std::string name = std::filesystem::path(output).filename().string();
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  const bool known = std::any_of(kVolumeExtensions.begin(), kVolumeExtensions.end(), [&](std::string_view ext) {
    return name.size() > ext.size() && name.compare(name.size() - ext.size(), ext.size(), ext) == 0;
  });
  if (!known) throw InvalidInputError(output + ": unsupported volume extension; use .mha, .nrrd, .nii or .nii.gz");
  check_output_path(output);
}

nlohmann::json to_json(const Eigen::Vector3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

int run_phantom(const PhantomArgs& a) {
  apply_common_options(a.common);
  const auto start = std::chrono::steady_clock::now();
  const PhantomShape shape = parse_phantom_shape(a.shape);
  PhantomVolumeOptions options;
  options.spacing = parse_spacing(a.spacing);
  if (!std::isfinite(a.noise) || a.noise < 0.0) throw InvalidInputError("--noise must be a sigma >= 0 in HU");
  check_contour_noise(a.contour_noise);
  if (!std::isfinite(a.blur) || a.blur < 0.0) throw InvalidInputError("--blur must be a sigma >= 0 in mm");
  if (!std::isfinite(a.margin) || a.margin < 0.0) throw InvalidInputError("--margin must be >= 0 mm");
  options.noise = a.noise;
  options.contour_noise = a.contour_noise;
  options.blur = a.blur;
  options.seed = a.seed;
  options.margin = a.margin;
  check_output(a.output);

  ProgressDisplay progress("phantom", a.common.quiet || a.json);
  progress.stage("phantom");
  const Phantom phantom = make_phantom(shape);
  const CtImage::Pointer image = render_phantom(phantom, options);
  progress.stage("write");
  write_volume(image, a.output, progress.callback());
  progress.finish();

  const auto size = image->GetLargestPossibleRegion().GetSize();
  const Eigen::Vector3d origin(image->GetOrigin()[0], image->GetOrigin()[1], image->GetOrigin()[2]);
  if (a.json) {
    nlohmann::json j;
    j["command"] = "phantom";
    j["shape"] = std::string(to_string(shape));
    j["output"] = a.output;
    j["size"] = {size[0], size[1], size[2]};
    j["spacing"] = to_json(options.spacing);
    j["origin"] = to_json(origin);
    j["margin"] = options.margin;
    j["bone_hu"] = options.bone_hu;
    j["tissue_hu"] = options.tissue_hu;
    j["noise"] = options.noise;
    j["contour_noise"] = options.contour_noise;
    j["blur"] = options.blur;
    j["seed"] = options.seed;
    j["solid_volume_mm3"] = phantom.volume;
    j["bounds_min"] = to_json(phantom.bounds.min());
    j["bounds_max"] = to_json(phantom.bounds.max());
    j["surface_components"] = phantom.surface_components;
    j["euler_characteristic"] = phantom.euler_characteristic;
    j["feature_points"] = phantom.feature_points.size();
    j["seconds"] = seconds_since(start);
    print_json(j);
  } else {
    if (a.common.quiet) return kOk;
    std::cout << std::setprecision(6) << "phantom " << to_string(shape) << ": " << size[0] << " x " << size[1] << " x "
              << size[2] << " voxels of " << options.spacing.x() << " x " << options.spacing.y() << " x "
              << options.spacing.z() << " mm, noise " << options.noise << " HU, ";
    if (options.contour_noise > 0.0) std::cout << "contour noise " << options.contour_noise << " mm, ";
    std::cout << "blur " << options.blur << " mm, seed "
              << options.seed << "\n"
              << "  solid volume " << phantom.volume << " mm^3, " << phantom.surface_components << " surface"
              << (phantom.surface_components == 1 ? "" : "s") << ", Euler characteristic "
              << phantom.euler_characteristic << "\n"
              << "  wrote " << a.output << " in " << std::setprecision(3) << seconds_since(start) << " s\n";
  }
  return kOk;
}

}  // namespace

void add_phantom_command(CLI::App& app) {
  auto args = std::make_shared<PhantomArgs>();
  const std::string shapes = phantom_shape_names(" | ");
  CLI::App* cmd = app.add_subcommand("phantom", "Write a synthetic CT volume (HU) of a built-in phantom");
  cmd->add_option("--shape", args->shape, shapes)->required();
  cmd->add_option("-o,--output", args->output, "Output volume: .mha, .nrrd, .nii or .nii.gz")->required();
  cmd->add_option("--spacing", args->spacing, "Voxel size in mm: sx,sy,sz (z is the slice axis)")
      ->capture_default_str();
  cmd->add_option("--noise", args->noise, "Gaussian noise sigma in HU (>= 0)")->capture_default_str();
  add_contour_noise_option(cmd, args->contour_noise);
  cmd->add_option("--blur", args->blur, "Gaussian blur sigma in mm (>= 0; partial-volume / scanner PSF)")
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "Noise seed (>= 0): the same seed gives the same volume")
      ->check(CLI::Validator(
          [](std::string& value) {
            return !value.empty() && value.front() == '-' ? std::string("the seed must be a whole number >= 0")
                                                          : std::string();
          },
          "", "non-negative seed"))
      ->capture_default_str();
  cmd->add_option("--margin", args->margin, "Soft tissue around the solid's bounding box, in mm (>= 0)")
      ->capture_default_str();
  cmd->add_flag("--json", args->json, "Print one JSON object on stdout instead of the summary");
  add_common_options(cmd, args->common);
  cmd->callback([args] { set_exit_code(run_guarded("phantom", [&] { return run_phantom(*args); })); });
}

}  // namespace contourmesh::cli
