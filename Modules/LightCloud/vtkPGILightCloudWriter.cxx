#include "vtkPGILightCloudWriter.h"

#include "pgiLightCloudFile.h"
#include "vtkPGILightCloud.h"

#include "vtkInformation.h"
#include "vtkObjectFactory.h"

#include <string>

vtkStandardNewMacro(vtkPGILightCloudWriter);

vtkPGILightCloudWriter::vtkPGILightCloudWriter() = default;

vtkPGILightCloudWriter::~vtkPGILightCloudWriter()
{
  this->SetFileName(nullptr);
}

int vtkPGILightCloudWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPGILightCloud");
  return 1;
}

void vtkPGILightCloudWriter::WriteData()
{
  auto* cloud = vtkPGILightCloud::SafeDownCast(this->GetInput());
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "No FileName.");
    return;
  }
  if (!cloud || (cloud->GetNumberOfLights() == 0 && !cloud->IsCompressed()))
  {
    vtkErrorMacro(<< "No light cloud to write (an empty cloud on the input).");
    return;
  }
  std::string error;
  // Key 0: a file written by hand is no precompute's cache.
  if (!proxygi::WriteLightCloud(this->FileName, cloud, 0, error))
  {
    vtkErrorMacro(<< error);
  }
}

void vtkPGILightCloudWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}
