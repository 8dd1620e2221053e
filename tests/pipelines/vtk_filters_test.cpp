// The VTK filters inside real VTK pipelines: vtkContourFeatureSmoothingFilter must give exactly what the
// libsmooth calls give, vtkCtImageToContourSurfaceFilter exactly what reconstruct() gives; aborts, errors,
// missing ids and option clamping behave as documented.
#include <pipelines/mesh_io.h>
#include <pipelines/vtkContourFeatureSmoothingFilter.h>
#include <pipelines/vtkCtImageToContourSurfaceFilter.h>
#include <pipelines/vtk_convert.h>
#include <pipelines/vtk_image_convert.h>
#include <reconstruct/phantom.h>
#include <reconstruct/reconstruction.h>
#include <reconstruct/volume.h>
#include <smooth/adjacency.h>
#include <smooth/cross_slice.h>
#include <smooth/errors.h>
#include <smooth/feature_detection.h>
#include <smooth/feature_smoothing.h>
#include <smooth/shapes.h>
#include <smooth/smooth.h>
#include <smooth/smoothing.h>
#include <smooth/topology.h>

#include <gtest/gtest.h>

#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSTLWriter.h>
#include <vtkSmartPointer.h>
#include <vtkTrivialProducer.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <string>

#include "test_support.h"

