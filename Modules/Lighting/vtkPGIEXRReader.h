/**
 * @class   vtkPGIEXRReader
 * @brief   Reads an OpenEXR image (R, G, B channels, any pixel type) as a
 *          vtkImageData with a 3-component float "Radiance" point array.
 *
 * VTK's rows run bottom-up, so the EXR's top row becomes the image's last row.
 * With LatLong on (default) the image must be twice as wide as high, as a
 * lat-long environment map is (see pgiEnvironmentMap.h for the mapping).
 *
 * Errors (vtkErrorMacro, no output): missing or unreadable file, no R, G
 * and B channels, non-2:1 size when LatLong is on, more pixels than
 * MaximumNumberOfPixels, memory that cannot be allocated. NaN, Inf and negative
 * texels are not radiance: they are clamped (NaN and negative to 0, +Inf to
 * ClampValue), counted in GetNumberOfClampedValues() and a field-data array
 * "ClampedValues", and reported once per file (vtkLogger, INFO: a notice
 * about the data, not a fault).
 */
#ifndef vtkPGIEXRReader_h
#define vtkPGIEXRReader_h

#include "ProxyGILightingModule.h"
#include "vtkImageAlgorithm.h"

class PROXYGILIGHTING_EXPORT vtkPGIEXRReader : public vtkImageAlgorithm
{
public:
  static vtkPGIEXRReader* New();
  vtkTypeMacro(vtkPGIEXRReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);

  /// Require a 2:1 lat-long image (default on).
  vtkSetMacro(LatLong, bool);
  vtkGetMacro(LatLong, bool);
  vtkBooleanMacro(LatLong, bool);

  /// What +Inf texels become (default 65504, the largest half float).
  vtkSetMacro(ClampValue, double);
  vtkGetMacro(ClampValue, double);

  /// The largest image read, in pixels (default 2^28: 3 GiB of float RGB, a
  /// 23170 x 11585 lat-long map). A compressed EXR can claim far more pixels
  /// than its size suggests, so the header's size is checked against this.
  vtkSetClampMacro(MaximumNumberOfPixels, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(MaximumNumberOfPixels, vtkIdType);

  /// Texel channels clamped by the last read.
  vtkGetMacro(NumberOfClampedValues, vtkIdType);

protected:
  vtkPGIEXRReader();
  ~vtkPGIEXRReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  bool LatLong = true;
  double ClampValue = 65504.0;
  vtkIdType NumberOfClampedValues = 0;
  vtkIdType MaximumNumberOfPixels = vtkIdType(1) << 28;

private:
  bool ReadHeader(int& width, int& height);

  vtkPGIEXRReader(const vtkPGIEXRReader&) = delete;
  void operator=(const vtkPGIEXRReader&) = delete;
};

#endif
