#include "vtkPGIReferenceIllumination.h"

#include "pgiEnvironmentMap.h"
#include "pgiMaterial.h"
#include "pgiParallel.h"
#include "pgiReferenceScene.h"
#include "pgiReferenceTracer.h"
#include "vtkPGIGIBake.h"
#include "vtkPGILighting.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <cmath>
#include <cstdint>
#include <cstring>

vtkStandardNewMacro(vtkPGIReferenceIllumination);
vtkCxxSetObjectMacro(vtkPGIReferenceIllumination, Lighting, vtkPGILighting);
vtkCxxSetObjectMacro(vtkPGIReferenceIllumination, Controller, vtkMultiProcessController);

vtkPGIReferenceIllumination::vtkPGIReferenceIllumination()
{
  this->SetNumberOfInputPorts(3);
  this->SetAlbedoArrayName("Albedo");
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPGIReferenceIllumination::~vtkPGIReferenceIllumination()
{
  this->SetLighting(nullptr);
  this->SetController(nullptr);
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
  os << indent << "PositionSeeds: " << this->PositionSeeds << "\n";
  os << indent << "MaximumGatheredTriangles: " << this->MaximumGatheredTriangles << "\n";
  os << indent << "Controller: " << this->Controller << " ("
     << proxygi::parallel::Ranks(this->Controller) << " ranks)\n";
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

// A receiver's seed from its coordinates' bits (splitmix64 of each).
std::uint64_t PositionSeed(const double x[3])
{
  std::uint64_t h = 0x9E3779B97F4A7C15ull;
  for (int k = 0; k < 3; ++k)
  {
    std::uint64_t bits;
    std::memcpy(&bits, &x[k], sizeof bits);
    h ^= bits + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h ^= h >> 30;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 27;
    h *= 0x94D049BB133111EBull;
    h ^= h >> 31;
  }
  return h;
}

// What of a piece the scene needs: triangles and the albedo, no ghost cells.
vtkSmartPointer<vtkPolyData> SceneGeometry(vtkPolyData* piece, const char* albedoArray)
{
  auto geometry = vtkSmartPointer<vtkPolyData>::New();
  if (!piece || piece->GetNumberOfPoints() == 0)
  {
    return geometry;
  }
  auto owned = vtkSmartPointer<vtkPolyData>::New();
  owned->ShallowCopy(piece);
  if (piece->GetCellGhostArray())
  {
    owned->DeepCopy(piece);
    owned->RemoveGhostCells();
  }
  geometry->SetPoints(owned->GetPoints());
  geometry->SetPolys(owned->GetPolys());
  geometry->SetStrips(owned->GetStrips());
  if (albedoArray && owned->GetPointData()->GetArray(albedoArray))
  {
    geometry->GetPointData()->AddArray(owned->GetPointData()->GetArray(albedoArray));
  }
  return geometry;
}
} // namespace

int vtkPGIReferenceIllumination::RequestData(
  vtkInformation*, vtkInformationVector** in, vtkInformationVector* out)
{
  vtkPolyData* receivers = vtkPolyData::GetData(in[0]);
  vtkPolyData* output = vtkPolyData::GetData(out);
  this->CommunicationBytes = 0.0;
  // Under MPI every rank reaches every collective, whatever its piece.
  vtkMultiProcessController* controller = proxygi::parallel::Active(this->Controller);
  const bool emptyPiece = controller && (!receivers || receivers->GetNumberOfPoints() == 0);
  std::string localError, agreed;
  if (!emptyPiece && (!receivers || receivers->GetNumberOfPoints() == 0))
  {
    localError = "No receivers: input 0 is empty.";
  }
  else if (!emptyPiece && !FinitePoints(receivers))
  {
    localError = "The receivers hold NaN or Inf points.";
  }
  for (int c = 0; localError.empty() && c < this->GetNumberOfInputConnections(1); ++c)
  {
    vtkPolyData* object = vtkPolyData::GetData(in[1], c);
    if (object && !FinitePoints(object))
    {
      localError = "Scene object " + std::to_string(c) + " holds NaN or Inf points.";
    }
  }
  vtkNew<vtkPGILighting> defaultLighting;
  vtkPGILighting* lighting = this->Lighting ? this->Lighting : defaultLighting.Get();
  const proxygi::EnvironmentMap* environment = nullptr;
  std::string error;
  if (localError.empty() && !lighting->GetEnvironment(environment, error))
  {
    localError = "Bad environment: " + error;
  }

  // Normals: the input's, or computed (no splitting, so receivers stay 1:1).
  vtkSmartPointer<vtkPolyData> withNormals = receivers;
  if (localError.empty() && !emptyPiece && !receivers->GetPointData()->GetNormals())
  {
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(receivers);
    normals->SplittingOff();
    normals->ComputePointNormalsOn();
    proxygi::UpdateNormals(normals);
    withNormals = normals->GetOutput();
    if (withNormals->GetNumberOfPoints() != receivers->GetNumberOfPoints() ||
      !withNormals->GetPointData()->GetNormals())
    {
      localError = "Could not compute receiver normals (no polygons?); give point normals.";
    }
  }
  vtkPolyData* proxies =
    this->GetNumberOfInputConnections(2) ? vtkPolyData::GetData(in[2]) : nullptr;
  if (localError.empty() && this->UseProxies && !proxies)
  {
    localError = "UseProxies is on but input 2 (proxies) is not connected.";
  }
  // The scene's size over all ranks, before anything large moves.
  double triangles = 0.0;
  if (controller && localError.empty())
  {
    triangles += receivers ? static_cast<double>(receivers->GetNumberOfPolys()) : 0.0;
    for (int c = 0; !this->UseProxies && c < this->GetNumberOfInputConnections(1); ++c)
    {
      vtkPolyData* object = vtkPolyData::GetData(in[1], c);
      triangles += object ? static_cast<double>(object->GetNumberOfPolys()) : 0.0;
    }
  }
  triangles = proxygi::parallel::Sum(controller, triangles);
  if (controller && localError.empty() && triangles > this->MaximumGatheredTriangles)
  {
    localError = "the scene has " + std::to_string(static_cast<long long>(triangles)) +
      " triangles over all ranks, more than MaximumGatheredTriangles (" +
      std::to_string(static_cast<long long>(this->MaximumGatheredTriangles)) +
      "): each rank would hold all of them; trace a smaller scene or raise the limit";
  }
  if (!proxygi::parallel::AllOk(controller, localError.empty(), localError, agreed))
  {
    vtkErrorMacro(<< agreed);
    return 0;
  }

  // Every rank traces against the whole scene.
  proxygi::parallel::Traffic traffic;
  vtkSmartPointer<vtkPolyData> sceneReceivers = receivers;
  std::vector<vtkSmartPointer<vtkPolyData>> sceneObjects;
  vtkSmartPointer<vtkPolyData> sceneProxies = proxies;
  if (controller)
  {
    sceneReceivers = proxygi::parallel::AllGatherPolyData(
      controller, SceneGeometry(receivers, this->AlbedoArrayName), &traffic);
    if (this->UseProxies)
    {
      sceneProxies = proxygi::parallel::GatherProxies(controller, proxies, error, &traffic);
    }
    else
    {
      for (int c = 0; c < this->GetNumberOfInputConnections(1); ++c)
      {
        sceneObjects.push_back(proxygi::parallel::AllGatherPolyData(controller,
          SceneGeometry(vtkPolyData::GetData(in[1], c), this->AlbedoArrayName), &traffic));
      }
    }
    this->CommunicationBytes = static_cast<double>(traffic.BytesReceived);
  }
  else
  {
    for (int c = 0; c < this->GetNumberOfInputConnections(1); ++c)
    {
      sceneObjects.emplace_back(vtkPolyData::GetData(in[1], c));
    }
  }
  proxygi::ReferenceTracer tracer;
  tracer.SetEnvironment(environment);
  bool ok =
    proxygi::AddPolyData(tracer, sceneReceivers, this->DefaultAlbedo, this->AlbedoArrayName, error);
  if (ok && this->UseProxies)
  {
    ok = sceneProxies &&
      proxygi::AddProxySpheres(
        tracer, sceneProxies, this->DefaultAlbedo, this->AlbedoArrayName, error);
  }
  else
  {
    for (std::size_t c = 0; ok && c < sceneObjects.size(); ++c)
    {
      ok = proxygi::AddPolyData(
        tracer, sceneObjects[c], this->DefaultAlbedo, this->AlbedoArrayName, error);
    }
  }
  proxygi::AddLocalLights(tracer, lighting);
  ok = ok && tracer.Commit(error);
  if (!proxygi::parallel::AllOk(
        controller, ok, "Cannot build the scene: " + error, agreed, &traffic))
  {
    vtkErrorMacro(<< agreed);
    return 0;
  }
  const bool positionSeeds = this->PositionSeeds || controller;

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
  vtkSmartPointer<vtkDataArray> normals = withNormals->GetPointData()->GetNormals();
  if (!normals)
  {
    normals = vtkSmartPointer<vtkFloatArray>::New();
    normals->SetNumberOfComponents(3);
  }
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
          tracer.EstimateIrradiance(
            x, nrm, positionSeeds ? PositionSeed(x) : static_cast<std::uint64_t>(i), settings, e);
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
