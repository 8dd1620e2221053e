// SPDX-License-Identifier: BSD-3-Clause
// vtkContourFeatureSmoothingFilter as documented: aborts from a progress observer, missing contour ids,
// option clamping, locked vertices, diverging runs and presets.
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/vtk/vtkContourFeatureSmoothingFilter.h>
#include <contourmesh/vtk/vtkCtImageToContourSurfaceFilter.h>
#include <contourmesh/vtk/vtk_convert.h>
#include <contourmesh/vtk/vtk_image_convert.h>
#include <contourmesh/reconstruct/reconstruction.h>
#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/cross_slice.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/feature_detection.h>
#include <contourmesh/smooth/feature_smoothing.h>
#include <contourmesh/smooth/shapes.h>
#include <contourmesh/smooth/smooth.h>
#include <contourmesh/smooth/smoothing.h>
#include <contourmesh/smooth/topology.h>

#include <gtest/gtest.h>

#include <vtkCommand.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkTrivialProducer.h>
#include <vtkXMLPolyDataReader.h>

#include <limits>
#include <sstream>
#include <string>

#include "vtk_filter_support.h"

namespace contourmesh {
namespace {

using namespace vtk_filter_test;

// (c) A ProgressEvent observer that sets AbortExecute stops the run at the next progress report: the
// output is empty, no error is reported, and after Modified() the filter runs in full again.
TEST_F(VtkFilters, AbortFromProgressObserverStopsEarlyWithEmptyOutput) {
  const Mesh mesh = ridge_stack();
  vtkNew<vtkTrivialProducer> source;
  source->SetOutput(to_polydata(mesh));
  vtkNew<vtkContourFeatureSmoothingFilter> filter;
  filter->SetInputConnection(source->GetOutputPort());
  filter->SetMethodToPaper();  // one report per iteration, 40 iterations
  vtkNew<MessageObserver> messages;
  observe_messages(filter, messages);
  vtkNew<ProgressObserver> progress;
  progress->abort_at = 0.5;  // in the smoothing stage, [0.4, 1]
  const unsigned long tag = filter->AddObserver(vtkCommand::ProgressEvent, progress);
  filter->Update();
  EXPECT_TRUE(progress->aborted);
  EXPECT_EQ(progress->events_after_abort, 0) << "the filter went on reporting after the abort";
  EXPECT_LT(progress->last, 0.6);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfCells(), 0);
  EXPECT_EQ(messages->errors, "");

  filter->RemoveObserver(tag);
  vtkNew<ProgressObserver> watch;
  filter->AddObserver(vtkCommand::ProgressEvent, watch);
  filter->Modified();
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), mesh.num_vertices());
  EXPECT_EQ(watch->last, 1.0);
  EXPECT_GT(watch->events, 40) << "one report per iteration";

  // The reconstruction filter aborts the same way, during segmentation.
  vtkNew<vtkCtImageToContourSurfaceFilter> surface;
  surface->SetInputData(to_image_data(femur().GetPointer()));
  surface->SetThreshold(kIsoLevel);
  observe_messages(surface, messages);
  vtkNew<ProgressObserver> early;
  early->abort_at = 0.1;
  surface->AddObserver(vtkCommand::ProgressEvent, early);
  surface->Update();
  EXPECT_TRUE(early->aborted);
  EXPECT_EQ(early->events_after_abort, 0);
  EXPECT_LT(early->last, 0.7) << "abort during segmentation";
  EXPECT_EQ(surface->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(messages->errors, "");
}

