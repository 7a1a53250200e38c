#include "vtkPGILightCloudReader.h"

#include "pgiLightCloudFile.h"
#include "vtkPGILightCloud.h"

#include "vtkDemandDrivenPipeline.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkPGILightCloudReader);

vtkPGILightCloudReader::vtkPGILightCloudReader()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(1);
}

vtkPGILightCloudReader::~vtkPGILightCloudReader()
{
  this->SetFileName(nullptr);
}

vtkPGILightCloud* vtkPGILightCloudReader::GetOutput()
{
  return vtkPGILightCloud::SafeDownCast(this->GetOutputDataObject(0));
}

int vtkPGILightCloudReader::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkPGILightCloud");
  return 1;
}

vtkTypeBool vtkPGILightCloudReader::ProcessRequest(
  vtkInformation* request, vtkInformationVector** in, vtkInformationVector* out)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_OBJECT()))
  {
    vtkPGILightCloud::EnsureOutput(out);
    return 1;
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    vtkPGILightCloud* cloud = vtkPGILightCloud::GetData(out);
    cloud->Initialize();
    if (!this->FileName || !*this->FileName)
    {
      vtkErrorMacro(<< "No FileName.");
      return 0;
    }
    proxygi::LightCloudFileInfo info;
    std::string error;
    if (!proxygi::ReadLightCloud(this->FileName, cloud, info, error))
    {
      vtkErrorMacro(<< error);
      cloud->Initialize();
      return 0;
    }
    if (info.LightsRead != cloud->GetNumberOfLights())
    {
      vtkErrorMacro(<< "The light cloud file '" << this->FileName << "' is unfinished: "
                    << info.LightsRead << " of " << cloud->GetNumberOfLights()
                    << " lights (resume it with vtkPGILightCloudPrecompute's CacheFileName).");
      cloud->Initialize();
      return 0;
    }
    return 1;
  }
  return this->Superclass::ProcessRequest(request, in, out);
}

void vtkPGILightCloudReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}
