// SPDX-License-Identifier: BSD-3-Clause
// RT Structure Sets: reading the shared breast structure set and small written ones, conversion of an
// ROI to a contour stack, and the reconstruction of its light ROIs (the heavy ones, BODY, Lt Lung and
// Breast, are in rtstruct_realscan_test.cpp).
#include <contourmesh/reconstruct/contour_deviation.h>
#include <contourmesh/reconstruct/contour_reconstruction.h>
#include <contourmesh/reconstruct/rtstruct.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/metrics.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "reconstruct/mesh_checks.h"
#include "reconstruct/rtstruct_checks.h"
#include "reconstruct/rtstruct_writer.h"
#include "test_support.h"

namespace contourmesh {
namespace {

const std::filesystem::path kData = CONTOURMESH_SHARED_DATA;
const std::filesystem::path kBreast = kData / "rtstruct_breast" / "rtss.dcm";

class BreastStructureSet : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (std::filesystem::exists(kBreast)) set_ = new RtStructureSet(read_rt_structure_set(kBreast));
  }
  static void TearDownTestSuite() {
    delete set_;
    set_ = nullptr;
  }
  void SetUp() override {
    if (set_ == nullptr) GTEST_SKIP() << "no " << kBreast;
  }
  static RtStructureSet* set_;
};
RtStructureSet* BreastStructureSet::set_ = nullptr;

TEST_F(BreastStructureSet, ListsTheTenRois) {
  EXPECT_TRUE(set_->warnings.empty());
  EXPECT_EQ(set_->label, "CT_1");
  ASSERT_EQ(set_->rois.size(), 10u);
  const RtRoi& body = set_->rois[0];
  EXPECT_EQ(body.number, 1);
  EXPECT_EQ(body.name, "BODY");
  EXPECT_EQ(body.interpreted_type, "EXTERNAL");
  ASSERT_TRUE(body.color.has_value());
  EXPECT_EQ(*body.color, (std::array<int, 3>{154, 155, 100}));
  EXPECT_EQ(body.contours.size(), 141u);
  EXPECT_EQ(body.slices(), 98u);
  const RtRoi& lung = find_roi(*set_, "Lt Lung");  // stored as "Lt Lung " (DICOM pads to even length)
  EXPECT_EQ(lung.contours.size(), 165u);
  EXPECT_EQ(lung.slices(), 80u);
  EXPECT_EQ(find_roi(*set_, "Heart").contours.size(), 33u);
  EXPECT_EQ(find_roi(*set_, "Breast").contours.size(), 48u);
  EXPECT_EQ(find_roi(*set_, "Borders").slices(), 2u);
  EXPECT_TRUE(find_roi(*set_, "Areola").contours.empty());
  for (const RtRoi& roi : set_->rois) {
    for (const RtContour& c : roi.contours) EXPECT_EQ(c.type, RtContourType::ClosedPlanar) << roi.name;
  }
  EXPECT_NEAR(structure_set_slice_spacing(*set_).value_or(0.0), 3.0, 1e-6);
}

TEST_F(BreastStructureSet, FindsRoisByNameCaseOrNumber) {
  EXPECT_EQ(find_roi(*set_, "heart").number, 5);
  EXPECT_EQ(find_roi(*set_, "  Tumor Bed ").number, 9);
  EXPECT_EQ(find_roi(*set_, "7").name, "Nodes");
  try {
    (void)find_roi(*set_, "Liver");
    FAIL();
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("'Tumor Bed Block'"), std::string::npos) << e.what();
  }
}

TEST_F(BreastStructureSet, FileStemsAreSafe) {
  const std::vector<std::string> stems = roi_file_stems(*set_);
  EXPECT_EQ(stems[0], "BODY");
  EXPECT_EQ(stems[5], "Lt_Lung");
  EXPECT_EQ(stems[9], "Tumor_Bed_Block");
}

TEST_F(BreastStructureSet, AreolaHasNoContoursAndSaysSo) {
  try {
    (void)roi_contour_stack(find_roi(*set_, "Areola"));
    FAIL() << "an ROI without contours was converted";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("ROI 2 'Areola' has no contours"), std::string::npos) << e.what();
  }
}

