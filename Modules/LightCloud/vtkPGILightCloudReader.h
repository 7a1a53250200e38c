/**
 * @class   vtkPGILightCloudReader
 * @brief   Reads a light cloud file (pgiLightCloudFile: what
 *          vtkPGILightCloudPrecompute writes as its cache) into a pipeline.
 *
 * Errors: no file name, a missing, foreign, corrupted or unfinished file
 * (a cloud some of whose lights are not in it is refused: finish it by
 * running the precompute with the file as its cache).
 */
#ifndef vtkPGILightCloudReader_h
#define vtkPGILightCloudReader_h

#include "ProxyGILightCloudModule.h"
#include "vtkAlgorithm.h"

class vtkPGILightCloud;

class PROXYGILIGHTCLOUD_EXPORT vtkPGILightCloudReader : public vtkAlgorithm
{
public:
  static vtkPGILightCloudReader* New();
  vtkTypeMacro(vtkPGILightCloudReader, vtkAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);

  vtkPGILightCloud* GetOutput();
  vtkTypeBool ProcessRequest(
    vtkInformation* request, vtkInformationVector** in, vtkInformationVector* out) override;

protected:
  vtkPGILightCloudReader();
  ~vtkPGILightCloudReader() override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;

  char* FileName = nullptr;

private:
  vtkPGILightCloudReader(const vtkPGILightCloudReader&) = delete;
  void operator=(const vtkPGILightCloudReader&) = delete;
};

#endif
