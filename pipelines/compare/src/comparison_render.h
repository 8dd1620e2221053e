// SPDX-License-Identifier: BSD-3-Clause
// Offscreen VTK renders for the comparison report: flat-shaded meshes from one camera, and the
// paper's labels as coloured points on the surface. Private to pipelines.
#pragma once

#include <contourmesh/smooth/feature_detection.h>
#include <contourmesh/smooth/mesh.h>

#include <vtkSmartPointer.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

class vtkCamera;
class vtkRenderWindow;
class vtkRenderer;

namespace contourmesh::detail {

/// True when an X display accepts a connection (probed through libX11 loaded at run time, so that a
/// missing display is reported instead of VTK aborting the process).
[[nodiscard]] bool x_display_available(std::string* reason);

/// One offscreen render window, reused for every picture; the camera is fixed from the framing mesh
/// (looking along its shortest extent, turned 35 degrees about and 25 degrees above it, the longest
/// extent horizontal, and just far enough for every vertex of the framing mesh to be in view).
class SceneRenderer {
 public:
  /// `color_levels` per channel (2 to 256) in the PNG files.
  SceneRenderer(const Mesh& framing, int width, int height, int color_levels = 256);
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  /// The mesh flat-shaded, with `title` in the top-left corner.
  void surface(const Mesh& mesh, const std::string& title, const std::filesystem::path& png);
  /// The mesh in grey with coloured points: one colour per group (vertices with that group index; -1:
  /// none), point size per group, and a legend line per group.
  struct PointGroup {
    std::string legend;
    double color[3];
    double size;  ///< pixels
  };
  void points(const Mesh& mesh, const std::vector<int>& group_of_vertex, const std::vector<PointGroup>& groups,
              const std::string& title, const std::filesystem::path& png);

 private:
  void clear();
  void add_title(const std::string& title);
  void snapshot(const std::filesystem::path& png);

  int width_, height_, color_levels_;
  vtkSmartPointer<vtkRenderWindow> window_;
  vtkSmartPointer<vtkRenderer> renderer_;
  vtkSmartPointer<vtkCamera> camera_;
  double edge_length_ = 1.0;
};

}  // namespace contourmesh::detail