TEST_F(BreastStructureSet, LungStackHasHolesAndSeveralContoursPerSlice) {
  const RoiStack r = roi_contour_stack(find_roi(*set_, "Lt Lung"));
  const ContourStack& s = r.planar.stack;
  EXPECT_EQ(s.axis_w, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(s.slices.size(), 80u);
  EXPECT_EQ(s.num_contours(), 165u);
  EXPECT_EQ(r.planar.report.hole_contours, 77u);  // vessels and airways inside the lung outline
  std::size_t most = 0;
  for (const auto& sl : s.slices) most = std::max(most, sl.contours.size());
  EXPECT_EQ(most, 7u);
  EXPECT_DOUBLE_EQ(r.planar.report.typical_spacing, 3.0);
  for (std::size_t k = 1; k < s.slices.size(); ++k) EXPECT_GT(s.slices[k].w, s.slices[k - 1].w);
}

// The light ROIs; each checks a closed, manifold, outward-oriented mesh, the volume within 5 % of
// the slice-wise volume and the drawn contours reproduced within 0.1 mm in their planes.
TEST_F(BreastStructureSet, Heart) { test::expect_roi_reconstructs(find_roi(*set_, "Heart")); }
TEST_F(BreastStructureSet, Borders) { test::expect_roi_reconstructs(find_roi(*set_, "Borders")); }
TEST_F(BreastStructureSet, TumorBed) { test::expect_roi_reconstructs(find_roi(*set_, "Tumor Bed")); }
TEST_F(BreastStructureSet, TumorBedBlock) { test::expect_roi_reconstructs(find_roi(*set_, "Tumor Bed Block")); }
TEST_F(BreastStructureSet, Nodes) { test::expect_roi_reconstructs(find_roi(*set_, "Nodes")); }
TEST_F(BreastStructureSet, Scar) { test::expect_roi_reconstructs(find_roi(*set_, "Scar")); }

// --- written structure sets ---

class WrittenStructureSet : public ::testing::Test {
 protected:
  std::filesystem::path write(const std::vector<test::TestRoi>& rois, const std::string& modality = "RTSTRUCT") {
    const auto path = dir_.path() / "rs.dcm";
    test::write_rtstruct(path, rois, modality);
    return path;
  }
  static test::TestRoi cylinder(int number, const std::string& name, int slices = 4) {
    test::TestRoi roi = test::roi_of(number, name);
    roi.color = std::array<int, 3>{255, 0, 0};
    for (int k = 0; k < slices; ++k)
      roi.contours.push_back(test::contour_of("CLOSED_PLANAR", test::ellipse(0, 0, 10, 8, 2.5 * k)));
    return roi;
  }
  test::ScopedTempDir dir_{"rtstruct"};
};

TEST_F(WrittenStructureSet, RoundTripsNamesColoursAndContours) {
  const auto path = write({cylinder(3, "GTV"), cylinder(8, "Cord", 6)});
  EXPECT_TRUE(is_rt_structure_set(path));
  const RtStructureSet set = read_rt_structure_set(path);
  ASSERT_EQ(set.rois.size(), 2u);
  EXPECT_EQ(set.rois[1].number, 8);
  EXPECT_EQ(set.rois[1].name, "Cord");
  EXPECT_EQ(set.rois[1].contours.size(), 6u);
  EXPECT_EQ(set.rois[1].slices(), 6u);
  EXPECT_EQ(*set.rois[0].color, (std::array<int, 3>{255, 0, 0}));
  test::expect_roi_reconstructs(set.rois[1]);
}

TEST_F(WrittenStructureSet, PointAndOpenContoursAreSkippedWithAWarningNamingThem) {
  test::TestRoi roi = cylinder(4, "Mixed");
  roi.contours.push_back(test::contour_of("POINT", {{1, 2, 3}}));
  roi.contours.push_back(test::contour_of("OPEN_PLANAR", {{0, 0, 2.5}, {5, 0, 2.5}, {5, 5, 2.5}}));
  const RtStructureSet set = read_rt_structure_set(write({roi}));
  const RoiStack r = roi_contour_stack(set.rois[0]);
  EXPECT_EQ(r.skipped_contours, 2u);
  ASSERT_FALSE(r.planar.report.warnings.empty());
  const std::string w = r.planar.report.warnings[0];
  EXPECT_NE(w.find("ROI 4 'Mixed'"), std::string::npos) << w;
  EXPECT_NE(w.find("POINT (contour 5)"), std::string::npos) << w;
  EXPECT_NE(w.find("OPEN_PLANAR (contour 6)"), std::string::npos) << w;
  EXPECT_EQ(r.planar.stack.num_contours(), 4u);
}

TEST_F(WrittenStructureSet, OnlyPointsIsAnErrorNamingTheRoi) {
  const RtStructureSet set =
      read_rt_structure_set(write({test::roi_of(2, "Marker", {test::contour_of("POINT", {{1, 2, 3}})})}));
  try {
    (void)roi_contour_stack(set.rois[0]);
    FAIL();
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("ROI 2 'Marker' has no closed planar contour"), std::string::npos) << e.what();
  }
}

