// SPDX-License-Identifier: BSD-3-Clause
// vtkContourPolylinesToSurfaceFilter in VTK pipelines: the same mesh as build_contour_stack() +
// reconstruct_from_contours(), slice ids per cell, per point or from positions, errors, abort,
// clamping, and the chain into vtkContourFeatureSmoothingFilter.
#include <contourmesh/vtk/vtkContourFeatureSmoothingFilter.h>
#include <contourmesh/vtk/vtkContourPolylinesToSurfaceFilter.h>
#include <contourmesh/vtk/vtk_convert.h>
#include <contourmesh/reconstruct/contour_reconstruction.h>
#include <contourmesh/reconstruct/planar_contours.h>
#include <contourmesh/smooth/topology.h>

#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace contourmesh {
namespace {

class Messages : public vtkCommand {
 public:
  static Messages* New() { return new Messages; }
  void Execute(vtkObject*, unsigned long event, void* data) override {
    const std::string message = data != nullptr ? static_cast<const char*>(data) : "";
    (event == vtkCommand::ErrorEvent ? errors : warnings) += message + "\n";
  }
  std::string errors;
  std::string warnings;
};

class AbortAtStart : public vtkCommand {
 public:
  static AbortAtStart* New() { return new AbortAtStart; }
  void Execute(vtkObject* caller, unsigned long, void*) override {
    static_cast<vtkAlgorithm*>(caller)->AbortExecuteOn();
  }
};

void observe(vtkAlgorithm* filter, Messages* messages) {
  filter->AddObserver(vtkCommand::ErrorEvent, messages);
  filter->AddObserver(vtkCommand::WarningEvent, messages);
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, messages);
}

using Points = std::vector<Eigen::Vector3d>;

Points ellipse(double cx, double rx, double ry, double z, int n, bool clockwise = false) {
  Points p;
  for (int i = 0; i < n; ++i) {
    const double t = (clockwise ? -2.0 : 2.0) * std::numbers::pi * i / n;
    p.emplace_back(cx + rx * std::cos(t), ry * std::sin(t), z);
  }
  return p;
}

// A tapering body with a split at the top and a hole in the middle, in mixed orientations.
std::vector<Points> contours() {
  return {ellipse(0, 14, 8, 0.0, 40),         ellipse(0, 13, 8, 2.5, 40, true), ellipse(0, 4, 3, 2.5, 20, true),
          ellipse(0, 13, 7, 5.0, 40),         ellipse(0, 4, 3, 5.0, 20),        ellipse(-6, 5, 5, 7.5, 30),
          ellipse(6, 5, 5, 7.5, 30, true)};
}

enum class Ids { None, PerCell, PerPoint };

// The contours as polylines; `close` repeats each first point at the end.
vtkSmartPointer<vtkPolyData> polylines(const std::vector<Points>& cs, Ids ids, bool close = false) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkIntArray> cell_ids, point_ids;
  cell_ids->SetName("SliceId");
  point_ids->SetName("SliceId");
  for (const Points& c : cs) {
    const int slice = static_cast<int>(std::lround(c[0].z() / 2.5));
    std::vector<vtkIdType> cell;
    for (const auto& p : c) {
      cell.push_back(points->InsertNextPoint(p.x(), p.y(), p.z()));
      point_ids->InsertNextValue(slice);
    }
    if (close) cell.push_back(cell.front());
    lines->InsertNextCell(static_cast<vtkIdType>(cell.size()), cell.data());
    cell_ids->InsertNextValue(slice);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetLines(lines);
  if (ids == Ids::PerCell) poly->GetCellData()->AddArray(cell_ids);
  if (ids == Ids::PerPoint) poly->GetPointData()->AddArray(point_ids);
  return poly;
}

ContourReconstruction library_result(const std::vector<Points>& cs) {
  std::vector<PlanarContour> planar;
  for (std::size_t i = 0; i < cs.size(); ++i) planar.push_back({cs[i], "cell " + std::to_string(i), {}});
  return reconstruct_from_contours(build_contour_stack(planar, "input").stack, "input");
}

