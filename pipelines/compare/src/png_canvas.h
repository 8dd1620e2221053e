// SPDX-License-Identifier: BSD-3-Clause
// A small RGB raster for plots written as PNG without OpenGL: anti-aliased lines, rectangles and
// FreeType text (VTK's vtkFreeTypeTools), so that plots need no display. Private to pipelines.
#pragma once

#include <vtkSmartPointer.h>

#include <array>
#include <filesystem>
#include <string>

class vtkImageData;

namespace contourmesh::detail {

using Rgb = std::array<double, 3>;  ///< components in [0, 1]

enum class Align { Start, Center, End };

class Canvas {
 public:
  /// A width x height canvas filled with `background`. Coordinates are pixels, x to the right and y
  /// up, with (0, 0) the centre of the bottom-left pixel.
  Canvas(int width, int height, Rgb background);

  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int height() const { return height_; }

  /// Blends `color` into pixel (x, y) with opacity `alpha`; pixels outside are ignored.
  void blend(int x, int y, const Rgb& color, double alpha);
  /// A line of the given width in pixels, anti-aliased.
  void line(double x0, double y0, double x1, double y1, const Rgb& color, double width = 1.0);
  /// A filled axis-aligned rectangle.
  void fill_rect(double x0, double y0, double x1, double y1, const Rgb& color);
  /// Text anchored at (x, y) with the given alignment; `vertical` rotates it by 90 degrees
  /// counter-clockwise. Returns the text's width in pixels (before rotation).
  int text(const std::string& text, double x, double y, const Rgb& color, int size, Align horizontal = Align::Start,
           Align vertical_align = Align::Start, bool bold = false, bool vertical = false);

  /// The pixels as a vtkImageData (unsigned char RGB, row 0 at the bottom).
  [[nodiscard]] vtkSmartPointer<vtkImageData> image() const;
  /// Writes a PNG atomically; throws InvalidInputError naming the file on failure.
  void write_png(const std::filesystem::path& path) const;

 private:
  int width_, height_;
  vtkSmartPointer<vtkImageData> image_;
  unsigned char* pixels_;
};

/// Writes any RGB(A) vtkImageData as a PNG atomically; throws InvalidInputError naming the file.
void write_png_atomically(vtkImageData* image, const std::filesystem::path& path);

}  // namespace contourmesh::detail
