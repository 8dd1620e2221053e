// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/vtk/vtkCtImageToContourSurfaceFilter.h"

#include "contourmesh/vtk/vtk_convert.h"
#include "contourmesh/vtk/vtk_image_convert.h"
#include "vtk_progress.h"
#include "vtk_tiling_properties.h"

#include <contourmesh/reconstruct/reconstruction.h>
#include <contourmesh/smooth/errors.h>

#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkDataSetAttributes.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <cstddef>
#include <limits>
#include <string>

vtkStandardNewMacro(vtkCtImageToContourSurfaceFilter);

vtkCtImageToContourSurfaceFilter::vtkCtImageToContourSurfaceFilter()
    : ThresholdUsed(std::numeric_limits<double>::quiet_NaN()) {
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

vtkCtImageToContourSurfaceFilter::~vtkCtImageToContourSurfaceFilter() {
}

int vtkCtImageToContourSurfaceFilter::FillInputPortInformation(int, vtkInformation* info) {
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkCtImageToContourSurfaceFilter::RequestUpdateExtent(vtkInformation*, vtkInformationVector** inputVector,
                                                        vtkInformationVector*) {
  // Tiling needs every slice: ask for the whole volume, whatever piece is requested downstream.
  vtkInformation* in = inputVector[0]->GetInformationObject(0);
  if (in != nullptr && in->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT())) {
    in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
            in->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
    in->Set(vtkStreamingDemandDrivenPipeline::EXACT_EXTENT(), 1);
  }
  return 1;
}

int vtkCtImageToContourSurfaceFilter::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                                vtkInformationVector* outputVector) {
  using namespace contourmesh;
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (output == nullptr) {
    vtkErrorMacro(<< "no output polydata");
    return 0;
  }
  output->Initialize();
  this->ThresholdUsed = std::numeric_limits<double>::quiet_NaN();
  if (input == nullptr) {
    vtkErrorMacro(<< "no input image");
    return 0;
  }
  try {
    if (this->ContourIdArrayName == nullptr || this->ContourIndexArrayName == nullptr) {
      throw InvalidInputError("ContourIdArrayName and ContourIndexArrayName must be set");
    }
    if (this->AbortRequested()) throw CancelledError("start");
    vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector);
    if (scalars == nullptr) throw InvalidInputError("the input image has no point scalars to segment");
    const CtImage::Pointer image = to_ct_image(input, scalars);
    // As read_volume checks a file: a sheared or degenerate grid, or NaN voxels, would give a wrong surface.
    check_volume_geometry(*image, "input");
    check_voxel_values(*image, "input", NonFiniteVoxels::Refuse);

    ReconstructionOptions o;
    SegmentationOptions& seg = o.segmentation;
    seg.threshold_method = this->ThresholdMethod == THRESHOLD_OTSU ? contourmesh::ThresholdMethod::Otsu
                                                                   : contourmesh::ThresholdMethod::Fixed;
    seg.threshold = this->Threshold;
    seg.smoothing = this->Denoising == DENOISING_MEDIAN                  ? ImageSmoothing::Median
                    : this->Denoising == DENOISING_CURVATURE_ANISOTROPIC ? ImageSmoothing::CurvatureAnisotropic
                                                                         : ImageSmoothing::None;
    seg.components = this->KeepLargestComponent ? ComponentSelection::KeepLargest : ComponentSelection::KeepAll;
    seg.min_region_area = this->MinRegionArea;
    seg.fill_holes = this->FillHoles != 0;
    seg.sampling = this->Sampling;
    seg.min_contour_length = this->MinContourLength;
    seg.flat_crossings = this->FlatCrossings == FLAT_CROSSINGS_PER_PIXEL ? contourmesh::FlatCrossings::PerPixel
                                                                         : contourmesh::FlatCrossings::Patches;
    o.tiling = filter_detail::tiling_options(*this);
    o.off_slice.placement = this->OffSlicePlacement == OFF_SLICE_TILED ? contourmesh::OffSlicePlacement::Tiled
                                                                       : contourmesh::OffSlicePlacement::ImageCrossing;
    o.min_component_voxels = this->MinComponentVoxels;
    o.single_slice = this->SingleSliceContours == SINGLE_SLICE_DROP ? contourmesh::SingleSliceContours::Drop
                                                                    : contourmesh::SingleSliceContours::Slab;

    filter_detail::StageProgress stages(
        this, [](vtkAlgorithm* a) { return static_cast<vtkCtImageToContourSurfaceFilter*>(a)->AbortRequested(); });
    stages.add("segment", 0.0, 0.7);
    stages.add("tile", 0.7, 0.3);
    const Reconstruction r = reconstruct(*image, o, stages.callback());
    if (this->AbortRequested()) throw CancelledError("output");
    output->ShallowCopy(
        to_polydata(r.mesh, ContourIdArrayNames{this->ContourIdArrayName, this->ContourIndexArrayName}));
    this->ThresholdUsed = r.report.threshold;
    return 1;
  } catch (const CancelledError&) {
    output->Initialize();
    vtkDebugMacro(<< "aborted: the output is empty");
    return 1;
  } catch (const std::exception& e) {
    output->Initialize();
    vtkErrorMacro(<< e.what());
    return 0;
  }
}

void vtkCtImageToContourSurfaceFilter::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ThresholdMethod: " << (this->ThresholdMethod == THRESHOLD_OTSU ? "Otsu" : "Fixed") << "\n";
  os << indent << "Threshold: " << this->Threshold << "\n";
  os << indent << "ThresholdUsed: " << this->ThresholdUsed << "\n";
  os << indent << "Denoising: "
     << (this->Denoising == DENOISING_MEDIAN                  ? "Median"
         : this->Denoising == DENOISING_CURVATURE_ANISOTROPIC ? "CurvatureAnisotropic"
                                                              : "None")
     << "\n";
  os << indent << "KeepLargestComponent: " << (this->KeepLargestComponent ? "On" : "Off") << "\n";
  os << indent << "MinRegionArea: " << this->MinRegionArea << "\n";
  os << indent << "FillHoles: " << (this->FillHoles ? "On" : "Off") << "\n";
  os << indent << "Sampling: " << this->Sampling << (this->Sampling > 0.0 ? "" : " (pixel spacing)") << "\n";
  os << indent << "MinContourLength: " << this->MinContourLength << "\n";
  os << indent << "FlatCrossings: " << (this->FlatCrossings == FLAT_CROSSINGS_PER_PIXEL ? "PerPixel" : "Patches")
     << "\n";
  os << indent << "SingleSliceContours: " << (this->SingleSliceContours == SINGLE_SLICE_DROP ? "Drop" : "Slab")
     << "\n";
  os << indent << "OffSlicePlacement: " << (this->OffSlicePlacement == OFF_SLICE_TILED ? "Tiled" : "ImageCrossing")
     << "\n";
  os << indent << "MinComponentVoxels: " << this->MinComponentVoxels << "\n";
}
