// SPDX-License-Identifier: BSD-3-Clause
// contourmesh_scan_render: side-by-side offscreen renders of meshes made from one CT volume and of the
// voxel route a 3D Slicer user takes on it (threshold, vtkDiscreteFlyingEdges3D, then
// vtkWindowedSincPolyDataFilter with Slicer's closed-surface settings), from one camera. Used by
// scripts/real_scan_renders.sh for docs/real_scans.md; needs an X display (xvfb-run -a).
//
//   contourmesh_scan_render VOLUME --threshold T --mesh a.vtp "title a" [--mesh b.vtp "title b" ...]
//       --focus x,y,z --distance D [--azimuth A] [--elevation E] [--size 1800x600] [--color-levels N] -o out.png
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/vtk/vtk_convert.h>
#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/metrics.h>

#include <CLI/CLI.hpp>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDiscreteFlyingEdges3D.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace contourmesh;

Eigen::Vector3d parse_vector(const std::string& text, const char* what) {
  std::stringstream s(text);
  Eigen::Vector3d v;
  char c1 = 0, c2 = 0;
  if (!(s >> v.x() >> c1 >> v.y() >> c2 >> v.z()) || c1 != ',' || c2 != ',') {
    throw InvalidInputError(std::string(what) + " must be x,y,z, got '" + text + "'");
  }
  return v;
}

// The voxel route in physical coordinates: voxels at or above the threshold, their discrete flying-edges
// surface, and 20 iterations of windowed sinc with passband 0.01 on normalized coordinates (3D Slicer's
// closed-surface conversion).
Mesh voxel_route(const CtImage& image, double threshold) {
  const auto size = image.GetLargestPossibleRegion().GetSize();
  const auto spacing = image.GetSpacing();
  vtkNew<vtkImageData> binary;
  // One voxel of background around the volume, so that the surface closes at its border.
  binary->SetExtent(-1, static_cast<int>(size[0]), -1, static_cast<int>(size[1]), -1, static_cast<int>(size[2]));
  binary->SetSpacing(spacing[0], spacing[1], spacing[2]);
  binary->SetOrigin(0.0, 0.0, 0.0);
  binary->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* out = static_cast<unsigned char*>(binary->GetScalarPointer());
  const int nx = static_cast<int>(size[0]) + 2, ny = static_cast<int>(size[1]) + 2;
  const float* in = image.GetBufferPointer();
  for (int k = -1; k <= static_cast<int>(size[2]); ++k) {
    for (int j = -1; j <= static_cast<int>(size[1]); ++j) {
      for (int i = -1; i <= static_cast<int>(size[0]); ++i) {
        const bool inside = i >= 0 && j >= 0 && k >= 0 && i < static_cast<int>(size[0]) &&
                            j < static_cast<int>(size[1]) && k < static_cast<int>(size[2]);
        const std::size_t src = (static_cast<std::size_t>(k) * size[1] + static_cast<std::size_t>(j)) * size[0] +
                                static_cast<std::size_t>(i);
        out[(static_cast<std::size_t>(k + 1) * ny + static_cast<std::size_t>(j + 1)) * nx +
            static_cast<std::size_t>(i + 1)] = inside && in[src] >= threshold ? 1 : 0;
      }
    }
  }
  vtkNew<vtkDiscreteFlyingEdges3D> surface;
  surface->SetInputData(binary);
  surface->SetValue(0, 1.0);
  surface->ComputeNormalsOff();
  surface->ComputeGradientsOff();
  surface->ComputeScalarsOff();
  vtkNew<vtkWindowedSincPolyDataFilter> sinc;
  sinc->SetInputConnection(surface->GetOutputPort());
  sinc->SetNumberOfIterations(20);
  sinc->SetPassBand(0.01);
  sinc->NormalizeCoordinatesOn();
  sinc->BoundarySmoothingOff();
  sinc->FeatureEdgeSmoothingOff();
  sinc->NonManifoldSmoothingOn();
  sinc->Update();
  Mesh mesh = from_polydata(sinc->GetOutput());
  Eigen::Matrix3d direction;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) direction(r, c) = image.GetDirection()(r, c);
  }
  const Eigen::Vector3d origin(image.GetOrigin()[0], image.GetOrigin()[1], image.GetOrigin()[2]);
  mesh.positions = (direction * mesh.positions).colwise() + origin;
  return mesh;
}

struct Panel {
  Mesh mesh;
  std::string title;
};