// (d) No contour-id array: an error and an empty output; with SliceAxis the ids are recovered by binning
// and the result is the one with the original ids.
TEST_F(VtkFilters, MissingIdsIsAnErrorUnlessSliceAxisRecoversThem) {
  const Mesh mesh = ridge_stack();
  Mesh bare = mesh;
  bare.slice_ids.clear();
  bare.contour_ids.clear();
  const fs::path input = write_stack(bare, "bare.vtp");

  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(input.c_str());
  vtkNew<vtkContourFeatureSmoothingFilter> filter;
  filter->SetInputConnection(reader->GetOutputPort());
  vtkNew<MessageObserver> messages;
  observe_messages(filter, messages);
  // The default, cross-slice smoothing, needs the ids whatever the detection mode.
  filter->SetDetectionModeToAutomatic();
  filter->Update();
  EXPECT_NE(messages->errors.find("which cross-slice smoothing needs"), std::string::npos) << messages->errors;
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);

  // The paper's method: an error too, unless the ids are recovered or the detection falls back.
  messages->errors.clear();
  filter->SetMethodToPaper();
  filter->SetDetectionModeToContourContinuity();
  filter->Update();
  EXPECT_NE(messages->errors.find("no contour-id point array 'ContourId'"), std::string::npos) << messages->errors;
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);

  // The array name is configurable: a file whose ids are under another name.
  messages->errors.clear();
  filter->SetContourIdArrayName("SliceIndex");
  filter->Update();
  EXPECT_NE(messages->errors.find("'SliceIndex'"), std::string::npos) << messages->errors;

  messages->errors.clear();
  filter->SetSliceAxisToZ();
  filter->Update();
  EXPECT_EQ(messages->errors, "");
  vtkPolyData* out = filter->GetOutput();
  EXPECT_EQ(int_array(out, "SliceIndex"), std::vector<int>(mesh.slice_ids.begin(), mesh.slice_ids.end()));
  const FeatureSmoothingResult expected = feature_preserving_smooth(mesh);
  EXPECT_EQ(max_difference(from_polydata(out).positions, expected.mesh.positions), 0.0);

  // Binning along an axis the slices are not normal to fails with a clear error.
  messages->errors.clear();
  filter->SetSliceAxisToX();
  filter->Update();
  EXPECT_NE(messages->errors.find("do not lie on planes normal to the slice axis x"), std::string::npos)
      << messages->errors;
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);

  // Automatic detection falls back to curvature-only with a warning, as the CLI does.
  messages->errors.clear();
  filter->SetSliceAxisToNone();
  filter->SetDetectionModeToAutomatic();
  filter->Update();
  EXPECT_EQ(messages->errors, "");
  EXPECT_NE(messages->warnings.find("curvature-only"), std::string::npos);
  FeatureSmoothingOptions curvature_only;
  curvature_only.detection.mode = DetectionMode::CurvatureOnly;
  EXPECT_EQ(max_difference(from_polydata(filter->GetOutput()).positions,
                           feature_preserving_smooth(bare, curvature_only).mesh.positions),
            0.0);

  // Empty in, empty out, no error.
  messages->errors.clear();
  vtkNew<vtkContourFeatureSmoothingFilter> on_empty;
  vtkNew<vtkPolyData> empty;
  on_empty->SetInputData(empty);
  observe_messages(on_empty, messages);
  on_empty->Update();
  EXPECT_EQ(messages->errors, "");
  EXPECT_EQ(on_empty->GetOutput()->GetNumberOfPoints(), 0);

  // A baseline needs no ids at all.
  messages->warnings.clear();
  filter->SetDetectionModeToContourContinuity();
  filter->SetMethodToLaplacian();
  filter->Update();
  EXPECT_EQ(messages->errors, "");
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), mesh.num_vertices());
}

