// SPDX-License-Identifier: BSD-3-Clause
// Helpers shared by the tests of the evaluation harness: small fast comparisons, text and PNG checks,
// and the contourmesh CLI run as a user would (under xvfb-run for the renders when there is no display).
#pragma once

#include <compare/comparison.h>
#include <compare/report.h>
#include <contourmesh/reconstruct/phantom.h>
#include <contourmesh/reconstruct/volume.h>

#include <gtest/gtest.h>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.h"

namespace contourmesh::compare_test {

namespace fs = std::filesystem;

inline const std::vector<std::string> kMethods = {
    "none",        "laplacian",         "taubin",
    "mcf",         "mindist",           "paper",
    "cross-slice", "vtk-windowed-sinc", "vtk-smooth-feature-edges",
    "voxel-flying-edges", "voxel-windowed-sinc"};

// Coarse truth sampling and fewer samples per mm^2 than the default: the same code, a tenth of the work.
inline ComparisonTruth coarse_truth(const Phantom& phantom) { return phantom_truth(phantom, 0.8); }

inline ComparisonOptions fast_options() {
  ComparisonOptions o;
  o.reconstruction.segmentation.threshold = 520.0;
  o.metrics.density = 1.0;
  return o;
}

// A ridge-box at coarse voxels: a fast comparison for the output tests.
inline const Comparison& small_comparison() {
  static const Comparison c = [] {
    const Phantom phantom = make_phantom(PhantomShape::RidgeBox);
    PhantomVolumeOptions v;
    v.spacing = {1.5, 1.5, 3.0};
    v.noise = 20.0;
    const CtImage::Pointer image = render_phantom(phantom, v);
    return run_comparison(*image, "small ridge-box", coarse_truth(phantom), fast_options());
  }();
  return c;
}

// A femur at coarse voxels with strong noise (200 HU against a 960 HU step), shared by the checks of one
// test.
inline const Comparison& femur_comparison() {
  static const Comparison c = [] {
    const Phantom phantom = make_phantom(PhantomShape::Femur);
    PhantomVolumeOptions v;
    v.spacing = {1.2, 1.2, 3.0};
    v.noise = 200.0;
    v.blur = 0.5;
    const CtImage::Pointer image = render_phantom(phantom, v);
    return run_comparison(*image, "femur test phantom", coarse_truth(phantom), fast_options());
  }();
  return c;
}

inline std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), {}};
}

inline std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::string item;
  std::istringstream s(line);
  while (std::getline(s, item, sep)) out.push_back(item);
  if (!line.empty() && line.back() == sep) out.emplace_back();
  return out;
}

// Grey-level statistics of a PNG: the variance, and the fraction of pixels that are not the background
// (the colour of the corner pixel).
struct PngStats {
  int width = 0, height = 0;
  double variance = 0.0;
  double foreground = 0.0;
};

inline PngStats png_stats(const fs::path& path) {
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(path.string().c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  PngStats s;
  int dims[3];
  image->GetDimensions(dims);
  s.width = dims[0];
  s.height = dims[1];
  const int components = image->GetNumberOfScalarComponents();
  if (s.width <= 0 || s.height <= 0 || components < 3) return s;
  const auto* p = static_cast<const unsigned char*>(image->GetScalarPointer());
  const std::size_t n = static_cast<std::size_t>(s.width) * static_cast<std::size_t>(s.height);
  double sum = 0.0, sum_sq = 0.0;
  std::size_t foreground = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char* px = p + components * i;
    const double grey = (px[0] + px[1] + px[2]) / 3.0;
    sum += grey;
    sum_sq += grey * grey;
    if (px[0] != p[0] || px[1] != p[1] || px[2] != p[2]) ++foreground;
  }
  const double mean = sum / static_cast<double>(n);
  s.variance = sum_sq / static_cast<double>(n) - mean * mean;
  s.foreground = static_cast<double>(foreground) / static_cast<double>(n);
  return s;
}

using test::CliRun;

// Runs `contourmesh args`; with `display`, under xvfb-run when no X display is reachable. `env` is a
// prefix such as "env -u DISPLAY".
inline CliRun run_cli(const std::string& args, const fs::path& dir, bool display = false, const std::string& env = "") {
  std::string prefix = env;
  if (display && !rendering_available()) prefix += (prefix.empty() ? "" : " ") + test::xvfb_prefix(dir);
  return test::run_cli(CONTOURMESH_CLI, args, dir, prefix);
}

inline const char* kSmallPhantom = "--spacing 1.5,1.5,3 --noise 100 --repeat 1";

}  // namespace contourmesh::compare_test
