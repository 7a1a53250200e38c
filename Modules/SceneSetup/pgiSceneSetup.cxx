#include "pgiSceneSetup.h"

#include "vtkPGIGIBake.h"
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILighting.h"
#include "vtkPGIMeshOccluder.h"
#include "vtkPGIOcclusionFit.h"
#include "vtkPGIReferenceIllumination.h"
#include "vtkPGISelfVisibility.h"
#include "vtkPGISphereHierarchy.h"
#include "vtkPGISphereLightSampler.h"
#include "vtkPGISphereSetApproximation.h"

#include "vtkAppendPolyData.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"
#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>
#include <unistd.h>

namespace proxygi
{
namespace
{
using Clock = std::chrono::steady_clock;

// Updates a long filter under the monitor; false (error "interrupted") when it was stopped.
bool Run(vtkAlgorithm* filter, const std::string& what, SetupMonitor* monitor, std::string& error)
{
  if (monitor)
  {
    monitor->Begin(filter, what);
  }
  filter->Update();
  if ((monitor && !monitor->End(filter)) || filter->GetAbortExecute())
  {
    error = "interrupted while " + what;
    return false;
  }
  return true;
}

bool Exists(const std::string& path)
{
  return !path.empty() && static_cast<bool>(std::ifstream(path));
}

vtkSmartPointer<vtkPolyData> Read(const std::string& path)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* out = reader->GetOutput();
  return out && out->GetNumberOfPoints() > 0 ? vtkSmartPointer<vtkPolyData>(out) : nullptr;
}

// Cache entries appear whole or not at all: written aside, then renamed.
void Write(vtkPolyData* data, const std::string& path)
{
  // Per process: two runs filling one cache do not write the same file.
  const std::string aside = path + ".writing-" + std::to_string(getpid());
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetFileName(aside.c_str());
  writer->SetInputData(data);
  writer->SetDataModeToAppended();
  if (writer->Write() != 1 || std::rename(aside.c_str(), path.c_str()) != 0)
  {
    std::remove(aside.c_str());
  }
}

// A cache key that changes whenever what the cached data depends on does.
std::string Key(const std::string& description)
{
  std::ostringstream s;
  s << std::hex << std::hash<std::string>()(description);
  return s.str();
}

double FieldValue(vtkPolyData* data, const char* name)
{
  vtkDataArray* a = data->GetFieldData()->GetArray(name);
  return a && a->GetNumberOfTuples() > 0 ? a->GetTuple1(0) : 0.0;
}

std::string Describe(const SceneObject& o)
{
  std::ostringstream s;
  s.precision(17);
  s << o.Name << '|' << o.MeshPath << '|' << static_cast<int>(o.Type) << '|' << o.Scale;
  for (int i = 0; i < 3; ++i)
  {
    s << '|' << o.Translate[i] << '|' << o.Rotate[i] << '|' << o.Albedo[i];
  }
  // The generated shapes' own geometry.
  if (o.Type == SceneObject::Kind::Plane)
  {
    s << "|plane" << o.PlaneSize << ',' << o.PlaneCorners << ',' << o.PlaneResolution[0] << ','
      << o.PlaneResolution[1];
    for (int i = 0; i < 3; ++i)
    {
      s << ',' << o.PlaneCenter[i] << ',' << o.PlaneOrigin[i] << ',' << o.PlanePoint1[i] << ','
        << o.PlanePoint2[i];
    }
  }
  else if (o.Type == SceneObject::Kind::Sphere)
  {
    s << "|sphere" << o.SphereRadius << ',' << o.SphereResolution;
    for (double c : o.SphereCenter)
    {
      s << ',' << c;
    }
  }
  else if (o.Type == SceneObject::Kind::Box)
  {
    s << "|box" << o.BoxResolution;
    for (int i = 0; i < 3; ++i)
    {
      s << ',' << o.BoxCenter[i] << ',' << o.BoxSize[i];
    }
  }
  return s.str();
}

} // namespace

std::string DescribeScene(const SceneDescription& scene)
{
  std::ostringstream s;
  s.precision(17);
  s << scene.Name << '|' << scene.EnvironmentMap << '|' << scene.EnvironmentRotation << '|'
    << scene.EnvironmentScale << '|' << scene.Lights.size();
  for (const SceneObject& o : scene.Objects)
  {
    s << '#' << Describe(o);
  }
  for (const SceneLight& l : scene.Lights)
  {
    s << '#' << l.Sphere << l.Position[0] << l.Position[1] << l.Position[2] << l.Radius
      << l.Value[0];
  }
  return s.str();
}