// (g) Setters clamp to the valid range; a value at an open end of a range is rejected when run.
TEST_F(VtkFilters, OptionsClampAndPrintSelfListsThem) {
  vtkNew<vtkContourFeatureSmoothingFilter> f;
  f->SetLambda(2.0);
  EXPECT_EQ(f->GetLambda(), 1.0);
  f->SetLambda(-0.5);
  EXPECT_EQ(f->GetLambda(), 0.0);
  f->SetMu(-3.0);
  EXPECT_EQ(f->GetMu(), -1.0);
  f->SetMu(0.5);
  EXPECT_EQ(f->GetMu(), 0.0);
  f->SetBeta(5.0);
  EXPECT_EQ(f->GetBeta(), 2.0);
  EXPECT_EQ(f->GetMethod(), vtkContourFeatureSmoothingFilter::METHOD_CROSS_SLICE) << "the default preset";
  EXPECT_EQ(f->GetPreset(), vtkContourFeatureSmoothingFilter::PRESET_DEFAULT);
  f->SetMethod(99);
  EXPECT_EQ(f->GetMethod(), vtkContourFeatureSmoothingFilter::METHOD_CROSS_SLICE);
  f->SetMethod(-4);
  EXPECT_EQ(f->GetMethod(), vtkContourFeatureSmoothingFilter::METHOD_NONE);
  f->SetNumberOfIterations(-7);
  EXPECT_EQ(f->GetNumberOfIterations(), -1);
  f->SetGamma(-5.0);
  EXPECT_EQ(f->GetGamma(), -1.0);
  f->SetDelta(-0.1);
  EXPECT_EQ(f->GetDelta(), -0.1) << "any negative value means automatic";
  f->SetWindow(3);
  EXPECT_EQ(f->GetWindow(), 5);
  f->SetCornerSpread(-1.0);
  EXPECT_EQ(f->GetCornerSpread(), 0.0);
  f->SetMaxLevels(-1);
  EXPECT_EQ(f->GetMaxLevels(), 0);
  f->SetDiffusionMethod(vtkContourFeatureSmoothingFilter::METHOD_PAPER);
  EXPECT_EQ(f->GetDiffusionMethod(), vtkContourFeatureSmoothingFilter::METHOD_TAUBIN);
  f->SetDiffusionMethod(vtkContourFeatureSmoothingFilter::METHOD_NONE);
  EXPECT_EQ(f->GetDiffusionMethod(), vtkContourFeatureSmoothingFilter::METHOD_LAPLACIAN);
  f->SetSliceAxis(7);
  EXPECT_EQ(f->GetSliceAxis(), vtkContourFeatureSmoothingFilter::SLICE_AXIS_Z);
  f->SetMinReciprocalCondition(3.0);
  EXPECT_EQ(f->GetMinReciprocalCondition(), 1.0);
  f->SetAnisotropy(0.2);
  EXPECT_EQ(f->GetAnisotropy(), 1.0);

  vtkNew<vtkCtImageToContourSurfaceFilter> s;
  s->SetMinOverlapFraction(2.0);
  EXPECT_EQ(s->GetMinOverlapFraction(), 1.0);
  s->SetMinRegionArea(-1.0);
  EXPECT_EQ(s->GetMinRegionArea(), 0.0);
  s->SetThreshold(std::numeric_limits<double>::infinity());
  EXPECT_EQ(s->GetThreshold(), VTK_DOUBLE_MAX);
  s->SetDenoising(9);
  EXPECT_EQ(s->GetDenoising(), vtkCtImageToContourSurfaceFilter::DENOISING_CURVATURE_ANISOTROPIC);
  s->SetFullDynamicProgrammingLimit(-3);
  EXPECT_EQ(s->GetFullDynamicProgrammingLimit(), 0);
  s->SetBranching(5);
  EXPECT_EQ(s->GetBranching(), vtkCtImageToContourSurfaceFilter::BRANCHING_MID_PLANE);
  s->SetMaxIntermediateContours(0);
  EXPECT_EQ(s->GetMaxIntermediateContours(), 1);
  // The defaults are the library's.
  vtkNew<vtkCtImageToContourSurfaceFilter> d;
  const TilingOptions t;
  EXPECT_EQ(d->GetMaxBranchingDepth(), t.max_branching_depth);
  EXPECT_EQ(d->GetMaxBandSliverShare(), t.max_band_sliver_share);
  EXPECT_EQ(d->GetMaxBandAspect(), t.max_band_aspect);
  EXPECT_EQ(d->GetMaxIntermediateContours(), t.max_intermediate_contours);
  EXPECT_EQ(d->GetInterpolationGrid(), t.interpolation_grid);
  EXPECT_EQ(d->GetMinOverlapOfLarger(), t.min_overlap_of_larger);
  EXPECT_EQ(d->GetMinOverlapFraction(), t.min_overlap_fraction);
  EXPECT_EQ(d->GetBandFraction(), t.band_fraction);
  EXPECT_EQ(static_cast<std::size_t>(d->GetFullDynamicProgrammingLimit()), t.full_dp_limit);

  // Mu clamped to 0 is outside Taubin's [-1, 0): an error naming it when run, output empty.
  vtkNew<vtkContourFeatureSmoothingFilter> taubin;
  taubin->SetInputData(to_polydata(ridge_stack()));
  taubin->SetMethodToTaubin();
  taubin->SetMu(1.0);
  vtkNew<MessageObserver> messages;
  observe_messages(taubin, messages);
  taubin->Update();
  EXPECT_NE(messages->errors.find("mu must be in [-1, 0)"), std::string::npos) << messages->errors;
  EXPECT_EQ(taubin->GetOutput()->GetNumberOfPoints(), 0);

  std::ostringstream printed;
  f->Print(printed);
  for (const char* option : {"Preset: Default",
                             "Method: None",
                             "NumberOfIterations: -1 (automatic)",
                             "Lambda",
                             "Mu",
                             "Beta",
                             "BoundarySmoothing",
                             "TimeStepMode",
                             "DetectionMode",
                             "Anisotropy",
                             "Gamma: -1 (automatic)",
                             "GammaFactor",
                             "UmbrellaMeasure",
                             "Delta",
                             "DeltaFactor",
                             "Window: 5",
                             "CornerSpread",
                             "InSliceFeatures: Noise",
                             "PrefilterIterations",
                             "UmbilicTolerance",
                             "MinReciprocalCondition",
                             "MaxLevels",
                             "DiffusionMethod: Laplacian",
                             "KeepAdaptiveMesh",
                             "CreaseRestoration: None",
                             "OffSliceVolume: Free",
                             "GenerateLabels",
                             "SliceAxis: Z",
                             "SliceTolerance",
                             "ContourIdArrayName: ContourId",
                             "ContourIndexArrayName: ContourIndex",
                             "LockedArrayName"}) {
    EXPECT_NE(printed.str().find(option), std::string::npos) << option;
  }
  std::ostringstream printed_surface;
  s->Print(printed_surface);
  for (const char* option : {"ThresholdMethod", "Threshold", "Denoising", "KeepLargestComponent", "MinRegionArea",
                             "FillHoles", "Sampling", "MinContourLength", "EndCaps", "CapRefinement",
                             "MinOverlapFraction: 1", "FullDynamicProgrammingLimit", "BandFraction",
                             "Branching", "MaxBranchingDepth", "BandRefinement", "MaxBandSliverShare", "MaxBandAspect",
                             "MaxIntermediateContours", "InterpolationGrid", "MinOverlapOfLarger",
                             "MinComponentVoxels", "ContourIdArrayName"}) {
    EXPECT_NE(printed_surface.str().find(option), std::string::npos) << option;
  }
}

