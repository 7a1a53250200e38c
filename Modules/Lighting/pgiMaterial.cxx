#include "pgiMaterial.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>

namespace proxygi
{

void AlbedoOf(vtkPolyData* mesh, const char* albedoArray, vtkIdType id,
  const double defaultAlbedo[3], double rgb[3])
{
  vtkDataArray* array = albedoArray && mesh ? mesh->GetPointData()->GetArray(albedoArray) : nullptr;
  if (!array || array->GetNumberOfComponents() < 3 || id >= array->GetNumberOfTuples())
  {
    std::copy(defaultAlbedo, defaultAlbedo + 3, rgb);
    return;
  }
  const double scale = vtkUnsignedCharArray::SafeDownCast(array) ? 1.0 / 255.0 : 1.0;
  for (int k = 0; k < 3; ++k)
  {
    const double v = array->GetComponent(id, k) * scale;
    rgb[k] = std::isfinite(v) ? std::min(1.0, std::max(0.0, v)) : 0.0;
  }
}

} // namespace proxygi