TEST(VtkPolylinesFilter, GivesTheLibraryResult) {
  const ContourReconstruction expected = library_result(contours());
  for (const Ids ids : {Ids::None, Ids::PerCell, Ids::PerPoint}) {
    for (const bool close : {false, true}) {
      vtkNew<vtkContourPolylinesToSurfaceFilter> filter;
      filter->SetInputData(polylines(contours(), ids, close));
      vtkNew<Messages> messages;
      observe(filter, messages);
      filter->Update();
      EXPECT_EQ(messages->errors, "");
      const Mesh out = from_polydata(filter->GetOutput());
      ASSERT_EQ(out.num_vertices(), expected.mesh.num_vertices());
      EXPECT_EQ((out.positions - expected.mesh.positions).cwiseAbs().maxCoeff(), 0.0);
      EXPECT_EQ(out.triangles, expected.mesh.triangles);
      EXPECT_EQ(out.slice_ids, expected.mesh.slice_ids);
      EXPECT_EQ(out.contour_ids, expected.mesh.contour_ids);
      const TopologySummary t = summarize_topology(out);
      EXPECT_TRUE(t.closed && t.manifold) << t.first_problems;
      EXPECT_NEAR(filter->GetSlicewiseVolume(), expected.report.slicewise_volume, 1e-9);
    }
  }
}

TEST(VtkPolylinesFilter, SliceIdsSeparatePlanesCloserThanTheTolerance) {
  // Two slices 0.05 mm apart: one slice by position, two by id.
  const std::vector<Points> cs{ellipse(0, 10, 6, 0.0, 30), ellipse(0, 10, 6, 0.05, 30)};
  vtkSmartPointer<vtkPolyData> poly = polylines(cs, Ids::None);
  vtkNew<vtkIntArray> ids;
  ids->SetName("Level");
  ids->InsertNextValue(3);
  ids->InsertNextValue(4);
  poly->GetCellData()->AddArray(ids);
  vtkNew<vtkContourPolylinesToSurfaceFilter> filter;
  filter->SetInputData(poly);
  vtkNew<Messages> messages;
  observe(filter, messages);
  filter->Update();
  EXPECT_NE(messages->errors.find("meet"), std::string::npos) << "one slice of two coincident contours";
  messages->errors.clear();
  filter->SetSliceIdArrayName("Level");
  filter->Update();
  EXPECT_EQ(messages->errors, "");
  EXPECT_GT(filter->GetOutput()->GetNumberOfPolys(), 0);
}

TEST(VtkPolylinesFilter, ErrorsNameTheCellAndLeaveTheOutputEmpty) {
  vtkNew<vtkContourPolylinesToSurfaceFilter> filter;
  vtkNew<Messages> messages;
  observe(filter, messages);
  // No lines.
  vtkNew<vtkPolyData> empty;
  filter->SetInputData(empty);
  filter->Update();
  EXPECT_NE(messages->errors.find("no lines"), std::string::npos) << messages->errors;
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
  // Loose segments.
  messages->errors.clear();
  vtkSmartPointer<vtkPolyData> poly = polylines(contours(), Ids::None);
  vtkIdType segment[2] = {0, 1};
  poly->GetLines()->InsertNextCell(2, segment);
  filter->SetInputData(poly);
  filter->Update();
  EXPECT_NE(messages->errors.find("cell 7 has 2 points"), std::string::npos) << messages->errors;
  EXPECT_NE(messages->errors.find("vtkStripper"), std::string::npos) << messages->errors;
  // Points of one contour with different slice ids.
  messages->errors.clear();
  poly = polylines(contours(), Ids::PerPoint);
  vtkIntArray::SafeDownCast(poly->GetPointData()->GetArray("SliceId"))->SetValue(3, 9);
  filter->SetInputData(poly);
  filter->Update();
  EXPECT_NE(messages->errors.find("cell 0: its points carry different slice ids"), std::string::npos)
      << messages->errors;
  // A non-planar contour.
  messages->errors.clear();
  std::vector<Points> bent = contours();
  bent[3][5].z() += 1.0;
  filter->SetInputData(polylines(bent, Ids::None));
  filter->Update();
  EXPECT_NE(messages->errors.find("cell 3"), std::string::npos) << messages->errors;
  EXPECT_NE(messages->errors.find("not planar"), std::string::npos) << messages->errors;
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_TRUE(std::isnan(filter->GetSlicewiseVolume()));
  // One slice only: refused without a slab thickness, a slab with one.
  messages->errors.clear();
  filter->SetInputData(polylines({ellipse(0, 10, 6, 1.0, 30)}, Ids::None));
  filter->Update();
  EXPECT_NE(messages->errors.find("one slice"), std::string::npos) << messages->errors;
  messages->errors.clear();
  filter->SetSlabThickness(2.0);
  filter->Update();
  EXPECT_EQ(messages->errors, "");
  EXPECT_GT(filter->GetOutput()->GetNumberOfPolys(), 0);
}

