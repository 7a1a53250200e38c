/**
 * @file pgiReferenceScene.h
 * @brief Feeding VTK data to the ReferenceTracer (shared by the per-vertex
 * filter, the per-pixel image source, the occluder and the light cloud).
 */
#ifndef pgiReferenceScene_h
#define pgiReferenceScene_h

#include "ProxyGIReferenceModule.h"
#include "pgiReferenceTracer.h"

#include "vtkType.h"

#include <string>

class vtkPGILighting;
class vtkPolyData;

namespace proxygi
{
/**
 * Adds a vtkPolyData's polygons (triangulated) to the tracer. Albedo: the
 * named point array (3 components; unsigned char is read as 0..255) or the
 * default.
 */
PROXYGIREFERENCE_EXPORT bool AddPolyData(ReferenceTracer& tracer, vtkPolyData* mesh,
  const double defaultAlbedo[3], const char* albedoArray, std::string& error);

/// Adds proxy spheres: points with a "Radius" point array.
PROXYGIREFERENCE_EXPORT bool AddProxySpheres(ReferenceTracer& tracer, vtkPolyData* proxies,
  const double defaultAlbedo[3], const char* albedoArray, std::string& error);

/// Adds the lighting's spherical and point lights to the tracer.
PROXYGIREFERENCE_EXPORT void AddLocalLights(ReferenceTracer& tracer, vtkPGILighting* lighting);
} // namespace proxygi

#endif
