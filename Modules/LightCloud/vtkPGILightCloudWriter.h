/**
 * @class   vtkPGILightCloudWriter
 * @brief   Writes a light cloud, dense or compressed, to a file that
 *          vtkPGILightCloudReader reads back (pgiLightCloudFile).
 *
 * Errors: no file name, no cloud on the input, a file that cannot be
 * written.
 */
#ifndef vtkPGILightCloudWriter_h
#define vtkPGILightCloudWriter_h

#include "ProxyGILightCloudModule.h"
#include "vtkWriter.h"

class PROXYGILIGHTCLOUD_EXPORT vtkPGILightCloudWriter : public vtkWriter
{
public:
  static vtkPGILightCloudWriter* New();
  vtkTypeMacro(vtkPGILightCloudWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);

protected:
  vtkPGILightCloudWriter();
  ~vtkPGILightCloudWriter() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  char* FileName = nullptr;

private:
  vtkPGILightCloudWriter(const vtkPGILightCloudWriter&) = delete;
  void operator=(const vtkPGILightCloudWriter&) = delete;
};

#endif
