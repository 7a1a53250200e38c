#include "vtkPGILightCloudTransfer.h"

#include "vtkPGILightCloud.h"

#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <string>

namespace
{
// The relight filter's error message, for the GI filter's own error.
class ErrorCatcher : public vtkCommand
{
public:
  static ErrorCatcher* New() { return new ErrorCatcher; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    if (this->Message.empty())
    {
      this->Message = data ? static_cast<const char*>(data) : "an error";
    }
  }
  std::string Message;
};
} // namespace

vtkStandardNewMacro(vtkPGILightCloudTransfer);
vtkCxxSetObjectMacro(vtkPGILightCloudTransfer, Cloud, vtkPGILightCloud);

vtkPGILightCloudTransfer::vtkPGILightCloudTransfer() = default;

vtkPGILightCloudTransfer::~vtkPGILightCloudTransfer()
{
  this->SetCloud(nullptr);
}

vtkMTimeType vtkPGILightCloudTransfer::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  return this->Cloud ? std::max(t, this->Cloud->GetMTime()) : t;
}

bool vtkPGILightCloudTransfer::CarriesDirectLight()
{
  return this->Cloud && this->Cloud->GetContents() == vtkPGILightCloud::DirectAndIndirect;
}

bool vtkPGILightCloudTransfer::AddLight(vtkPolyData* receivers,
  const std::vector<vtkPGILighting::PointLight>& lights, float* radiance,
  std::vector<std::string>& plan, std::string& why)
{
  if (!this->Cloud)
  {
    why = "no cloud (vtkPGILightCloudTransfer::SetCloud)";
    return false;
  }
  // The GI filter's point lights; unchanged ones leave the filter up to date.
  vtkPGILightCloudRelight* relight = this->Relight;
  relight->SetLights(lights);
  if (relight->GetInput(0) != receivers)
  {
    relight->SetInputData(receivers);
  }
  if (relight->GetInputDataObject(1, 0) != this->Cloud)
  {
    relight->SetCloudData(this->Cloud);
  }
  const vtkMTimeType before = relight->GetOutput()->GetMTime();
  vtkNew<ErrorCatcher> errors;
  // Caught here (the executive's too): the GI filter reports it as its own.
  const unsigned long tag = relight->AddObserver(vtkCommand::ErrorEvent, errors);
  vtkExecutive* executive = relight->GetExecutive();
  const unsigned long executiveTag = executive->AddObserver(vtkCommand::ErrorEvent, errors);
  relight->Update();
  relight->RemoveObserver(tag);
  executive->RemoveObserver(executiveTag);
  if (!errors->Message.empty())
  {
    why = errors->Message;
    while (!why.empty() && (why.back() == '\n' || why.back() == ' '))
    {
      why.pop_back();
    }
    return false;
  }
  const bool recomputed = relight->GetOutput()->GetMTime() != before;
  this->Relights += recomputed ? 1 : 0;
  vtkPolyData* out = relight->GetOutput();
  auto* light = vtkFloatArray::SafeDownCast(out->GetPointData()->GetArray("LightCloudRadiance"));
  if (!light || light->GetNumberOfTuples() != receivers->GetNumberOfPoints())
  {
    why = "the relight filter gave no radiance";
    return false;
  }
  const float* v = light->GetPointer(0);
  for (vtkIdType k = 0; k < light->GetNumberOfValues(); ++k)
  {
    radiance[k] += v[k];
  }
  if (auto* lines = vtkStringArray::SafeDownCast(out->GetFieldData()->GetAbstractArray("Plan")))
  {
    for (vtkIdType k = 0; k < lines->GetNumberOfValues(); ++k)
    {
      plan.push_back(lines->GetValue(k));
    }
  }
  plan.push_back(recomputed ? "light cloud: recomputed (point lights, cloud or receivers changed)"
                            : "light cloud: reused (the point lights did not move)");
  return true;
}

void vtkPGILightCloudTransfer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Cloud: " << this->Cloud << "\n";
  os << indent << "Relights: " << this->Relights << "\n";
  os << indent << "Relight:\n";
  this->Relight->PrintSelf(os, indent.GetNextIndent());
}
