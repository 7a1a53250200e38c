#include "vtkPGILightCloudPrecompute.h"

#include "pgiLightCloudCompression.h"
#include "pgiLightCloudFile.h"
#include "pgiLightCloudGlossy.h"
#include "pgiMaterial.h"
#include "pgiReferenceScene.h"
#include "pgiReferenceTracer.h"
#include "vtkPGILightCloud.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkExecutive.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkTimerLog.h"

#include <algorithm>
#include <cmath>
#include <sys/stat.h>
#include <vector>

vtkStandardNewMacro(vtkPGILightCloudPrecompute);
vtkCxxSetObjectMacro(vtkPGILightCloudPrecompute, LightPositions, vtkPoints);

namespace
{
struct Fnv
{
  std::uint64_t Value = 1469598103934665603ull;
  void Add(const void* data, std::size_t bytes)
  {
    const unsigned char* b = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i)
    {
      this->Value = (this->Value ^ b[i]) * 1099511628211ull;
    }
  }
  template <class T>
  void AddValue(const T& v)
  {
    this->Add(&v, sizeof(v));
  }
};

bool FinitePoints(vtkPolyData* mesh)
{
  for (vtkIdType i = 0; mesh && i < mesh->GetNumberOfPoints(); ++i)
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

// What a mesh gives the tracer: points, triangles' connectivity, albedo.
void HashMesh(Fnv& h, vtkPolyData* mesh, const char* albedoArray, const double defaultAlbedo[3])
{
  const vtkIdType n = mesh->GetNumberOfPoints();
  h.AddValue(static_cast<long long>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3], a[3];
    mesh->GetPoint(i, p);
    proxygi::AlbedoOf(mesh, albedoArray, i, defaultAlbedo, a);
    h.Add(p, sizeof(p));
    h.Add(a, sizeof(a));
  }
  if (vtkCellArray* polys = mesh->GetPolys())
  {
    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
    {
      polys->GetCellAtId(c, ids);
      h.AddValue(static_cast<long long>(ids->GetNumberOfIds()));
      for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      {
        h.AddValue(static_cast<long long>(ids->GetId(k)));
      }
    }
  }
}

bool FileExists(const std::string& path)
{
  struct stat st;
  return stat(path.c_str(), &st) == 0;
}
} // namespace

vtkPGILightCloudPrecompute::vtkPGILightCloudPrecompute()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(1);
  this->SetAlbedoArrayName("Albedo");
}

vtkPGILightCloudPrecompute::~vtkPGILightCloudPrecompute()
{
  this->SetLightPositions(nullptr);
  this->SetAlbedoArrayName(nullptr);
  this->SetCacheFileName(nullptr);
}

vtkMTimeType vtkPGILightCloudPrecompute::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->LightPositions)
  {
    t = std::max(t, this->LightPositions->GetMTime());
  }
  return t;
}

vtkPGILightCloud* vtkPGILightCloudPrecompute::GetOutput()
{
  return vtkPGILightCloud::SafeDownCast(this->GetOutputDataObject(0));
}

int vtkPGILightCloudPrecompute::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  }
  return 1;
}

int vtkPGILightCloudPrecompute::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkPGILightCloud");
  return 1;
}

vtkTypeBool vtkPGILightCloudPrecompute::ProcessRequest(
  vtkInformation* request, vtkInformationVector** in, vtkInformationVector* out)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_OBJECT()))
  {
    vtkPGILightCloud::EnsureOutput(out);
    return 1;
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return this->RequestData(request, in, out);
  }
  return this->Superclass::ProcessRequest(request, in, out);
}

