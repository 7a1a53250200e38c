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

class vtkDataArray;

namespace proxygi
{
/// The albedo of many points of one mesh: the array is looked up once.
class PROXYGILIGHTING_EXPORT AlbedoReader
{
public:
  AlbedoReader(vtkPolyData* mesh, const char* albedoArray, const double defaultAlbedo[3]);
  void Get(vtkIdType id, double rgb[3]) const;

private:
  vtkDataArray* Array;
  double Scale;
  double Default[3];
};

/// One point's albedo (AlbedoReader for a single lookup).
PROXYGILIGHTING_EXPORT void AlbedoOf(vtkPolyData* mesh, const char* albedoArray, vtkIdType id,
  const double defaultAlbedo[3], double rgb[3]);
} // namespace proxygi

#endif
