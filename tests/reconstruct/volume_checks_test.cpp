// SPDX-License-Identifier: BSD-3-Clause
// read_volume's checks that need the library itself: the resampling of an uneven DICOM series, and the
// volume writer at a file size limit.
#include "damaged_inputs.h"
#include "test_support.h"

#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/errors.h>

#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

namespace contourmesh {
namespace {

namespace fs = std::filesystem;

TEST(VolumeChecks, AMissingSliceIsResampledFromItsNeighboursOnRequest) {
  if (!fs::is_directory(test::headneck_series())) GTEST_SKIP() << "no " << test::headneck_series();
  const test::ScopedTempDir tmp("contourmesh_volume_checks");
  const fs::path series = tmp.path() / "series";
  const std::vector<fs::path> slices = test::copy_headneck_slices(series, 20, 5);
  const CtImage::Pointer whole = read_volume(series);
  fs::remove(slices[2]);
  EXPECT_THROW((void)read_volume(series), InvalidInputError);
  VolumeReadOptions options;
  options.uneven_slices = UnevenSlices::Resample;
  std::vector<std::string> warnings;
  options.on_warning = [&](const std::string& w) { warnings.push_back(w); };
  const CtImage::Pointer resampled = read_volume(series, options);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings.front().find("resampled the 4 slices onto 5 slices"), std::string::npos) << warnings.front();
  ASSERT_EQ(resampled->GetLargestPossibleRegion().GetSize(), whole->GetLargestPossibleRegion().GetSize());
  for (int d = 0; d < 3; ++d) {
    EXPECT_NEAR(resampled->GetSpacing()[d], whole->GetSpacing()[d], 1e-9);
    EXPECT_NEAR(resampled->GetOrigin()[d], whole->GetOrigin()[d], 1e-9);
  }
  // Slices at the known positions are the files' own; the missing one is the mean of its neighbours.
  double worst_kept = 0.0, worst_mean = 0.0;
  for (int y = 0; y < 512; y += 7) {
    for (int x = 0; x < 512; x += 5) {
      for (int k : {0, 1, 3, 4}) {
        worst_kept = std::max(worst_kept, std::abs(static_cast<double>(resampled->GetPixel({{x, y, k}})) -
                                                   whole->GetPixel({{x, y, k}})));
      }
      const double mean = 0.5 * (static_cast<double>(whole->GetPixel({{x, y, 1}})) + whole->GetPixel({{x, y, 3}}));
      worst_mean = std::max(worst_mean, std::abs(resampled->GetPixel({{x, y, 2}}) - mean));
    }
  }
  EXPECT_EQ(worst_kept, 0.0);
  EXPECT_LE(worst_mean, 1e-3);
}

TEST(VolumeChecks, TheVolumeWriterFailsCleanlyAtTheFileSizeLimit) {
  const test::ScopedTempDir tmp("contourmesh_volume_checks");
  const CtImage::Pointer image = test::small_volume();
  std::mt19937 noise(3);  // so that no format compresses it below the limit
  for (float* v = image->GetBufferPointer(); v != image->GetBufferPointer() + 28 * 24 * 12; ++v) {
    *v += static_cast<float>(noise() % 100);
  }
  // NRRD is left out: ITK 5.2's NRRD writer leaks its state when a write fails (LeakSanitizer sees it);
  // the check after writing is the same for every format.
  for (const std::string ext : {"mha", "nii", "nii.gz"}) {
    const fs::path out = tmp.path() / ("precious." + ext);
    std::ofstream(out) << "precious";
    rlimit previous{};
    ::getrlimit(RLIMIT_FSIZE, &previous);
    auto handler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = previous;
    limit.rlim_cur = 4096;  // the volume is 32 kB, about 12 kB compressed
    ::setrlimit(RLIMIT_FSIZE, &limit);
    std::string error;
    try {
      write_volume(image, out);
    } catch (const InvalidInputError& e) {
      error = e.what();
    }
    ::setrlimit(RLIMIT_FSIZE, &previous);
    std::signal(SIGXFSZ, handler);
    EXPECT_NE(error.find(out.string() + ": cannot write"), std::string::npos) << ext << ": " << error;
    std::ifstream in(out);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "precious") << ext;
  }
  for (const auto& e : fs::directory_iterator(tmp.path())) {
    EXPECT_NE(e.path().filename().string().front(), '.') << "stray temporary " << e.path();
  }
}

}  // namespace
}  // namespace contourmesh
