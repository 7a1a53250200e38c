/**
 * @file pgiMaterial.h
 * @brief Diffuse albedo of a receiver point, read the same way by every
 * renderer: a 3-component point array (floats in 0..1, or unsigned char read
 * as 0..255), clamped to [0, 1], NaN read as 0; the default where the array
 * is missing.
 */
#ifndef pgiMaterial_h
#define pgiMaterial_h

#include "ProxyGILightingModule.h"
#include "vtkType.h"

class vtkPolyData;

namespace proxygi
{
PROXYGILIGHTING_EXPORT void AlbedoOf(vtkPolyData* mesh, const char* albedoArray, vtkIdType id,
  const double defaultAlbedo[3], double rgb[3]);
} // namespace proxygi

#endif
