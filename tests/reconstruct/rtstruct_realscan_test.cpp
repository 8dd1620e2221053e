// SPDX-License-Identifier: BSD-3-Clause
// The heavy ROIs of the breast structure set (BODY: 430k vertices, 10 s; Lt Lung: 165 contours with
// 37 holes, up to 7 a slice; Breast): the checks of rtstruct_checks.h. Label "realscan".
#include <contourmesh/reconstruct/rtstruct.h>

#include <gtest/gtest.h>

#include <filesystem>

#include "reconstruct/rtstruct_checks.h"

namespace contourmesh {
namespace {

const std::filesystem::path kBreast = std::filesystem::path(CONTOURMESH_SHARED_DATA) / "rtstruct_breast" / "rtss.dcm";

void expect_roi(const std::string& name) {
  if (!std::filesystem::exists(kBreast)) GTEST_SKIP() << "no " << kBreast;
  const RtStructureSet set = read_rt_structure_set(kBreast);
  test::expect_roi_reconstructs(find_roi(set, name));
}

TEST(RtStructBreast, Body) { expect_roi("BODY"); }
TEST(RtStructBreast, LtLung) { expect_roi("Lt Lung"); }
TEST(RtStructBreast, Breast) { expect_roi("Breast"); }

}  // namespace
}  // namespace contourmesh
