#include "vtkPGIReferenceIllumination.h"

#include "pgiEnvironmentMap.h"
#include "pgiMaterial.h"
#include "pgiReferenceScene.h"
#include "pgiReferenceTracer.h"
#include "vtkPGILighting.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <cmath>

vtkStandardNewMacro(vtkPGIReferenceIllumination);
vtkCxxSetObjectMacro(vtkPGIReferenceIllumination, Lighting, vtkPGILighting);

vtkPGIReferenceIllumination::vtkPGIReferenceIllumination()
{
  this->SetNumberOfInputPorts(3);
  this->SetAlbedoArrayName("Albedo");
}

vtkPGIReferenceIllumination::~vtkPGIReferenceIllumination()
{
  this->SetLighting(nullptr);
  this->SetAlbedoArrayName(nullptr);
}

vtkMTimeType vtkPGIReferenceIllumination::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->Lighting)
  {
    t = std::max(t, this->Lighting->GetMTime());
  }
  return t;
}

void vtkPGIReferenceIllumination::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Lighting: " << this->Lighting << "\n";
  os << indent << "Samples: " << this->Samples << "\n";
  os << indent << "MaxBounces: " << this->MaxBounces << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "UseProxies: " << this->UseProxies << "\n";
  os << indent << "DefaultAlbedo: " << this->DefaultAlbedo[0] << " " << this->DefaultAlbedo[1]
     << " " << this->DefaultAlbedo[2] << "\n";
  os << indent << "AlbedoArrayName: " << (this->AlbedoArrayName ? this->AlbedoArrayName : "(none)")
     << "\n";
}

int vtkPGIReferenceIllumination::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  }
  else if (port == 2)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

namespace
{
bool FinitePoints(vtkPolyData* mesh)
{
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      return false;
    }
  }
  return true;
}
} // namespace

