#include "vtkPGIReferenceImage.h"

#include "pgiEnvironmentMap.h"
#include "pgiReferenceScene.h"
#include "pgiReferenceTracer.h"
#include "vtkPGILighting.h"

#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <cmath>

vtkStandardNewMacro(vtkPGIReferenceImage);
vtkCxxSetObjectMacro(vtkPGIReferenceImage, Lighting, vtkPGILighting);
vtkCxxSetObjectMacro(vtkPGIReferenceImage, Camera, vtkCamera);

vtkPGIReferenceImage::vtkPGIReferenceImage()
{
  this->SetNumberOfInputPorts(2);
  this->SetAlbedoArrayName("Albedo");
}

vtkPGIReferenceImage::~vtkPGIReferenceImage()
{
  this->SetLighting(nullptr);
  this->SetCamera(nullptr);
  this->SetAlbedoArrayName(nullptr);
}

vtkMTimeType vtkPGIReferenceImage::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->Lighting)
  {
    t = std::max(t, this->Lighting->GetMTime());
  }
  if (this->Camera)
  {
    t = std::max(t, this->Camera->GetMTime());
  }
  return t;
}

void vtkPGIReferenceImage::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Size[0] << " x " << this->Size[1] << "\n";
  os << indent << "Samples: " << this->Samples << "\n";
  os << indent << "MaxBounces: " << this->MaxBounces << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "UseProxies: " << this->UseProxies << "\n";
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "Lighting: " << this->Lighting << "\n";
}

int vtkPGIReferenceImage::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  }
  else
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

int vtkPGIReferenceImage::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  const int extent[6] = { 0, std::max(1, this->Size[0]) - 1, 0, std::max(1, this->Size[1]) - 1, 0,
    0 };
  vtkInformation* info = out->GetInformationObject(0);
  info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  vtkDataObject::SetPointDataActiveScalarInfo(info, VTK_FLOAT, 3);
  return 1;
}

int vtkPGIReferenceImage::RequestData(
  vtkInformation*, vtkInformationVector** in, vtkInformationVector* out)
{
  vtkImageData* image = vtkImageData::GetData(out);
  if (!this->Camera)
  {
    vtkErrorMacro("No camera set.");
    return 0;
  }
  if (this->Size[0] < 1 || this->Size[1] < 1)
  {
    vtkErrorMacro("Size must be at least 1 x 1.");
    return 0;
  }
  vtkNew<vtkPGILighting> defaultLighting;
  vtkPGILighting* lighting = this->Lighting ? this->Lighting : defaultLighting.Get();
  const proxygi::EnvironmentMap* environment = nullptr;
  std::string error;
  if (!lighting->GetEnvironment(environment, error))
  {
    vtkErrorMacro("Bad environment: " << error);
    return 0;
  }
  proxygi::ReferenceTracer tracer;
  tracer.SetEnvironment(environment);
  bool ok = true;
  if (this->UseProxies)
  {
    vtkPolyData* proxies =
      this->GetNumberOfInputConnections(1) ? vtkPolyData::GetData(in[1]) : nullptr;
    ok = proxies &&
      proxygi::AddProxySpheres(tracer, proxies, this->DefaultAlbedo, this->AlbedoArrayName, error);
    if (!proxies)
    {
      error = "UseProxies is on but input 1 (proxies) is not connected";
    }
  }
  else
  {
    for (int c = 0; ok && c < this->GetNumberOfInputConnections(0); ++c)
    {
      ok = proxygi::AddPolyData(
        tracer, vtkPolyData::GetData(in[0], c), this->DefaultAlbedo, this->AlbedoArrayName, error);
    }
  }
  proxygi::AddLocalLights(tracer, lighting);
  if (!ok || !tracer.Commit(error))
  {
    vtkErrorMacro("Cannot build the scene: " << error);
    return 0;
  }

  // Camera frame: a pinhole with the vtkCamera's vertical view angle.
  const int w = this->Size[0], h = this->Size[1];
  double eye[3], focal[3], up[3], forward[3], right[3];
  this->Camera->GetPosition(eye);
  this->Camera->GetFocalPoint(focal);
  this->Camera->GetViewUp(up);
  for (int k = 0; k < 3; ++k)
  {
    forward[k] = focal[k] - eye[k];
  }
  vtkMath::Normalize(forward);
  vtkMath::Cross(forward, up, right);
  vtkMath::Normalize(right);
  vtkMath::Cross(right, forward, up);
  const double tanHalf = std::tan(vtkMath::RadiansFromDegrees(this->Camera->GetViewAngle()) / 2);
  const double aspect = static_cast<double>(w) / h;

  image->SetExtent(0, w - 1, 0, h - 1, 0, 0);
  vtkNew<vtkFloatArray> radiance, stdErr, direct, indirect;
  radiance->SetName("Radiance");
  stdErr->SetName("RadianceStdErr");
  direct->SetName("DirectShadowed");
  indirect->SetName("IndirectOneBounce");
  for (vtkFloatArray* a : { radiance.Get(), stdErr.Get(), direct.Get(), indirect.Get() })
  {
    a->SetNumberOfComponents(3);
    a->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
  }
  proxygi::ReferenceTracer::Settings settings;
  settings.Samples = this->Samples;
  settings.MaxBounces = this->MaxBounces;
  settings.Seed = this->Seed;
  for (int row = 0; row < h && !this->GetAbortExecute(); ++row)
  {
    vtkSMPTools::For(0, w,
      [&](vtkIdType first, vtkIdType last)
      {
        for (vtkIdType col = first; col < last; ++col)
        {
          // VTK row 0 is the bottom of the picture.
          const double sx = (2.0 * (col + 0.5) / w - 1.0) * tanHalf * aspect;
          const double sy = (2.0 * (row + 0.5) / h - 1.0) * tanHalf;
          double dir[3];
          for (int k = 0; k < 3; ++k)
          {
            dir[k] = forward[k] + sx * right[k] + sy * up[k];
          }
          vtkMath::Normalize(dir);
          const vtkIdType pixel = static_cast<vtkIdType>(row) * w + col;
          proxygi::ReferenceTracer::RadianceEstimate e;
          tracer.EstimateRadianceAlongRay(eye, dir, static_cast<std::uint64_t>(pixel), settings, e);
          auto put = [pixel](vtkFloatArray* a, const double* v)
          {
            const float f[3] = { float(v[0]), float(v[1]), float(v[2]) };
            a->SetTypedTuple(pixel, f);
          };
          put(radiance, e.Total);
          put(stdErr, e.TotalStdErr);
          put(direct, e.Direct);
          put(indirect, e.Indirect);
        }
      });
    this->UpdateProgress(static_cast<double>(row + 1) / h);
  }
  image->GetPointData()->SetScalars(radiance);
  image->GetPointData()->AddArray(stdErr);
  image->GetPointData()->AddArray(direct);
  image->GetPointData()->AddArray(indirect);
  return 1;
}
