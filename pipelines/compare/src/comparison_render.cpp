// SPDX-License-Identifier: BSD-3-Clause
#include "comparison_render.h"

#include "contourmesh/vtk/vtk_convert.h"
#include "png_canvas.h"

#include <contourmesh/smooth/errors.h>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>

#include <dlfcn.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <numeric>

namespace contourmesh::detail {

bool x_display_available(std::string* reason) {
  const auto fail = [&](const std::string& why) {
    if (reason != nullptr) *reason = why;
    return false;
  };
  const char* display = std::getenv("DISPLAY");
  if (display == nullptr || *display == '\0') {
    return fail("no X display (DISPLAY is not set): VTK 9.1 on Debian renders through X; run under `xvfb-run -a`");
  }
  void* x11 = dlopen("libX11.so.6", RTLD_LAZY | RTLD_LOCAL);
  if (x11 == nullptr) return fail("libX11.so.6 cannot be loaded, so VTK cannot render");
  using OpenDisplay = void* (*)(const char*);
  using CloseDisplay = int (*)(void*);
  const auto open = reinterpret_cast<OpenDisplay>(dlsym(x11, "XOpenDisplay"));
  const auto close = reinterpret_cast<CloseDisplay>(dlsym(x11, "XCloseDisplay"));
  bool ok = false;
  if (open != nullptr && close != nullptr) {
    if (void* d = open(nullptr)) {
      close(d);
      ok = true;
    }
  }
  dlclose(x11);
  if (!ok) return fail(std::string("the X display '") + display + "' refuses connections; run under `xvfb-run -a`");
  return true;
}

namespace {

Eigen::Matrix3Xd vertex_normals(const Mesh& mesh) {
  Eigen::Matrix3Xd n = Eigen::Matrix3Xd::Zero(3, mesh.num_vertices());
  for (const Triangle& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.positions.col(t[0]), b = mesh.positions.col(t[1]), c = mesh.positions.col(t[2]);
    const Eigen::Vector3d area_normal = (b - a).cross(c - a);  // twice the area, outward
    for (Index v : t) n.col(v) += area_normal;
  }
  for (Index i = 0; i < n.cols(); ++i) {
    const double len = n.col(i).norm();
    if (len > 0.0) n.col(i) /= len;
  }
  return n;
}

double mean_edge_length(const Mesh& mesh) {
  double sum = 0.0;
  std::size_t count = 0;
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      sum += (mesh.positions.col(t[k]) - mesh.positions.col(t[(k + 1) % 3])).norm();
      ++count;
    }
  }
  return count > 0 ? sum / static_cast<double>(count) : 1.0;
}

}  // namespace

SceneRenderer::SceneRenderer(const Mesh& framing, int width, int height, int color_levels)
    : width_(width),
      height_(height),
      color_levels_(color_levels),
      window_(vtkSmartPointer<vtkRenderWindow>::New()),
      renderer_(vtkSmartPointer<vtkRenderer>::New()),
      camera_(vtkSmartPointer<vtkCamera>::New()) {
  if (width < 16 || height < 16) throw InvalidInputError("renders must be at least 16 x 16 pixels");
  if (color_levels < 2 || color_levels > 256) throw InvalidInputError("renders need 2 to 256 colour levels");
  if (framing.num_vertices() == 0) throw InvalidInputError("nothing to render: the mesh is empty");
  window_->SetOffScreenRendering(1);
  window_->SetSize(width, height);
  window_->AddRenderer(renderer_);
  renderer_->SetBackground(1.0, 1.0, 1.0);
  window_->SetMultiSamples(8);  // FXAA renders blank through Mesa offscreen; multisampling works

  const Eigen::Vector3d lo = framing.positions.rowwise().minCoeff();
  const Eigen::Vector3d hi = framing.positions.rowwise().maxCoeff();
  const Eigen::Vector3d extent = hi - lo;
  const Eigen::Vector3d center = 0.5 * (lo + hi);
  std::array<int, 3> axes = {0, 1, 2};
  std::sort(axes.begin(), axes.end(), [&](int a, int b) { return extent[a] > extent[b]; });
  // Look along the shortest extent with the middle one up, so the longest runs across the picture.
  Eigen::Vector3d view = Eigen::Vector3d::Unit(axes[2]);
  const Eigen::Vector3d up = Eigen::Vector3d::Unit(axes[1]);
  const double distance = 3.0 * extent.norm();
  camera_->SetFocalPoint(center.data());
  const Eigen::Vector3d position = center + distance * view;
  camera_->SetPosition(position.data());
  camera_->SetViewUp(up.data());
  camera_->Azimuth(35.0);
  camera_->Elevation(25.0);
  camera_->OrthogonalizeViewUp();
  renderer_->SetActiveCamera(camera_);
  // Move the camera back until every vertex is inside the view, with a margin: a vertex nearer than
  // the focal plane by `depth` appears larger by d / (d - depth).
  Eigen::Vector3d eye, view_up;
  camera_->GetPosition(eye.data());
  camera_->GetViewUp(view_up.data());
  const Eigen::Vector3d toward_eye = (eye - center).normalized();
  const Eigen::Vector3d right = view_up.cross(toward_eye).normalized();
  const double aspect = static_cast<double>(width) / static_cast<double>(height);
  constexpr double kPi = 3.14159265358979323846;
  const double tan_half_angle = std::tan(0.5 * camera_->GetViewAngle() * kPi / 180.0);
  constexpr double kMargin = 1.15;  // room for the title
  double fit = 0.0;
  for (Index i = 0; i < framing.num_vertices(); ++i) {
    const Eigen::Vector3d rel = framing.positions.col(i) - center;
    const double half = std::max(std::abs(rel.dot(view_up)), std::abs(rel.dot(right)) / aspect);
    fit = std::max(fit, kMargin * half / tan_half_angle + rel.dot(toward_eye));
  }
  const Eigen::Vector3d fitted = center + fit * toward_eye;
  camera_->SetPosition(fitted.data());
  edge_length_ = mean_edge_length(framing);
}

