#include "pgiMaterial.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>

namespace proxygi
{

AlbedoReader::AlbedoReader(
  vtkPolyData* mesh, const char* albedoArray, const double defaultAlbedo[3])
  : Array(albedoArray && mesh ? mesh->GetPointData()->GetArray(albedoArray) : nullptr)
  , Scale(vtkUnsignedCharArray::SafeDownCast(this->Array) ? 1.0 / 255.0 : 1.0)
{
  std::copy(defaultAlbedo, defaultAlbedo + 3, this->Default);
  if (this->Array && this->Array->GetNumberOfComponents() < 3)
  {
    this->Array = nullptr;
  }
}

void AlbedoReader::Get(vtkIdType id, double rgb[3]) const
{
  if (!this->Array || id >= this->Array->GetNumberOfTuples())
  {
    std::copy(this->Default, this->Default + 3, rgb);
    return;
  }
  for (int k = 0; k < 3; ++k)
  {
    const double v = this->Array->GetComponent(id, k) * this->Scale;
    rgb[k] = std::isfinite(v) ? std::min(1.0, std::max(0.0, v)) : 0.0;
  }
}

void AlbedoOf(vtkPolyData* mesh, const char* albedoArray, vtkIdType id,
  const double defaultAlbedo[3], double rgb[3])
{
  AlbedoReader(mesh, albedoArray, defaultAlbedo).Get(id, rgb);
}

} // namespace proxygi
