// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/vtk/vtkContourTilingAlgorithm.h"

#include <vtkVersion.h>

vtkContourTilingAlgorithm::vtkContourTilingAlgorithm() {
  this->SetContourIdArrayName("ContourId");
  this->SetContourIndexArrayName("ContourIndex");
}

vtkContourTilingAlgorithm::~vtkContourTilingAlgorithm() {
  this->SetContourIdArrayName(nullptr);
  this->SetContourIndexArrayName(nullptr);
}

bool vtkContourTilingAlgorithm::AbortRequested() {
#if VTK_MAJOR_VERSION > 9 || (VTK_MAJOR_VERSION == 9 && VTK_MINOR_VERSION >= 3)
  return this->CheckAbort();
#else
  return this->GetAbortExecute() != 0;  // vtkAlgorithm::CheckAbort arrived in VTK 9.3
#endif
}

void vtkContourTilingAlgorithm::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  auto str = [](const char* s) { return s != nullptr ? s : "(none)"; };
  os << indent << "EndCaps: " << (this->EndCaps == END_CAPS_AT_END_SLICE ? "AtEndSlice" : "HalfSpacing") << "\n";
  os << indent << "CapRefinement: " << (this->CapRefinement == CAP_REFINEMENT_EAR_CLIPPING ? "EarClipping" : "Interior")
     << "\n";
  os << indent << "MinOverlapFraction: " << this->MinOverlapFraction << "\n";
  os << indent << "FullDynamicProgrammingLimit: " << this->FullDynamicProgrammingLimit << "\n";
  os << indent << "BandFraction: " << this->BandFraction << "\n";
  os << indent << "Branching: " << (this->Branching == BRANCHING_MID_PLANE ? "MidPlane" : "Interpolated") << "\n";
  os << indent << "MaxBranchingDepth: " << this->MaxBranchingDepth << "\n";
  os << indent << "BandRefinement: " << (this->BandRefinement == BAND_REFINEMENT_NONE ? "None" : "Interpolated")
     << "\n";
  os << indent << "MaxBandSliverShare: " << this->MaxBandSliverShare << "\n";
  os << indent << "MaxBandAspect: " << this->MaxBandAspect << "\n";
  os << indent << "MaxIntermediateContours: " << this->MaxIntermediateContours << "\n";
  os << indent << "InterpolationGrid: " << this->InterpolationGrid << "\n";
  os << indent << "MinOverlapOfLarger: " << this->MinOverlapOfLarger << "\n";
  os << indent << "ContourIdArrayName: " << str(this->ContourIdArrayName) << "\n";
  os << indent << "ContourIndexArrayName: " << str(this->ContourIndexArrayName) << "\n";
}