SceneRenderer::~SceneRenderer() = default;

void SceneRenderer::clear() { renderer_->RemoveAllViewProps(); }

void SceneRenderer::add_title(const std::string& title) {
  vtkNew<vtkTextActor> text;
  text->SetInput(title.c_str());
  text->GetTextProperty()->SetFontSize(std::max(14, width_ / 32));
  text->GetTextProperty()->SetColor(0.1, 0.1, 0.1);
  text->GetTextProperty()->SetVerticalJustificationToTop();
  text->SetDisplayPosition(12, height_ - 10);
  renderer_->AddActor2D(text);
}

void SceneRenderer::snapshot(const std::filesystem::path& png) {
  renderer_->ResetCameraClippingRange();
  window_->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window_);
  grab->ReadFrontBufferOff();
  grab->SetInputBufferTypeToRGB();
  grab->Update();
  if (color_levels_ < 256) {
    // Fewer levels per channel: flat-shaded triangles of nearly the same shade merge, and the PNG
    // shrinks by about half at 32 levels with no visible change.
    const int step = 256 / color_levels_;
    vtkImageData* image = grab->GetOutput();
    auto* p = static_cast<unsigned char*>(image->GetScalarPointer());
    const std::size_t n = static_cast<std::size_t>(image->GetNumberOfPoints()) *
                          static_cast<std::size_t>(image->GetNumberOfScalarComponents());
    for (std::size_t i = 0; i < n; ++i)
      p[i] = static_cast<unsigned char>(std::min(255, (p[i] + step / 2) / step * step));
  }
  write_png_atomically(grab->GetOutput(), png);
}

void SceneRenderer::surface(const Mesh& mesh, const std::string& title, const std::filesystem::path& png) {
  clear();
  vtkSmartPointer<vtkPolyData> poly = to_polydata(mesh);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(poly);
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkProperty* p = actor->GetProperty();
  p->SetInterpolationToFlat();
  p->SetColor(0.93, 0.89, 0.80);
  p->SetAmbient(0.15);
  p->SetDiffuse(0.85);
  p->SetSpecular(0.15);
  p->SetSpecularPower(20.0);
  renderer_->AddActor(actor);
  add_title(title);
  snapshot(png);
}

void SceneRenderer::points(const Mesh& mesh, const std::vector<int>& group_of_vertex,
                           const std::vector<PointGroup>& groups, const std::string& title,
                           const std::filesystem::path& png) {
  clear();
  vtkSmartPointer<vtkPolyData> poly = to_polydata(mesh);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(poly);
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetInterpolationToFlat();
  actor->GetProperty()->SetColor(0.82, 0.82, 0.82);
  renderer_->AddActor(actor);

  // Each group's vertices, lifted a little along the normal so that the surface does not hide them.
  const Eigen::Matrix3Xd normals = vertex_normals(mesh);
  const double lift = 0.25 * edge_length_;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    for (Index i = 0; i < mesh.num_vertices(); ++i) {
      if (group_of_vertex[i] != static_cast<int>(g)) continue;
      const Eigen::Vector3d p = mesh.positions.col(i) + lift * normals.col(i);
      points->InsertNextPoint(p.data());
    }
    vtkNew<vtkCellArray> verts;
    for (vtkIdType k = 0; k < points->GetNumberOfPoints(); ++k) verts->InsertNextCell(1, &k);
    vtkNew<vtkPolyData> cloud;
    cloud->SetPoints(points);
    cloud->SetVerts(verts);
    vtkNew<vtkPolyDataMapper> cloud_mapper;
    cloud_mapper->SetInputData(cloud);
    vtkNew<vtkActor> cloud_actor;
    cloud_actor->SetMapper(cloud_mapper);
    cloud_actor->GetProperty()->SetColor(groups[g].color[0], groups[g].color[1], groups[g].color[2]);
    cloud_actor->GetProperty()->SetPointSize(static_cast<float>(groups[g].size));
    cloud_actor->GetProperty()->RenderPointsAsSpheresOn();
    cloud_actor->GetProperty()->LightingOff();
    renderer_->AddActor(cloud_actor);

    vtkNew<vtkTextActor> legend;
    legend->SetInput(groups[g].legend.c_str());
    legend->GetTextProperty()->SetFontSize(16);
    legend->GetTextProperty()->SetBold(1);
    legend->GetTextProperty()->SetColor(groups[g].color[0], groups[g].color[1], groups[g].color[2]);
    legend->SetDisplayPosition(12, 10 + 22 * static_cast<int>(groups.size() - 1 - g));
    renderer_->AddActor2D(legend);
  }
  add_title(title);
  snapshot(png);
}

}  // namespace contourmesh::detail