namespace contourmesh {
namespace {

namespace fs = std::filesystem;

/// Records ErrorEvent / WarningEvent messages instead of printing them.
class MessageObserver : public vtkCommand {
 public:
  static MessageObserver* New() { return new MessageObserver; }
  void Execute(vtkObject*, unsigned long event, void* data) override {
    const std::string message = data != nullptr ? static_cast<const char*>(data) : "";
    if (event == vtkCommand::ErrorEvent) errors += message + "\n";
    else warnings += message + "\n";
  }
  std::string errors;
  std::string warnings;
};

/// Watches ProgressEvent; calls AbortExecuteOn once the progress reaches `abort_at`.
class ProgressObserver : public vtkCommand {
 public:
  static ProgressObserver* New() { return new ProgressObserver; }
  void Execute(vtkObject* caller, unsigned long, void* data) override {
    const double progress = *static_cast<double*>(data);
    if (aborted) ++events_after_abort;
    ++events;
    last = progress;
    if (!aborted && progress >= abort_at) {
      static_cast<vtkAlgorithm*>(caller)->AbortExecuteOn();
      aborted = true;
    }
  }
  double abort_at = 2.0;
  bool aborted = false;
  int events = 0;
  int events_after_abort = 0;
  double last = -1.0;
};

void observe_messages(vtkAlgorithm* filter, MessageObserver* observer) {
  filter->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  // vtkExecutive reports "returned failure for request" on itself.
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
}

double max_difference(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b) {
  if (a.cols() != b.cols()) return std::numeric_limits<double>::infinity();
  return a.cols() == 0 ? 0.0 : (a - b).cwiseAbs().maxCoeff();
}

std::vector<int> int_array(vtkPolyData* poly, const char* name) {
  vtkDataArray* array = poly->GetPointData()->GetArray(name);
  if (array == nullptr) return {};
  std::vector<int> out(static_cast<std::size_t>(array->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i) out[i] = static_cast<int>(array->GetComponent(i, 0));
  return out;
}

class VtkFilters : public ::testing::Test {
 protected:
  /// A closed contour stack with a sharp ridge and in-plane noise, caps in the end slices (so that
  /// every vertex lies on a slice plane and binning recovers the ids exactly).
  static Mesh ridge_stack() {
    ContourStackSpec spec;
    spec.curve = ridge_circle_curve(10.0, 2.5, 0.4);
    spec.slices = 12;
    spec.points_per_contour = 48;
    spec.end_caps = EndCaps::AtEndSlice;
    Mesh m = make_contour_stack(spec);
    add_noise(m, {0.1, 5, NoiseDirection::InPlane});
    return m;
  }

  /// The stack written as .vtp, the start of the file-based pipelines.
  fs::path write_stack(const Mesh& m, const char* name = "stack.vtp") const {
    const fs::path path = tmp_.path() / name;
    write_mesh(m, path);
    return path;
  }

  /// A small, coarse femur phantom and its reconstruction options (the partial-volume iso-level).
  static CtImage::Pointer femur() {
    PhantomVolumeOptions vo;
    vo.spacing = {1.2, 1.2, 3.0};
    vo.margin = 3.0;
    return render_phantom(make_phantom(PhantomShape::Femur), vo);
  }
  static constexpr double kIsoLevel = 0.5 * (1000.0 + 40.0);

  test::ScopedTempDir tmp_{"contourmesh_vtk_filters"};
};

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
  const std::vector<int> labels = int_array(b->GetOutput(), "FeatureLabel");
  ASSERT_EQ(labels.size(), static_cast<std::size_t>(out.num_vertices()));
  for (Index i = 0; i < out.num_vertices(); ++i) {
    const int want = i < mesh.num_vertices() ? static_cast<int>(expected.detection.labels[i]) : -1;
    ASSERT_EQ(labels[i], want) << "vertex " << i;
  }
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

  vtkSmartPointer<vtkPolyData> poly = to_polydata(mesh, {}, {PointScalars{"Extra", std::vector<double>(mesh.num_vertices(), 7.0)}});
  for (const int method : {vtkContourFeatureSmoothingFilter::METHOD_PAPER, vtkContourFeatureSmoothingFilter::METHOD_CROSS_SLICE,
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

// (e) CT volume -> vtkImageData -> reconstruction filter: the mesh of reconstruct(), closed.
TEST_F(VtkFilters, ReconstructionFilterMatchesReconstruct) {
  const CtImage::Pointer image = femur();
  ReconstructionOptions ro;
  ro.segmentation.threshold = kIsoLevel;
  ro.segmentation.components = ComponentSelection::KeepLargest;
  ro.tiling.end_caps = EndCaps::AtEndSlice;
  const Reconstruction expected = reconstruct(*image, ro);

  vtkNew<vtkTrivialProducer> source;
  source->SetOutput(to_image_data(image.GetPointer(), "HU"));
  vtkNew<vtkCtImageToContourSurfaceFilter> filter;
  filter->SetInputConnection(source->GetOutputPort());
  filter->SetThreshold(kIsoLevel);
  filter->KeepLargestComponentOn();
  filter->SetEndCapsToAtEndSlice();
  vtkNew<MessageObserver> messages;
  observe_messages(filter, messages);
  vtkNew<ProgressObserver> progress;
  filter->AddObserver(vtkCommand::ProgressEvent, progress);
  filter->Update();
  EXPECT_EQ(messages->errors, "");
  EXPECT_EQ(progress->last, 1.0);
  EXPECT_EQ(filter->GetThresholdUsed(), kIsoLevel);

  const Mesh out = from_polydata(filter->GetOutput());
  ASSERT_GT(out.num_vertices(), 100);
  EXPECT_EQ(max_difference(out.positions, expected.mesh.positions), 0.0);
  EXPECT_EQ(out.triangles, expected.mesh.triangles);
  EXPECT_EQ(out.slice_ids, expected.mesh.slice_ids);
  EXPECT_EQ(out.contour_ids, expected.mesh.contour_ids);
  const TopologySummary topology = summarize_topology(out);
  EXPECT_TRUE(topology.closed);
  EXPECT_TRUE(topology.manifold) << topology.first_problems;

  // Every option at its default is the library's default.
  vtkNew<vtkCtImageToContourSurfaceFilter> defaults;
  defaults->SetInputConnection(source->GetOutputPort());
  defaults->Update();
  const Mesh d = from_polydata(defaults->GetOutput());
  const Reconstruction library_default = reconstruct(*image);
  EXPECT_EQ(max_difference(d.positions, library_default.mesh.positions), 0.0);
  EXPECT_EQ(d.triangles, library_default.mesh.triangles);

  // Otsu reports the threshold it chose.
  filter->SetThresholdMethodToOtsu();
  filter->Update();
  EXPECT_EQ(messages->errors, "");
  EXPECT_GT(filter->GetThresholdUsed(), 40.0);
  EXPECT_LT(filter->GetThresholdUsed(), 1000.0);

  // A threshold above the data: an error naming it, an empty output.
  filter->SetThresholdMethodToFixed();
  filter->SetThreshold(5000.0);
  filter->Update();
  EXPECT_NE(messages->errors.find("threshold 5000"), std::string::npos) << messages->errors;
  EXPECT_TRUE(std::isnan(filter->GetThresholdUsed()));
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
}

// Same for the reconstruction options, on a noisy cavity phantom (specks, holes) segmented low, on two
// objects side by side, and on the tilted pelvis ring (contours shift between slices).
TEST_F(VtkFilters, NonDefaultReconstructionOptionsReachTheLibrary) {
  using Filter = vtkCtImageToContourSurfaceFilter;
  PhantomVolumeOptions vo;
  vo.spacing = {1.2, 1.2, 3.0};
  vo.margin = 3.0;
  const CtImage::Pointer two = render_phantom(make_phantom(PhantomShape::TwoObjects), vo);
  const CtImage::Pointer pelvis = render_phantom(make_phantom(PhantomShape::Pelvis), vo);
  vo.noise = 160.0;
  const CtImage::Pointer cavity = render_phantom(make_phantom(PhantomShape::Cavity), vo);
  ReconstructionOptions base;  // keep the specks, so that the options that drop them matter
  base.segmentation.threshold = 350.0;
  base.segmentation.min_region_area = 0.0;
  base.segmentation.min_contour_length = 0.0;

  // `plain`: both the reference and the checked run tile every band by the minimum-area programme alone
  // (BandRefinement::None), for the options of that programme.
  std::map<std::pair<const CtImage*, bool>, Mesh> references;
  auto check = [&](const char* name, const CtImage::Pointer& image,
                   const std::function<void(ReconstructionOptions&)>& library,
                   const std::function<void(Filter*)>& configure, bool plain = false) {
    SCOPED_TRACE(name);
    ReconstructionOptions start = base;
    if (plain) start.tiling.band_refinement = BandRefinement::None;
    auto [cached, missing] = references.try_emplace(std::pair{image.GetPointer(), plain});
    if (missing) cached->second = reconstruct(*image, start).mesh;
    const Mesh& reference = cached->second;
    ReconstructionOptions o = start;
    library(o);
    const Mesh expected = reconstruct(*image, o).mesh;
    EXPECT_TRUE(expected.num_vertices() != reference.num_vertices() ||
                max_difference(expected.positions, reference.positions) > 0.0 ||
                expected.triangles != reference.triangles)
        << "the option changes nothing here";
    vtkNew<Filter> filter;
    filter->SetInputData(to_image_data(image.GetPointer()));
    filter->SetThreshold(350.0);
    filter->SetMinRegionArea(0.0);
    filter->SetMinContourLength(0.0);
    if (plain) filter->SetBandRefinementToNone();
    configure(filter.GetPointer());
    vtkNew<MessageObserver> messages;
    observe_messages(filter, messages);
    filter->Update();
    EXPECT_EQ(messages->errors, "");
    const Mesh out = from_polydata(filter->GetOutput());
    EXPECT_EQ(max_difference(out.positions, expected.positions), 0.0);
    EXPECT_EQ(out.triangles, expected.triangles);
    EXPECT_EQ(out.contour_ids, expected.contour_ids);
  };
  check("threshold", cavity, [](auto& o) { o.segmentation.threshold = 600.0; },
        [](Filter* f) { f->SetThreshold(600.0); });
  check("otsu", cavity, [](auto& o) { o.segmentation.threshold_method = ThresholdMethod::Otsu; },
        [](Filter* f) { f->SetThresholdMethodToOtsu(); });
  check("median", cavity, [](auto& o) { o.segmentation.smoothing = ImageSmoothing::Median; },
        [](Filter* f) { f->SetDenoisingToMedian(); });
  check("anisotropic", cavity, [](auto& o) { o.segmentation.smoothing = ImageSmoothing::CurvatureAnisotropic; },
        [](Filter* f) { f->SetDenoisingToCurvatureAnisotropic(); });
  check("keep largest", two, [](auto& o) { o.segmentation.components = ComponentSelection::KeepLargest; },
        [](Filter* f) { f->KeepLargestComponentOn(); });
  check("min region area", cavity, [](auto& o) { o.segmentation.min_region_area = 12.0; },
        [](Filter* f) { f->SetMinRegionArea(12.0); });
  check("fill holes", cavity, [](auto& o) { o.segmentation.fill_holes = true; },
        [](Filter* f) { f->FillHolesOn(); });
  check("sampling", cavity, [](auto& o) { o.segmentation.sampling = 2.0; }, [](Filter* f) { f->SetSampling(2.0); });
  check("min contour length", cavity, [](auto& o) { o.segmentation.min_contour_length = 15.0; },
        [](Filter* f) { f->SetMinContourLength(15.0); });
  check("end caps", cavity, [](auto& o) { o.tiling.end_caps = EndCaps::AtEndSlice; },
        [](Filter* f) { f->SetEndCapsToAtEndSlice(); });
  check("cap refinement", cavity, [](auto& o) { o.tiling.cap_refinement = CapRefinement::EarClipping; },
        [](Filter* f) { f->SetCapRefinementToEarClipping(); });
  check("off-slice placement", cavity, [](auto& o) { o.off_slice.placement = OffSlicePlacement::Tiled; },
        [](Filter* f) { f->SetOffSlicePlacementToTiled(); });
  check("min overlap", pelvis, [](auto& o) { o.tiling.min_overlap_fraction = 0.9; },
        [](Filter* f) { f->SetMinOverlapFraction(0.9); });
  // The narrowest corridor (8 points either side of the arc-length diagonal) holds the optimum of every
  // band of the cavity; the pelvis's contours shift between slices, and some of its optima lie outside.
  check("band", pelvis,
        [](auto& o) {
          o.tiling.full_dp_limit = 0;
          o.tiling.band_fraction = 0.0;
        },
        [](Filter* f) {
          f->SetFullDynamicProgrammingLimit(0);
          f->SetBandFraction(0.0);
        },
        true);
  check("min overlap of larger", cavity, [](auto& o) { o.tiling.min_overlap_of_larger = 0.0; },
        [](Filter* f) { f->SetMinOverlapOfLarger(0.0); });
  check("mid-plane branching", cavity, [](auto& o) { o.tiling.branching = Branching::MidPlaneComposite; },
        [](Filter* f) { f->SetBranchingToMidPlane(); });
  check("max branching depth", cavity, [](auto& o) { o.tiling.max_branching_depth = 0; },
        [](Filter* f) { f->SetMaxBranchingDepth(0); });
  check("no band refinement", cavity, [](auto& o) { o.tiling.band_refinement = BandRefinement::None; },
        [](Filter* f) { f->SetBandRefinementToNone(); });
  check("max band sliver share", cavity, [](auto& o) { o.tiling.max_band_sliver_share = 0.2; },
        [](Filter* f) { f->SetMaxBandSliverShare(0.2); });
  check("max band aspect", cavity, [](auto& o) { o.tiling.max_band_aspect = 1.0; },
        [](Filter* f) { f->SetMaxBandAspect(1.0); });
  check("max intermediate contours", cavity, [](auto& o) { o.tiling.max_intermediate_contours = 1; },
        [](Filter* f) { f->SetMaxIntermediateContours(1); });
  check("interpolation grid", cavity, [](auto& o) { o.tiling.interpolation_grid = 1.0; },
        [](Filter* f) { f->SetInterpolationGrid(1.0); });
  check("min component voxels", cavity, [](auto& o) { o.min_component_voxels = 0.0; },
        [](Filter* f) { f->SetMinComponentVoxels(0.0); });

  // Other array names.
  vtkNew<Filter> named;
  named->SetInputData(to_image_data(two.GetPointer()));
  named->SetThreshold(350.0);
  named->SetContourIdArrayName("Slice");
  named->SetContourIndexArrayName("Contour");
  named->Update();
  ReconstructionOptions defaults;
  defaults.segmentation.threshold = 350.0;
  const Mesh expected = reconstruct(*two, defaults).mesh;
  const Mesh out = from_polydata(named->GetOutput(), {"Slice", "Contour"});
  EXPECT_EQ(out.slice_ids, expected.slice_ids);
  EXPECT_EQ(out.contour_ids, expected.contour_ids);
  EXPECT_NE(*std::max_element(out.contour_ids.begin(), out.contour_ids.end()), 0) << "two contours per slice";
}

// to_ct_image keeps every voxel's physical position and value for an extent that does not start at 0,
// a rotated direction matrix, a negative spacing and a non-float scalar type.
TEST_F(VtkFilters, ImageConversionKeepsPhysicalPositions) {
  vtkNew<vtkImageData> image;
  image->SetExtent(2, 5, -1, 1, 3, 4);
  image->SetSpacing(0.5, -0.75, 2.0);
  image->SetOrigin(10.0, -20.0, 30.0);
  image->SetDirectionMatrix(0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0);
  image->AllocateScalars(VTK_SHORT, 1);
  for (int k = 3; k <= 4; ++k) {
    for (int j = -1; j <= 1; ++j) {
      for (int i = 2; i <= 5; ++i) *static_cast<short*>(image->GetScalarPointer(i, j, k)) = static_cast<short>(100 * i + 10 * j + k);
    }
  }
  const CtImage::Pointer ct = to_ct_image(image);
  const auto size = ct->GetLargestPossibleRegion().GetSize();
  EXPECT_EQ(size[0], 4u);
  EXPECT_EQ(size[1], 3u);
  EXPECT_EQ(size[2], 2u);
  for (int k = 3; k <= 4; ++k) {
    for (int j = -1; j <= 1; ++j) {
      for (int i = 2; i <= 5; ++i) {
        double vtk_point[3];
        image->TransformIndexToPhysicalPoint(i, j, k, vtk_point);
        const CtImage::IndexType index = {{i - 2, j + 1, k - 3}};
        CtImage::PointType itk_point;
        ct->TransformIndexToPhysicalPoint(index, itk_point);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(itk_point[c], vtk_point[c], 1e-12);
        EXPECT_EQ(ct->GetPixel(index), static_cast<float>(100 * i + 10 * j + k));
      }
    }
  }
  // And back: same values, positions and direction.
  vtkSmartPointer<vtkImageData> back = to_image_data(ct.GetPointer());
  double first[3];
  back->TransformIndexToPhysicalPoint(1, 2, 1, first);
  double original[3];
  image->TransformIndexToPhysicalPoint(3, 1, 4, original);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(first[c], original[c], 1e-12);
  EXPECT_EQ(back->GetScalarComponentAsDouble(1, 2, 1, 0), 100 * 3 + 10 * 1 + 4);

  vtkNew<vtkImageData> no_scalars;
  no_scalars->SetDimensions(2, 2, 2);
  EXPECT_THROW((void)to_ct_image(no_scalars), InvalidInputError);
}

// (f) image -> surface -> smoothing -> vtkSTLWriter, end to end; the smoothed surface is the library's.
TEST_F(VtkFilters, ImageToSurfaceToSmoothingToStlChain) {
  const CtImage::Pointer image = femur();
  ReconstructionOptions ro;
  ro.segmentation.threshold = kIsoLevel;
  const Mesh expected = cross_slice_smooth(reconstruct(*image, ro).mesh).mesh;  // the default preset

  vtkNew<vtkTrivialProducer> source;
  source->SetOutput(to_image_data(image.GetPointer()));
  vtkNew<vtkCtImageToContourSurfaceFilter> surface;
  surface->SetInputConnection(source->GetOutputPort());
  surface->SetThreshold(kIsoLevel);
  vtkNew<vtkContourFeatureSmoothingFilter> smoothing;
  smoothing->SetInputConnection(surface->GetOutputPort());
  smoothing->GenerateLabelsOn();
  vtkNew<MessageObserver> messages;
  observe_messages(surface, messages);
  observe_messages(smoothing, messages);
  const fs::path stl = tmp_.path() / "femur.stl";
  vtkNew<vtkSTLWriter> writer;
  writer->SetInputConnection(smoothing->GetOutputPort());
  writer->SetFileName(stl.c_str());
  writer->SetFileTypeToBinary();
  ASSERT_EQ(writer->Write(), 1);
  EXPECT_EQ(messages->errors, "");

  const Mesh out = from_polydata(smoothing->GetOutput());
  EXPECT_EQ(max_difference(out.positions, expected.positions), 0.0);
  EXPECT_EQ(out.triangles, expected.triangles);
  ASSERT_TRUE(fs::exists(stl));
  const Mesh from_stl = read_mesh(stl);
  EXPECT_EQ(from_stl.num_faces(), expected.num_faces());
  EXPECT_TRUE(summarize_topology(from_stl).closed);
}

// The filters and the contourmesh CLI agree: `smooth --method paper` with options and `reconstruct`.
TEST_F(VtkFilters, SameResultAsTheCli) {
  const fs::path dir = tmp_.path();
  const fs::path input = write_stack(ridge_stack());
  const std::string quiet = " > " + (dir / "out.txt").string() + " 2>&1";
  const std::string smooth_cmd = std::string(CONTOURMESH_CLI) + " smooth " + input.string() + " -o " +
                                 (dir / "cli.vtp").string() +
                                 " --method paper --gamma 0.3 --window 9 --max-levels 2 --iterations 25" +
                                 " --labels-out " + (dir / "labels.vtp").string() + quiet;
  ASSERT_EQ(std::system(smooth_cmd.c_str()), 0) << smooth_cmd;
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(input.c_str());
  vtkNew<vtkContourFeatureSmoothingFilter> filter;
  filter->SetInputConnection(reader->GetOutputPort());
  filter->SetMethodToPaper();
  filter->SetGamma(0.3);
  filter->SetWindow(9);
  filter->SetMaxLevels(2);
  filter->SetNumberOfIterations(25);
  filter->GenerateLabelsOn();
  filter->Update();
  EXPECT_EQ(max_difference(from_polydata(filter->GetOutput()).positions, read_mesh(dir / "cli.vtp").positions), 0.0);
  vtkNew<vtkXMLPolyDataReader> labels;
  labels->SetFileName((dir / "labels.vtp").c_str());
  labels->Update();
  EXPECT_EQ(int_array(filter->GetOutput(), "FeatureLabel"), int_array(labels->GetOutput(), "FeatureLabel"));

  // The defaults agree (cross-slice smoothing), and so do the presets with an option on top.
  for (const std::string preset : {"default", "xu2006"}) {
    SCOPED_TRACE(preset);
    const bool xu = preset == "xu2006";
    const std::string cmd = std::string(CONTOURMESH_CLI) + " smooth " + input.string() + " -o " +
                            (dir / "cli_preset.vtp").string() + " --preset " + preset +
                            (xu ? " --in-slice along-line" : "") + " --labels-out " +
                            (dir / "labels_preset.vtp").string() + quiet;
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    vtkNew<vtkContourFeatureSmoothingFilter> f;
    f->SetInputConnection(reader->GetOutputPort());
    if (xu) {
      f->SetPresetToXu2006();
      f->SetInSliceFeaturesToAlongLine();
    }
    f->GenerateLabelsOn();
    f->Update();
    EXPECT_EQ(max_difference(from_polydata(f->GetOutput()).positions, read_mesh(dir / "cli_preset.vtp").positions), 0.0);
    vtkNew<vtkXMLPolyDataReader> l;
    l->SetFileName((dir / "labels_preset.vtp").c_str());
    l->Update();
    EXPECT_EQ(int_array(f->GetOutput(), "FeatureLabel"), int_array(l->GetOutput(), "FeatureLabel"));
  }

  const fs::path volume = dir / "femur.mha";
  write_volume(femur().GetPointer(), volume);
  const std::string reconstruct_cmd = std::string(CONTOURMESH_CLI) + " reconstruct " + volume.string() + " -o " +
                                      (dir / "rec.vtp").string() + " --threshold 520 --keep largest" + quiet;
  ASSERT_EQ(std::system(reconstruct_cmd.c_str()), 0) << reconstruct_cmd;
  vtkNew<vtkCtImageToContourSurfaceFilter> surface;
  surface->SetInputData(to_image_data(read_volume(volume).GetPointer()));
  surface->SetThreshold(520.0);
  surface->KeepLargestComponentOn();
  surface->Update();
  const Mesh cli = read_mesh(dir / "rec.vtp");
  const Mesh out = from_polydata(surface->GetOutput());
  EXPECT_EQ(max_difference(out.positions, cli.positions), 0.0);
  EXPECT_EQ(out.triangles, cli.triangles);
  EXPECT_EQ(out.slice_ids, cli.slice_ids);
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
  for (const char* option :
       {"Preset: Default", "Method: None", "NumberOfIterations: -1 (automatic)", "Lambda", "Mu", "Beta", "BoundarySmoothing",
        "TimeStepMode", "DetectionMode", "Anisotropy", "Gamma: -1 (automatic)", "GammaFactor", "UmbrellaMeasure",
        "Delta", "DeltaFactor", "Window: 5", "CornerSpread", "InSliceFeatures: Noise", "PrefilterIterations", "UmbilicTolerance", "MinReciprocalCondition",
        "MaxLevels", "DiffusionMethod: Laplacian", "KeepAdaptiveMesh", "GenerateLabels", "SliceAxis: Z",
        "SliceTolerance", "ContourIdArrayName: ContourId", "ContourIndexArrayName: ContourIndex", "LockedArrayName"}) {
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
