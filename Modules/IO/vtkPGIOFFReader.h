/**
 * @class   vtkPGIOFFReader
 * @brief   Reads Object File Format (OFF, COFF, NOFF) polygon meshes.
 *
 * Reads the header ("OFF", "COFF", "NOFF" or "CNOFF", or none), the counts
 * line, the vertices and the faces. Faces keep their vertex count (no
 * triangulation here; vtkTriangleFilter does that). Per-vertex colours of
 * COFF files become an unsigned-char "Colors" array, NOFF normals a "Normals"
 * array; per-face colours become a cell "Colors" array.
 *
 * The text comes from FileName, or from InputString when ReadFromInputString
 * is on (as vtkDataReader's readers do).
 *
 * Errors (vtkErrorMacro, empty output): missing file, truncated data, face
 * indices out of range, non-numeric tokens, counts the input is too short to
 * hold (refused before anything is allocated: a vertex line takes at least 6
 * bytes, a face 4), memory that cannot be allocated. Non-finite coordinates are read
 * as they are and reported once with a warning: filters downstream decide.
 */
#ifndef vtkPGIOFFReader_h
#define vtkPGIOFFReader_h

#include "ProxyGIIOModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <iosfwd>
#include <string>

class vtkPolyData;

class PROXYGIIO_EXPORT vtkPGIOFFReader : public vtkPolyDataAlgorithm
{
public:
  static vtkPGIOFFReader* New();
  vtkTypeMacro(vtkPGIOFFReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);

  ///@{
  /// Read the OFF text from InputString instead of FileName (default off).
  vtkSetMacro(ReadFromInputString, bool);
  vtkGetMacro(ReadFromInputString, bool);
  vtkBooleanMacro(ReadFromInputString, bool);
  void SetInputString(const std::string& text);
  const std::string& GetInputString() const { return this->InputString; }
  ///@}

protected:
  vtkPGIOFFReader();
  ~vtkPGIOFFReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int ReadOFF(std::istream& in, unsigned long long bytes, vtkPolyData* output);
  std::string InputName() const;

  char* FileName = nullptr;
  bool ReadFromInputString = false;
  std::string InputString;

private:
  vtkPGIOFFReader(const vtkPGIOFFReader&) = delete;
  void operator=(const vtkPGIOFFReader&) = delete;
};

#endif
