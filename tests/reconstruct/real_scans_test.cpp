// SPDX-License-Identifier: BSD-3-Clause
// The reconstruction chain on the real scans in ../shared/data (skipped when they are absent).
#include <contourmesh/reconstruct/reconstruction.h>
#include <contourmesh/reconstruct/volume.h>

#include <gtest/gtest.h>

#include <filesystem>

#include "reconstruct/mesh_checks.h"

namespace contourmesh {
namespace {

const std::filesystem::path kData = CONTOURMESH_SHARED_DATA;

void expect_closed_manifold(const std::filesystem::path& file, double threshold) {
  if (!std::filesystem::exists(kData / file)) GTEST_SKIP() << "no " << (kData / file);
  const CtImage::Pointer image = read_volume(kData / file);
  ReconstructionOptions o;
  o.segmentation.threshold = threshold;
  const Reconstruction r = reconstruct(*image, o);
  const test::Topology t = test::topology_of(r.mesh);
  EXPECT_TRUE(t.closed) << file;
  EXPECT_TRUE(t.manifold) << file << ": " << t.problems;
  EXPECT_GT(r.report.contours, 10u);
}

TEST(RealScans, HeadCtRawValues) { expect_closed_manifold("headsq_quarter/headsq_quarter.mhd", 1150.0); }
TEST(RealScans, PelvisCtNifti) { expect_closed_manifold("totalsegmentator_ct/example_ct_sm.nii.gz", 300.0); }
TEST(RealScans, HeadNeckDicomSeries) { expect_closed_manifold("dicom_series_headneck", 300.0); }

}  // namespace
}  // namespace contourmesh
