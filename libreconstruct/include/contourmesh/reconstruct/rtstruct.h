// SPDX-License-Identifier: BSD-3-Clause
// DICOM RT Structure Sets (RTSTRUCT): the regions of interest (ROIs) a radiotherapy planning system
// or a clinician drew, as planar contours in patient coordinates, and their conversion into contour
// stacks for tiling. Read with GDCM. See docs/contours.md.
#pragma once

#include "contourmesh/reconstruct/planar_contours.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace contourmesh {

/// Contour Geometric Type (3006,0042) of a contour.
enum class RtContourType {
  ClosedPlanar,     ///< CLOSED_PLANAR: a closed polygon in one plane; the only type that bounds a volume
  ClosedPlanarXor,  ///< CLOSEDPLANAR_XOR: the same, nested contours combined by exclusive or (= holes)
  OpenPlanar,       ///< OPEN_PLANAR: a polyline in one plane
  OpenNonplanar,    ///< OPEN_NONPLANAR: a polyline in space
  Point,            ///< POINT: a single point (a marker)
  Unknown,          ///< missing or any other value
};

/// One contour of an ROI, as stored.
struct RtContour {
  RtContourType type = RtContourType::Unknown;
  std::string type_name;                 ///< the value in the file ("CLOSED_PLANAR")
  std::vector<Eigen::Vector3d> points;   ///< Contour Data (3006,0050): patient coordinates (LPS), mm
};

/// One region of interest: Structure Set ROI Sequence (3006,0020), with its ROI Contour Sequence
/// (3006,0039) item and RT ROI Observations (3006,0080) item.
struct RtRoi {
  int number = 0;                                ///< ROI Number (3006,0022)
  std::string name;                              ///< ROI Name (3006,0026), blanks trimmed, UTF-8
  std::optional<std::array<int, 3>> color;       ///< ROI Display Color (3006,002A), RGB 0-255
  std::string interpreted_type;                  ///< RT ROI Interpreted Type (3006,00A4): EXTERNAL, ORGAN, PTV...
  std::string generation_algorithm;              ///< ROI Generation Algorithm (3006,0036): MANUAL, AUTOMATIC...
  std::vector<RtContour> contours;               ///< in file order; contour k is "contour k + 1" in messages
  /// Set when a contour of this ROI could not be read (Contour Data that is not numbers in threes):
  /// the message, naming the ROI and the contour. roi_contour_stack throws it; other ROIs are usable.
  std::string error;

  /// "ROI 5 'Heart'", for messages.
  [[nodiscard]] std::string label() const;
  /// Contours of type CLOSED_PLANAR (or CLOSEDPLANAR_XOR).
  [[nodiscard]] std::size_t closed_contours() const;
  /// Distinct planes of the closed contours: mean coordinates along the axis of largest spread of
  /// their normals' sum, merged within `tolerance` mm (the slices `roi_contour_stack` will build).
  [[nodiscard]] std::size_t slices(double tolerance = 0.1) const;
  /// Points of all contours.
  [[nodiscard]] std::size_t points() const;
};

struct RtStructureSet {
  std::filesystem::path file;
  std::string label;                 ///< Structure Set Label (3006,0002)
  std::string name;                  ///< Structure Set Name (3006,0004), often empty
  std::string frame_of_reference;    ///< the Frame of Reference UID of the ROIs (the first one met)
  std::vector<RtRoi> rois;           ///< in Structure Set ROI Sequence order
  std::vector<std::string> warnings; ///< anomalies that did not stop the reading, one line each
};

/// True if `file` is a DICOM file of an RT Structure Set (its SOP Class UID, or Modality RTSTRUCT).
/// Reads only the header; false for anything else, unreadable files included.
[[nodiscard]] bool is_rt_structure_set(const std::filesystem::path& file);

/// Reads an RT Structure Set. Throws InvalidInputError naming the file for: an unreadable or non-DICOM
/// file, a DICOM file of another kind (naming its modality), a file with no Structure Set ROI Sequence.
/// Contour Data that is not a list of numbers in threes marks its ROI (RtRoi::error). An ROI Contour
/// item for an ROI number not declared, a Number of Contour Points that disagrees with the data, and
/// ROI numbers declared twice are warnings. Character sets: ISO_IR 100 (Latin-1) and ISO_IR 192 (UTF-8) names are
/// converted to UTF-8; other bytes above 127 are replaced by '?'.
[[nodiscard]] RtStructureSet read_rt_structure_set(const std::filesystem::path& file);

/// The ROI named `selector`: its exact name (blanks trimmed), else its name ignoring case if only one
/// matches, else its ROI number when `selector` is a number. Throws InvalidInputError listing the ROI
/// names otherwise.
[[nodiscard]] const RtRoi& find_roi(const RtStructureSet& set, const std::string& selector);

/// What `roi_contour_stack` did besides building the stack.
struct RoiStack {
  PlanarStack planar;  ///< the stack (patient coordinates: u = x, v = y, w = z for axial contours) and report
  std::size_t skipped_contours = 0;  ///< contours of other geometric types, not used
};

/// The ROI's closed planar contours as an ordered contour stack in patient coordinates (LPS), through
/// build_contour_stack (slice axis from the contours, nesting gives holes, orientation normalised,
/// slices ordered, gaps warned about). POINT, OPEN_PLANAR, OPEN_NONPLANAR and unknown contours are
/// skipped with one warning naming them. Throws InvalidInputError naming the ROI (and the contour) when
/// it has unreadable contour data, no contours, no closed planar contour, or a contour
/// build_contour_stack refuses.
[[nodiscard]] RoiStack roi_contour_stack(const RtRoi& roi, const PlanarStackOptions& options = {});

/// The distance between adjacent contour planes of the whole set (the median over the planes of every
/// ROI's closed contours): the CT slice spacing the structures were drawn on. nullopt with fewer than
/// two planes.
[[nodiscard]] std::optional<double> structure_set_slice_spacing(const RtStructureSet& set);

/// The name as a file name: letters, digits, '.', '-' and '_' kept, every other run of characters
/// (blanks, '/', non-ASCII) one '_', no leading or trailing '_' or '.'; "roi<number>" when nothing is
/// left.
[[nodiscard]] std::string roi_file_stem(const RtRoi& roi);

/// File stems for every ROI of the set, unique: a stem met twice (after case folding) gets
/// "_<ROI number>" appended.
[[nodiscard]] std::vector<std::string> roi_file_stems(const RtStructureSet& set);

[[nodiscard]] const char* to_string(RtContourType type);

}  // namespace contourmesh
