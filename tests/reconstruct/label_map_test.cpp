// SPDX-License-Identifier: BSD-3-Clause
// Label maps and 3D Slicer segmentations (contourmesh/reconstruct/label_map.h): reading, selecting, and the
// surface of each label against its voxel volume.
#include <contourmesh/reconstruct/label_map.h>
#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/metrics.h>
#include <contourmesh/smooth/topology.h>

#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace contourmesh {
namespace {

namespace fs = std::filesystem;

constexpr int kNx = 40, kNy = 32, kNz = 24;  // 1 x 1 x 2 mm voxels

// Voxel values of a 3-D map: a ball of label 1 (radius 8 mm) and a box of label 2 (14 x 10 x 28 mm).
std::uint8_t two_labels(int i, int j, int k) {
  const double x = i, y = j, z = 2.0 * k;
  if ((x - 11) * (x - 11) + (y - 16) * (y - 16) + (z - 24) * (z - 24) < 64.0) return 1;
  if (i >= 22 && i < 36 && j >= 10 && j < 20 && k >= 5 && k < 19) return 2;
  return 0;
}

// Writes an attached-header NRRD of unsigned chars: `layers` == 0 for a 3-D file, else a 4-D file whose
// first axis (kind "list") holds the layers, as 3D Slicer writes overlapping segments.
void write_nrrd(const fs::path& path, int layers, const std::function<std::uint8_t(int, int, int, int)>& value,
                const std::vector<std::string>& keys) {
  std::ofstream out(path, std::ios::binary);
  out << "NRRD0004\ntype: unsigned char\nspace: left-posterior-superior\n";
  if (layers == 0) {
    out << "dimension: 3\nsizes: " << kNx << " " << kNy << " " << kNz
        << "\nspace directions: (1,0,0) (0,1,0) (0,0,2)\nkinds: domain domain domain\n";
  } else {
    out << "dimension: 4\nsizes: " << layers << " " << kNx << " " << kNy << " " << kNz
        << "\nspace directions: none (1,0,0) (0,1,0) (0,0,2)\nkinds: list domain domain domain\n";
  }
  out << "encoding: raw\nspace origin: (-20,-16,-24)\n";
  for (const std::string& k : keys) out << k << "\n";
  out << "\n";
  for (int k = 0; k < kNz; ++k) {
    for (int j = 0; j < kNy; ++j) {
      for (int i = 0; i < kNx; ++i) {
        for (int l = 0; l < std::max(layers, 1); ++l) out.put(static_cast<char>(value(i, j, k, l)));
      }
    }
  }
}

std::size_t count_voxels(const std::function<bool(int, int, int)>& inside) {
  std::size_t n = 0;
  for (int k = 0; k < kNz; ++k)
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i) n += inside(i, j, k) ? 1 : 0;
  return n;
}

class LabelMapTest : public ::testing::Test {
 protected:
  test::ScopedTempDir tmp_{"contourmesh_labels"};
  const fs::path& dir_ = tmp_.path();
};

TEST_F(LabelMapTest, PlainMapListsItsValuesWithTheirVoxelCounts) {
  write_nrrd(dir_ / "map.nrrd", 0, [](int i, int j, int k, int) { return two_labels(i, j, k); }, {});
  const LabelMap map = read_label_map(dir_ / "map.nrrd");
  ASSERT_EQ(map.labels.size(), 2u);
  EXPECT_FALSE(map.has_segment_metadata);
  EXPECT_EQ(map.labels[0].value, 1);
  EXPECT_EQ(map.labels[1].value, 2);
  EXPECT_EQ(map.labels[0].voxels, count_voxels([](int i, int j, int k) { return two_labels(i, j, k) == 1; }));
  EXPECT_EQ(map.labels[1].voxels, 14u * 10u * 14u);
  EXPECT_EQ(map.labels[1].display_name(), "2");
}

TEST_F(LabelMapTest, LabelTwoGivesOneClosedMeshOfItsVoxelVolume) {
  write_nrrd(dir_ / "map.nrrd", 0, [](int i, int j, int k, int) { return two_labels(i, j, k); }, {});
  const LabelMap map = read_label_map(dir_ / "map.nrrd");
  for (const Label& label : map.labels) {
    const Reconstruction r = reconstruct_label(map, label);
    const TopologySummary topo = summarize_topology(r.mesh);
    EXPECT_TRUE(topo.closed) << label.value;
    EXPECT_EQ(topo.components, 1) << label.value;
    const double voxel_volume = 2.0 * static_cast<double>(label.voxels);
    EXPECT_NEAR(enclosed_volume(r.mesh) / voxel_volume, 1.0, 0.03) << label.value;
    // The box of label 2 lies within x in [2, 16) mm of its voxel centres: the surface half a voxel out.
    if (label.value == 2) {
      EXPECT_NEAR(r.mesh.positions.row(0).minCoeff(), -20.0 + 22 - 0.5, 1e-6);
      EXPECT_NEAR(r.mesh.positions.row(0).maxCoeff(), -20.0 + 35 + 0.5, 1e-6);
    }
  }
}

