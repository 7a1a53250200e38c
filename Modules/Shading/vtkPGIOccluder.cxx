#include "vtkPGIOccluder.h"

void vtkPGIOccluder::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
