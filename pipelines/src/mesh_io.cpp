// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/vtk/mesh_io.h"

#include "contourmesh/vtk/atomic_file.h"
#include "contourmesh/vtk/ply_io.h"
#include "contourmesh/vtk/vtk_convert.h"

#include "mesh_readers.h"
#include "mesh_writers.h"
#include "vtkCheckedXMLPolyDataReader.h"

#include <contourmesh/smooth/errors.h>

#include <vtkAlgorithm.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringOutputWindow.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cctype>
#include <exception>
#include <fstream>
#include <iterator>
#include <sstream>

namespace contourmesh {

namespace fs = std::filesystem;

std::string_view to_string(MeshFormat format) {
  switch (format) {
    case MeshFormat::Auto: return "auto";
    case MeshFormat::StlBinary: return "stl";
    case MeshFormat::StlAscii: return "stl-ascii";
    case MeshFormat::Ply: return "ply";
    case MeshFormat::Vtp: return "vtp";
    case MeshFormat::Obj: return "obj";
  }
  return "unknown";
}

MeshFormat parse_mesh_format(std::string_view name) {
  for (MeshFormat f : {MeshFormat::Auto, MeshFormat::StlBinary, MeshFormat::StlAscii, MeshFormat::Ply, MeshFormat::Vtp,
                       MeshFormat::Obj}) {
    if (name == to_string(f)) return f;
  }
  throw InvalidInputError("unknown mesh format '" + std::string(name) + "' (expected stl, stl-ascii, ply, vtp, obj)");
}

MeshFormat format_from_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".stl") return MeshFormat::StlBinary;
  if (ext == ".ply") return MeshFormat::Ply;
  if (ext == ".vtp") return MeshFormat::Vtp;
  if (ext == ".obj") return MeshFormat::Obj;
  throw InvalidInputError(path.string() + ": unknown mesh extension '" + ext + "' (expected .stl, .ply, .vtp or .obj)");
}

bool format_keeps_contour_ids(MeshFormat format) { return format == MeshFormat::Ply || format == MeshFormat::Vtp; }

namespace {

// Routes VTK's error and warning text into a string for the lifetime of the object, so failures can
// be reported as one clear exception instead of VTK's multi-line console output.
// VTK also logs every error to stderr through vtkLogger; that is switched off meanwhile.
class CapturedVtkMessages {
 public:
  CapturedVtkMessages()
      : previous_(vtkOutputWindow::GetInstance()), previous_verbosity_(vtkLogger::GetCurrentVerbosityCutoff()) {
    vtkOutputWindow::SetInstance(window_);
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  }
  ~CapturedVtkMessages() {
    vtkLogger::SetStderrVerbosity(previous_verbosity_);
    vtkOutputWindow::SetInstance(previous_);
  }
  CapturedVtkMessages(const CapturedVtkMessages&) = delete;
  CapturedVtkMessages& operator=(const CapturedVtkMessages&) = delete;

  // The first error's message without VTK's "ERROR: In file, line" preamble; empty if none.
  [[nodiscard]] std::string first_error() const {
    std::istringstream lines(window_->GetOutput());
    std::string line;
    bool in_error = false;
    while (std::getline(lines, line)) {
      if (line.find("ERROR:") != std::string::npos) {
        in_error = true;
        continue;
      }
      if (in_error && !line.empty()) {
        const auto pos = line.find("): ");
        return printable(pos == std::string::npos ? line : line.substr(pos + 3));
      }
    }
    return {};
  }

 private:
  // VTK quotes the offending text, which may be binary: keep it printable and short.
  static std::string printable(const std::string& text) {
    std::string out;
    for (char c : text.substr(0, 160)) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
    return text.size() > 160 ? out + "..." : out;
  }

  vtkSmartPointer<vtkOutputWindow> previous_;
  vtkLogger::Verbosity previous_verbosity_;
  vtkNew<vtkStringOutputWindow> window_;
};

MeshFormat resolve(MeshFormat requested, const fs::path& path) {
  return requested == MeshFormat::Auto ? format_from_extension(path) : requested;
}

vtkSmartPointer<vtkPolyData> run_reader(vtkAlgorithm* reader, vtkPolyData* output, const fs::path& path,
                                        const CapturedVtkMessages& messages) {
  try {
    reader->Update();
  } catch (const std::exception& e) {  // VTK's containers throw on sizes from a corrupt file
    throw InvalidInputError(path.string() + ": cannot read: " + e.what() + " (corrupt file?)");
  }
  const std::string error = messages.first_error();
  if (!error.empty()) throw InvalidInputError(path.string() + ": cannot read: " + error);
  return output;
}

// The whole file, for the parsers that work on bytes.
std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InvalidInputError(path.string() + ": read error");
  return bytes;
}

// Checks every format's result: finite coordinates, indices in range, the vertex limit.
void check_read_mesh(const Mesh& mesh, const fs::path& path, const MeshReadOptions& options) {
  const Index n = mesh.num_vertices();
  if (n > options.max_vertices) {
    throw LimitError(path.string() + ": " + std::to_string(n) + " vertices, more than the limit of " +
                     std::to_string(options.max_vertices));
  }
  for (Index i = 0; i < n; ++i) {
    if (!mesh.positions.col(i).allFinite()) {
      std::ostringstream msg;
      msg << path.string() << ": vertex " << i << " has a non-finite coordinate (" << mesh.positions(0, i) << ", "
          << mesh.positions(1, i) << ", " << mesh.positions(2, i) << ")";
      throw InvalidInputError(msg.str());
    }
  }
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (Index v : mesh.triangles[f]) {
      if (v < 0 || v >= n) {
        throw InvalidInputError(path.string() + ": triangle " + std::to_string(f) + " references vertex " +
                                std::to_string(v) + " but the file has " + std::to_string(n) + " vertices");
      }
    }
  }
}

}  // namespace

