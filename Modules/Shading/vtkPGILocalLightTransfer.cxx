#include "vtkPGILocalLightTransfer.h"

void vtkPGILocalLightTransfer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