std::vector<vtkSmartPointer<vtkPolyData>> SceneReceivers(const LoadedScene& loaded)
{
  std::vector<vtkSmartPointer<vtkPolyData>> receivers;
  for (const auto& object : loaded.Objects)
  {
    const int index = static_cast<int>(receivers.size());
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(object);
    normals->SplittingOff();
    normals->ConsistencyOn();
    normals->AutoOrientNormalsOff();
    proxygi::UpdateNormals(normals);
    auto copy = vtkSmartPointer<vtkPolyData>::New();
    copy->DeepCopy(normals->GetOutput());
    // The object each receiver is on, as the proxies' ObjectId names it: a
    // plane's receivers own no spheres (no self-shadow rules for them).
    vtkNew<vtkIntArray> ids;
    ids->SetName("ObjectId");
    ids->SetNumberOfTuples(copy->GetNumberOfPoints());
    ids->FillValue(index);
    copy->GetPointData()->AddArray(ids);
    receivers.push_back(copy);
  }
  return receivers;
}

SetupMonitor::~SetupMonitor() = default;

bool BuildSceneProxies(const SceneDescription& scene, const LoadedScene& loaded, int spheresPerMesh,
  const std::string& cacheDir, SceneProxies& proxies, std::string& error, SetupMonitor* monitor,
  ProxyFit fit)
{
  const auto t0 = Clock::now();
  if (!cacheDir.empty())
  {
    vtksys::SystemTools::MakeDirectory(cacheDir); // with its parents
  }
  vtkNew<vtkPoints> centres;
  vtkNew<vtkFloatArray> radii, albedos;
  radii->SetName("Radius");
  albedos->SetName("Albedo");
  albedos->SetNumberOfComponents(3);
  vtkNew<vtkIntArray> objectIds;
  objectIds->SetName("ObjectId");
  proxies.Planes.clear();
  proxies.Fits.clear();
  proxies.Fit = fit;
  proxies.Cached = true;
  for (std::size_t k = 0; k < scene.Objects.size() && k < loaded.Objects.size(); ++k)
  {
    const SceneObject& object = scene.Objects[k];
    vtkPolyData* mesh = loaded.Objects[k];
    double b[6];
    mesh->GetBounds(b);
    const double centre[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
    if (object.Type == SceneObject::Kind::Plane)
    {
      double n[3] = { 0, 0, 1 };
      vtkNew<vtkPolyDataNormals> normals;
      normals->SetInputData(mesh);
      normals->ComputeCellNormalsOn();
      normals->ComputePointNormalsOff();
      normals->Update();
      if (vtkDataArray* cellNormals = normals->GetOutput()->GetCellData()->GetNormals())
      {
        cellNormals->GetTuple(0, n);
      }
      double middle[3], e1[3], e2[3];
      PlaneExtent(object, middle, e1, e2);
      proxies.Planes.push_back(
        { middle[0], middle[1], middle[2], n[0], n[1], n[2], object.Albedo[0], object.Albedo[1],
          object.Albedo[2], e1[0], e1[1], e1[2], e2[0], e2[1], e2[2] });
      continue;
    }
    if (object.Type == SceneObject::Kind::Sphere)
    {
      centres->InsertNextPoint(centre);
      radii->InsertNextValue(static_cast<float>(0.5 * (b[1] - b[0])));
      albedos->InsertNextTuple(object.Albedo);
      objectIds->InsertNextValue(static_cast<int>(k));
      continue;
    }
    const std::string key = Describe(object) + '|' + std::to_string(spheresPerMesh) + '|' +
      std::to_string(mesh->GetNumberOfPoints());
    const std::string cached =
      cacheDir.empty() ? std::string() : cacheDir + "/proxies-" + Key(key) + ".vtp";
    vtkSmartPointer<vtkPolyData> set = Exists(cached) ? Read(cached) : nullptr;
    if (!set)
    {
      proxies.Cached = false;
      vtkNew<vtkPGISphereSetApproximation> approximation;
      approximation->SetInputData(mesh);
      approximation->SetNumberOfSpheres(spheresPerMesh);
      if (!Run(approximation, "building the proxies of '" + object.Name + "'", monitor, error))
      {
        return false;
      }
      set = approximation->GetOutput();
      if (!cached.empty() && set->GetNumberOfPoints() > 0)
      {
        Write(set, cached);
      }
    }
    if (fit == ProxyFit::Occlusion && set->GetNumberOfPoints() > 0)
    {
      const std::string fittedCache = cacheDir.empty()
        ? std::string()
        : cacheDir + "/proxies-" + Key(key + "|occlusion") + ".vtp";
      vtkSmartPointer<vtkPolyData> fitted = Exists(fittedCache) ? Read(fittedCache) : nullptr;
      if (!fitted)
      {
        proxies.Cached = false;
        vtkNew<vtkPGIOcclusionFit> occlusion;
        occlusion->SetInputData(set);
        occlusion->SetMeshData(mesh);
        if (!Run(occlusion, "fitting the proxies of '" + object.Name + "' for occlusion", monitor,
              error))
        {
          return false;
        }
        fitted = occlusion->GetOutput();
        if (!fittedCache.empty())
        {
          Write(fitted, fittedCache);
        }
      }
      SceneProxies::OcclusionFit report;
      report.Object = object.Name;
      report.ErrorBefore = FieldValue(fitted, "OcclusionErrorBefore");
      report.ErrorAfter = FieldValue(fitted, "OcclusionErrorAfter");
      report.BiasBefore = FieldValue(fitted, "OcclusionBiasBefore");
      report.BiasAfter = FieldValue(fitted, "OcclusionBiasAfter");
      proxies.Fits.push_back(report);
      set = fitted;
    }
    vtkDataArray* r = set->GetPointData()->GetArray("Radius");
    vtkDataArray* level = set->GetPointData()->GetArray("Level");
    if (!r || set->GetNumberOfPoints() == 0)
    {
      error = "no sphere proxies could be built for '" + object.Name + "'";
      return false;
    }
    for (vtkIdType i = 0; i < set->GetNumberOfPoints(); ++i)
    {
      if (!level || level->GetTuple1(i) == 0.0)
      {
        centres->InsertNextPoint(set->GetPoint(i));
        radii->InsertNextValue(static_cast<float>(r->GetTuple1(i)));
        albedos->InsertNextTuple(object.Albedo);
        objectIds->InsertNextValue(static_cast<int>(k));
      }
    }
  }
  vtkNew<vtkPolyData> leaves;
  leaves->SetPoints(centres);
  leaves->GetPointData()->AddArray(radii);
  leaves->GetPointData()->AddArray(albedos);
  leaves->GetPointData()->AddArray(objectIds);
  proxies.Leaves = leaves->GetNumberOfPoints();
  if (proxies.Leaves > 0)
  {
    vtkNew<vtkPGISphereHierarchy> hierarchy;
    hierarchy->SetInputData(leaves);
    // Surface samples and albedo SH of every sphere, parents included, for
    // the shadowed one-bounce light (vtkPGIGlobalIllumination IndirectMode).
    vtkNew<vtkAppendPolyData> meshes;
    for (std::size_t k = 0; k < scene.Objects.size() && k < loaded.Objects.size(); ++k)
    {
      if (scene.Objects[k].Type == SceneObject::Kind::Plane)
      {
        continue;
      }
      vtkNew<vtkPolyData> mesh;
      mesh->ShallowCopy(loaded.Objects[k]);
      vtkNew<vtkIntArray> id;
      id->SetName("ObjectId");
      id->SetNumberOfTuples(mesh->GetNumberOfPoints());
      id->FillValue(static_cast<int>(k));
      mesh->GetPointData()->AddArray(id);
      meshes->AddInputData(mesh);
    }
    vtkNew<vtkPGISphereLightSampler> sampler;
    sampler->SetInputConnection(meshes->GetOutputPort());
    sampler->SetProxiesConnection(hierarchy->GetOutputPort());
    if (!Run(sampler, "sampling the proxies' surfaces", monitor, error))
    {
      return false;
    }
    proxies.Spheres = sampler->GetOutput();
    if (!proxies.Spheres || proxies.Spheres->GetNumberOfPoints() == 0)
    {
      error = "sampling the proxies' surfaces failed";
      return false;
    }
  }
  else
  {
    proxies.Spheres = leaves;
  }
  proxies.Seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return true;
}

void ConfigureGlobalIllumination(vtkPGIGlobalIllumination* gi, const SceneDescription& scene,
  const LoadedScene& loaded, const SceneProxies& proxies)
{
  gi->SetLighting(loaded.Lighting);
  gi->SetProxiesData(proxies.Spheres);
  gi->RemoveAllBlockerPlanes();
  for (const auto& p : proxies.Planes)
  {
    gi->AddBlockerPlane(p.data(), p.data() + 3, p.data() + 6, p.data() + 9, p.data() + 12);
  }
  ConfigureSettings(gi->GetSettings(), scene);
}

std::vector<vtkSmartPointer<vtkPolyData>> ShadeEach(
  vtkPGIGlobalIllumination* gi, const std::vector<vtkSmartPointer<vtkPolyData>>& receivers)
{
  std::vector<vtkSmartPointer<vtkPolyData>> shaded;
  for (const auto& receiver : receivers)
  {
    gi->SetInputData(receiver);
    gi->Update();
    // A shallow copy suffices: the filter gives the next update new arrays
    // while anyone else holds the last ones (a deep copy of the bunny's
    // output took 12 ms, 6% of the default scene's shading).
    auto copy = vtkSmartPointer<vtkPolyData>::New();
    copy->ShallowCopy(gi->GetOutput());
    shaded.push_back(copy);
  }
  return shaded;
}

void ConfigureSettings(vtkPGIGISettings* settings, const SceneDescription& scene)
{
  settings->SetShadows(scene.Shadows);
  settings->SetIndirect(scene.Indirect);
  settings->SetLocalLights(scene.LocalLights);
}

vtkSmartPointer<vtkPGIOccluder> SceneOccluder(
  const std::vector<vtkSmartPointer<vtkPolyData>>& receivers)
{
  auto occluder = vtkSmartPointer<vtkPGIMeshOccluder>::New();
  for (const auto& mesh : receivers)
  {
    occluder->AddMesh(mesh);
  }
  return occluder;
}

bool AddSelfVisibility(const SceneDescription& scene,
  std::vector<vtkSmartPointer<vtkPolyData>>& receivers, int order, int samples,
  const std::string& cacheDir, double& seconds, std::string& error, SetupMonitor* monitor)
{
  const auto t0 = Clock::now();
  bool traced = false;
  if (!cacheDir.empty())
  {
    vtksys::SystemTools::MakeDirectory(cacheDir);
  }
  const char* names[] = { "SelfLogVisibility", "SelfVisibilityRest", "ObjectId" };
  const char* fieldNames[] = { "SelfBounceOffsets", "SelfBounceTargets", "SelfBounceWeights",
    "SelfBounceHitPoints" };
  for (std::size_t k = 0; k < receivers.size() && k < scene.Objects.size(); ++k)
  {
    if (scene.Objects[k].Type != SceneObject::Kind::Mesh)
    {
      continue;
    }
    vtkPolyData* receiver = receivers[k];
    const vtkIdType n = receiver->GetNumberOfPoints();
    const std::string cached = cacheDir.empty() ? std::string()
                                                : cacheDir + "/self-visibility-" +
        Key(Describe(scene.Objects[k]) + '|' + std::to_string(n) + '|' + std::to_string(order) +
          '|' + std::to_string(samples) + "|nearest-corner bounce, front hits, hit points") +
        ".vtp";
    vtkSmartPointer<vtkPolyData> arrays = Exists(cached) ? Read(cached) : nullptr;
    if (arrays && arrays->GetNumberOfPoints() != n)
    {
      arrays = nullptr;
    }
    for (const char* name : names)
    {
      arrays = arrays && arrays->GetPointData()->GetArray(name) ? arrays : nullptr;
    }
    for (const char* name : fieldNames)
    {
      arrays = arrays && arrays->GetFieldData()->GetArray(name) ? arrays : nullptr;
    }
    if (!arrays)
    {
      traced = true;
      vtkNew<vtkPGISelfVisibility> self;
      self->SetInputData(receiver);
      self->SetOrder(order);
      self->SetSamples(samples);
      self->SetObjectId(static_cast<int>(k));
      if (!Run(
            self, "tracing the self-visibility of '" + scene.Objects[k].Name + "'", monitor, error))
      {
        return false;
      }
      if (self->GetOutput()->GetNumberOfPoints() != n)
      {
        error = "the self-visibility of '" + scene.Objects[k].Name + "' failed";
        return false;
      }
      arrays = vtkSmartPointer<vtkPolyData>::New();
      vtkNew<vtkPoints> points;
      points->DeepCopy(receiver->GetPoints());
      arrays->SetPoints(points);
      for (const char* name : names)
      {
        arrays->GetPointData()->AddArray(self->GetOutput()->GetPointData()->GetArray(name));
      }
      for (const char* name : fieldNames)
      {
        arrays->GetFieldData()->AddArray(self->GetOutput()->GetFieldData()->GetArray(name));
      }
      if (!cached.empty())
      {
        Write(arrays, cached);
      }
    }
    auto with = vtkSmartPointer<vtkPolyData>::New();
    with->ShallowCopy(receiver);
    for (const char* name : names)
    {
      with->GetPointData()->AddArray(arrays->GetPointData()->GetArray(name));
    }
    for (const char* name : fieldNames)
    {
      with->GetFieldData()->AddArray(arrays->GetFieldData()->GetArray(name));
    }
    receivers[k] = with;
  }
  seconds = traced ? std::chrono::duration<double>(Clock::now() - t0).count() : 0.0;
  return true;
}

std::vector<vtkSmartPointer<vtkPolyData>> SceneReference(const SceneDescription& scene,
  const LoadedScene& loaded, const std::vector<vtkSmartPointer<vtkPolyData>>& receivers, int spp,
  const std::string& cacheDir, const SceneProxies* proxies, double& seconds, std::string& error,
  unsigned int seed, bool traceMissing, SetupMonitor* monitor)
{
  std::vector<vtkSmartPointer<vtkPolyData>> result;
  seconds = 0.0;
  if (!cacheDir.empty())
  {
    vtksys::SystemTools::MakeDirectory(cacheDir); // with its parents
  }
  const std::string sceneKey = DescribeScene(scene);
  for (std::size_t k = 0; k < receivers.size(); ++k)
  {
    const std::string cached = cacheDir.empty() ? std::string()
                                                : cacheDir + "/reference-" +
        Key(sceneKey + '|' + std::to_string(k) + '|' +
          std::to_string(receivers[k]->GetNumberOfPoints()) +
          (proxies ? "|proxies" + std::to_string(proxies->Leaves) : std::string()) +
          (proxies && proxies->Fit == ProxyFit::Occlusion ? "|occlusion" : "") +
          (seed != 1 ? "|seed" + std::to_string(seed) : std::string())) +
        "-spp" + std::to_string(spp) + ".vtp";
    vtkSmartPointer<vtkPolyData> reference = Exists(cached) ? Read(cached) : nullptr;
    if (reference && reference->GetNumberOfPoints() == receivers[k]->GetNumberOfPoints())
    {
      double s = 0.0;
      std::ifstream(cached + ".seconds") >> s;
      seconds += s;
      result.push_back(reference);
      continue;
    }
    if (!traceMissing)
    {
      error = "not cached";
      return {};
    }
    vtkNew<vtkPGIReferenceIllumination> ref;
    ref->SetInputData(receivers[k]);
    // Proxy mode: the other objects' meshes are replaced by their spheres
    // (planes stay: they are exact in the SH filter too).
    for (std::size_t j = 0; j < loaded.Objects.size(); ++j)
    {
      if (j != k && (!proxies || scene.Objects[j].Type == SceneObject::Kind::Plane))
      {
        ref->AddSceneObjectData(loaded.Objects[j]);
      }
    }
    if (proxies)
    {
      vtkNew<vtkPolyData> others;
      vtkNew<vtkPoints> centres;
      vtkNew<vtkFloatArray> radii, albedos;
      radii->SetName("Radius");
      albedos->SetName("Albedo");
      albedos->SetNumberOfComponents(3);
      vtkDataArray* id = proxies->Spheres->GetPointData()->GetArray("ObjectId");
      vtkDataArray* r = proxies->Spheres->GetPointData()->GetArray("Radius");
      vtkDataArray* a = proxies->Spheres->GetPointData()->GetArray("Albedo");
      for (vtkIdType i = 0; i < proxies->Leaves; ++i)
      {
        if (static_cast<std::size_t>(id->GetTuple1(i)) != k)
        {
          centres->InsertNextPoint(proxies->Spheres->GetPoint(i));
          radii->InsertNextTuple(r->GetTuple(i));
          albedos->InsertNextTuple(a->GetTuple(i));
        }
      }
      others->SetPoints(centres);
      others->GetPointData()->AddArray(radii);
      others->GetPointData()->AddArray(albedos);
      ref->SetProxiesData(others);
      ref->UseProxiesOn();
    }
    ref->SetLighting(loaded.Lighting);
    ref->SetSamples(spp);
    ref->SetSeed(seed);
    const auto t0 = Clock::now();
    if (!Run(ref, "tracing the reference of '" + scene.Objects[k].Name + "'", monitor, error))
    {
      return {};
    }
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    seconds += s;
    reference = ref->GetOutput();
    if (!reference->GetPointData()->GetArray("Radiance"))
    {
      error = "the Embree reference failed for object '" + scene.Objects[k].Name + "'";
      return {};
    }
    if (!cached.empty())
    {
      Write(reference, cached);
      std::ofstream(cached + ".seconds") << s;
    }
    result.push_back(reference);
  }
  return result;
}

namespace
{
// Over the given objects (all when empty) and RGB components: the sums of
// |a - b|^2, of |b|^2 and, with `noiseB`, of b's standard error squared.
// False when an array is missing or the point counts differ.
bool DifferenceSums(const std::vector<vtkSmartPointer<vtkPolyData>>& a, const char* arrayA,
  const std::vector<vtkSmartPointer<vtkPolyData>>& b, const char* arrayB, const char* noiseB,
  const std::vector<std::size_t>& objects, double& sq, double& ref, double& noise)
{
  sq = ref = noise = 0.0;
  for (std::size_t k = 0; k < a.size() && k < b.size(); ++k)
  {
    if (!objects.empty() && std::find(objects.begin(), objects.end(), k) == objects.end())
    {
      continue;
    }
    vtkDataArray* x = a[k]->GetPointData()->GetArray(arrayA);
    vtkDataArray* y = b[k]->GetPointData()->GetArray(arrayB);
    vtkDataArray* s = noiseB ? b[k]->GetPointData()->GetArray(noiseB) : nullptr;
    if (!x || !y || (noiseB && !s) || x->GetNumberOfTuples() != y->GetNumberOfTuples())
    {
      return false;
    }
    for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        const double d = x->GetComponent(i, c) - y->GetComponent(i, c);
        sq += d * d;
        ref += y->GetComponent(i, c) * y->GetComponent(i, c);
        noise += s ? s->GetComponent(i, c) * s->GetComponent(i, c) : 0.0;
      }
    }
  }
  return true;
}
} // namespace