TEST(VtkPolylinesFilter, WarningsReportGapsAndRepairs) {
  std::vector<Points> cs{ellipse(0, 10, 6, 0.0, 30), ellipse(0, 10, 6, 2.5, 30), ellipse(0, 10, 6, 10.0, 30)};
  cs[0].insert(cs[0].begin() + 4, cs[0][4]);
  vtkNew<vtkContourPolylinesToSurfaceFilter> filter;
  filter->SetInputData(polylines(cs, Ids::None));
  vtkNew<Messages> messages;
  observe(filter, messages);
  filter->Update();
  EXPECT_EQ(messages->errors, "");
  EXPECT_NE(messages->warnings.find("repeated point"), std::string::npos) << messages->warnings;
  EXPECT_NE(messages->warnings.find("7.50 mm apart"), std::string::npos) << messages->warnings;
}

TEST(VtkPolylinesFilter, AbortLeavesAnEmptyOutputAndNoError) {
  vtkNew<vtkContourPolylinesToSurfaceFilter> filter;
  filter->SetInputData(polylines(contours(), Ids::None));
  vtkNew<Messages> messages;
  observe(filter, messages);
  vtkNew<AbortAtStart> abort;
  filter->AddObserver(vtkCommand::ProgressEvent, abort);  // the first report, 0, comes before RequestData
  filter->Update();
  EXPECT_EQ(messages->errors, "");
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
}

TEST(VtkPolylinesFilter, SettersClampAndPrintSelfListsEveryOption) {
  vtkNew<vtkContourPolylinesToSurfaceFilter> f;
  f->SetMinOverlapFraction(2.0);
  EXPECT_EQ(f->GetMinOverlapFraction(), 1.0);
  f->SetSampling(-1.0);
  EXPECT_EQ(f->GetSampling(), 0.0);
  f->SetDriftAlignment(7);
  EXPECT_EQ(f->GetDriftAlignment(), vtkContourPolylinesToSurfaceFilter::DRIFT_ALIGNMENT_NONE);
  f->SetPlanarityTolerance(-1.0);
  EXPECT_EQ(f->GetPlanarityTolerance(), 0.0);
  // A tolerance of 0 is refused when the filter runs.
  f->SetInputData(polylines(contours(), Ids::None));
  vtkNew<Messages> messages;
  observe(f, messages);
  f->Update();
  EXPECT_NE(messages->errors.find("planarity tolerance"), std::string::npos) << messages->errors;
  std::ostringstream os;
  f->Print(os);
  for (const char* option : {"SliceIdArrayName", "SliceAxis", "PlanarityTolerance", "SliceTolerance", "Sampling",
                             "SamplingTolerance", "DriftAlignment", "SingleSliceContours", "SlabThickness", "EndCaps",
                             "CapRefinement", "MinOverlapFraction", "FullDynamicProgrammingLimit", "BandFraction",
                             "Branching", "MaxBranchingDepth", "BandRefinement", "MaxBandSliverShare", "MaxBandAspect",
                             "MaxIntermediateContours", "InterpolationGrid", "MinOverlapOfLarger",
                             "ContourIdArrayName", "ContourIndexArrayName"}) {
    EXPECT_NE(os.str().find(option), std::string::npos) << option;
  }
}

TEST(VtkPolylinesFilter, ChainsIntoTheSmoothingFilter) {
  vtkNew<vtkContourPolylinesToSurfaceFilter> surface;
  surface->SetInputData(polylines(contours(), Ids::PerCell));
  vtkNew<vtkContourFeatureSmoothingFilter> smoothing;
  smoothing->SetInputConnection(surface->GetOutputPort());
  vtkNew<Messages> messages;
  observe(surface, messages);
  observe(smoothing, messages);
  smoothing->Update();
  EXPECT_EQ(messages->errors, "");
  EXPECT_EQ(smoothing->GetOutput()->GetNumberOfPoints(), surface->GetOutput()->GetNumberOfPoints());
  EXPECT_GT(smoothing->GetOutput()->GetNumberOfPoints(), 0);
}

}  // namespace
}  // namespace contourmesh