// Locked vertices (LockedArrayName) stay where they are, as with the library's lock mask.
TEST_F(VtkFilters, LockedArrayKeepsVerticesInPlace) {
  const Mesh mesh = ridge_stack();
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (std::size_t i = 0; i < mask.size(); i += 3) mask[i] = 1;
  FeatureSmoothingOptions o;
  o.locked = mask;
  const Mesh expected = feature_preserving_smooth(mesh, o).mesh;

  PointScalars lock{"Lock", std::vector<double>(mask.begin(), mask.end()), ScalarType::Int32};
  vtkNew<vtkContourFeatureSmoothingFilter> filter;
  filter->SetInputData(to_polydata(mesh, {}, {lock}));
  filter->SetLockedArrayName("Lock");
  vtkNew<MessageObserver> messages;
  observe_messages(filter, messages);
  filter->Update();  // the default, cross-slice smoothing, cannot lock: an error, not a silent ignore
  EXPECT_NE(messages->errors.find("cross-slice smoothing cannot lock"), std::string::npos) << messages->errors;
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
  messages->errors.clear();
  filter->SetMethodToPaper();
  filter->Update();
  EXPECT_EQ(messages->errors, "");
  const Mesh out = from_polydata(filter->GetOutput());
  ASSERT_EQ(out.num_vertices(), mesh.num_vertices());
  EXPECT_EQ(max_difference(out.positions, expected.positions), 0.0);
  for (std::size_t i = 0; i < mask.size(); i += 3) EXPECT_EQ(out.positions.col(i), mesh.positions.col(i));
}