double RelativeRMSE(const std::vector<vtkSmartPointer<vtkPolyData>>& a, const char* arrayA,
  const std::vector<vtkSmartPointer<vtkPolyData>>& b, const char* arrayB,
  const std::vector<std::size_t>& objects)
{
  double sq = 0.0, ref = 0.0, noise = 0.0;
  if (!DifferenceSums(a, arrayA, b, arrayB, nullptr, objects, sq, ref, noise))
  {
    return std::nan("");
  }
  return ref > 0.0 ? std::sqrt(sq / ref) : 0.0;
}

double RelativeRMS(const std::vector<vtkSmartPointer<vtkPolyData>>& a, const char* arrayA,
  const char* arrayValue, const std::vector<std::size_t>& objects)
{
  double sq = 0.0, ref = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    if (!objects.empty() && std::find(objects.begin(), objects.end(), k) == objects.end())
    {
      continue;
    }
    vtkDataArray* x = a[k]->GetPointData()->GetArray(arrayA);
    vtkDataArray* y = a[k]->GetPointData()->GetArray(arrayValue);
    if (!x || !y)
    {
      return std::nan("");
    }
    for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        sq += x->GetComponent(i, c) * x->GetComponent(i, c);
        ref += y->GetComponent(i, c) * y->GetComponent(i, c);
      }
    }
  }
  return ref > 0.0 ? std::sqrt(sq / ref) : 0.0;
}

double EstimatedRelativeRMSE(const std::vector<vtkSmartPointer<vtkPolyData>>& a,
  const std::vector<vtkSmartPointer<vtkPolyData>>& cheap, int cheapSpp, int targetSpp)
{
  // E|a - b|^2 = |a - t|^2 + s^2 and E|b|^2 = |t|^2 + s^2 per component (s
  // the cheap run's standard error); a reference of targetSpp samples keeps
  // s^2 cheapSpp / targetSpp of that noise.
  const double removed = 1.0 - std::min(1.0, static_cast<double>(cheapSpp) / targetSpp);
  double sq = 0.0, ref = 0.0, noise = 0.0;
  if (!DifferenceSums(a, "Radiance", cheap, "Radiance", "RadianceStdErr", {}, sq, ref, noise))
  {
    return std::nan("");
  }
  const double signal = ref - removed * noise;
  return signal > 0.0 ? std::sqrt(std::max(0.0, sq - removed * noise) / signal) : 0.0;
}

} // namespace proxygi