TEST_F(LabelMapTest, SlicerSegmentationNamesItsSegments) {
  write_nrrd(dir_ / "knee.seg.nrrd", 0, [](int i, int j, int k, int) { return two_labels(i, j, k); },
             {"Segment0_ID:=Segment_1", "Segment0_Name:=Left femur", "Segment0_LabelValue:=1", "Segment0_Layer:=0",
              "Segment1_ID:=Segment_2", "Segment1_Name:=tibia", "Segment1_LabelValue:=2", "Segment1_Layer:=0",
              "Segment2_ID:=Segment_3", "Segment2_Name:=empty", "Segment2_LabelValue:=3", "Segment2_Layer:=0"});
  const LabelMap map = read_label_map(dir_ / "knee.seg.nrrd");
  EXPECT_TRUE(map.has_segment_metadata);
  ASSERT_EQ(map.labels.size(), 3u);
  EXPECT_EQ(map.labels[0].name, "Left femur");
  EXPECT_EQ(map.labels[1].name, "tibia");
  EXPECT_EQ(map.labels[2].voxels, 0u);
  EXPECT_EQ(label_file_tag(map.labels[0]), "Left_femur");
  const std::vector<Label> all = select_labels(map, "all");  // the empty segment is left out
  ASSERT_EQ(all.size(), 2u);
  const std::vector<Label> by_name = select_labels(map, "TIBIA, 1");
  ASSERT_EQ(by_name.size(), 2u);
  EXPECT_EQ(by_name[0].value, 2);
  EXPECT_EQ(by_name[1].name, "Left femur");
  try {
    (void)select_labels(map, "patella");
    FAIL() << "an unknown segment was selected";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("'tibia' (2)"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)reconstruct_label(map, map.labels[2]), InvalidInputError);
}

TEST_F(LabelMapTest, LayeredSegmentationReadsEachLayer) {
  // Layer 0: the box (value 1); layer 1: a slab overlapping it (value 1) and the ball (value 2).
  write_nrrd(
      dir_ / "layers.seg.nrrd", 2,
      [](int i, int j, int k, int l) -> std::uint8_t {
        if (l == 0) return two_labels(i, j, k) == 2 ? 1 : 0;
        if (i >= 28 && i < 38 && j >= 4 && j < 28 && k >= 8 && k < 14) return 1;
        return two_labels(i, j, k) == 1 ? 2 : 0;
      },
      {"Segment0_Name:=box", "Segment0_LabelValue:=1", "Segment0_Layer:=0", "Segment1_Name:=slab",
       "Segment1_LabelValue:=1", "Segment1_Layer:=1", "Segment2_Name:=ball", "Segment2_LabelValue:=2",
       "Segment2_Layer:=1"});
  const LabelMap map = read_label_map(dir_ / "layers.seg.nrrd");
  ASSERT_EQ(map.layers.size(), 2u);
  ASSERT_EQ(map.labels.size(), 3u);
  EXPECT_EQ(map.labels[0].voxels, 14u * 10u * 14u);
  EXPECT_EQ(map.labels[1].voxels, 10u * 24u * 6u);
  EXPECT_EQ(map.labels[1].layer, 1);
  const Reconstruction slab = reconstruct_label(map, map.labels[1]);
  EXPECT_NEAR(enclosed_volume(slab.mesh) / (2.0 * 10 * 24 * 6), 1.0, 0.03);
}

TEST_F(LabelMapTest, SegmentInAMissingLayerIsRefused) {
  write_nrrd(dir_ / "bad.seg.nrrd", 0, [](int i, int j, int k, int) { return two_labels(i, j, k); },
             {"Segment0_Name:=a", "Segment0_LabelValue:=1", "Segment0_Layer:=2"});
  try {
    (void)read_label_map(dir_ / "bad.seg.nrrd");
    FAIL();
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("layer 2 but the file has 1 layer"), std::string::npos) << e.what();
  }
}

TEST_F(LabelMapTest, CtVolumeIsNotALabelMap) {
  auto image = CtImage::New();
  CtImage::RegionType region;
  region.SetSize({{8, 8, 4}});
  image->SetRegions(region);
  image->Allocate();
  image->FillBuffer(-1000.0f);
  image->SetPixel({{3, 2, 1}}, 40.5f);
  try {
    (void)label_map_from_image(image);
    FAIL();
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a label map"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace contourmesh
