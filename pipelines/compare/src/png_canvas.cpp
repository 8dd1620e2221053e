// SPDX-License-Identifier: BSD-3-Clause
#include "png_canvas.h"

#include "contourmesh/vtk/atomic_file.h"

#include <contourmesh/smooth/errors.h>

#include <vtkFreeTypeTools.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkStdString.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>

namespace contourmesh::detail {

Canvas::Canvas(int width, int height, Rgb background)
    : width_(width), height_(height), image_(vtkSmartPointer<vtkImageData>::New()) {
  if (width < 1 || height < 1) throw InvalidInputError("canvas: width and height must be >= 1");
  image_->SetDimensions(width, height, 1);
  image_->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  pixels_ = static_cast<unsigned char*>(image_->GetScalarPointer());
  for (int i = 0; i < width * height; ++i) {
    for (int c = 0; c < 3; ++c) pixels_[3 * i + c] = static_cast<unsigned char>(std::lround(255.0 * background[c]));
  }
}

void Canvas::blend(int x, int y, const Rgb& color, double alpha) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_ || !(alpha > 0.0)) return;
  alpha = std::min(alpha, 1.0);
  unsigned char* p = pixels_ + 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + x);
  for (int c = 0; c < 3; ++c) {
    const double v = (1.0 - alpha) * p[c] + alpha * 255.0 * std::clamp(color[c], 0.0, 1.0);
    p[c] = static_cast<unsigned char>(std::lround(std::clamp(v, 0.0, 255.0)));
  }
}

void Canvas::line(double x0, double y0, double x1, double y1, const Rgb& color, double width) {
  // Coverage of each pixel centre from its distance to the segment: a one-pixel soft edge.
  const double half = 0.5 * width;
  const int xmin = static_cast<int>(std::floor(std::min(x0, x1) - half - 1));
  const int xmax = static_cast<int>(std::ceil(std::max(x0, x1) + half + 1));
  const int ymin = static_cast<int>(std::floor(std::min(y0, y1) - half - 1));
  const int ymax = static_cast<int>(std::ceil(std::max(y0, y1) + half + 1));
  const double dx = x1 - x0, dy = y1 - y0;
  const double len2 = dx * dx + dy * dy;
  for (int y = std::max(ymin, 0); y <= std::min(ymax, height_ - 1); ++y) {
    for (int x = std::max(xmin, 0); x <= std::min(xmax, width_ - 1); ++x) {
      double t = len2 > 0.0 ? ((x - x0) * dx + (y - y0) * dy) / len2 : 0.0;
      t = std::clamp(t, 0.0, 1.0);
      const double d = std::hypot(x - (x0 + t * dx), y - (y0 + t * dy));
      blend(x, y, color, std::clamp(half + 0.5 - d, 0.0, 1.0));
    }
  }
}

void Canvas::fill_rect(double x0, double y0, double x1, double y1, const Rgb& color) {
  const int xa = static_cast<int>(std::lround(std::min(x0, x1))), xb = static_cast<int>(std::lround(std::max(x0, x1)));
  const int ya = static_cast<int>(std::lround(std::min(y0, y1))), yb = static_cast<int>(std::lround(std::max(y0, y1)));
  for (int y = ya; y <= yb; ++y) {
    for (int x = xa; x <= xb; ++x) blend(x, y, color, 1.0);
  }
}

int Canvas::text(const std::string& text, double x, double y, const Rgb& color, int size, Align horizontal,
                 Align vertical_align, bool bold, bool vertical) {
  if (text.empty()) return 0;
  vtkNew<vtkTextProperty> property;
  property->SetFontFamilyToArial();
  property->SetFontSize(size);
  property->SetBold(bold ? 1 : 0);
  property->SetColor(color[0], color[1], color[2]);
  vtkNew<vtkImageData> glyphs;
  int dims[2] = {0, 0};
  if (!vtkFreeTypeTools::GetInstance()->RenderString(property, vtkStdString(text), 72, glyphs, dims)) return 0;
  const auto offset = [](Align a, int extent) {
    return a == Align::Start ? 0.0 : a == Align::Center ? -0.5 * extent : -static_cast<double>(extent);
  };
  // Position of the text box's bottom-left corner, in the text's own (unrotated) frame.
  const double u0 = offset(horizontal, dims[0]);
  const double v0 = offset(vertical_align, dims[1]);
  int extent[6];
  glyphs->GetExtent(extent);
  const int components = glyphs->GetNumberOfScalarComponents();
  for (int j = extent[2]; j <= extent[3]; ++j) {
    for (int i = extent[0]; i <= extent[1]; ++i) {
      const auto* p = static_cast<const unsigned char*>(glyphs->GetScalarPointer(i, j, 0));
      const double alpha = components == 4 ? p[3] / 255.0 : 1.0;
      if (alpha <= 0.0) continue;
      const Rgb c = {p[0] / 255.0, p[1] / 255.0, p[2] / 255.0};
      const double u = u0 + i - extent[0], v = v0 + j - extent[2];
      // Rotating by +90 degrees maps (u, v) to (-v, u).
      const double px = vertical ? x - v : x + u;
      const double py = vertical ? y + u : y + v;
      blend(static_cast<int>(std::lround(px)), static_cast<int>(std::lround(py)), c, alpha);
    }
  }
  return dims[0];
}

vtkSmartPointer<vtkImageData> Canvas::image() const { return image_; }

void Canvas::write_png(const std::filesystem::path& path) const { write_png_atomically(image_, path); }

void write_png_atomically(vtkImageData* image, const std::filesystem::path& path) {
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(temporary.string().c_str());
    writer->SetInputData(image);
    writer->SetCompressionLevel(9);  // renders go into the repository's docs: smallest files
    writer->Write();
    if (writer->GetErrorCode() != 0 || !std::filesystem::exists(temporary)) {
      throw InvalidInputError(path.string() + ": cannot write the PNG file");
    }
  });
}

}  // namespace contourmesh::detail