int vtkPGILightCloudPrecompute::RequestData(
  vtkInformation*, vtkInformationVector** in, vtkInformationVector* out)
{
  vtkNew<vtkTimerLog> timer;
  timer->StartTimer();
  this->LightsTraced = this->LightsFromCache = 0;
  this->RayCount = this->Seconds = 0.0;
  vtkPolyData* receivers = vtkPolyData::GetData(in[0]);
  vtkPGILightCloud* cloud = vtkPGILightCloud::GetData(out);
  if (!receivers || receivers->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro(<< "No receivers: input 0 is empty.");
    return 0;
  }
  if (!FinitePoints(receivers))
  {
    vtkErrorMacro(<< "The receivers hold NaN or Inf points.");
    return 0;
  }
  std::vector<vtkPolyData*> objects;
  for (int c = 0; c < this->GetNumberOfInputConnections(1); ++c)
  {
    vtkPolyData* object = vtkPolyData::GetData(in[1], c);
    if (object && !FinitePoints(object))
    {
      vtkErrorMacro(<< "Scene object " << c << " holds NaN or Inf points.");
      return 0;
    }
    if (object)
    {
      objects.push_back(object);
    }
  }

  // The scene's box, for the default region and the clamp distance.
  double box[6];
  receivers->GetBounds(box);
  for (vtkPolyData* object : objects)
  {
    double b[6];
    object->GetBounds(b);
    for (int k = 0; k < 3; ++k)
    {
      box[2 * k] = std::min(box[2 * k], b[2 * k]);
      box[2 * k + 1] = std::max(box[2 * k + 1], b[2 * k + 1]);
    }
  }
  const double diagonal = std::sqrt((box[1] - box[0]) * (box[1] - box[0]) +
    (box[3] - box[2]) * (box[3] - box[2]) + (box[5] - box[4]) * (box[5] - box[4]));
  const double clamp = this->ClampDistance > 0.0 ? this->ClampDistance : 1e-3 * diagonal;

  // The cloud lights.
  std::vector<double> lights;
  if (this->LightPositions)
  {
    for (vtkIdType j = 0; j < this->LightPositions->GetNumberOfPoints(); ++j)
    {
      double p[3];
      this->LightPositions->GetPoint(j, p);
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      {
        vtkErrorMacro(<< "Cloud light " << j << " has a NaN or Inf position.");
        return 0;
      }
      lights.insert(lights.end(), p, p + 3);
    }
  }
  else
  {
    const double* r = this->RegionOfInterest;
    const bool own = r[0] < r[1] && r[2] < r[3] && r[4] < r[5];
    for (double v : this->RegionOfInterest)
    {
      if (own && !std::isfinite(v))
      {
        vtkErrorMacro(<< "RegionOfInterest holds NaN or Inf.");
        return 0;
      }
    }
    const double* region = own ? r : box;
    const int* res = this->GridResolution;
    if (res[0] < 1 || res[1] < 1 || res[2] < 1)
    {
      vtkErrorMacro(<< "GridResolution must be at least 1 along each axis.");
      return 0;
    }
    for (int k = 0; k < res[2]; ++k)
    {
      for (int j = 0; j < res[1]; ++j)
      {
        for (int i = 0; i < res[0]; ++i)
        {
          const int idx[3] = { i, j, k };
          for (int a = 0; a < 3; ++a)
          {
            // Cell centres: never on the region's walls.
            lights.push_back(
              region[2 * a] + (idx[a] + 0.5) * (region[2 * a + 1] - region[2 * a]) / res[a]);
          }
        }
      }
    }
  }
  if (lights.empty())
  {
    vtkErrorMacro(<< "No cloud lights: the light positions are empty.");
    return 0;
  }

  // The scene on Embree.
  std::string error;
  proxygi::ReferenceTracer tracer;
  bool ok =
    proxygi::AddPolyData(tracer, receivers, this->DefaultAlbedo, this->AlbedoArrayName, error);
  for (std::size_t c = 0; ok && c < objects.size(); ++c)
  {
    ok =
      proxygi::AddPolyData(tracer, objects[c], this->DefaultAlbedo, this->AlbedoArrayName, error);
  }
  ok = ok && tracer.Commit(error);
  if (!ok)
  {
    vtkErrorMacro(<< "Cannot build the scene: " << error);
    return 0;
  }

  // Lights inside solids light nothing: left out. Lights almost on a
  // surface have a response too peaked to interpolate (1/d^2): moved off
  // it to the margin, on both sides when the surface is a thin wall, so a
  // grid plane that falls on a wall leaves no gap of two cells.
  // Moved lights stay inside the grid's region (the given lights' bounds).
  double keepBox[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  if (this->LightPositions)
  {
    for (std::size_t j = 0; j < lights.size(); ++j)
    {
      const int a = static_cast<int>(j % 3);
      keepBox[2 * a] = std::min(keepBox[2 * a], lights[j]);
      keepBox[2 * a + 1] = std::max(keepBox[2 * a + 1], lights[j]);
    }
  }
  else
  {
    const double* r = this->RegionOfInterest;
    const bool own = r[0] < r[1] && r[2] < r[3] && r[4] < r[5];
    std::copy(own ? r : box, (own ? r : box) + 6, keepBox);
  }
  double margin = this->SurfaceMargin;
  if (margin < 0.0)
  {
    double spacing = 0.0;
    if (this->LightPositions)
    {
      vtkNew<vtkPGILightCloud> probe;
      probe->Allocate(static_cast<vtkIdType>(lights.size() / 3), 0);
      for (std::size_t j = 0; j < lights.size() / 3; ++j)
      {
        probe->GetLightPositions()->SetPoint(static_cast<vtkIdType>(j), &lights[3 * j]);
      }
      spacing = probe->GetSpacing();
    }
    else
    {
      const double* r = this->RegionOfInterest;
      const bool own = r[0] < r[1] && r[2] < r[3] && r[4] < r[5];
      const double* region = own ? r : box;
      spacing = VTK_DOUBLE_MAX;
      for (int a = 0; a < 3; ++a)
      {
        spacing = std::min(spacing, (region[2 * a + 1] - region[2 * a]) / this->GridResolution[a]);
      }
    }
    margin = 0.25 * spacing;
  }
  this->LightsDropped = 0;
  this->LightsMoved = 0;
  if (margin > 0.0)
  {
    const int rays = 26;
    std::vector<double> kept;
    for (std::size_t j = 0; j < lights.size() / 3; ++j)
    {
      const double* p = &lights[3 * j];
      const proxygi::ReferenceTracer::PointPlace place = tracer.PlacePoint(p, rays);
      if (!place.Inside && place.NearestHit >= margin)
      {
        kept.insert(kept.end(), p, p + 3);
        continue;
      }
      bool moved = false;
      if (!place.Inside)
      {
        // Back from the nearest surface to the margin, and across it.
        const double* d = place.NearestDirection;
        for (double along : { place.NearestHit - margin, place.NearestHit + margin })
        {
          const double q[3] = { p[0] + along * d[0], p[1] + along * d[1], p[2] + along * d[2] };
          bool inBox = true;
          for (int a = 0; a < 3; ++a)
          {
            // Half a margin of slack: the nearest ray is not quite the normal.
            inBox = inBox && q[a] >= keepBox[2 * a] - 0.5 * margin &&
              q[a] <= keepBox[2 * a + 1] + 0.5 * margin;
          }
          if (!inBox)
          {
            continue;
          }
          const proxygi::ReferenceTracer::PointPlace there = tracer.PlacePoint(q, rays);
          if (!there.Inside && there.NearestHit >= 0.5 * margin)
          {
            kept.insert(kept.end(), q, q + 3);
            moved = true;
          }
        }
      }
      ++(moved ? this->LightsMoved : this->LightsDropped);
    }
    lights.swap(kept);
  }
  const vtkIdType lightCount = static_cast<vtkIdType>(lights.size() / 3);
  if (lightCount == 0)
  {
    vtkErrorMacro(<< "No cloud lights left: all " << this->LightsDropped
                  << " lie inside solids or nearer a surface than SurfaceMargin (" << margin
                  << ").");
    return 0;
  }

  std::vector<double> normal;
  if (!proxygi::ReceiverNormals(receivers, normal, error))
  {
    vtkErrorMacro(<< "Receivers: " << error << ".");
    return 0;
  }
  const vtkIdType n = receivers->GetNumberOfPoints();
  std::vector<double> albedo(3 * n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    proxygi::AlbedoOf(receivers, this->AlbedoArrayName, i, this->DefaultAlbedo, &albedo[3 * i]);
  }

  // Everything the cloud depends on.
  Fnv key;
  HashMesh(key, receivers, this->AlbedoArrayName, this->DefaultAlbedo);
  key.Add(normal.data(), normal.size() * sizeof(double));
  for (vtkPolyData* object : objects)
  {
    HashMesh(key, object, this->AlbedoArrayName, this->DefaultAlbedo);
  }
  key.Add(lights.data(), lights.size() * sizeof(double));
  key.AddValue(this->Samples);
  key.AddValue(this->IncludeDirect);
  key.AddValue(this->Seed);
  key.AddValue(clamp);
  const bool glossy = this->SpecularAlbedo > 0.0;
  if (glossy)
  {
    key.AddValue(this->SpecularAlbedo);
    key.AddValue(this->PhongExponent);
    key.AddValue(this->GlossyOrder);
  }
  const int coefficients = glossy ? this->GlossyOrder * this->GlossyOrder : 1;
  const int stride = 3 * coefficients;

  cloud->Initialize();
  cloud->Allocate(lightCount, n, coefficients);
  for (vtkIdType j = 0; j < lightCount; ++j)
  {
    cloud->GetLightPositions()->SetPoint(j, &lights[3 * j]);
  }
  cloud->SetContents(
    this->IncludeDirect ? vtkPGILightCloud::DirectAndIndirect : vtkPGILightCloud::IndirectOnly);
  cloud->SetSamples(this->Samples);
  cloud->SetReceiverKey(vtkPGILightCloud::ReceiverKeyOf(receivers));

  // The cache: whole, partial (resume) or for something else (replace).
  std::vector<char> done(static_cast<std::size_t>(lightCount), 0);
  const std::string cachePath = this->CacheFileName ? this->CacheFileName : "";
  bool appendToCache = false;
  if (!cachePath.empty() && FileExists(cachePath))
  {
    vtkNew<vtkPGILightCloud> cached;
    proxygi::LightCloudFileInfo info;
    if (!proxygi::ReadLightCloud(cachePath, cached, info, error))
    {
      vtkErrorMacro(<< error << " (delete the file to recompute the cloud)");
      return 0;
    }
    if (info.Key == key.Value && cached->GetNumberOfLights() == lightCount &&
      cached->GetNumberOfReceivers() == n && cached->GetCoefficients() == coefficients)
    {
      for (vtkIdType j = 0; j < lightCount; ++j)
      {
        if (info.Present[j])
        {
          std::copy_n(cached->GetResponse(j), stride * n, cloud->GetResponse(j));
          done[j] = 1;
        }
      }
      this->LightsFromCache = info.LightsRead;
      appendToCache = !info.TornTail;
      if (info.TornTail)
      {
        vtkWarningMacro(<< "The cache '" << cachePath
                        << "' ends inside a record (a stopped run); resuming from "
                        << info.LightsRead << " of " << lightCount << " lights.");
      }
    }
    else
    {
      vtkWarningMacro(<< "The cache '" << cachePath
                      << "' holds another scene's or settings' cloud; recomputing it.");
    }
  }
  if (!cachePath.empty() && !appendToCache && this->LightsFromCache < lightCount)
  {
    // A fresh file, with the lights already known written back first.
    std::vector<vtkIdType> known;
    for (vtkIdType j = 0; j < lightCount; ++j)
    {
      if (done[j])
      {
        known.push_back(j);
      }
    }
    if (!proxygi::WriteLightCloudHeader(cachePath, cloud, key.Value, error) ||
      !proxygi::AppendLightCloudRecords(cachePath, cloud, known, error))
    {
      vtkWarningMacro(<< error << "; going on without a cache.");
    }
    else
    {
      appendToCache = true;
    }
  }
  if (this->LightsFromCache == lightCount && !this->Compress)
  {
    this->UpdateProgress(1.0);
    timer->StopTimer();
    this->Seconds = timer->GetElapsedTime();
    return 1;
  }

  const double offset = tracer.GetRayOffset();

  // Gather hits once per receiver; every light then lights the same hits,
  // so the responses of neighbouring lights share their noise (smooth
  // interpolation between them).
  std::vector<std::vector<proxygi::ReferenceTracer::GatherHit>> hits(static_cast<std::size_t>(n));
  vtkSMPTools::For(0, n,
    [&](vtkIdType first, vtkIdType last)
    {
      for (vtkIdType i = first; i < last; ++i)
      {
        double x[3];
        receivers->GetPoint(i, x);
        tracer.GatherHits(
          x, &normal[3 * i], this->Seed, static_cast<std::uint64_t>(i), this->Samples, hits[i]);
      }
    });
  this->UpdateProgress(0.05);

  std::vector<vtkIdType> todo;
  for (vtkIdType j = 0; j < lightCount; ++j)
  {
    if (!done[j])
    {
      todo.push_back(j);
    }
  }
  const double clamp2 = clamp * clamp;
  const double invSamples = 1.0 / this->Samples;
  const proxygi::GlossyProjection projection(this->GlossyOrder, this->PhongExponent);
  // What a gather hit passes on from a unit light at p, per unit albedo:
  // its irradiance over Samples (0 when the light does not reach it).
  auto hitGain = [&](const proxygi::ReferenceTracer::GatherHit& hit, const double* p)
  {
    const double y[3] = { hit.Position[0], hit.Position[1], hit.Position[2] };
    const double w[3] = { p[0] - y[0], p[1] - y[1], p[2] - y[2] };
    const double d2 = vtkMath::Dot(w, w);
    const double c = (hit.Normal[0] * w[0] + hit.Normal[1] * w[1] + hit.Normal[2] * w[2]) /
      std::sqrt(std::max(d2, 1e-300));
    return c > 0.0 && !tracer.SegmentBlocked(y, p) ? c / std::max(d2, clamp2) * invSamples : 0.0;
  };
  // A glossy receiver's frame, its gather hits' lobes (light-independent)
  // and the irradiance each hit brings; rebuilt per receiver and block.
  struct GlossyReceiver
  {
    vtkIdType Id = -1;
    double Frame[9];
    std::vector<double> ToWorld, Transfer, Local;
  };
  auto glossyResponse = [&](const double* p, vtkIdType i, GlossyReceiver& g, float* out)
  {
    double x[3];
    receivers->GetPoint(i, x);
    const double* nrm = &normal[3 * i];
    const std::size_t count = hits[i].size();
    if (g.Id != i)
    {
      g.Id = i;
      projection.Frame(nrm, g.Frame, g.ToWorld);
      std::vector<double> directions(3 * count);
      for (std::size_t s = 0; s < count; ++s)
      {
        double w[3] = { hits[i][s].Position[0] - x[0], hits[i][s].Position[1] - x[1],
          hits[i][s].Position[2] - x[2] };
        vtkMath::Normalize(w);
        proxygi::GlossyProjection::ToLocal(g.Frame, w, &directions[3 * s]);
      }
      projection.Lobes(directions.data(), static_cast<int>(count), g.Transfer);
    }
    const double o[3] = { x[0] + offset * nrm[0], x[1] + offset * nrm[1], x[2] + offset * nrm[2] };
    // Local coefficients, coefficient-major, RGB inside.
    g.Local.assign(static_cast<std::size_t>(stride), 0.0);
    double e[3] = { 0, 0, 0 };
    if (this->IncludeDirect)
    {
      double w[3] = { p[0] - x[0], p[1] - x[1], p[2] - x[2] };
      const double d2 = vtkMath::Dot(w, w);
      const double c = vtkMath::Dot(nrm, w) / std::sqrt(std::max(d2, 1e-300));
      if (c > 0.0 && !tracer.SegmentBlocked(o, p))
      {
        const double irradiance = c / std::max(d2, clamp2);
        e[0] = e[1] = e[2] = irradiance;
        vtkMath::Normalize(w);
        double local[3];
        proxygi::GlossyProjection::ToLocal(g.Frame, w, local);
        std::vector<double> lobe(static_cast<std::size_t>(coefficients), 0.0);
        projection.AddLobe(local, this->SpecularAlbedo * irradiance, lobe.data());
        for (int c2 = 0; c2 < coefficients; ++c2)
        {
          for (int k = 0; k < 3; ++k)
          {
            g.Local[3 * c2 + k] += lobe[c2];
          }
        }
      }
    }
    for (std::size_t s = 0; s < count; ++s)
    {
      const auto& hit = hits[i][s];
      const double gain = hitGain(hit, p);
      if (gain > 0.0)
      {
        for (int k = 0; k < 3; ++k)
        {
          const double irradiance = hit.Albedo[k] * gain;
          e[k] += irradiance;
          for (int c2 = 0; c2 < coefficients; ++c2)
          {
            g.Local[3 * c2 + k] += this->SpecularAlbedo * irradiance * g.Transfer[c2 * count + s];
          }
        }
      }
    }
    // The Lambert part is constant over the hemisphere: coefficient 0.
    for (int k = 0; k < 3; ++k)
    {
      g.Local[k] +=
        albedo[3 * i + k] / vtkMath::Pi() * e[k] * proxygi::GlossyProjection::ConstantCoefficient();
    }
    for (int r = 0; r < coefficients; ++r)
    {
      for (int k = 0; k < 3; ++k)
      {
        double v = 0.0;
        for (int c2 = 0; c2 < coefficients; ++c2)
        {
          v += g.ToWorld[static_cast<std::size_t>(r) * coefficients + c2] * g.Local[3 * c2 + k];
        }
        out[3 * r + k] = static_cast<float>(v);
      }
    }
  };
  // Receiver i's exit radiance from a unit point light at p.
  auto response = [&](const double* p, vtkIdType i, float* out)
  {
    if (glossy)
    {
      GlossyReceiver g;
      glossyResponse(p, i, g, out);
      return;
    }
    double x[3];
    receivers->GetPoint(i, x);
    const double* nrm = &normal[3 * i];
    const double o[3] = { x[0] + offset * nrm[0], x[1] + offset * nrm[1], x[2] + offset * nrm[2] };
    double e[3] = { 0, 0, 0 };
    if (this->IncludeDirect)
    {
      // The geometry from x itself; the offset is the ray's alone.
      const double w[3] = { p[0] - x[0], p[1] - x[1], p[2] - x[2] };
      const double d2 = vtkMath::Dot(w, w);
      const double c = vtkMath::Dot(nrm, w) / std::sqrt(std::max(d2, 1e-300));
      if (c > 0.0 && !tracer.SegmentBlocked(o, p))
      {
        e[0] = e[1] = e[2] = c / std::max(d2, clamp2);
      }
    }
    for (const auto& hit : hits[i])
    {
      const double g = hitGain(hit, p);
      for (int k = 0; k < 3; ++k)
      {
        e[k] += hit.Albedo[k] * g;
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      out[k] = static_cast<float>(albedo[3 * i + k] / vtkMath::Pi() * e[k]);
    }
  };
  // Glossy receivers share their lobes over a block: larger blocks.
  const std::size_t block = glossy ? 16 : 4;
  for (std::size_t b0 = 0; b0 < todo.size() && !this->GetAbortExecute(); b0 += block)
  {
    const std::size_t b1 = std::min(todo.size(), b0 + block);
    vtkSMPTools::For(0, n,
      [&](vtkIdType first, vtkIdType last)
      {
        GlossyReceiver g;
        for (vtkIdType i = first; i < last; ++i)
        {
          for (std::size_t b = b0; b < b1; ++b)
          {
            float* out = cloud->GetResponse(todo[b]) + stride * i;
            if (glossy)
            {
              glossyResponse(&lights[3 * todo[b]], i, g, out);
            }
            else
            {
              response(&lights[3 * todo[b]], i, out);
            }
          }
        }
      });
    std::vector<vtkIdType> finished(todo.begin() + static_cast<std::ptrdiff_t>(b0),
      todo.begin() + static_cast<std::ptrdiff_t>(b1));
    this->LightsTraced += static_cast<vtkIdType>(finished.size());
    if (appendToCache && !proxygi::AppendLightCloudRecords(cachePath, cloud, finished, error))
    {
      vtkWarningMacro(<< error << "; going on without a cache.");
      appendToCache = false;
    }
    this->UpdateProgress(0.05 + 0.95 * static_cast<double>(b1) / todo.size());
  }
  if (this->GetAbortExecute())
  {
    // The lights not reached are zero: not a cloud to relight from.
    vtkWarningMacro(<< "Aborted after " << this->LightsTraced + this->LightsFromCache << " of "
                    << lightCount << " lights"
                    << (appendToCache ? "; the cache resumes from there." : "."));
    cloud->Initialize();
  }
  else if (this->Compress)
  {
    // The compressed cloud has a cache of its own beside the dense one,
    // keyed by the dense cloud and the compression's knobs.
    Fnv compressionKey;
    compressionKey.AddValue(key.Value);
    compressionKey.AddValue(this->ZoneSize);
    compressionKey.AddValue(this->MaximumZones);
    compressionKey.AddValue(this->MergeDistance);
    compressionKey.AddValue(this->MergeTolerance);
    compressionKey.AddValue(this->MergedResponse);
    compressionKey.AddValue(this->PCAClusters);
    compressionKey.AddValue(this->VectorsPerReceiver);
    compressionKey.AddValue(this->PCAIterations);
    const std::string compressedPath = cachePath.empty() ? "" : cachePath + ".compressed";
    this->CompressedFromCache = false;
    if (!compressedPath.empty() && FileExists(compressedPath))
    {
      vtkNew<vtkPGILightCloud> cached;
      proxygi::LightCloudFileInfo info;
      if (proxygi::ReadLightCloud(compressedPath, cached, info, error) &&
        info.Key == compressionKey.Value && cached->IsCompressed() &&
        cached->GetNumberOfReceivers() == n && cached->GetCoefficients() == coefficients)
      {
        cloud->SetZones(cached->GetZones());
        this->CompressionSeconds = 0.0;
        this->PCARelativeError = 0.0;
        this->CompressedLights = 0.0;
        for (const vtkPGILightCloud::Zone& zone : cloud->GetZones())
        {
          const std::size_t zoneLights = zone.Lights.size() / 3;
          this->CompressedLights += static_cast<double>(zoneLights) *
            static_cast<double>(zone.Receivers.size()) / static_cast<double>(n);
        }
        this->CompressedFromCache = true;
      }
      else
      {
        vtkWarningMacro(<< "The compressed cache '" << compressedPath << "' "
                        << (error.empty() ? "holds another cloud" : error)
                        << "; compressing again.");
        error.clear();
      }
    }
    if (!this->CompressedFromCache)
    {
      vtkNew<vtkTimerLog> compressTimer;
      compressTimer->StartTimer();
      this->CompressCloud(cloud, receivers, lights, tracer, response);
      compressTimer->StopTimer();
      this->CompressionSeconds = compressTimer->GetElapsedTime();
      if (!compressedPath.empty() &&
        !proxygi::WriteLightCloud(compressedPath, cloud, compressionKey.Value, error))
      {
        vtkWarningMacro(<< error << "; the compressed cloud is not cached.");
      }
    }
  }
  this->RayCount = static_cast<double>(tracer.GetRayCount());
  timer->StopTimer();
  this->Seconds = timer->GetElapsedTime();
  return 1;
}

void vtkPGILightCloudPrecompute::CompressCloud(vtkPGILightCloud* cloud, vtkPolyData* receivers,
  const std::vector<double>& lights, const proxygi::ReferenceTracer& tracer,
  const std::function<void(const double*, vtkIdType, float*)>& response)
{
  const vtkIdType n = receivers->GetNumberOfPoints();
  const int stride = cloud->GetValuesPerReceiver();
  const vtkIdType lightCount = static_cast<vtkIdType>(lights.size() / 3);
  const std::size_t nl = static_cast<std::size_t>(lightCount);
  std::vector<double> points(static_cast<std::size_t>(3 * n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    receivers->GetPoint(i, &points[3 * i]);
  }
  const auto zoneIds = proxygi::SplitIntoZones(points, this->ZoneSize, this->MaximumZones);
  const double mergeDistance =
    this->MergeDistance > 0.0 ? this->MergeDistance : 2.0 * cloud->GetSpacing();
  const double w1 = mergeDistance > 0.0 ? 1.0 / mergeDistance : 0.0;

  // Mutual visibility of the lights close enough to merge (V_jk).
  std::vector<char> visible(nl * nl, 0);
  vtkSMPTools::For(0, lightCount,
    [&](vtkIdType first, vtkIdType last)
    {
      for (vtkIdType j = first; j < last; ++j)
      {
        visible[j * nl + j] = 1;
        for (vtkIdType k = j + 1; k < lightCount; ++k)
        {
          const double* p = &lights[3 * j];
          const double* q = &lights[3 * k];
          const double d2 = vtkMath::Distance2BetweenPoints(p, q);
          if (w1 * std::sqrt(d2) < 1.0 && !tracer.SegmentBlocked(p, q))
          {
            visible[j * nl + k] = 1;
          }
        }
      }
    });
  for (std::size_t j = 0; j < nl; ++j)
  {
    for (std::size_t k = 0; k < j; ++k)
    {
      visible[j * nl + k] = visible[k * nl + j];
    }
  }

  std::vector<vtkPGILightCloud::Zone> zones;
  this->CompressedLights = 0.0;
  double squaredError = 0.0, squared = 0.0;
  for (std::size_t z = 0; z < zoneIds.size() && !this->GetAbortExecute(); ++z)
  {
    vtkPGILightCloud::Zone zone;
    zone.Receivers = zoneIds[z];
    const vtkIdType r = static_cast<vtkIdType>(zone.Receivers.size());
    // The zone's dense responses, light-major.
    std::vector<std::vector<float>> dense(
      nl, std::vector<float>(static_cast<std::size_t>(stride) * static_cast<std::size_t>(r)));
    double largest = 0.0;
    for (std::size_t j = 0; j < nl; ++j)
    {
      const float* all = cloud->GetResponse(static_cast<vtkIdType>(j));
      for (vtkIdType c = 0; c < r; ++c)
      {
        for (int k = 0; k < stride; ++k)
        {
          dense[j][stride * c + k] = all[stride * zone.Receivers[c] + k];
          largest = std::max(largest, static_cast<double>(std::fabs(dense[j][stride * c + k])));
        }
      }
    }
    std::vector<const float*> pointers(nl);
    for (std::size_t j = 0; j < nl; ++j)
    {
      pointers[j] = dense[j].data();
    }
    const double w2 = largest > 0.0 ? 1.0 / (this->MergeTolerance * largest) : 0.0;
    const proxygi::MergedLights merged =
      proxygi::ClusterLights(pointers, lights, r, w1, w2, visible, stride);
    const int k = static_cast<int>(merged.Members.size());
    zone.Lights = merged.Positions;
    for (const auto& members : merged.Members)
    {
      zone.LightMembers.push_back(static_cast<int>(members.size()));
    }
    // Rows: per receiver, its values (RGB per coefficient) per cluster light.
    zone.Dimension = stride * k;
    std::vector<float> rows(static_cast<std::size_t>(r) * zone.Dimension, 0.0f);
    vtkSMPTools::For(0, r,
      [&](vtkIdType first, vtkIdType last)
      {
        for (vtkIdType c = first; c < last; ++c)
        {
          float* row = &rows[static_cast<std::size_t>(c) * zone.Dimension];
          for (int q = 0; q < k; ++q)
          {
            const auto& members = merged.Members[q];
            if (this->MergedResponse == RECOMPUTED_RESPONSE && members.size() > 1)
            {
              response(&zone.Lights[3 * q], zone.Receivers[c], row + stride * q);
              continue;
            }
            for (vtkIdType m : members)
            {
              for (int a = 0; a < stride; ++a)
              {
                row[stride * q + a] +=
                  dense[m][stride * c + a] / static_cast<float>(members.size());
              }
            }
          }
        }
      });
    const proxygi::ClusteredPCACode code = proxygi::ClusteredPCA(rows, r, zone.Dimension,
      this->PCAClusters, this->VectorsPerReceiver, this->PCAIterations, this->Seed + z);
    zone.Cluster = code.Cluster;
    zone.Means = code.Means;
    zone.BasisStart = code.BasisStart;
    zone.BasisCount = code.BasisCount;
    zone.Basis = code.Basis;
    zone.WeightStart = code.WeightStart;
    zone.Weights = code.Weights;
    squaredError += code.SquaredError;
    squared += code.Squared;
    this->CompressedLights += static_cast<double>(k) * r / n;
    zones.push_back(std::move(zone));
    this->UpdateProgress(0.95 + 0.05 * static_cast<double>(z + 1) / zoneIds.size());
  }
  if (this->GetAbortExecute())
  {
    vtkWarningMacro(<< "Aborted while compressing; the output is the dense cloud.");
    return;
  }
  this->PCARelativeError = squared > 0.0 ? std::sqrt(squaredError / squared) : 0.0;
  cloud->SetZones(std::move(zones));
}

void vtkPGILightCloudPrecompute::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const double* r = this->RegionOfInterest;
  os << indent << "RegionOfInterest: " << r[0] << " " << r[1] << " " << r[2] << " " << r[3] << " "
     << r[4] << " " << r[5] << "\n";
  os << indent << "GridResolution: " << this->GridResolution[0] << " " << this->GridResolution[1]
     << " " << this->GridResolution[2] << "\n";
  os << indent
     << "LightPositions: " << (this->LightPositions ? this->LightPositions->GetNumberOfPoints() : 0)
     << "\n";
  os << indent << "Samples: " << this->Samples << "\n";
  os << indent << "IncludeDirect: " << this->IncludeDirect << "\n";
  os << indent << "SpecularAlbedo: " << this->SpecularAlbedo
     << ", PhongExponent: " << this->PhongExponent << ", GlossyOrder: " << this->GlossyOrder
     << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "ClampDistance: " << this->ClampDistance << "\n";
  os << indent << "CacheFileName: " << (this->CacheFileName ? this->CacheFileName : "(none)")
     << "\n";
  os << indent << "SurfaceMargin: " << this->SurfaceMargin
     << " (last update: " << this->LightsDropped << " lights left out, " << this->LightsMoved
     << " moved)\n";
  os << indent << "Compress: " << this->Compress << ", ZoneSize: " << this->ZoneSize
     << ", MaximumZones: " << this->MaximumZones << "\n";
  os << indent << "MergeDistance: " << this->MergeDistance
     << ", MergeTolerance: " << this->MergeTolerance << ", MergedResponse: "
     << (this->MergedResponse == RECOMPUTED_RESPONSE ? "recomputed" : "averaged") << "\n";
  os << indent << "PCAClusters: " << this->PCAClusters
     << ", VectorsPerReceiver: " << this->VectorsPerReceiver
     << ", PCAIterations: " << this->PCAIterations << "\n";
  os << indent << "LightsTraced: " << this->LightsTraced
     << ", LightsFromCache: " << this->LightsFromCache << ", Seconds: " << this->Seconds << "\n";
  os << indent << "CompressedLights: " << this->CompressedLights
     << ", PCARelativeError: " << this->PCARelativeError
     << ", CompressionSeconds: " << this->CompressionSeconds << "\n";
}
