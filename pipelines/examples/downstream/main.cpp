// SPDX-License-Identifier: BSD-3-Clause
// A downstream program built against an installed ContourMesh (see CMakeLists.txt next to it): renders
// the ridge-box phantom as a noisy CT volume (libreconstruct), reconstructs a mesh with contour ids,
// smooths it with the paper's method (libsmooth), writes it as STL and reads it back (ContourMesh::vtk),
// runs the two surface filters (the CT image, and the contours it found as polylines) in VTK
// pipelines, and prints a summary. Exits 0 only if every stage produced what it should.
//
// Usage: contourmesh_downstream [OUT.stl]   (default: downstream_ridge_box.stl)
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/vtk/vtkContourPolylinesToSurfaceFilter.h>
#include <contourmesh/vtk/vtkCtImageToContourSurfaceFilter.h>
#include <contourmesh/vtk/vtk_convert.h>
#include <contourmesh/vtk/vtk_image_convert.h>
#include <contourmesh/reconstruct/phantom.h>
#include <contourmesh/reconstruct/reconstruction.h>
#include <contourmesh/smooth/feature_smoothing.h>
#include <contourmesh/smooth/metrics.h>
#include <contourmesh/smooth/topology.h>

#include <vtkCellArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <cmath>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>

namespace cm = contourmesh;

namespace {

bool check(bool ok, const std::string& what) {
  if (!ok) std::cerr << "contourmesh_downstream: FAILED: " << what << '\n';
  return ok;
}

// The contours of a stack as closed polylines in physical space, one line cell each.
vtkSmartPointer<vtkPolyData> contour_polylines(const cm::ContourStack& stack) {
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> lines;
  for (const cm::SliceContours& slice : stack.slices) {
    for (const cm::Contour& contour : slice.contours) {
      lines->InsertNextCell(static_cast<vtkIdType>(contour.points.size()));
      for (const Eigen::Vector2d& uv : contour.points) {
        const Eigen::Vector3d p = stack.to_physical(uv, slice.w);
        lines->InsertCellPoint(points->InsertNextPoint(p.x(), p.y(), p.z()));
      }
    }
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetLines(lines);
  return poly;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::filesystem::path out = argc > 1 ? argv[1] : "downstream_ridge_box.stl";

    // libreconstruct: analytic phantom -> CT volume -> mesh with per-vertex slice and contour ids.
    const cm::Phantom phantom = cm::make_phantom(cm::PhantomShape::RidgeBox);
    cm::PhantomVolumeOptions volume_options;
    volume_options.noise = 20.0;
    volume_options.blur = 0.5;
    const cm::CtImage::Pointer image = cm::render_phantom(phantom, volume_options);
    cm::ReconstructionOptions reconstruction_options;
    reconstruction_options.segmentation.threshold = 0.5 * (volume_options.bone_hu + volume_options.tissue_hu);
    const cm::Reconstruction reconstruction = cm::reconstruct(*image, reconstruction_options);

    // libsmooth: the paper's feature-preserving smoothing (default options = the paper's settings).
    const cm::FeatureSmoothingResult smoothed = cm::feature_preserving_smooth(reconstruction.mesh);

    // ContourMesh::vtk: atomic STL write, read back, and the vtkPolyData view of the result.
    cm::write_mesh(smoothed.mesh, out);
    const cm::Mesh reread = cm::read_mesh(out);
    const vtkSmartPointer<vtkPolyData> polydata = cm::to_polydata(smoothed.mesh);

    // The VTK filters: CT image -> surface, and the contours found -> surface.
    vtkNew<vtkCtImageToContourSurfaceFilter> image_surface;
    image_surface->SetInputData(cm::to_image_data(image.GetPointer(), "HU"));
    image_surface->SetThreshold(reconstruction_options.segmentation.threshold);
    image_surface->Update();
    vtkNew<vtkContourPolylinesToSurfaceFilter> polyline_surface;
    polyline_surface->SetInputData(contour_polylines(reconstruction.contours));
    polyline_surface->Update();
    const cm::Mesh from_polylines = cm::from_polydata(polyline_surface->GetOutput());

    const cm::TopologySummary topology = cm::summarize_topology(smoothed.mesh);
    const double volume = cm::enclosed_volume(smoothed.mesh);
    const double volume_error = std::abs(volume - phantom.volume) / phantom.volume;
    const cm::DistanceStats distance = cm::distance_to_surface(smoothed.mesh.positions, phantom.sdf);

    std::cout << "phantom ridge-box: " << reconstruction.report.slices << " slices, "
              << reconstruction.report.contours << " contours\n"
              << "reconstructed: " << reconstruction.mesh.num_vertices() << " vertices, "
              << reconstruction.mesh.num_faces() << " triangles\n"
              << "paper smoothing: " << smoothed.detection.edges << " edge and " << smoothed.detection.corners
              << " corner vertices, " << smoothed.subdivided_vertices << " subdivided\n"
              << "result: " << (topology.closed ? "closed" : "open") << ", "
              << (topology.manifold ? "manifold" : "non-manifold") << ", Euler characteristic "
              << topology.euler_characteristic << ", volume " << volume << " mm^3 (analytic "
              << phantom.volume << ", error " << 100.0 * volume_error << " %), mean distance to the surface "
              << distance.mean << " mm\n"
              << "wrote " << out.string() << " (" << std::filesystem::file_size(out) << " bytes, "
              << reread.num_faces() << " triangles read back, " << polydata->GetNumberOfPolys()
              << " polygons in vtkPolyData)\n"
              << "VTK filters: " << image_surface->GetOutput()->GetNumberOfPolys() << " triangles from the image, "
              << from_polylines.num_faces() << " from the contours as polylines (volume "
              << cm::enclosed_volume(from_polylines) << " mm^3)\n";

    bool ok = true;
    ok &= check(reconstruction.mesh.has_contour_ids(), "the reconstructed mesh has contour ids");
    ok &= check(topology.closed && topology.manifold, "the smoothed mesh is closed and manifold");
    ok &= check(topology.euler_characteristic == phantom.euler_characteristic,
                "Euler characteristic matches the phantom's");
    ok &= check(volume_error < 0.05, "volume within 5 % of the analytic volume");
    ok &= check(distance.mean < 0.5, "mean distance to the analytic surface below 0.5 mm");
    ok &= check(reread.num_faces() == smoothed.mesh.num_faces(), "the STL read back has every triangle");
    ok &= check(polydata->GetNumberOfPolys() == smoothed.mesh.num_faces(), "vtkPolyData has every triangle");
    ok &= check(image_surface->GetOutput()->GetNumberOfPolys() == reconstruction.mesh.num_faces(),
                "the image filter gives the reconstruction");
    const cm::TopologySummary polyline_topology = cm::summarize_topology(from_polylines);
    ok &= check(polyline_topology.closed && polyline_topology.manifold,
                "the polyline filter gives a closed manifold mesh");
    ok &= check(std::abs(cm::enclosed_volume(from_polylines) - phantom.volume) < 0.05 * phantom.volume,
                "the polyline filter's volume within 5 % of the analytic volume");
    return ok ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const std::exception& e) {
    std::cerr << "contourmesh_downstream: " << e.what() << '\n';
    return EXIT_FAILURE;
  }
}