TEST_F(WrittenStructureSet, NonPlanarContourIsAnErrorNamingRoiAndContour) {
  test::TestRoi roi = cylinder(6, "Bent");
  roi.contours[2].points[10].z() += 1.5;
  const RtStructureSet set = read_rt_structure_set(write({roi}));
  try {
    (void)roi_contour_stack(set.rois[0]);
    FAIL();
  } catch (const InvalidInputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("ROI 6 'Bent'"), std::string::npos) << m;
    EXPECT_NE(m.find("contour 3"), std::string::npos) << m;
  }
}

TEST_F(WrittenStructureSet, MalformedContourDataIsAnErrorOfItsRoiOnly) {
  test::TestRoi roi = cylinder(1, "Broken");
  roi.contours[1].raw_data = "1.0\\2.0\\abc";
  const auto path = write({roi, cylinder(2, "Fine")});
  const RtStructureSet set = read_rt_structure_set(path);
  try {
    (void)roi_contour_stack(set.rois[0]);
    FAIL();
  } catch (const InvalidInputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("ROI 1 'Broken', contour 2: Contour Data (3006,0050) is not a list"), std::string::npos) << m;
  }
  EXPECT_EQ(roi_contour_stack(set.rois[1]).planar.stack.slices.size(), 4u);
}

TEST_F(WrittenStructureSet, NumberOfContourPointsMismatchIsAWarning) {
  test::TestRoi roi = cylinder(1, "Counted");
  roi.contours[0].raw_data = "0\\0\\0\\10\\0\\0\\10\\10\\0";  // 3 points, declared 48
  const RtStructureSet set = read_rt_structure_set(write({roi}));
  ASSERT_EQ(set.warnings.size(), 1u);
  EXPECT_NE(set.warnings[0].find("Number of Contour Points"), std::string::npos) << set.warnings[0];
}

TEST_F(WrittenStructureSet, OtherDicomAndOtherFilesAreRefused) {
  const auto ct = write({cylinder(1, "A")}, "CT");
  EXPECT_FALSE(is_rt_structure_set(ct));
  try {
    (void)read_rt_structure_set(ct);
    FAIL();
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("not an RT Structure Set (modality 'CT'"), std::string::npos) << e.what();
  }
  const auto text = dir_.path() / "notes.dcm";
  std::ofstream(text) << "not dicom";
  EXPECT_FALSE(is_rt_structure_set(text));
  EXPECT_THROW((void)read_rt_structure_set(text), InvalidInputError);
  EXPECT_THROW((void)read_rt_structure_set(dir_.path() / "missing.dcm"), InvalidInputError);
}

TEST_F(WrittenStructureSet, NamesBecomeSafeUniqueFileStems) {
  test::TestRoi a = cylinder(1, "PTV 50/25 (boost)");
  test::TestRoi b = cylinder(2, "../etc");
  test::TestRoi c = cylinder(3, "   ");
  test::TestRoi d = cylinder(4, "ptv_50_25_boost");
  const RtStructureSet set = read_rt_structure_set(write({a, b, c, d}));
  const std::vector<std::string> stems = roi_file_stems(set);
  EXPECT_EQ(stems[0], "PTV_50_25_boost_1");
  EXPECT_EQ(stems[1], "etc");
  EXPECT_EQ(stems[2], "roi3");
  EXPECT_EQ(stems[3], "ptv_50_25_boost_4");
}

}  // namespace
}  // namespace contourmesh