int vtkPGIReferenceIllumination::RequestData(
  vtkInformation*, vtkInformationVector** in, vtkInformationVector* out)
{
  vtkPolyData* receivers = vtkPolyData::GetData(in[0]);
  vtkPolyData* output = vtkPolyData::GetData(out);
  if (!receivers || receivers->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro("No receivers: input 0 is empty.");
    return 0;
  }
  if (!FinitePoints(receivers))
  {
    vtkErrorMacro("The receivers hold NaN or Inf points.");
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

  // Normals: the input's, or computed (no splitting, so receivers stay 1:1).
  vtkSmartPointer<vtkPolyData> withNormals = receivers;
  if (!receivers->GetPointData()->GetNormals())
  {
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(receivers);
    normals->SplittingOff();
    normals->ComputePointNormalsOn();
    normals->Update();
    withNormals = normals->GetOutput();
    if (withNormals->GetNumberOfPoints() != receivers->GetNumberOfPoints() ||
      !withNormals->GetPointData()->GetNormals())
    {
      vtkErrorMacro("Could not compute receiver normals (no polygons?); give point normals.");
      return 0;
    }
  }

  proxygi::ReferenceTracer tracer;
  tracer.SetEnvironment(environment);
  bool ok =
    proxygi::AddPolyData(tracer, receivers, this->DefaultAlbedo, this->AlbedoArrayName, error);
  vtkPolyData* proxies =
    this->GetNumberOfInputConnections(2) ? vtkPolyData::GetData(in[2]) : nullptr;
  if (ok && this->UseProxies)
  {
    if (!proxies)
    {
      vtkErrorMacro("UseProxies is on but input 2 (proxies) is not connected.");
      return 0;
    }
    ok =
      proxygi::AddProxySpheres(tracer, proxies, this->DefaultAlbedo, this->AlbedoArrayName, error);
  }
  else
  {
    for (int c = 0; ok && c < this->GetNumberOfInputConnections(1); ++c)
    {
      vtkPolyData* object = vtkPolyData::GetData(in[1], c);
      if (object && !FinitePoints(object))
      {
        vtkErrorMacro("Scene object " << c << " holds NaN or Inf points.");
        return 0;
      }
      ok = proxygi::AddPolyData(tracer, object, this->DefaultAlbedo, this->AlbedoArrayName, error);
    }
  }
  proxygi::AddLocalLights(tracer, lighting);
  if (!ok || !tracer.Commit(error))
  {
    vtkErrorMacro("Cannot build the scene: " << error);
    return 0;
  }

  const vtkIdType n = receivers->GetNumberOfPoints();
  auto makeArray = [n](const char* name)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(3);
    a->SetNumberOfTuples(n);
    return vtkSmartPointer<vtkFloatArray>(a.Get());
  };
  auto direct = makeArray("DirectShadowed"), indirect = makeArray("IndirectOneBounce"),
       total = makeArray("Radiance"), totalErr = makeArray("RadianceStdErr"),
       directErr = makeArray("DirectStdErr"), indirectErr = makeArray("IndirectStdErr");
  vtkDataArray* normals = withNormals->GetPointData()->GetNormals();
  proxygi::ReferenceTracer::Settings settings;
  settings.Samples = this->Samples;
  settings.MaxBounces = this->MaxBounces;
  settings.Seed = this->Seed;

  // Blocks of receivers in parallel; progress and abort between blocks.
  const vtkIdType blocks = std::min<vtkIdType>(100, n);
  for (vtkIdType b = 0; b < blocks && !this->GetAbortExecute(); ++b)
  {
    const vtkIdType begin = n * b / blocks, end = n * (b + 1) / blocks;
    vtkSMPTools::For(begin, end,
      [&](vtkIdType first, vtkIdType last)
      {
        for (vtkIdType i = first; i < last; ++i)
        {
          double x[3], nrm[3], albedo[3];
          receivers->GetPoint(i, x);
          normals->GetTuple(i, nrm);
          if (vtkMath::Normalize(nrm) == 0.0 || !std::isfinite(nrm[0]))
          {
            nrm[0] = nrm[1] = 0.0;
            nrm[2] = 1.0;
          }
          proxygi::AlbedoOf(receivers, this->AlbedoArrayName, i, this->DefaultAlbedo, albedo);
          proxygi::ReferenceTracer::Estimate e;
          tracer.EstimateIrradiance(x, nrm, static_cast<std::uint64_t>(i), settings, e);
          float d[3], id[3], t[3], te[3], de[3], ie[3];
          for (int k = 0; k < 3; ++k)
          {
            const double s = albedo[k] / vtkMath::Pi();
            d[k] = static_cast<float>(s * e.Direct[k]);
            id[k] = static_cast<float>(s * e.Indirect[k]);
            t[k] = d[k] + id[k];
            te[k] = static_cast<float>(s * e.TotalStdErr[k]);
            de[k] = static_cast<float>(s * e.DirectStdErr[k]);
            ie[k] = static_cast<float>(s * e.IndirectStdErr[k]);
          }
          direct->SetTypedTuple(i, d);
          indirect->SetTypedTuple(i, id);
          total->SetTypedTuple(i, t);
          totalErr->SetTypedTuple(i, te);
          directErr->SetTypedTuple(i, de);
          indirectErr->SetTypedTuple(i, ie);
        }
      });
    this->UpdateProgress(static_cast<double>(b + 1) / blocks);
  }

  output->ShallowCopy(receivers);
  vtkPointData* pd = output->GetPointData();
  for (vtkFloatArray* a : { direct.Get(), indirect.Get(), total.Get(), totalErr.Get(),
         directErr.Get(), indirectErr.Get() })
  {
    pd->AddArray(a);
  }
  if (!receivers->GetPointData()->GetNormals())
  {
    pd->SetNormals(normals);
  }
  // Mean relative standard error of the luminance of Radiance.
  double rel = 0.0, errSq = 0.0, valueSq = 0.0;
  vtkIdType counted = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    const float* t = total->GetPointer(3 * i);
    const float* te = totalErr->GetPointer(3 * i);
    const double lum = 0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2];
    const double lumErr = 0.2126 * te[0] + 0.7152 * te[1] + 0.0722 * te[2];
    errSq += lumErr * lumErr;
    valueSq += lum * lum;
    if (lum > 0.0)
    {
      rel += lumErr / lum;
      ++counted;
    }
  }
  auto field = [&](const char* name, double value)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->InsertNextValue(value);
    output->GetFieldData()->AddArray(a);
  };
  field("Samples", this->Samples);
  field("Rays", static_cast<double>(tracer.GetRayCount()));
  field("MeanRelativeStdErr", counted ? rel / counted : 0.0);
  // The normalisation of the project's error metric (relative RMSE).
  field("RelativeRMSStdErr", valueSq > 0.0 ? std::sqrt(errSq / valueSq) : 0.0);
  field("SkippedTriangles", static_cast<double>(tracer.GetSkippedTriangles()));
  return 1;
}
