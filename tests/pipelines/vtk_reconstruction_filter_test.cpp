// SPDX-License-Identifier: BSD-3-Clause
// vtkCtImageToContourSurfaceFilter gives exactly what reconstruct() gives, for every option; the image
// conversion keeps physical positions; image -> surface -> smoothing chains and the contourmesh CLI agree
// with the filters.
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/vtk/vtkContourFeatureSmoothingFilter.h>
#include <contourmesh/vtk/vtkCtImageToContourSurfaceFilter.h>
#include <contourmesh/vtk/vtk_convert.h>
#include <contourmesh/vtk/vtk_image_convert.h>
#include <contourmesh/reconstruct/phantom.h>
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

#include "reconstruct/partial_volume.h"

#include <vtkCommand.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSTLWriter.h>
#include <vtkSmartPointer.h>
#include <vtkTrivialProducer.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <string>

#include "cli_runner.h"
#include "vtk_filter_support.h"

namespace contourmesh {
namespace {

using namespace vtk_filter_test;

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
  // A block with a cavity that only the slice at z = 6 sees.
  const CtImage::Pointer pocket = test::pixel_volume({32, 32, 8}, {1.0, 1.0, 2.0}, [](int i, int j, int k) {
    const bool block = i >= 4 && i < 28 && j >= 4 && j < 28 && k >= 1 && k < 7;
    const bool hole = k == 3 && (i - 16) * (i - 16) + (j - 16) * (j - 16) <= 25;
    return block && !hole ? 1000.0f : 0.0f;
  });
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
  check("flat crossings", two, [](auto& o) { o.segmentation.flat_crossings = FlatCrossings::PerPixel; },
        [](Filter* f) { f->SetFlatCrossingsToPerPixel(); });
  check("single-slice contours", pocket, [](auto& o) { o.single_slice = SingleSliceContours::Drop; },
        [](Filter* f) { f->SetSingleSliceContoursToDrop(); });
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
      for (int i = 2; i <= 5; ++i)
        *static_cast<short*>(image->GetScalarPointer(i, j, k)) = static_cast<short>(100 * i + 10 * j + k);
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
  const auto run = [&dir](const std::string& args) { return test::run_cli(CONTOURMESH_CLI, args, dir); };
  const test::CliRun smoothed = run("smooth " + input.string() + " -o " + (dir / "cli.vtp").string() +
                                    " --method paper --gamma 0.3 --window 9 --max-levels 2 --iterations 25" +
                                    " --labels-out " + (dir / "labels.vtp").string());
  ASSERT_EQ(smoothed.code, 0) << smoothed.err;
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
    const test::CliRun r = run("smooth " + input.string() + " -o " + (dir / "cli_preset.vtp").string() +
                               " --preset " + preset + (xu ? " --in-slice along-line" : "") + " --labels-out " +
                               (dir / "labels_preset.vtp").string());
    ASSERT_EQ(r.code, 0) << r.err;
    vtkNew<vtkContourFeatureSmoothingFilter> f;
    f->SetInputConnection(reader->GetOutputPort());
    if (xu) {
      f->SetPresetToXu2006();
      f->SetInSliceFeaturesToAlongLine();
    }
    f->GenerateLabelsOn();
    f->Update();
    EXPECT_EQ(max_difference(from_polydata(f->GetOutput()).positions, read_mesh(dir / "cli_preset.vtp").positions),
              0.0);
    vtkNew<vtkXMLPolyDataReader> l;
    l->SetFileName((dir / "labels_preset.vtp").c_str());
    l->Update();
    EXPECT_EQ(int_array(f->GetOutput(), "FeatureLabel"), int_array(l->GetOutput(), "FeatureLabel"));
  }

  const fs::path volume = dir / "femur.mha";
  write_volume(femur().GetPointer(), volume);
  const test::CliRun reconstructed =
      run("reconstruct " + volume.string() + " -o " + (dir / "rec.vtp").string() + " --threshold 520 --keep largest");
  ASSERT_EQ(reconstructed.code, 0) << reconstructed.err;
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

}  // namespace
}  // namespace contourmesh
