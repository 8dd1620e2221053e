// SPDX-License-Identifier: BSD-3-Clause
// Private: VTK's XML PolyData reader with the checks VTK 9.1 leaves out, so that a corrupt .vtp file
// gives an error instead of a crash (found by tests/fuzz/fuzz_read_vtp.cpp, docs/robustness.md).
// VTK allocates for the points and cells a piece announces before reading any data, and trusts the
// header of compressed data: it allocates for the block count it announces, divides by the block
// size (SIGFPE when 0) and allocates each block's announced size; it sizes a cell array's connectivity
// from its last offset; it leaks when the points do not have 3 components. This reader checks those
// fields,
// read through VTK's own XML parse (attributes, offsets and data positions as VTK reads them), and
// reports a problem as a VTK error, which makes VTK stop reading.
#pragma once

#include <vtkXMLPolyDataReader.h>

#include <string>

class vtkCheckedXMLPolyDataReader : public vtkXMLPolyDataReader {
 public:
  static vtkCheckedXMLPolyDataReader* New();
  vtkTypeMacro(vtkCheckedXMLPolyDataReader, vtkXMLPolyDataReader)  // no ";": the macro ends with "public:" (-Wpedantic)

  /// Files whose pieces announce more points in total are refused (and more than 8 cells per allowed
  /// point: a surface has about 2 triangles per vertex, and each cell array entry costs memory too).
  vtkSetMacro(MaximumNumberOfPoints, vtkIdType);
  vtkGetMacro(MaximumNumberOfPoints, vtkIdType);

  /// The message of the limit that stopped the last read; empty when none did.
  const std::string& GetLimitError() const { return this->LimitError; }

 protected:
  vtkCheckedXMLPolyDataReader() = default;
  ~vtkCheckedXMLPolyDataReader() override = default;

  int ReadXMLInformation() override;
  using vtkXMLPolyDataReader::ReadPiece;
  int ReadPiece(vtkXMLDataElement* ePiece) override;
  int ReadArrayValues(vtkXMLDataElement* da, vtkIdType arrayIndex, vtkAbstractArray* array, vtkIdType startIndex,
                      vtkIdType numValues, FieldType fieldType = vtkXMLReader::OTHER) override;

 private:
  vtkCheckedXMLPolyDataReader(const vtkCheckedXMLPolyDataReader&) = delete;
  void operator=(const vtkCheckedXMLPolyDataReader&) = delete;

  // The problem with the compression header of the data `da` refers to; empty when there is none.
  std::string CheckCompressionHeader(vtkXMLDataElement* da);

  vtkIdType MaximumNumberOfPoints = VTK_ID_MAX;
  vtkIdType AnnouncedPoints = 0;
  vtkIdType AnnouncedCells = 0;
  std::string LimitError;
};
