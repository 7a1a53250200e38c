/**
 * @class   vtkPGIEXRWriter
 * @brief   Writes a vtkImageData's RGB point scalars (float or double, 3 or 4
 *          components) as a 32-bit float, ZIP-compressed OpenEXR file: a
 *          lossless round trip with vtkPGIEXRReader.
 */
#ifndef vtkPGIEXRWriter_h
#define vtkPGIEXRWriter_h

#include "ProxyGILightingModule.h"
#include "vtkImageAlgorithm.h"

class PROXYGILIGHTING_EXPORT vtkPGIEXRWriter : public vtkImageAlgorithm
{
public:
  static vtkPGIEXRWriter* New();
  vtkTypeMacro(vtkPGIEXRWriter, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);

  /// Writes the input; returns false (and reports) on failure.
  bool Write();

protected:
  vtkPGIEXRWriter();
  ~vtkPGIEXRWriter() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int FillOutputPortInformation(int, vtkInformation*) override;

  char* FileName = nullptr;

private:
  vtkPGIEXRWriter(const vtkPGIEXRWriter&) = delete;
  void operator=(const vtkPGIEXRWriter&) = delete;
};

#endif