Mesh read_mesh(const fs::path& path, const MeshReadOptions& options) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InvalidInputError(path.string() + ": no such file");
  if (fs::is_directory(path, ec)) throw InvalidInputError(path.string() + ": is a directory, expected a mesh file");
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw InvalidInputError(path.string() + ": cannot open for reading (permission?)");
  }
  if (fs::file_size(path, ec) == 0) throw InvalidInputError(path.string() + ": file is empty");
  const MeshFormat format = resolve(options.format, path);

  Mesh mesh;
  try {
    if (format == MeshFormat::Ply) {
      std::ifstream in(path, std::ios::binary);
      mesh = read_ply(in, options.arrays, options.max_vertices);
    } else if (format == MeshFormat::StlBinary || format == MeshFormat::StlAscii) {
      mesh = detail::read_stl(slurp(path), options.max_vertices);
    } else if (format == MeshFormat::Obj) {
      mesh = detail::read_obj(slurp(path), options.max_vertices);
    } else {
      CapturedVtkMessages messages;
      vtkNew<vtkCheckedXMLPolyDataReader> reader;  // checks what VTK's reader trusts (fuzzing found crashes)
      reader->SetFileName(path.c_str());
      reader->SetMaximumNumberOfPoints(options.max_vertices);
      vtkSmartPointer<vtkPolyData> poly;
      try {
        poly = run_reader(reader, reader->GetOutput(), path, messages);
      } catch (const InvalidInputError&) {
        if (!reader->GetLimitError().empty()) throw LimitError(reader->GetLimitError());
        throw;
      }
      if (poly->GetNumberOfPoints() > options.max_vertices) {
        throw LimitError(std::to_string(poly->GetNumberOfPoints()) + " vertices, more than the limit of " +
                         std::to_string(options.max_vertices));
      }
      mesh = from_polydata(poly, options.arrays);
    }
  } catch (const InvalidInputError&) {
    rethrow_with_context(path.string());  // keeps the type; a message that names the file stays as it is
  }
  check_read_mesh(mesh, path, options);
  if (mesh.num_faces() == 0) {
    throw InvalidInputError(path.string() + ": no triangles found (" + std::to_string(mesh.num_vertices()) +
                            " points); is it a " + std::string(to_string(format)) + " surface mesh?");
  }
  return mesh;
}

void write_mesh(const Mesh& mesh, const fs::path& path, const MeshWriteOptions& options) {
  const MeshFormat format = resolve(options.format, path);
  if (!options.point_scalars.empty() && !format_keeps_contour_ids(format)) {
    throw InvalidInputError(path.string() + ": " + std::string(to_string(format)) +
                            " cannot carry per-vertex arrays such as '" + options.point_scalars.front().name +
                            "': write .vtp or .ply");
  }
  // No format gets a non-finite coordinate: such a file could not be read back, by us or anyone.
  if (!mesh.positions.allFinite()) {
    for (Index i = 0; i < mesh.num_vertices(); ++i) {
      if (!mesh.positions.col(i).allFinite()) {
        std::ostringstream msg;
        msg << path.string() << ": cannot write: vertex " << i << " has a non-finite coordinate ("
            << mesh.positions(0, i) << ", " << mesh.positions(1, i) << ", " << mesh.positions(2, i) << ")";
        throw InvalidInputError(msg.str());
      }
    }
  }
  write_atomically(
      path,
      [&](const fs::path& tmp) {
        try {
          if (format == MeshFormat::StlBinary || format == MeshFormat::StlAscii) {
            detail::write_stl(tmp, mesh, format == MeshFormat::StlBinary);
            return;
          }
          if (format == MeshFormat::Obj) {
            detail::write_obj(tmp, mesh);
            return;
          }
        } catch (const InvalidInputError&) {
          rethrow_with_context(path.string());
        }
        if (format == MeshFormat::Ply) {
          std::ofstream out(tmp, std::ios::binary);
          if (!out) throw InvalidInputError(path.string() + ": cannot open for writing");
          write_ply(out, mesh, options.arrays, options.point_scalars);
          out.close();
          if (!out) throw InvalidInputError(path.string() + ": cannot write: write failed (disk full?)");
          return;
        }
        CapturedVtkMessages messages;
        const vtkSmartPointer<vtkPolyData> poly = to_polydata(mesh, options.arrays, options.point_scalars);
        vtkNew<vtkXMLPolyDataWriter> writer;
        writer->SetInputData(poly);
        writer->SetFileName(tmp.c_str());
        writer->SetDataModeToAppended();
        writer->SetCompressorTypeToZLib();
        const int ok = writer->Write() && writer->GetErrorCode() == 0;
        const std::string error = messages.first_error();
        if (!ok || !error.empty()) {
          throw InvalidInputError(path.string() + ": cannot write: " + (error.empty() ? "VTK writer failed" : error));
        }
      },
      options.progress);
}

}  // namespace contourmesh
