#include "vtkPGILighting.h"

#include "pgiEnvironmentMap.h"
#include "vtkImageData.h"
#include "vtkObjectFactory.h"

#include <cmath>

vtkStandardNewMacro(vtkPGILighting);
vtkCxxSetObjectMacro(vtkPGILighting, EnvironmentImage, vtkImageData);

vtkPGILighting::vtkPGILighting() = default;

vtkPGILighting::~vtkPGILighting()
{
  this->SetEnvironmentImage(nullptr);
}

void vtkPGILighting::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EnvironmentImage: " << this->EnvironmentImage << "\n";
  os << indent << "UniformRadiance: " << this->UniformRadiance[0] << " " << this->UniformRadiance[1]
     << " " << this->UniformRadiance[2] << "\n";
  os << indent << "EnvironmentRotation: " << this->EnvironmentRotation << "\n";
  os << indent << "SphereLights: " << this->SphereLights.size() << "\n";
  os << indent << "PointLights: " << this->PointLights.size() << "\n";
}

void vtkPGILighting::AddSphereLight(const double c[3], double r, const double radiance[3])
{
  this->SphereLights.push_back(
    { { c[0], c[1], c[2] }, r, { radiance[0], radiance[1], radiance[2] } });
  this->Modified();
}

void vtkPGILighting::AddPointLight(const double p[3], const double intensity[3])
{
  this->PointLights.push_back(
    { { p[0], p[1], p[2] }, { intensity[0], intensity[1], intensity[2] } });
  this->Modified();
}

void vtkPGILighting::RemoveAllLights()
{
  this->SphereLights.clear();
  this->PointLights.clear();
  this->Modified();
}

bool vtkPGILighting::GetEnvironment(const proxygi::EnvironmentMap*& map, std::string& error)
{
  vtkMTimeType time = this->GetMTime();
  if (this->EnvironmentImage)
  {
    time = std::max(time, this->EnvironmentImage->GetMTime());
  }
  if (!this->Cached || this->CachedTime < time)
  {
    std::unique_ptr<proxygi::EnvironmentMap> built(new proxygi::EnvironmentMap);
    if (this->EnvironmentImage)
    {
      if (!proxygi::EnvironmentMap::FromImage(this->EnvironmentImage, *built, error))
      {
        map = nullptr;
        return false;
      }
    }
    else
    {
      for (double v : this->UniformRadiance)
      {
        if (!std::isfinite(v) || v < 0.0)
        {
          error = "uniform radiance must be finite and non-negative";
          map = nullptr;
          return false;
        }
      }
      *built = proxygi::EnvironmentMap::Uniform(static_cast<float>(this->UniformRadiance[0]),
        static_cast<float>(this->UniformRadiance[1]), static_cast<float>(this->UniformRadiance[2]));
    }
    built->SetRotation(this->EnvironmentRotation * 3.14159265358979323846 / 180.0);
    this->Cached = std::move(built);
    this->CachedTime = time;
  }
  map = this->Cached.get();
  return true;
}
