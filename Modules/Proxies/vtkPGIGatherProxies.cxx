#include "vtkPGIGatherProxies.h"

#include "pgiParallel.h"

#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

vtkStandardNewMacro(vtkPGIGatherProxies);
vtkCxxSetObjectMacro(vtkPGIGatherProxies, Controller, vtkMultiProcessController);

vtkPGIGatherProxies::vtkPGIGatherProxies()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPGIGatherProxies::~vtkPGIGatherProxies()
{
  this->SetController(nullptr);
}

void vtkPGIGatherProxies::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << " ("
     << proxygi::parallel::Ranks(this->Controller) << " ranks)\n";
  os << indent << "ReceivedBytes: " << this->ReceivedBytes << "\n";
  os << indent << "GatherTime: " << this->GatherTime << "\n";
}

int vtkPGIGatherProxies::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  proxygi::parallel::Traffic traffic;
  std::string error;
  vtkSmartPointer<vtkPolyData> global =
    proxygi::parallel::GatherProxies(this->Controller, input, error, &traffic);
  this->ReceivedBytes = static_cast<double>(traffic.BytesReceived);
  this->GatherTime = traffic.Seconds;
  if (!global)
  {
    vtkErrorMacro(<< "Cannot gather the proxies: " << error << ".");
    return 0;
  }
  output->ShallowCopy(global);
  return 1;
}
