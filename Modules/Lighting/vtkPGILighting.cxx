#include "vtkPGILighting.h"

#include "pgiEnvironmentMap.h"
#include "vtkPGIEXRReader.h"

#include "vtkCallbackCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <cmath>

vtkStandardNewMacro(vtkPGILighting);
vtkCxxSetObjectMacro(vtkPGILighting, EnvironmentImage, vtkImageData);

vtkPGILighting::vtkPGILighting() = default;

vtkPGILighting::~vtkPGILighting()
{
  this->SetEnvironmentImage(nullptr);
  this->SetEnvironmentFileName(nullptr);
}

void vtkPGILighting::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EnvironmentImage: " << this->EnvironmentImage << "\n";
  os << indent << "UniformRadiance: " << this->UniformRadiance[0] << " " << this->UniformRadiance[1]
     << " " << this->UniformRadiance[2] << "\n";
  os << indent << "EnvironmentFileName: "
     << (this->EnvironmentFileName ? this->EnvironmentFileName : "(none)") << "\n";
  os << indent << "EnvironmentScale: " << this->EnvironmentScale << "\n";
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

void vtkPGILighting::AddSphereLight(
  double x, double y, double z, double radius, double r, double g, double b)
{
  const double c[3] = { x, y, z }, radiance[3] = { r, g, b };
  this->AddSphereLight(c, radius, radiance);
}

void vtkPGILighting::AddPointLight(double x, double y, double z, double r, double g, double b)
{
  const double p[3] = { x, y, z }, intensity[3] = { r, g, b };
  this->AddPointLight(p, intensity);
}

void vtkPGILighting::RemoveAllSphereLights()
{
  if (!this->SphereLights.empty())
  {
    this->SphereLights.clear();
    this->Modified();
  }
}

void vtkPGILighting::RemoveAllPointLights()
{
  if (!this->PointLights.empty())
  {
    this->PointLights.clear();
    this->Modified();
  }
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
    vtkSmartPointer<vtkImageData> image = this->EnvironmentImage;
    if (!image && this->EnvironmentFileName && *this->EnvironmentFileName)
    {
      vtkNew<vtkPGIEXRReader> reader;
      reader->SetFileName(this->EnvironmentFileName);
      // The failure is returned to the caller, not printed twice.
      vtkNew<vtkCallbackCommand> quiet;
      reader->AddObserver(vtkCommand::ErrorEvent, quiet);
      reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, quiet);
      reader->Update();
      image = reader->GetOutput();
      if (!image || image->GetNumberOfPoints() == 0)
      {
        error = std::string("cannot read the environment file '") + this->EnvironmentFileName +
          "' (an OpenEXR lat-long image is expected)";
        map = nullptr;
        return false;
      }
    }
    if (image && this->EnvironmentScale != 1.0)
    {
      auto scaled = vtkSmartPointer<vtkImageData>::New();
      scaled->DeepCopy(image);
      vtkDataArray* texels = scaled->GetPointData()->GetScalars();
      for (vtkIdType i = 0; texels && i < texels->GetNumberOfValues(); ++i)
      {
        texels->SetVariantValue(i, texels->GetVariantValue(i).ToDouble() * this->EnvironmentScale);
      }
      image = scaled;
    }
    if (image)
    {
      if (!proxygi::EnvironmentMap::FromImage(image, *built, error))
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
      const double k = this->EnvironmentScale;
      *built = proxygi::EnvironmentMap::Uniform(static_cast<float>(k * this->UniformRadiance[0]),
        static_cast<float>(k * this->UniformRadiance[1]),
        static_cast<float>(k * this->UniformRadiance[2]));
    }
    built->SetRotation(this->EnvironmentRotation * 3.14159265358979323846 / 180.0);
    this->Cached = std::move(built);
    this->CachedTime = time;
  }
  map = this->Cached.get();
  return true;
}