// A run that diverges (a million Taubin iterations) is an error and an empty output, as in the CLI.
TEST_F(VtkFilters, ADivergingRunIsAnErrorNotAnOverflowingMesh) {
  vtkNew<vtkContourFeatureSmoothingFilter> filter;
  filter->SetInputData(to_polydata(ridge_stack()));
  filter->SetMethodToTaubin();
  filter->SetNumberOfIterations(1000000);
  vtkNew<MessageObserver> messages;
  observe_messages(filter, messages);
  filter->Update();
  EXPECT_NE(messages->errors.find("smoothing diverged at iteration"), std::string::npos) << messages->errors;
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
}

// Presets set the method and the options they fix; the xu2006 preset is the library's, on the golden mesh
// (tests/data/xu2006); options set after a preset override it.
TEST_F(VtkFilters, PresetsAreTheLibrarys) {
  using Filter = vtkContourFeatureSmoothingFilter;
  const Mesh mesh = read_mesh(fs::path(CONTOURMESH_TEST_DATA) / "xu2006" / "input.ply");
  const MethodConfig xu = preset(Preset::Xu2006);
  const SmoothResult expected = smooth(mesh, xu.method, xu.options);
  vtkNew<Filter> f;
  f->SetInputData(to_polydata(mesh));
  f->SetPresetToXu2006();
  EXPECT_EQ(f->GetPreset(), Filter::PRESET_XU2006);
  EXPECT_EQ(f->GetMethod(), Filter::METHOD_PAPER);
  EXPECT_EQ(f->GetNumberOfIterations(), 40);
  EXPECT_EQ(f->GetLambda(), 0.6307);
  EXPECT_GT(f->GetCornerSpread(), 1.0 / 3.0);
  f->GenerateLabelsOn();
  f->Update();
  EXPECT_EQ(max_difference(from_polydata(f->GetOutput()).positions, expected.mesh.positions), 0.0);
  std::vector<int> want;
  for (VertexLabel l : expected.labels) want.push_back(static_cast<int>(l));
  EXPECT_EQ(int_array(f->GetOutput(), "FeatureLabel"), want);
  // An option after the preset overrides it.
  f->SetNumberOfIterations(39);
  f->Update();
  EXPECT_GT(max_difference(from_polydata(f->GetOutput()).positions, expected.mesh.positions), 1e-6);
  EXPECT_EQ(f->GetPreset(), Filter::PRESET_XU2006) << "the preset last applied";
  // Back to the default preset: cross-slice smoothing, every option at its default.
  f->SetPresetToDefault();
  EXPECT_EQ(f->GetMethod(), Filter::METHOD_CROSS_SLICE);
  EXPECT_EQ(f->GetNumberOfIterations(), -1);
  EXPECT_EQ(f->GetCornerSpread(), DetectionOptions{}.corner_spread);
  f->Update();
  EXPECT_EQ(max_difference(from_polydata(f->GetOutput()).positions, cross_slice_smooth(mesh).mesh.positions), 0.0);
}

}  // namespace
}  // namespace contourmesh
