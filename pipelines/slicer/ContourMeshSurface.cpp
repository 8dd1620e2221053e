// SPDX-License-Identifier: BSD-3-Clause
// ContourMeshSurface: a 3D Slicer command-line module (Slicer Execution Model). `--xml` prints the module
// description; otherwise it is called as Slicer calls its CLI modules: flags from the description, then
// the input volume and the output model as positional arguments. Progress goes to stdout as
// <filter-progress> lines, errors to stderr as one line with exit code 2 (docs/slicer.md).
#include "slicer_progress.h"

#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/reconstruct/label_map.h>
#include <contourmesh/reconstruct/reconstruction.h>
#include <contourmesh/reconstruct/threads.h>
#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/smooth.h>

#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

namespace contourmesh::slicer {
namespace {

// The module description, generated from ContourMeshSurface.xml.in at configure time.
constexpr const char* kModuleXml =
#include "ContourMeshSurface.xml.inc"
    ;

struct Args {
  std::string input, output;
  double threshold = 300.0;
  std::string label;
  bool keep_largest = false;
  std::string method = CONTOURMESH_DEFAULT_METHOD;
  int iterations = -1;
  std::string creases = "none";
  int threads = 0;
};

// The module's methods: the ones of the command line, less those only worth comparing against.
constexpr SmoothingMethod kMethods[] = {SmoothingMethod::CrossSlice, SmoothingMethod::FeaturePreserving,
                                        SmoothingMethod::Taubin, SmoothingMethod::Laplacian, SmoothingMethod::None};

SmoothingMethod module_method(const std::string& name) {
  for (SmoothingMethod m : kMethods) {
    if (name == to_string(m)) return m;
  }
  throw InvalidInputError("--method must be cross-slice, paper, taubin, laplacian or none, got '" + name + "'");
}

// --creases: Slicer passes it whatever the method, so only "restore" needs cross-slice smoothing.
CreaseRestoration module_creases(const Args& a, SmoothingMethod method) {
  if (a.creases == "none") return CreaseRestoration::None;
  if (a.creases != "restore") throw InvalidInputError("--creases must be none or restore, got '" + a.creases + "'");
  if (method != SmoothingMethod::CrossSlice) {
    throw InvalidInputError("--creases restore needs the cross-slice method, not " + a.method);
  }
  return CreaseRestoration::Subdivide;
}

// libsmooth's one entry point, as `contourmesh run --method M [--iterations N] [--creases C]` calls it;
// --iterations is ignored by the methods without an iteration count (cross-slice, none).
Mesh smooth_mesh(const Mesh& mesh, SmoothingMethod method, const Args& a, const ProgressCallback& progress) {
  SmoothOptions o;
  if (a.iterations >= 0 && default_iterations(method) > 0) o.iterations = a.iterations;
  o.cross_slice.crease_restoration = module_creases(a, method);
  o.progress = progress;
  return smooth(mesh, method, o).mesh;
}

int run(const Args& a) {
  const SmoothingMethod method = module_method(a.method);
  (void)module_creases(a, method);  // fail before the work
  MeshWriteOptions write_options;
  (void)format_from_extension(a.output);  // fail before the work
  const ThreadLimit limit(a.threads);
  FilterProgress progress("ContourMesh Surface");
  progress.stage("read");
  ReconstructionOptions options;
  options.segmentation.threshold = a.threshold;
  options.segmentation.components = a.keep_largest ? ComponentSelection::KeepLargest : ComponentSelection::KeepAll;
  Reconstruction r;
  try {
    if (a.label.empty()) {
      const CtImage::Pointer image = read_volume(a.input);
      r = reconstruct(*image, options, progress.callback());
    } else {
      const LabelMap map = read_label_map(a.input);
      const std::vector<Label> labels = select_labels(map, a.label);
      if (labels.size() != 1) throw InvalidInputError("--label takes one label");
      r = reconstruct_label(map, labels.front(), options, progress.callback());
    }
  } catch (const LimitError& e) {
    throw LimitError(a.input + ": " + e.what());
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(a.input + ": " + e.what());
  }
  Mesh smoothed;
  try {
    smoothed = smooth_mesh(r.mesh, method, a, progress.callback());
  } catch (const InvalidInputError&) {
    rethrow_with_context(a.input);
  }
  progress.stage("write");
  write_mesh(smoothed, a.output, write_options);
  progress.finish();
  return 0;
}

}  // namespace
}  // namespace contourmesh::slicer

int main(int argc, char** argv) {
  using contourmesh::slicer::Args;
  Args args;
  bool xml = false;
  CLI::App app{"ContourMesh Surface: a 3D Slicer CLI module (CT volume or label map -> smoothed surface model)"};
  app.add_flag("--xml", xml, "Print the Slicer Execution Model description and exit");
  app.add_option("inputVolume", args.input, "CT volume or label map (.nrrd, .nii, .mha, ...)");
  app.add_option("outputModel", args.output, "Output model (.stl, .ply, .vtp, .obj); carries SPACE=LPS");
  app.add_option("--threshold", args.threshold, "Threshold in HU")->capture_default_str();
  app.add_option("--label", args.label, "A label value or segment name instead of the threshold");
  app.add_flag("--keep-largest", args.keep_largest, "Keep the largest connected piece only");
  app.add_option("--method", args.method, "cross-slice | paper | taubin | laplacian | none")->capture_default_str();
  app.add_option("--iterations", args.iterations, "Smoothing iterations; -1: the method's default")
      ->capture_default_str();
  app.add_option("--creases", args.creases, "cross-slice: none | restore (sharpen the creases the blur rounded)")
      ->capture_default_str();
  app.add_option("--threads", args.threads, "Threads; 0: every core")->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;
  }
  if (xml) {
    std::cout << contourmesh::slicer::kModuleXml;
    return 0;
  }
  if (args.input.empty() || args.output.empty()) {
    std::cerr << "ContourMeshSurface: error: an input volume and an output model are required (or --xml)\n";
    return 1;
  }
  try {
    return contourmesh::slicer::run(args);
  } catch (const contourmesh::InvalidInputError& e) {
    std::cerr << "ContourMeshSurface: error: " << e.what() << "\n";
    return 2;
  } catch (const contourmesh::CancelledError& e) {
    std::cerr << "ContourMeshSurface: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "ContourMeshSurface: internal error: " << e.what() << "\n";
    return 3;
  }
}
