// SPDX-License-Identifier: BSD-3-Clause
// Writes small RT Structure Sets for tests (GDCM): ROIs with contours of any geometric type, and
// deliberately broken values.
#pragma once

#include <gdcmDataElement.h>
#include <gdcmDataSet.h>
#include <gdcmFile.h>
#include <gdcmItem.h>
#include <gdcmSequenceOfItems.h>
#include <gdcmTag.h>
#include <gdcmTransferSyntax.h>
#include <gdcmWriter.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace contourmesh::test {

struct TestContour {
  std::string type = "CLOSED_PLANAR";
  std::vector<Eigen::Vector3d> points;
  std::optional<std::string> raw_data;  ///< Contour Data as written, instead of `points`
};

struct TestRoi {
  int number = 1;
  std::string name;
  std::optional<std::array<int, 3>> color;
  std::vector<TestContour> contours;
  bool has_contour_item = true;  ///< false: no ROI Contour Sequence item at all
};

inline TestContour contour_of(std::string type, std::vector<Eigen::Vector3d> points) {
  TestContour c;
  c.type = std::move(type);
  c.points = std::move(points);
  return c;
}

inline TestRoi roi_of(int number, std::string name, std::vector<TestContour> contours = {}) {
  TestRoi r;
  r.number = number;
  r.name = std::move(name);
  r.contours = std::move(contours);
  return r;
}

/// A closed polygon approximating an ellipse in the plane z, counter-clockwise.
inline std::vector<Eigen::Vector3d> ellipse(double cx, double cy, double rx, double ry, double z, int n = 48) {
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * 3.14159265358979323846 * i / n;
    p.emplace_back(cx + rx * std::cos(t), cy + ry * std::sin(t), z);
  }
  return p;
}

namespace detail {

inline void put(gdcm::DataSet& ds, uint16_t group, uint16_t element, gdcm::VR vr, std::string value) {
  if (value.size() % 2 == 1) value += (vr == gdcm::VR::UI ? '\0' : ' ');
  gdcm::DataElement de(gdcm::Tag(group, element));
  de.SetVR(vr);
  de.SetByteValue(value.data(), static_cast<uint32_t>(value.size()));
  ds.Insert(de);
}

inline void put_sequence(gdcm::DataSet& ds, uint16_t group, uint16_t element, const std::vector<gdcm::Item>& items) {
  gdcm::SmartPointer<gdcm::SequenceOfItems> sq = new gdcm::SequenceOfItems();
  sq->SetLengthToUndefined();
  for (const gdcm::Item& item : items) sq->AddItem(item);
  gdcm::DataElement de(gdcm::Tag(group, element));
  de.SetVR(gdcm::VR::SQ);
  de.SetValue(*sq);
  de.SetVLToUndefined();
  ds.Insert(de);
}

inline gdcm::Item new_item() {
  gdcm::Item item;
  item.SetVLToUndefined();
  return item;
}

}  // namespace detail

/// Writes an RT Structure Set with these ROIs (explicit VR little endian) to `path`.
inline void write_rtstruct(const std::filesystem::path& path, const std::vector<TestRoi>& rois,
                           const std::string& modality = "RTSTRUCT") {
  using detail::put;
  gdcm::Writer writer;
  gdcm::File& file = writer.GetFile();
  gdcm::DataSet& ds = file.GetDataSet();
  const std::string sop_class = modality == "RTSTRUCT" ? "1.2.840.10008.5.1.4.1.1.481.3" : "1.2.840.10008.5.1.4.1.1.2";
  put(ds, 0x0008, 0x0016, gdcm::VR::UI, sop_class);
  put(ds, 0x0008, 0x0018, gdcm::VR::UI, "1.2.826.0.1.3680043.2.1125.1.1");
  put(ds, 0x0008, 0x0060, gdcm::VR::CS, modality);
  put(ds, 0x3006, 0x0002, gdcm::VR::SH, "TEST");
  std::vector<gdcm::Item> roi_items, contour_items;
  for (const TestRoi& roi : rois) {
    gdcm::Item item = detail::new_item();
    put(item.GetNestedDataSet(), 0x3006, 0x0022, gdcm::VR::IS, std::to_string(roi.number));
    put(item.GetNestedDataSet(), 0x3006, 0x0026, gdcm::VR::LO, roi.name);
    roi_items.push_back(item);
    if (!roi.has_contour_item) continue;
    gdcm::Item rc = detail::new_item();
    gdcm::DataSet& rcs = rc.GetNestedDataSet();
    put(rcs, 0x3006, 0x0084, gdcm::VR::IS, std::to_string(roi.number));
    if (roi.color) {
      put(rcs, 0x3006, 0x002A, gdcm::VR::IS,
          std::to_string((*roi.color)[0]) + "\\" + std::to_string((*roi.color)[1]) + "\\" +
              std::to_string((*roi.color)[2]));
    }
    std::vector<gdcm::Item> contours;
    for (const TestContour& c : roi.contours) {
      gdcm::Item ci = detail::new_item();
      gdcm::DataSet& cs = ci.GetNestedDataSet();
      put(cs, 0x3006, 0x0042, gdcm::VR::CS, c.type);
      put(cs, 0x3006, 0x0046, gdcm::VR::IS, std::to_string(c.points.size()));
      std::string data;
      if (c.raw_data) {
        data = *c.raw_data;
      } else {
        std::ostringstream s;
        s.precision(10);
        for (std::size_t i = 0; i < c.points.size(); ++i) {
          s << (i ? "\\" : "") << c.points[i].x() << "\\" << c.points[i].y() << "\\" << c.points[i].z();
        }
        data = s.str();
      }
      put(cs, 0x3006, 0x0050, gdcm::VR::DS, data);
      contours.push_back(ci);
    }
    if (!contours.empty()) detail::put_sequence(rcs, 0x3006, 0x0040, contours);
    contour_items.push_back(rc);
  }
  detail::put_sequence(ds, 0x3006, 0x0020, roi_items);
  detail::put_sequence(ds, 0x3006, 0x0039, contour_items);
  file.GetHeader().SetDataSetTransferSyntax(gdcm::TransferSyntax::ExplicitVRLittleEndian);
  writer.SetFileName(path.string().c_str());
  if (!writer.Write()) throw std::runtime_error("cannot write the test structure set " + path.string());
}

}  // namespace contourmesh::test
