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
 * Errors (vtkErrorMacro, empty output): missing file, truncated data, face
 * indices out of range, non-numeric tokens. Non-finite coordinates are read
 * as they are and reported once with a warning: filters downstream decide.
 */
#ifndef vtkPGIOFFReader_h
#define vtkPGIOFFReader_h

#include "ProxyGIIOModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <string>

class PROXYGIIO_EXPORT vtkPGIOFFReader : public vtkPolyDataAlgorithm
{
public:
  static vtkPGIOFFReader* New();
  vtkTypeMacro(vtkPGIOFFReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);

protected:
  vtkPGIOFFReader();
  ~vtkPGIOFFReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;

private:
  vtkPGIOFFReader(const vtkPGIOFFReader&) = delete;
  void operator=(const vtkPGIOFFReader&) = delete;
};

#endif
