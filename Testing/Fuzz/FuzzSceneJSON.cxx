// libFuzzer harness: scene JSON through proxygi::ParseScene and, when it is
// accepted, proxygi::BuildScene (planes and spheres are built; mesh and map
// files are looked for in a folder that does not exist). Findings: a crash,
// an uncaught exception, a hang, an allocation, or an accepted scene with a
// non-finite number or a built object with non-finite points.
#include "pgiFuzz.h"

#include "pgiScene.h"
#include "vtkPolyData.h"

#include <cstdint>
#include <cstdlib>
#include <string>

namespace
{
bool Finite(const double* v, int n)
{
  for (int i = 0; i < n; ++i)
  {
    if (!std::isfinite(v[i]))
    {
      return false;
    }
  }
  return true;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const bool quiet = pgiFuzz::Quiet() && setenv("PROXYGI_DATA_DIR", "/nonexistent", 1) == 0;
  (void)quiet;
  proxygi::SceneDescription scene;
  std::string error;
  if (!proxygi::ParseScene(
        std::string(reinterpret_cast<const char*>(data), size), "/nonexistent", scene, error))
  {
    if (error.empty())
    {
      pgiFuzz::Finding("a refusal without a message");
    }
    return 0;
  }
  bool finite = Finite(scene.UniformRadiance, 3) && std::isfinite(scene.EnvironmentRotation) &&
    std::isfinite(scene.EnvironmentScale) && Finite(scene.CameraPosition, 3) &&
    Finite(scene.FocalPoint, 3) && Finite(scene.ViewUp, 3) && std::isfinite(scene.ViewAngle);
  for (const proxygi::SceneObject& o : scene.Objects)
  {
    finite = finite && Finite(o.PlaneCenter, 3) && std::isfinite(o.PlaneSize) &&
      Finite(o.SphereCenter, 3) && std::isfinite(o.SphereRadius) && Finite(o.Translate, 3) &&
      Finite(o.Rotate, 3) && std::isfinite(o.Scale) && Finite(o.Albedo, 3) &&
      Finite(o.PlaneOrigin, 3) && Finite(o.PlanePoint1, 3) && Finite(o.PlanePoint2, 3) &&
      Finite(o.BoxCenter, 3) && Finite(o.BoxSize, 3);
  }
  for (const proxygi::SceneLight& l : scene.Lights)
  {
    finite = finite && Finite(l.Position, 3) && std::isfinite(l.Radius) && Finite(l.Value, 3);
  }
  if (!finite)
  {
    pgiFuzz::Finding("an accepted scene with a non-finite number");
  }
  proxygi::LoadedScene loaded;
  if (!proxygi::BuildScene(scene, loaded, error))
  {
    return 0;
  }
  for (const auto& object : loaded.Objects)
  {
    if (!pgiFuzz::Finite(object->GetPoints()))
    {
      pgiFuzz::Finding("a built object with non-finite points");
    }
  }
  return 0;
}
