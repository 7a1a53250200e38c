#include "vtkPGIDataServerProxyProperty.h"

#include "vtkObjectFactory.h"
#include "vtkPVSession.h"
#include "vtkProcessModule.h"

vtkStandardNewMacro(vtkPGIDataServerProxyProperty);

bool vtkPGIDataServerProxyProperty::Push(vtkSMMessage* message, int offset)
{
  vtkProcessModule* module = vtkProcessModule::GetProcessModule();
  auto* session = module ? vtkPVSession::SafeDownCast(module->GetActiveSession()) : nullptr;
  if (session && !session->HasProcessRole(vtkPVSession::DATA_SERVER))
  {
    return true; // a client of a server: the source is not here
  }
  return this->Superclass::Push(message, offset);
}

void vtkPGIDataServerProxyProperty::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
