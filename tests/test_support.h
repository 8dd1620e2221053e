// SPDX-License-Identifier: BSD-3-Clause
// Helpers shared by the test suites: a per-test scratch directory and a small noisy contour stack.
#pragma once

#include <contourmesh/smooth/shapes.h>

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <string>

#include <unistd.h>

namespace contourmesh::test {

/// A fresh directory named after the running test and the process, removed at scope exit (the process
/// id keeps two builds' test runs on one machine, which share /tmp, out of each other's files).
class ScopedTempDir {
 public:
  explicit ScopedTempDir(const std::string& prefix)
      : path_(std::filesystem::temp_directory_path() /
              (prefix + "_" + std::to_string(::getpid()) + "_" +
               ::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name() + "_" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name())) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScopedTempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScopedTempDir(const ScopedTempDir&) = delete;
  ScopedTempDir& operator=(const ScopedTempDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// A contour stack of a radius-10 cylinder with a ridge, with in-plane noise of 0.1 mm.
inline Mesh noisy_ridge_stack(int slices, int points, double ridge_height, std::uint64_t seed) {
  ContourStackSpec spec;
  spec.curve = ridge_circle_curve(10.0, ridge_height, 0.4);
  spec.slices = slices;
  spec.points_per_contour = points;
  Mesh m = make_contour_stack(spec);
  add_noise(m, {0.1, seed, NoiseDirection::InPlane});
  return m;
}

}  // namespace contourmesh::test
