// SPDX-License-Identifier: BSD-3-Clause
// Shared by the VTK filter tests: observers of VTK's error, warning and progress events, comparisons of
// point arrays, and the VtkFilters fixture (a noisy ridge stack, a coarse femur phantom, a scratch folder).
#pragma once

#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/reconstruct/phantom.h>
#include <contourmesh/reconstruct/volume.h>
#include <contourmesh/smooth/mesh.h>
#include <contourmesh/smooth/shapes.h>

#include <gtest/gtest.h>

#include <vtkAlgorithm.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "test_support.h"

namespace contourmesh::vtk_filter_test {

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

inline void observe_messages(vtkAlgorithm* filter, MessageObserver* observer) {
  filter->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  // vtkExecutive reports "returned failure for request" on itself.
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
}

inline double max_difference(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b) {
  if (a.cols() != b.cols()) return std::numeric_limits<double>::infinity();
  return a.cols() == 0 ? 0.0 : (a - b).cwiseAbs().maxCoeff();
}

inline std::vector<int> int_array(vtkPolyData* poly, const char* name) {
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

}  // namespace contourmesh::vtk_filter_test