void render(const std::vector<Panel>& panels, const Eigen::Vector3d& focus, double distance, double azimuth,
            double elevation, int width, int height, const std::string& png, int color_levels) {
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(width, height);
  vtkNew<vtkCamera> camera;
  const double az = azimuth * std::numbers::pi / 180.0, el = elevation * std::numbers::pi / 180.0;
  const Eigen::Vector3d eye =
      focus + distance * Eigen::Vector3d(std::cos(el) * std::sin(az), -std::cos(el) * std::cos(az), std::sin(el));
  camera->SetFocalPoint(focus.data());
  camera->SetPosition(eye.data());
  camera->SetViewUp(0.0, 0.0, 1.0);
  camera->SetViewAngle(30.0);
  const double share = 1.0 / static_cast<double>(panels.size());
  for (std::size_t k = 0; k < panels.size(); ++k) {
    vtkNew<vtkRenderer> renderer;
    renderer->SetViewport(share * static_cast<double>(k), 0.0, share * static_cast<double>(k + 1), 1.0);
    renderer->SetBackground(1.0, 1.0, 1.0);
    renderer->SetActiveCamera(camera);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(to_polydata(panels[k].mesh));
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetInterpolationToFlat();  // every facet as tiled: nothing hides a sliver
    actor->GetProperty()->SetColor(0.89, 0.86, 0.79);
    renderer->AddActor(actor);
    vtkNew<vtkTextActor> title;
    title->SetInput(panels[k].title.c_str());
    title->GetTextProperty()->SetColor(0.1, 0.1, 0.1);
    title->GetTextProperty()->SetFontSize(std::max(12, height / 32));
    title->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
    title->SetPosition(0.03, 0.92);
    renderer->AddViewProp(title);
    window->AddRenderer(renderer);
    renderer->ResetCameraClippingRange();
  }
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->Update();
  if (color_levels < 256) {
    // Fewer levels per channel: facets of nearly the same shade merge, and the PNG shrinks.
    const int step = 256 / color_levels;
    vtkImageData* image = grab->GetOutput();
    auto* p = static_cast<unsigned char*>(image->GetScalarPointer());
    const std::size_t n = static_cast<std::size_t>(image->GetNumberOfPoints()) *
                          static_cast<std::size_t>(image->GetNumberOfScalarComponents());
    for (std::size_t i = 0; i < n; ++i)
      p[i] = static_cast<unsigned char>(std::min(255, (p[i] + step / 2) / step * step));
  }
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(png.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Side-by-side renders of meshes of a CT volume and of its voxel route (3D Slicer's chain)"};
  std::string volume, output, focus_text, size_text = "1800x600";
  double threshold = 300.0, distance = 150.0, azimuth = 30.0, elevation = 20.0;
  int color_levels = 256;
  std::vector<std::string> meshes;
  app.add_option("volume", volume, "CT volume or DICOM directory")->required();
  app.add_option("--threshold", threshold, "Threshold of the voxel route")->required();
  app.add_option("--mesh", meshes,
                 "A mesh file and its title (repeatable), rendered left to right before the voxel route")
      ->expected(2)
      ->take_all();
  app.add_option("--focus", focus_text, "Point looked at, x,y,z in mm (physical)")->required();
  app.add_option("--distance", distance, "Distance of the camera from the focus, mm")->capture_default_str();
  app.add_option("--azimuth", azimuth, "Camera direction about the slice axis, degrees (0: from -y)")
      ->capture_default_str();
  app.add_option("--elevation", elevation, "Camera elevation above the slice planes, degrees")->capture_default_str();
  app.add_option("--size", size_text, "Picture size WIDTHxHEIGHT in pixels")->capture_default_str();
  app.add_option("--color-levels", color_levels, "Levels per colour channel, 2 to 256 (32 shrinks the PNG)")
      ->check(CLI::Range(2, 256))
      ->capture_default_str();
  app.add_option("-o,--output", output, "PNG file")->required();
  CLI11_PARSE(app, argc, argv);
  try {
    int width = 0, height = 0;
    if (std::sscanf(size_text.c_str(), "%dx%d", &width, &height) != 2 || width < 100 || height < 100) {
      throw InvalidInputError("--size must be WIDTHxHEIGHT, at least 100x100, got '" + size_text + "'");
    }
    if (meshes.size() % 2 != 0) throw InvalidInputError("--mesh takes a file and a title");
    std::vector<Panel> panels;
    for (std::size_t k = 0; k < meshes.size(); k += 2) panels.push_back({read_mesh(meshes[k]), meshes[k + 1]});
    const CtImage::Pointer image = read_volume(volume);
    panels.push_back({voxel_route(*image, threshold), "voxel route: threshold, flying edges, windowed sinc"});
    render(panels, parse_vector(focus_text, "--focus"), distance, azimuth, elevation, width, height, output,
           color_levels);
  } catch (const std::exception& e) {
    std::cerr << "contourmesh_scan_render: error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
