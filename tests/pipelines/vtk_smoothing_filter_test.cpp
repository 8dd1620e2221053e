// SPDX-License-Identifier: BSD-3-Clause
// vtkContourFeatureSmoothingFilter inside real VTK pipelines gives exactly what the libsmooth calls give:
// positions for every method and option, chains of filters, and the FeatureLabel array.
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/vtk/vtkContourFeatureSmoothingFilter.h>
#include <contourmesh/vtk/vtk_convert.h>
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

#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTrivialProducer.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <functional>
#include <string>

#include "vtk_filter_support.h"

namespace contourmesh {
namespace {

using namespace vtk_filter_test;

// A filter's FeatureLabel array on an output that may have more points than its input: `labels` on the
// input's points, which come first, then -1 on the points the filter added.
void expect_labels_then_added(vtkPolyData* output, Index input_points, const std::vector<VertexLabel>& labels) {
  const std::vector<int> got = int_array(output, "FeatureLabel");
  ASSERT_EQ(got.size(), static_cast<std::size_t>(output->GetNumberOfPoints()));
  for (Index i = 0; i < output->GetNumberOfPoints(); ++i) {
    const int want = i < input_points ? static_cast<int>(labels[static_cast<std::size_t>(i)]) : -1;
    ASSERT_EQ(got[static_cast<std::size_t>(i)], want) << "vertex " << i;
  }
}

// (a) reader -> smoothing filter -> writer -> read back: bitwise the libsmooth result, for the default
// (cross-slice smoothing) and the paper's method with every option at its default (so the filter's
// defaults are the library's), and for Taubin.
TEST_F(VtkFilters, SmoothingFilterMatchesTheLibraryForPaperAndTaubin) {
  const fs::path input = write_stack(ridge_stack());
  const Mesh mesh = read_mesh(input);
  ASSERT_TRUE(mesh.has_contour_ids());

  const FeatureSmoothingResult paper = feature_preserving_smooth(mesh);
  ASSERT_GT(paper.detection.edges, 0u) << "the ridge should be detected, or the test proves little";
  SmoothingOptions taubin;
  taubin.method = SmoothingMethod::Taubin;
  taubin.iterations = 7;
  const Eigen::Matrix3Xd taubin_positions = smooth(mesh, taubin);
  const CrossSliceResult cross_slice = cross_slice_smooth(mesh);

  for (const std::string which : {"default", "paper", "taubin"}) {
    SCOPED_TRACE(which);
    const bool use_paper = which == "paper", use_default = which == "default";
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(input.c_str());
    vtkNew<vtkContourFeatureSmoothingFilter> filter;
    filter->SetInputConnection(reader->GetOutputPort());
    if (use_paper) filter->SetMethodToPaper();
    if (which == "taubin") {
      filter->SetMethodToTaubin();
      filter->SetNumberOfIterations(7);
    }
    vtkNew<MessageObserver> messages;
    observe_messages(filter, messages);
    const fs::path output = tmp_.path() / "smoothed.vtp";
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetInputConnection(filter->GetOutputPort());
    writer->SetFileName(output.c_str());
    ASSERT_EQ(writer->Write(), 1);
    EXPECT_EQ(messages->errors, "");
    EXPECT_EQ(messages->warnings, "");

    const Mesh smoothed = read_mesh(output);
    const Mesh& expected = use_paper ? paper.mesh : mesh;
    const Eigen::Matrix3Xd& expected_positions =
        use_paper ? paper.mesh.positions : (use_default ? cross_slice.mesh.positions : taubin_positions);
    EXPECT_EQ(max_difference(smoothed.positions, expected_positions), 0.0);
    EXPECT_EQ(smoothed.triangles, expected.triangles);
    EXPECT_EQ(smoothed.slice_ids, expected.slice_ids);
    EXPECT_EQ(smoothed.contour_ids, expected.contour_ids);
    EXPECT_GT(max_difference(smoothed.positions, mesh.positions), 0.01) << "nothing moved";
  }
}

// Two filters in a row (Taubin then the paper's method at the adaptive resolution): the ids the first
// writes are what the second reads, and the chain equals the two library calls.
TEST_F(VtkFilters, TwoSmoothingFiltersChainLikeTwoLibraryCalls) {
  const Mesh mesh = ridge_stack();
  SmoothingOptions taubin;
  taubin.method = SmoothingMethod::Taubin;
  taubin.iterations = 3;
  Mesh first = mesh;
  first.positions = smooth(mesh, taubin);
  FeatureSmoothingOptions paper;
  paper.output = OutputResolution::Adaptive;
  paper.max_levels = 2;
  paper.iterations = 10;
  const FeatureSmoothingResult expected = feature_preserving_smooth(first, paper);

  vtkNew<vtkTrivialProducer> source;
  source->SetOutput(to_polydata(mesh));
  vtkNew<vtkContourFeatureSmoothingFilter> a;
  a->SetInputConnection(source->GetOutputPort());
  a->SetMethodToTaubin();
  a->SetNumberOfIterations(3);
  vtkSmartPointer<vtkContourFeatureSmoothingFilter> b = vtkSmartPointer<vtkContourFeatureSmoothingFilter>::New();
  b->SetInputConnection(a->GetOutputPort());
  b->SetMethodToPaper();
  b->KeepAdaptiveMeshOn();
  b->SetMaxLevels(2);
  b->SetNumberOfIterations(10);
  b->GenerateLabelsOn();
  b->Update();
  const Mesh out = from_polydata(b->GetOutput());
  EXPECT_EQ(max_difference(out.positions, expected.mesh.positions), 0.0);
  EXPECT_EQ(out.triangles, expected.mesh.triangles);
  EXPECT_EQ(out.slice_ids, expected.mesh.slice_ids);
  ASSERT_GT(out.num_vertices(), mesh.num_vertices()) << "the adaptive mesh adds vertices";
  // Labels: the input vertices' labels, then -1 for the vertices the subdivision added.
  expect_labels_then_added(b->GetOutput(), mesh.num_vertices(), expected.detection.labels);
}

// An option of cross-slice smoothing, set with another method (Taubin): an error naming it, no output.
void expect_cross_slice_only(const Mesh& mesh, const std::function<void(vtkContourFeatureSmoothingFilter*)>& option) {
  vtkNew<vtkContourFeatureSmoothingFilter> taubin;
  taubin->SetInputData(to_polydata(mesh));
  taubin->SetMethodToTaubin();
  option(taubin.GetPointer());
  vtkNew<MessageObserver> messages;
  observe_messages(taubin, messages);
  taubin->Update();
  EXPECT_NE(messages->errors.find("needs cross-slice smoothing"), std::string::npos) << messages->errors;
  EXPECT_EQ(taubin->GetOutput()->GetNumberOfPoints(), 0);
}

// Crease restoration: the filter's refined mesh is the library's, point for point, with the input's
// labels first and -1 on the points it adds; another method refuses it.
TEST_F(VtkFilters, CreaseRestorationGivesTheLibrarysRefinedMesh) {
  const Mesh mesh = ridge_stack();
  CrossSliceOptions options;
  options.crease_restoration = CreaseRestoration::Subdivide;
  const CrossSliceResult expected = cross_slice_smooth(mesh, options);
  ASSERT_GT(expected.mesh.num_vertices(), mesh.num_vertices()) << "the ridge is restored on a refined mesh";

  vtkNew<vtkContourFeatureSmoothingFilter> filter;
  filter->SetInputData(to_polydata(mesh));
  filter->SetCreaseRestorationToSubdivide();
  filter->GenerateLabelsOn();
  filter->Update();
  const Mesh out = from_polydata(filter->GetOutput());
  EXPECT_EQ(max_difference(out.positions, expected.mesh.positions), 0.0);
  EXPECT_EQ(out.triangles, expected.mesh.triangles);
  EXPECT_EQ(out.slice_ids, expected.mesh.slice_ids);
  expect_labels_then_added(filter->GetOutput(), mesh.num_vertices(), expected.labels);

  expect_cross_slice_only(mesh, [](vtkContourFeatureSmoothingFilter* f) { f->SetCreaseRestorationToSubdivide(); });
}

// Keeping the off-slice volume: the filter's result is the library's, which differs from the default's
// here (or the case would prove nothing); another method refuses it.
TEST_F(VtkFilters, OffSliceVolumePreserveGivesTheLibrarysResult) {
  // A thin stack capped half a spacing beyond its end slices: the caps are vertices between the slices.
  Mesh mesh = make_contour_stack(ContourStackSpec{ridge_circle_curve(2.0, 1.0, 0.6), 6, 24});
  add_noise(mesh, {0.1, 5, NoiseDirection::InPlane});
  CrossSliceOptions options;
  options.off_slice.volume = OffSliceVolume::Preserve;
  const CrossSliceResult expected = cross_slice_smooth(mesh, options);
  ASSERT_GT(max_difference(expected.mesh.positions, cross_slice_smooth(mesh).mesh.positions), 0.0);

  vtkNew<vtkContourFeatureSmoothingFilter> filter;
  filter->SetInputData(to_polydata(mesh));
  filter->SetOffSliceVolumeToPreserve();
  filter->Update();
  EXPECT_EQ(max_difference(from_polydata(filter->GetOutput()).positions, expected.mesh.positions), 0.0);

  expect_cross_slice_only(mesh, [](vtkContourFeatureSmoothingFilter* f) { f->SetOffSliceVolumeToPreserve(); });
}

// Every option reaches the library: for each, a non-default value that changes the library's result on
// this mesh (checked, or the case would prove nothing) gives that result through the filter.
TEST_F(VtkFilters, NonDefaultSmoothingOptionsReachTheLibrary) {
  using Filter = vtkContourFeatureSmoothingFilter;
  const Mesh mesh = ridge_stack();
  auto run_filter = [](const Mesh& input, const std::function<void(Filter*)>& configure) {
    vtkNew<Filter> filter;
    filter->SetInputData(to_polydata(input));
    configure(filter.GetPointer());
    vtkNew<MessageObserver> messages;
    observe_messages(filter, messages);
    filter->Update();
    EXPECT_EQ(messages->errors, "");
    return from_polydata(filter->GetOutput()).positions;
  };
  auto check = [&](const char* name, const Eigen::Matrix3Xd& expected, const Eigen::Matrix3Xd& reference,
                   const std::function<void(Filter*)>& configure, const Mesh& input) {
    SCOPED_TRACE(name);
    EXPECT_GT(max_difference(expected, reference), 0.0) << "the option changes nothing here";
    EXPECT_EQ(max_difference(run_filter(input, configure), expected), 0.0);
  };

  // The paper's method, one option at a time against the defaults.
  const Eigen::Matrix3Xd paper_default = feature_preserving_smooth(mesh).mesh.positions;
  auto paper = [&](const char* name, const std::function<void(FeatureSmoothingOptions&)>& library,
                   const std::function<void(Filter*)>& configure) {
    FeatureSmoothingOptions o;
    library(o);
    check(name, feature_preserving_smooth(mesh, o).mesh.positions, paper_default,
          [&](Filter* f) {
            f->SetMethodToPaper();
            configure(f);
          },
          mesh);
  };
  paper("gamma", [](auto& o) { o.detection.gamma = 0.3; }, [](Filter* f) { f->SetGamma(0.3); });
  paper("gamma factor", [](auto& o) { o.detection.gamma_factor = 1.5; }, [](Filter* f) { f->SetGammaFactor(1.5); });
  paper("delta", [](auto& o) { o.detection.delta = 0.01; }, [](Filter* f) { f->SetDelta(0.01); });
  paper("delta factor", [](auto& o) { o.detection.delta_factor = 0.1; }, [](Filter* f) { f->SetDeltaFactor(0.1); });
  paper("measure", [](auto& o) { o.detection.measure = UmbrellaMeasure::NormalComponent; },
        [](Filter* f) { f->SetUmbrellaMeasureToNormalComponent(); });
  paper("window", [](auto& o) { o.detection.window = 9; }, [](Filter* f) { f->SetWindow(9); });
  paper("in-slice features", [](auto& o) { o.detection.in_slice = InSliceFeatures::AlongFeatureLine; },
        [](Filter* f) { f->SetInSliceFeaturesToAlongLine(); });
  paper("corner spread", [](auto& o) { o.detection.corner_spread = 0.0; }, [](Filter* f) { f->SetCornerSpread(0.0); });
  paper("prefilter", [](auto& o) { o.detection.prefilter_iterations = 2; },
        [](Filter* f) { f->SetPrefilterIterations(2); });
  paper("umbilic tolerance", [](auto& o) { o.detection.curvature.umbilic_tolerance = 3.0; },
        [](Filter* f) { f->SetUmbilicTolerance(3.0); });
  paper("min reciprocal condition", [](auto& o) { o.detection.curvature.min_reciprocal_condition = 0.5; },
        [](Filter* f) { f->SetMinReciprocalCondition(0.5); });
  paper("max levels", [](auto& o) { o.max_levels = 1; }, [](Filter* f) { f->SetMaxLevels(1); });
  paper("diffusion", [](auto& o) { o.diffusion = SmoothingMethod::Laplacian; },
        [](Filter* f) { f->SetDiffusionMethodToLaplacian(); });
  paper("iterations", [](auto& o) { o.iterations = 12; }, [](Filter* f) { f->SetNumberOfIterations(12); });
  paper("lambda", [](auto& o) { o.lambda = 0.4; }, [](Filter* f) { f->SetLambda(0.4); });
  paper("mu", [](auto& o) { o.mu = -0.7; }, [](Filter* f) { f->SetMu(-0.7); });
  paper("curvature-only", [](auto& o) { o.detection.mode = DetectionMode::CurvatureOnly; },
        [](Filter* f) { f->SetDetectionModeToCurvatureOnly(); });
  {
    FeatureSmoothingOptions base, o;
    base.detection.mode = o.detection.mode = DetectionMode::CurvatureOnly;
    o.detection.anisotropy = 1.5;
    check("anisotropy", feature_preserving_smooth(mesh, o).mesh.positions,
          feature_preserving_smooth(mesh, base).mesh.positions,
          [](Filter* f) {
            f->SetMethodToPaper();
            f->SetDetectionModeToCurvatureOnly();
            f->SetAnisotropy(1.5);
          },
          mesh);
  }

  // The baselines, against the input (the method) or the method with its defaults (the option).
  auto baseline = [&](const char* name, const SmoothingOptions& o, const SmoothingOptions& base,
                      const std::function<void(Filter*)>& configure, const Mesh& input) {
    check(name, smooth(input, o), smooth(input, base), configure, input);
  };
  SmoothingOptions none;
  none.method = SmoothingMethod::None;
  SmoothingOptions laplacian;
  laplacian.method = SmoothingMethod::Laplacian;
  baseline("laplacian", laplacian, none, [](Filter* f) { f->SetMethodToLaplacian(); }, mesh);
  SmoothingOptions taubin;
  baseline("taubin", taubin, none, [](Filter* f) { f->SetMethodToTaubin(); }, mesh);
  SmoothingOptions mcf;
  mcf.method = SmoothingMethod::MeanCurvatureFlow;
  baseline("mcf", mcf, none, [](Filter* f) { f->SetMethodToMeanCurvatureFlow(); }, mesh);
  SmoothingOptions mcf_absolute = mcf;
  mcf_absolute.time_step = TimeStep::Absolute;
  mcf_absolute.lambda = 0.01;
  mcf.lambda = 0.01;
  baseline("time step", mcf_absolute, mcf,
           [](Filter* f) {
             f->SetMethodToMeanCurvatureFlow();
             f->SetTimeStepModeToAbsolute();
             f->SetLambda(0.01);
           },
           mesh);
  SmoothingOptions mindist;
  mindist.method = SmoothingMethod::MinDistFlow;
  baseline("mindist", mindist, none, [](Filter* f) { f->SetMethodToMinDistFlow(); }, mesh);
  SmoothingOptions mindist_beta = mindist;
  mindist_beta.beta = 0.1;
  baseline("beta", mindist_beta, mindist,
           [](Filter* f) {
             f->SetMethodToMinDistFlow();
             f->SetBeta(0.1);
           },
           mesh);
  // Boundary policy, on the stack without its caps (an open tube).
  Mesh tube = mesh;
  std::erase_if(tube.triangles, [&](const Triangle& t) {
    return mesh.slice_ids[t[0]] == mesh.slice_ids[t[1]] && mesh.slice_ids[t[1]] == mesh.slice_ids[t[2]];
  });
  ASSERT_LT(tube.num_faces(), mesh.num_faces());
  SmoothingOptions free_boundary = laplacian;
  free_boundary.boundary = BoundaryPolicy::Free;
  baseline("boundary", free_boundary, laplacian,
           [](Filter* f) {
             f->SetMethodToLaplacian();
             f->BoundarySmoothingOn();
           },
           tube);
}

// (b) FeatureLabel equals detect_features, with the paper's method and with detection only (METHOD_NONE,
// positions unchanged), and the other input point arrays pass through.
TEST_F(VtkFilters, LabelArrayMatchesDetection) {
  const Mesh mesh = ridge_stack();
  const FeatureDetection d = detect_features(mesh, build_adjacency(mesh));
  ASSERT_GT(d.edges, 0u);
  ASSERT_GT(d.noise + d.corners, 0u) << "labels of one kind only would prove little";

  vtkSmartPointer<vtkPolyData> poly =
      to_polydata(mesh, {}, {PointScalars{"Extra", std::vector<double>(mesh.num_vertices(), 7.0)}});
  for (const int method :
       {vtkContourFeatureSmoothingFilter::METHOD_PAPER, vtkContourFeatureSmoothingFilter::METHOD_CROSS_SLICE,
        vtkContourFeatureSmoothingFilter::METHOD_NONE}) {
    const bool paper = method != vtkContourFeatureSmoothingFilter::METHOD_NONE;  // a method with its own labels
    vtkNew<vtkContourFeatureSmoothingFilter> filter;
    filter->SetInputData(poly);
    filter->GenerateLabelsOn();
    filter->SetMethod(method);
    SCOPED_TRACE(filter->GetMethodAsString());
    filter->Update();
    vtkPolyData* out = filter->GetOutput();
    const std::vector<int> labels = int_array(out, "FeatureLabel");
    // Cross-slice smoothing labels the creases of its result; the others the paper's detection.
    const std::vector<VertexLabel> want =
        method == vtkContourFeatureSmoothingFilter::METHOD_CROSS_SLICE ? cross_slice_smooth(mesh).labels : d.labels;
    ASSERT_EQ(labels.size(), want.size());
    for (std::size_t i = 0; i < labels.size(); ++i) ASSERT_EQ(labels[i], static_cast<int>(want[i])) << "vertex " << i;
    EXPECT_EQ(int_array(out, "Extra"), std::vector<int>(mesh.num_vertices(), 7));
    if (!paper) {
      EXPECT_EQ(max_difference(from_polydata(out).positions, mesh.positions), 0.0);
    }
  }
}

}  // namespace
}  // namespace contourmesh
