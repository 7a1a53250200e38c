/**
 * @class   vtkPGILighting
 * @brief   The light of a ProxyGI scene: an environment (a lat-long radiance
 *          image, or a uniform sky), its rotation about +z, spherical area
 *          lights and point lights.
 *
 * One object is handed to every renderer (the Embree reference, the SH
 * filters), so all of them light a scene identically. Units: radiance for
 * the environment and the spherical lights, radiant intensity (W/sr) for
 * point lights.
 */
#ifndef vtkPGILighting_h
#define vtkPGILighting_h

#include "ProxyGILightingModule.h"
#include "vtkObject.h"

#include <memory>
#include <string>
#include <vector>

class vtkImageData;

namespace proxygi
{
class EnvironmentMap;
}

class PROXYGILIGHTING_EXPORT vtkPGILighting : public vtkObject
{
public:
  static vtkPGILighting* New();
  vtkTypeMacro(vtkPGILighting, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The environment image (RGB point scalars, 2:1). Null: uniform sky.
  virtual void SetEnvironmentImage(vtkImageData* image);
  vtkGetObjectMacro(EnvironmentImage, vtkImageData);

  /// Radiance of the uniform sky used when there is no image (default 1, 1, 1).
  vtkSetVector3Macro(UniformRadiance, double);
  vtkGetVector3Macro(UniformRadiance, double);

  /// An OpenEXR lat-long file for the environment, read when there is no
  /// EnvironmentImage (vtkPGIEXRReader; re-read when the name changes).
  vtkSetStringMacro(EnvironmentFileName);
  vtkGetStringMacro(EnvironmentFileName);

  /// Scale of the environment's radiance (image, file or uniform sky).
  vtkSetClampMacro(EnvironmentScale, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(EnvironmentScale, double);

  /// Rotation of the environment about +z, in degrees.
  vtkSetMacro(EnvironmentRotation, double);
  vtkGetMacro(EnvironmentRotation, double);

  struct SphereLight
  {
    double Center[3];
    double Radius;
    double Radiance[3];
  };
  struct PointLight
  {
    double Position[3];
    double Intensity[3];
  };
  void AddSphereLight(const double center[3], double radius, const double radiance[3]);
  void AddPointLight(const double position[3], const double intensity[3]);
  void RemoveAllLights();
  /// The same with plain numbers (ParaView's repeated properties).
  void AddSphereLight(double x, double y, double z, double radius, double r, double g, double b);
  void AddPointLight(double x, double y, double z, double r, double g, double b);
  void RemoveAllSphereLights();
  void RemoveAllPointLights();
  const std::vector<SphereLight>& GetSphereLights() const { return this->SphereLights; }
  const std::vector<PointLight>& GetPointLights() const { return this->PointLights; }

  /// The environment as the renderers use it (built on demand, cached).
  bool GetEnvironment(const proxygi::EnvironmentMap*& map, std::string& error);

protected:
  vtkPGILighting();
  ~vtkPGILighting() override;

  vtkImageData* EnvironmentImage = nullptr;
  double UniformRadiance[3] = { 1.0, 1.0, 1.0 };
  double EnvironmentRotation = 0.0;
  char* EnvironmentFileName = nullptr;
  double EnvironmentScale = 1.0;
  std::vector<SphereLight> SphereLights;
  std::vector<PointLight> PointLights;

private:
  std::unique_ptr<proxygi::EnvironmentMap> Cached;
  vtkMTimeType CachedTime = 0;

  vtkPGILighting(const vtkPGILighting&) = delete;
  void operator=(const vtkPGILighting&) = delete;
};

#endif
