#include "pgiReferenceScene.h"

#include "pgiMaterial.h"
#include "vtkPGILighting.h"

#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <vector>

namespace proxygi
{

bool AddPolyData(ReferenceTracer& tracer, vtkPolyData* mesh, const double defaultAlbedo[3],
  const char* albedoArray, std::string& error)
{
  if (!mesh || mesh->GetNumberOfPoints() == 0)
  {
    return true; // nothing to add
  }
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputData(mesh);
  triangulate->PassVertsOff();
  triangulate->PassLinesOff();
  triangulate->Update();
  vtkPolyData* tris = triangulate->GetOutput();
  const vtkIdType np = tris->GetNumberOfPoints();
  std::vector<float> points(3 * np), albedo(3 * np);
  const bool perVertex = albedoArray && tris->GetPointData()->GetArray(albedoArray);
  const AlbedoReader albedoOf(tris, albedoArray, defaultAlbedo);
  for (vtkIdType i = 0; i < np; ++i)
  {
    double p[3], a[3];
    tris->GetPoint(i, p);
    albedoOf.Get(i, a);
    for (int k = 0; k < 3; ++k)
    {
      points[3 * i + k] = static_cast<float>(p[k]);
      albedo[3 * i + k] = static_cast<float>(a[k]);
    }
  }
  std::vector<unsigned> triangles;
  triangles.reserve(3 * tris->GetNumberOfPolys());
  vtkCellArray* polys = tris->GetPolys();
  vtkIdType npts;
  const vtkIdType* ids;
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    if (npts == 3)
    {
      triangles.insert(triangles.end(),
        { static_cast<unsigned>(ids[0]), static_cast<unsigned>(ids[1]),
          static_cast<unsigned>(ids[2]) });
    }
  }
  const float object[3] = { static_cast<float>(defaultAlbedo[0]),
    static_cast<float>(defaultAlbedo[1]), static_cast<float>(defaultAlbedo[2]) };
  return tracer.AddMesh(points, triangles, perVertex ? albedo.data() : nullptr, object, error);
}

bool AddProxySpheres(ReferenceTracer& tracer, vtkPolyData* proxies, const double defaultAlbedo[3],
  const char* albedoArray, std::string& error)
{
  if (!proxies || proxies->GetNumberOfPoints() == 0)
  {
    return true;
  }
  vtkDataArray* radius = proxies->GetPointData()->GetArray("Radius");
  if (!radius)
  {
    error = "proxies need a \"Radius\" point array";
    return false;
  }
  // Only the leaves (Level 0) are geometry; hierarchy parents bound them.
  vtkDataArray* level = proxies->GetPointData()->GetArray("Level");
  const AlbedoReader proxyAlbedo(proxies, albedoArray, defaultAlbedo);
  for (vtkIdType i = 0; i < proxies->GetNumberOfPoints(); ++i)
  {
    if (level && level->GetTuple1(i) != 0.0)
    {
      continue;
    }
    double c[3], a[3];
    proxies->GetPoint(i, c);
    proxyAlbedo.Get(i, a);
    const float af[3] = { static_cast<float>(a[0]), static_cast<float>(a[1]),
      static_cast<float>(a[2]) };
    if (!tracer.AddSphere(c, radius->GetTuple1(i), af, error))
    {
      return false;
    }
  }
  return true;
}

void AddLocalLights(ReferenceTracer& tracer, vtkPGILighting* lighting)
{
  for (const auto& l : lighting->GetSphereLights())
  {
    const float radiance[3] = { float(l.Radiance[0]), float(l.Radiance[1]), float(l.Radiance[2]) };
    tracer.AddSphereLight(l.Center, l.Radius, radiance);
  }
  for (const auto& l : lighting->GetPointLights())
  {
    const float intensity[3] = { float(l.Intensity[0]), float(l.Intensity[1]),
      float(l.Intensity[2]) };
    tracer.AddPointLight(l.Position, intensity);
  }
}

} // namespace proxygi
