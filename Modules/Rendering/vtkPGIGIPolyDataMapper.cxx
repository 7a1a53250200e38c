#include "vtkPGIGIPolyDataMapper.h"

#include "pgiGIComputeFS.h"
#include "pgiGIComputeVS.h"
#include "pgiGIMapperFS.h"
#include "pgiGIMapperFSImpl.h"
#include "pgiGIMapperVS.h"
#include "pgiGIMapperVSImpl.h"
#include "pgiGIShaders.h"

#include "pgiEnvironmentMap.h"
#include "pgiEnvironmentShading.h"
#include "pgiIndirectLight.h"
#include "pgiMaterial.h"
#include "pgiSoftShadows.h"
#include "pgiSphericalLights.h"
#include "vtkPGILighting.h"

#include "vtkActor.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkTransformFeedback.h"
#include "vtk_glew.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

vtkStandardNewMacro(vtkPGIGIPolyDataMapper);
vtkCxxSetObjectMacro(vtkPGIGIPolyDataMapper, Proxies, vtkPolyData);
vtkCxxSetObjectMacro(vtkPGIGIPolyDataMapper, Lighting, vtkPGILighting);

struct vtkPGIGIPolyDataMapper::Internals
{
  proxygi::gpu::GIResources Resources;
  vtkOpenGLRenderWindow* Window = nullptr;
  // Receivers (positions, normals, albedo: 9 floats per point) and results.
  vtkNew<vtkOpenGLBufferObject> Receivers;
  vtkNew<vtkOpenGLBufferObject> Results;
  vtkNew<vtkOpenGLVertexArrayObject> VAO;
  vtkSmartPointer<vtkTransformFeedback> Capture;
  std::string CaptureKey;
  vtkIdType Points = 0;
  int ResultFloats = 0; // per point
  bool HaveResults = false;
  // What the last GI pass used, to skip it when nothing changed.
  vtkMTimeType InputTime = 0, ProxiesTime = 0, LightingTime = 0;
  std::string Settings; // the knobs GI depends on (exposure & co. do not count)
  std::string AlbedoArray;
  vtkPolyData* Input = nullptr;
  std::array<double, 16> Matrix{};
  int LightOrder = 0;
  std::vector<float> Spheres;
  int ProxyCount = 0;
  int ProgramHandle = 0;
  bool GIInShaders = false;
  // Planes carried by the light: their visibility (for xi); indirect: the
  // secondary lights' response (interleaved RGB), proxies' albedo texture.
  bool PlanesInLight = false;
  std::vector<float> PlaneVisibility;
  std::vector<float> Response;
  std::vector<float> Albedos;
  vtkSmartPointer<vtkTextureObject> ProxyAlbedo;
  // Local lights: centre and radius (-1: point light), radiance; 4 floats each.
  std::vector<float> LocalLights, LocalRadiance;
  // The light the proxies' samples see (L, or the light above the planes),
  // per channel, for the shadowed bounce's first pass; what it did.
  std::vector<double> SampleLight;
  int SphericalLightCount = 0;
  std::string SphericalLightSummary;
  bool WarnedBudget = false;
  vtkTimeStamp ShaderModeTime;
};

vtkPGIGIPolyDataMapper::vtkPGIGIPolyDataMapper()
  : GPU(new Internals)
{
  this->SetAlbedoArrayName("Albedo");
  this->SetProxyAlbedoArrayName("Albedo");
}

vtkPGIGIPolyDataMapper::~vtkPGIGIPolyDataMapper()
{
  this->SetProxies(nullptr);
  this->SetLighting(nullptr);
  this->SetAlbedoArrayName(nullptr);
  this->SetProxyAlbedoArrayName(nullptr);
}

void vtkPGIGIPolyDataMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Proxies: " << this->Proxies << "\n";
  os << indent << "Lighting: " << this->Lighting << "\n";
  os << indent << "BlockerPlanes: " << this->BlockerPlanes.size() / 6 << "\n";
  os << indent << "GlobalIllumination: " << this->GlobalIllumination << "\n";
  os << indent << "Shadows: " << this->Shadows << "\n";
  os << indent << "Order: " << this->Order << "\n";
  os << indent << "Albedo: " << this->Albedo[0] << " " << this->Albedo[1] << " " << this->Albedo[2]
     << "\n";
  os << indent << "AlbedoArrayName: " << (this->AlbedoArrayName ? this->AlbedoArrayName : "(none)")
     << "\n";
  os << indent << "SelfShadowRules: " << this->SelfShadowRules << "\n";
  os << indent << "MinBlockerAngle: " << this->MinBlockerAngle << "\n";
  os << indent << "HybridMaxNorm: " << this->HybridMaxNorm << "\n";
  os << indent << "RangeTolerance: " << this->RangeTolerance << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
  os << indent << "SRGBOutput: " << this->SRGBOutput << "\n";
  os << indent << "CombineWithVTKLighting: " << this->CombineWithVTKLighting << "\n";
  os << indent << "CaptureVisibility: " << this->CaptureVisibility << "\n";
  os << indent << "AlwaysRecompute: " << this->AlwaysRecompute << "\n";
  os << indent << "PlaneBlocking: "
     << (this->PlaneBlocking == PLANES_IN_LIGHT ? "PLANES_IN_LIGHT" : "PLANES_IN_LOG_SPACE")
     << "\n";
  os << indent << "Indirect: " << this->Indirect << "\n";
  os << indent << "IndirectMode: "
     << (this->IndirectMode == INDIRECT_MODE_SHADOWED ? "SHADOWED" : "UNSHADOWED") << "\n";
  os << indent << "SphericalLightBlocking: "
     << (this->SphericalLightBlocking == BLOCKING_PER_OBJECT ? "PER_OBJECT" : "PER_SPHERE") << "\n";
  os << indent << "PlaneBounceShadows: " << this->PlaneBounceShadows << "\n";
  os << indent << "LocalLights: " << this->LocalLights << "\n";
  os << indent << "DefaultProxyAlbedo: " << this->DefaultProxyAlbedo[0] << " "
     << this->DefaultProxyAlbedo[1] << " " << this->DefaultProxyAlbedo[2] << "\n";
  os << indent << "ProxyAlbedoArrayName: "
     << (this->ProxyAlbedoArrayName ? this->ProxyAlbedoArrayName : "(none)") << "\n";
  os << indent << "NumberOfGIUpdates: " << this->NumberOfGIUpdates << "\n";
  os << indent << "GIStatus: " << this->GIStatus << "\n";
}

void vtkPGIGIPolyDataMapper::AddBlockerPlane(const double origin[3], const double normal[3])
{
  const double black[3] = { 0.0, 0.0, 0.0 };
  this->AddBlockerPlane(origin, normal, black);
}

void vtkPGIGIPolyDataMapper::AddBlockerPlane(
  const double origin[3], const double normal[3], const double albedo[3])
{
  if (this->BlockerPlanes.size() / 6 >= static_cast<std::size_t>(proxygi::gpu::MaxPlanes))
  {
    vtkErrorMacro("At most " << proxygi::gpu::MaxPlanes << " blocker planes.");
    return;
  }
  const double len =
    std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  this->BlockerPlanes.insert(this->BlockerPlanes.end(), origin, origin + 3);
  for (int k = 0; k < 3; ++k)
  {
    this->BlockerPlanes.push_back(len > 0.0 ? normal[k] / len : (k == 2 ? 1.0 : 0.0));
  }
  this->PlaneAlbedos.insert(this->PlaneAlbedos.end(), albedo, albedo + 3);
  this->Modified();
}

void vtkPGIGIPolyDataMapper::RemoveAllBlockerPlanes()
{
  this->BlockerPlanes.clear();
  this->PlaneAlbedos.clear();
  this->Modified();
}

void vtkPGIGIPolyDataMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  Internals& g = *this->GPU;
  g.Resources.ReleaseGraphicsResources(window);
  g.Receivers->ReleaseGraphicsResources();
  g.Results->ReleaseGraphicsResources();
  g.VAO->ReleaseGraphicsResources();
  g.Capture = nullptr;
  g.ProgramHandle = 0;
  g.CaptureKey.clear();
  g.HaveResults = false;
  if (g.ProxyAlbedo)
  {
    g.ProxyAlbedo->ReleaseGraphicsResources(window);
    g.ProxyAlbedo = nullptr;
  }
  g.Window = nullptr;
  g.Input = nullptr;
  g.LightOrder = 0;
  g.Settings.clear();
  this->Superclass::ReleaseGraphicsResources(window);
}

namespace
{
// One transform-feedback description per set of captured outputs, shared by
// all mappers: the shader cache relinks a program whenever it is handed a
// different vtkTransformFeedback object, and mappers of the same order share
// their compute program.
vtkTransformFeedback* SharedCapture(int visibilityVec4s)
{
  static std::map<int, vtkSmartPointer<vtkTransformFeedback>> captures;
  vtkSmartPointer<vtkTransformFeedback>& capture = captures[visibilityVec4s];
  if (!capture)
  {
    capture = vtkSmartPointer<vtkTransformFeedback>::New();
    capture->AddVarying(vtkTransformFeedback::Color_RGBA_F, "pgiRadiance");
    for (int k = 0; k < visibilityVec4s; ++k)
    {
      capture->AddVarying(vtkTransformFeedback::Color_RGBA_F, "pgiVisibility" + std::to_string(k));
    }
  }
  return capture;
}
} // namespace

bool vtkPGIGIPolyDataMapper::UpdateSphericalLights(vtkPGILighting* lighting)
{
  Internals& g = *this->GPU;
  const int order = this->Order, n2 = order * order;
  // What shadows the samples: the leaf proxies and the planes, as in the filter.
  proxygi::Blockers blockers;
  std::vector<vtkIdType> leafIds;
  vtkDataArray* level = this->Proxies ? this->Proxies->GetPointData()->GetArray("Level") : nullptr;
  const vtkIdType proxies = g.ProxyCount > 0 ? this->Proxies->GetNumberOfPoints() : 0;
  for (vtkIdType i = 0, leaf = 0; i < proxies; ++i)
  {
    if (level && level->GetTuple1(i) != 0.0)
    {
      continue;
    }
    const float* s = &g.Spheres[4 * leaf];
    blockers.AddSphere(s[0], s[1], s[2], s[3], &g.Albedos[4 * leaf]);
    leafIds.push_back(i);
    ++leaf;
  }
  for (std::size_t k = 0; 6 * k < this->BlockerPlanes.size(); ++k)
  {
    float v[9];
    for (int q = 0; q < 6; ++q)
    {
      v[q] = static_cast<float>(this->BlockerPlanes[6 * k + q]);
    }
    for (int q = 0; q < 3; ++q)
    {
      v[6 + q] = static_cast<float>(this->PlaneAlbedos[3 * k + q]);
    }
    blockers.AddPlane(v, v + 3, v + 6);
  }
  proxygi::SoftShadowSettings settings;
  settings.Order = order;
  settings.MinAngle = static_cast<float>(this->MinBlockerAngle);
  settings.SelfShadowRules = this->SelfShadowRules;
  settings.Exp.HybridMaxNorm = this->HybridMaxNorm;
  settings.Exp.RangeGuard = this->RangeTolerance >= 0.0;
  settings.Exp.RangeTolerance = std::max(0.0, this->RangeTolerance);
  settings.PlanesInLogSpace = !g.PlanesInLight;
  const proxygi::ShadowedIndirect kernel(settings,
    this->SphericalLightBlocking == BLOCKING_PER_OBJECT
      ? proxygi::SphericalLightBlocking::PerObject
      : proxygi::SphericalLightBlocking::PerSphere);
  const double* light = g.SampleLight.data();
  const proxygi::EnvironmentShading shading(
    order, light, light + n2, light + 2 * n2, proxygi::EnvironmentShading::Path::ProductMatrix);
  const bool dark = light[0] <= 0.0 && light[n2] <= 0.0 && light[2 * n2] <= 0.0;
  proxygi::LocalEmitters emitters;
  if (this->LocalLights)
  {
    emitters.AddLights(*lighting);
  }
  proxygi::SphericalLights lights;
  std::string summary, error;
  const std::string why = proxygi::PrepareSphericalLights(this->Proxies, leafIds, nullptr, order,
    this->ProxyAlbedoArrayName, this->DefaultProxyAlbedo, shading, dark, blockers,
    emitters.Count() ? &emitters : nullptr, kernel, lights, summary, error);
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
    return false;
  }
  g.SphericalLightCount = why.empty() ? static_cast<int>(lights.Count()) : 0;
  g.SphericalLightSummary = why.empty() ? summary : "skipped: " + why;
  g.Resources.SetSphericalLights(
    why.empty() ? &lights : nullptr, this->SphericalLightBlocking == BLOCKING_PER_OBJECT);
  return true;
}

bool vtkPGIGIPolyDataMapper::UpdateGI(vtkRenderer* ren, vtkActor* act)
{
  Internals& g = *this->GPU;
  vtkPolyData* input = this->CurrentInput;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!this->GlobalIllumination || !input || input->GetNumberOfPoints() == 0 || !window)
  {
    this->GIStatus = !this->GlobalIllumination ? "GI off: VTK lighting" : "GI: nothing to draw";
    return false;
  }
  const vtkIdType n = input->GetNumberOfPoints();
  const int order = this->Order, n2 = order * order;
  std::ostringstream why;

  if (g.Window != window)
  {
    if (g.Window)
    {
      this->ReleaseGraphicsResources(g.Window);
    }
    g.Window = window;
    why << "new context; ";
  }

  // Light: the environment projected to SH at this order (as the filter does).
  vtkNew<vtkPGILighting> defaultLighting;
  vtkPGILighting* lighting = this->Lighting ? this->Lighting : defaultLighting.Get();
  const vtkMTimeType lightingTime = this->Lighting ? this->Lighting->GetMTime() : 0;
  if (!g.Resources.SetOrder(window, order))
  {
    vtkErrorMacro("Could not upload the SH tables of order " << order << ".");
    return false;
  }
  // The knobs the GI pass depends on; display knobs (exposure, sRGB,
  // combining with VTK's lights) only change uniforms of the surface pass.
  std::ostringstream knobs;
  knobs.precision(17);
  knobs << order << " " << this->Shadows << " " << this->Albedo[0] << " " << this->Albedo[1] << " "
        << this->Albedo[2] << " " << (this->AlbedoArrayName ? this->AlbedoArrayName : "") << " "
        << this->SelfShadowRules << " " << this->MinBlockerAngle << " " << this->HybridMaxNorm
        << " " << this->RangeTolerance << " " << this->CaptureVisibility << " "
        << this->PlaneBlocking << " " << this->Indirect << " " << this->DefaultProxyAlbedo[0] << " "
        << this->DefaultProxyAlbedo[1] << " " << this->DefaultProxyAlbedo[2] << " "
        << (this->ProxyAlbedoArrayName ? this->ProxyAlbedoArrayName : "") << " "
        << this->LocalLights << " " << this->PlaneBounceShadows << " " << this->IndirectMode << " "
        << this->SphericalLightBlocking;
  for (double v : this->BlockerPlanes)
  {
    knobs << " " << v;
  }
  for (double v : this->PlaneAlbedos)
  {
    knobs << " " << v;
  }
  const bool settingsChanged = knobs.str() != g.Settings;
  const int planeCount = static_cast<int>(this->BlockerPlanes.size() / 6);

  // The lights, built on the CPU as the filter builds them: L; with planes
  // carried by the light, L times the planes' steps (LightAbovePlanes) and
  // the planes' visibility; the secondary lights' response (SecondaryLights:
  // from the light above the planes, or from L times the planes' exp-log
  // visibility when the planes are in log space).
  bool lightChanged = false, proxiesChanged = false;
  if (g.LightOrder != order || g.LightingTime != lightingTime || settingsChanged)
  {
    const proxygi::EnvironmentMap* environment = nullptr;
    std::string error;
    if (!lighting->GetEnvironment(environment, error))
    {
      vtkErrorMacro("Bad environment: " << error);
      return false;
    }
    std::vector<double> lr(n2), lg(n2), lb(n2);
    environment->ProjectSH(order, lr.data(), lg.data(), lb.data());
    g.Resources.SetLight(lr.data(), lg.data(), lb.data());
    g.PlanesInLight = this->PlaneBlocking == PLANES_IN_LIGHT && planeCount > 0;
    proxygi::Blockers planes;
    for (int k = 0; k < planeCount; ++k)
    {
      float v[9];
      for (int q = 0; q < 6; ++q)
      {
        v[q] = static_cast<float>(this->BlockerPlanes[6 * k + q]);
      }
      for (int q = 0; q < 3; ++q)
      {
        v[6 + q] = static_cast<float>(this->PlaneAlbedos[3 * k + q]);
      }
      planes.AddPlane(v, v + 3, v + 6);
    }
    std::vector<double> planeVisibility(n2, 0.0);
    if (g.PlanesInLight)
    {
      proxygi::LightAbovePlanes(*environment, order, planes.PlaneNormal.data(), planeCount,
        lr.data(), lg.data(), lb.data(), planeVisibility.data());
      g.Resources.SetLightAbovePlanes(lr.data(), lg.data(), lb.data());
    }
    else
    {
      g.Resources.SetLightAbovePlanes(nullptr, nullptr, nullptr);
    }
    g.SampleLight.assign(lr.begin(), lr.end());
    g.SampleLight.insert(g.SampleLight.end(), lg.begin(), lg.end());
    g.SampleLight.insert(g.SampleLight.end(), lb.begin(), lb.end());
    lightChanged = true;
    g.PlaneVisibility.assign(planeVisibility.begin(), planeVisibility.end());
    const proxygi::SecondaryLights secondary(
      order, lr.data(), lg.data(), lb.data(), g.PlanesInLight ? nullptr : &planes);
    g.Response.resize(3 * static_cast<std::size_t>(n2));
    for (int i = 0; i < n2; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        g.Response[3 * i + c] = secondary.Response[c * n2 + i];
      }
    }
    // Local lights as the filter reads them: spheres, then points.
    g.LocalLights.clear();
    g.LocalRadiance.clear();
    if (this->LocalLights)
    {
      for (const auto& l : lighting->GetSphereLights())
      {
        g.LocalLights.insert(g.LocalLights.end(),
          { float(l.Center[0]), float(l.Center[1]), float(l.Center[2]), float(l.Radius) });
        g.LocalRadiance.insert(g.LocalRadiance.end(),
          { float(l.Radiance[0]), float(l.Radiance[1]), float(l.Radiance[2]) });
      }
      for (const auto& l : lighting->GetPointLights())
      {
        g.LocalLights.insert(g.LocalLights.end(),
          { float(l.Position[0]), float(l.Position[1]), float(l.Position[2]), -1.0f });
        g.LocalRadiance.insert(g.LocalRadiance.end(),
          { float(l.Intensity[0]), float(l.Intensity[1]), float(l.Intensity[2]) });
      }
      if (g.LocalLights.size() > 4 * static_cast<std::size_t>(MaxLocalLights))
      {
        vtkErrorMacro("At most " << MaxLocalLights << " local lights on the GPU; "
                                 << g.LocalLights.size() / 4 << " given, the first "
                                 << MaxLocalLights << " used.");
        g.LocalLights.resize(4 * MaxLocalLights);
        g.LocalRadiance.resize(3 * MaxLocalLights);
      }
    }
    g.Resources.SetAnalyticLightTable(!g.LocalLights.empty());
    if (g.LightOrder != order || g.LightingTime != lightingTime)
    {
      why << "light; ";
    }
    g.LightOrder = order;
    g.LightingTime = lightingTime;
  }

  // Blockers.
  const vtkMTimeType proxiesTime = this->Proxies ? this->Proxies->GetMTime() : 0;
  if (proxiesTime != g.ProxiesTime || settingsChanged || !g.ProxyAlbedo)
  {
    std::string error;
    if (!proxygi::gpu::ReadProxies(this->Proxies, g.Spheres, error))
    {
      vtkErrorMacro("Proxies ignored: " << error << ".");
    }
    std::vector<float> planes(this->BlockerPlanes.begin(), this->BlockerPlanes.end());
    g.Resources.SetBlockers(g.Spheres, planes);
    g.ProxyCount = static_cast<int>(g.Spheres.size() / 4);
    proxygi::gpu::UploadProxyAlbedos(window, this->Proxies, g.ProxyCount,
      this->ProxyAlbedoArrayName, this->DefaultProxyAlbedo, g.Albedos, g.ProxyAlbedo);
    proxiesChanged = true;
    if (proxiesTime != g.ProxiesTime)
    {
      why << "proxies; ";
    }
    g.ProxiesTime = proxiesTime;
  }
  proxygi::gpu::KernelSettings settings;
  settings.MinBlockerAngle = this->MinBlockerAngle;
  settings.SelfShadowRules = this->SelfShadowRules;
  settings.HybridMaxNorm = this->HybridMaxNorm;
  settings.RangeTolerance = this->RangeTolerance;
  g.Resources.SetSettings(settings);

  // Shadowed bounce: the proxies as spherical lights, their first pass on
  // the CPU (PrepareSphericalLights, as the filter runs it) whenever the
  // light, the proxies or a knob changed.
  const bool shadowedMode = this->Indirect && this->IndirectMode == INDIRECT_MODE_SHADOWED;
  if (!shadowedMode)
  {
    if (g.SphericalLightCount > 0 || lightChanged || proxiesChanged)
    {
      g.Resources.SetSphericalLights(nullptr, false);
    }
    g.SphericalLightCount = 0;
    g.SphericalLightSummary.clear();
  }
  else if (lightChanged || proxiesChanged)
  {
    if (!this->UpdateSphericalLights(lighting))
    {
      return false;
    }
  }

  // Receivers: positions, normals (computed as the filter does if missing), albedo.
  const std::string albedoArray = this->AlbedoArrayName ? this->AlbedoArrayName : "";
  if (g.Input != input || input->GetMTime() != g.InputTime || g.Points != n ||
    albedoArray != g.AlbedoArray || settingsChanged)
  {
    vtkSmartPointer<vtkDataArray> normals = input->GetPointData()->GetNormals();
    if (!normals)
    {
      vtkNew<vtkPolyDataNormals> computer;
      computer->SetInputData(input);
      computer->SplittingOff();
      computer->Update();
      if (computer->GetOutput()->GetNumberOfPoints() == n)
      {
        normals = computer->GetOutput()->GetPointData()->GetNormals();
      }
    }
    std::vector<float> data(9 * static_cast<std::size_t>(n));
    for (vtkIdType i = 0; i < n; ++i)
    {
      double p[3], nd[3] = { 0.0, 0.0, 1.0 }, albedo[3];
      input->GetPoint(i, p);
      // Normalised in double, as the CPU filter does, so both start from
      // the same floats.
      if (normals)
      {
        normals->GetTuple(i, nd);
        const double len = std::sqrt(nd[0] * nd[0] + nd[1] * nd[1] + nd[2] * nd[2]);
        if (len > 0.0)
        {
          nd[0] /= len;
          nd[1] /= len;
          nd[2] /= len;
        }
        else
        {
          nd[0] = nd[1] = 0.0;
          nd[2] = 1.0;
        }
      }
      proxygi::AlbedoOf(input, this->AlbedoArrayName, i, this->Albedo, albedo);
      float* row = &data[9 * i];
      for (int k = 0; k < 3; ++k)
      {
        row[k] = static_cast<float>(p[k]);
        row[3 + k] = static_cast<float>(nd[k]);
        row[6 + k] = static_cast<float>(albedo[k]);
      }
    }
    g.Receivers->Upload(data, vtkOpenGLBufferObject::ArrayBuffer);
    g.Input = input;
    g.InputTime = input->GetMTime();
    g.Points = n;
    g.AlbedoArray = albedoArray;
    why << "mesh; ";
  }

  // The actor's matrix (the mesh moves, proxies stay in world coordinates).
  std::array<double, 16> matrix;
  vtkMatrix4x4* m = act->GetMatrix();
  std::copy(&m->Element[0][0], &m->Element[0][0] + 16, matrix.begin());
  const bool moved = matrix != g.Matrix;
  if (moved)
  {
    why << "actor matrix; ";
  }
  if (settingsChanged)
  {
    why << "settings; ";
  }

  // The compute program: order and the captured outputs fix the source.
  const int visibilityVec4s = this->CaptureVisibility ? (n2 + 3) / 4 : 0;
  const std::string key = std::to_string(order) + "/" + std::to_string(visibilityVec4s);
  if (!g.Capture || g.CaptureKey != key)
  {
    g.Capture = SharedCapture(visibilityVec4s);
    g.CaptureKey = key;
    g.HaveResults = false;
    why << "program; ";
  }

  const std::string reasons = why.str();
  if (g.HaveResults && reasons.empty() && !this->AlwaysRecompute)
  {
    std::ostringstream status;
    status << "GI on the GPU: " << n << " vertices, " << g.ProxyCount << " proxies, "
           << this->BlockerPlanes.size() / 6 << " planes, order " << order
           << "; reused (nothing changed)";
    this->GIStatus = status.str();
    return true;
  }

  std::string vs = pgiGIComputeVS;
  std::ostringstream captureDec, captureImpl;
  for (int k = 0; k < visibilityVec4s; ++k)
  {
    captureDec << "out vec4 pgiVisibility" << k << ";\n";
    captureImpl << "  pgiVisibility" << k << " = vec4(";
    for (int c = 0; c < 4; ++c)
    {
      const int i = 4 * k + c;
      captureImpl << (c ? ", " : "") << (i < n2 ? "g[" + std::to_string(i) + "]" : "0.0");
    }
    captureImpl << ");\n";
  }
  // The shadowed bounce's code only where it runs (it is the costliest to compile).
  const bool sphericalLights = g.SphericalLightCount > 0;
  vtkShaderProgram::Substitute(vs, "//PGI::Defines",
    std::string("#define PGI_SPHERICAL_LIGHTS ") + (sphericalLights ? "1" : "0"));
  vtkShaderProgram::Substitute(vs, "//PGI::Library", proxygi::gpu::LibrarySource(order));
  vtkShaderProgram::Substitute(vs, "//PGI::ISLibrary", proxygi::gpu::IndirectLibrarySource());
  vtkShaderProgram::Substitute(vs, "//PGI::SLLibrary",
    sphericalLights ? proxygi::gpu::SphericalLightsLibrarySource(g.SphericalLightCount) : "");
  vtkShaderProgram::Substitute(vs, "//PGI::Capture::Dec", captureDec.str());
  vtkShaderProgram::Substitute(vs, "//PGI::Capture::Impl", captureImpl.str());
  vtkShaderProgram* program =
    window->GetShaderCache()->ReadyShaderProgram(vs.c_str(), pgiGIComputeFS, "", g.Capture);
  if (!program)
  {
    vtkErrorMacro("The GI shader did not compile.");
    return false;
  }
  if (program->GetHandle() != g.ProgramHandle)
  {
    g.VAO->ShaderProgramChanged();
    g.ProgramHandle = program->GetHandle();
  }
  g.Resources.Bind(program);
  // Column-major uploads of the actor matrix and its normal matrix.
  float modelToWorld[16];
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      modelToWorld[4 * c + r] = static_cast<float>(matrix[4 * r + c]);
    }
  }
  vtkNew<vtkMatrix3x3> normalMatrix;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      normalMatrix->SetElement(r, c, matrix[4 * r + c]);
    }
  }
  normalMatrix->Invert();
  normalMatrix->Transpose();
  float normalToWorld[9];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      normalToWorld[3 * c + r] = static_cast<float>(normalMatrix->GetElement(r, c));
    }
  }
  program->SetUniformMatrix4x4("pgiModelToWorld", modelToWorld);
  program->SetUniformMatrix3x3("pgiNormalToWorld", normalToWorld);
  const bool identity =
    matrix == std::array<double, 16>{ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  program->SetUniformi("pgiMoved", identity ? 0 : 1);
  program->SetUniformi("pgiShadows", this->Shadows ? 1 : 0);
  program->SetUniformi("pgiPlanesInLight", g.PlanesInLight ? 1 : 0);
  program->SetUniform1fv("pgiPlaneVisibility", n2, g.PlaneVisibility.data());
  program->SetUniformi("pgiIndirect", this->Indirect ? 1 : 0);
  program->SetUniformi("pgiIndirectShadowed", shadowedMode ? 1 : 0);
  program->SetUniformi("pgiPlaneBounceShadows", this->PlaneBounceShadows ? 1 : 0);
  program->SetUniform3fv("pgiResponse", n2, g.Response.data());
  {
    std::vector<float> albedos(3 * proxygi::gpu::MaxPlanes, 0.0f);
    for (std::size_t k = 0; k < this->PlaneAlbedos.size() && k < albedos.size(); ++k)
    {
      albedos[k] = static_cast<float>(this->PlaneAlbedos[k]);
    }
    program->SetUniform3fv("pgiPlaneAlbedo", proxygi::gpu::MaxPlanes, albedos.data());
  }
  {
    const int lights = static_cast<int>(g.LocalLights.size() / 4);
    std::vector<float> centres(4 * MaxLocalLights, 0.0f), radiance(3 * MaxLocalLights, 0.0f);
    std::copy(g.LocalLights.begin(), g.LocalLights.end(), centres.begin());
    std::copy(g.LocalRadiance.begin(), g.LocalRadiance.end(), radiance.begin());
    program->SetUniformi("pgiNumLocalLights", lights);
    program->SetUniform4fv("pgiLocalLight", MaxLocalLights, centres.data());
    program->SetUniform3fv("pgiLocalRadiance", MaxLocalLights, radiance.data());
    program->SetUniformf("pgiLobeMinTheta",
      lights > 0 ? static_cast<float>(g.Resources.GetAnalyticLightMinTheta()) : 0.0f);
  }
  g.ProxyAlbedo->Activate();
  program->SetUniformi("pgiProxyAlbedo", g.ProxyAlbedo->GetTextureUnit());

  g.VAO->Bind();
  const struct
  {
    const char* Name;
    int Offset;
  } attributes[] = { { "pgiPositionMC", 0 }, { "pgiNormalMC", 12 }, { "pgiAlbedoMC", 24 } };
  for (const auto& a : attributes)
  {
    if (program->IsAttributeUsed(a.Name) &&
      !g.VAO->AddAttributeArray(program, g.Receivers, a.Name, a.Offset, 36, VTK_FLOAT, 3, false))
    {
      vtkErrorMacro("Could not bind " << a.Name << ".");
    }
  }
  const int floats = 4 * (1 + visibilityVec4s);
  if (!g.HaveResults || g.ResultFloats != floats || g.Results->GetHandle() == 0 ||
    reasons.find("mesh") != std::string::npos)
  {
    g.Results->Upload(std::vector<float>(static_cast<std::size_t>(n) * floats, 0.0f),
      vtkOpenGLBufferObject::ArrayBuffer);
    g.ResultFloats = floats;
  }
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, g.Results->GetHandle());
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(n));
  glEndTransformFeedback();
  glDisable(GL_RASTERIZER_DISCARD);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  g.VAO->Release();
  g.ProxyAlbedo->Deactivate();
  g.Resources.Unbind();

  g.Matrix = matrix;
  g.Settings = knobs.str();
  g.HaveResults = true;
  ++this->NumberOfGIUpdates;
  std::ostringstream status;
  status << "GI on the GPU: " << n << " vertices, " << g.ProxyCount << " proxies, "
         << this->BlockerPlanes.size() / 6 << " planes, order " << order << ", "
         << (this->Shadows ? "SHEXP shadows (HYB)" : "no shadows")
         << (planeCount == 0      ? ""
                : g.PlanesInLight ? ", planes carried by the light"
                                  : ", planes in log space")
         << (!this->Indirect   ? ""
                : shadowedMode ? ", one-bounce indirect (shadowed: " + g.SphericalLightSummary + ")"
                               : std::string(", one-bounce indirect (averaged, xi)"))
         << (this->Indirect && this->PlaneBounceShadows && planeCount > 0
                ? ", planes' bounce shadowed"
                : "");
  if (!g.LocalLights.empty())
  {
    status << ", " << g.LocalLights.size() / 4 << " local lights";
  }
  // Mesa's llvmpipe ends every loop of a shader invocation once all its
  // loops together ran 65535 iterations (gallivm's loop limiter): past the
  // sizes measured to stay inside it (Documentation/Rendering.md), say so.
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const bool llvmpipe = renderer && std::strstr(renderer, "llvmpipe");
  const bool overBudget =
    g.ProxyCount > 1000 || (this->Indirect && g.ProxyCount > 600) || g.SphericalLightCount > 96;
  if (llvmpipe && overBudget)
  {
    status << "; on llvmpipe beyond its loop budget (more than 1000 proxies, 600 with the "
              "bounce or 96 spherical lights): results may be cut short";
    if (!g.WarnedBudget)
    {
      vtkWarningMacro(<< "llvmpipe stops a shader's loops after 65535 iterations in all: with "
                      << g.ProxyCount << " proxies and " << g.SphericalLightCount
                      << " spherical lights the GI pass may be cut short. Use a hardware GPU, "
                         "fewer proxies or vtkPGIGlobalIllumination.");
      g.WarnedBudget = true;
    }
  }
  status << "; recomputed ("
         << (reasons.empty() ? "AlwaysRecompute" : reasons.substr(0, reasons.size() - 2)) << ")";
  this->GIStatus = status.str();
  return true;
}

void vtkPGIGIPolyDataMapper::RenderPieceStart(vtkRenderer* ren, vtkActor* act)
{
  const bool gi = this->UpdateGI(ren, act);
  if (gi != this->GPU->GIInShaders)
  {
    this->GPU->GIInShaders = gi;
    this->GPU->ShaderModeTime.Modified();
  }
  this->Superclass::RenderPieceStart(ren, act);
}

bool vtkPGIGIPolyDataMapper::GetNeedToRebuildShaders(
  vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act)
{
  return this->Superclass::GetNeedToRebuildShaders(cellBO, ren, act) ||
    cellBO.ShaderSourceTime < this->GPU->ShaderModeTime;
}

void vtkPGIGIPolyDataMapper::ReplaceShaderValues(
  std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act)
{
  if (!this->GPU->GIInShaders)
  {
    this->Superclass::ReplaceShaderValues(shaders, ren, act);
    return;
  }
  // Ours first, keeping VTK's tags for VTK; the colour override goes after
  // VTK's lighting code, hence a tag of our own that VTK leaves alone.
  std::string vs = shaders[vtkShader::Vertex]->GetSource();
  std::string fs = shaders[vtkShader::Fragment]->GetSource();
  vtkShaderProgram::Substitute(vs, "//VTK::Color::Dec", pgiGIMapperVS, false);
  vtkShaderProgram::Substitute(vs, "//VTK::Color::Impl", pgiGIMapperVSImpl, false);
  vtkShaderProgram::Substitute(fs, "//VTK::Light::Dec", pgiGIMapperFS, false);
  vtkShaderProgram::Substitute(
    fs, "//VTK::Light::Impl", "//VTK::Light::Impl\n//PGI::GI::Impl\n", false);
  shaders[vtkShader::Vertex]->SetSource(vs);
  shaders[vtkShader::Fragment]->SetSource(fs);
  this->Superclass::ReplaceShaderValues(shaders, ren, act);
  fs = shaders[vtkShader::Fragment]->GetSource();
  vtkShaderProgram::Substitute(fs, "//PGI::GI::Impl", pgiGIMapperFSImpl, false);
  shaders[vtkShader::Fragment]->SetSource(fs);
}

void vtkPGIGIPolyDataMapper::SetMapperShaderParameters(
  vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act)
{
  this->Superclass::SetMapperShaderParameters(cellBO, ren, act);
  Internals& g = *this->GPU;
  vtkShaderProgram* program = cellBO.Program;
  if (!g.GIInShaders || !program || !program->IsAttributeUsed("pgiRadianceMC"))
  {
    return;
  }
  // The results buffer may have been reallocated since the VAO last saw it.
  cellBO.VAO->Bind();
  if (!cellBO.VAO->AddAttributeArray(program, g.Results, "pgiRadianceMC", 0,
        static_cast<size_t>(4 * g.ResultFloats), VTK_FLOAT, 4, false))
  {
    vtkErrorMacro("Could not bind the GI results.");
  }
  program->SetUniformf("pgiExposure", static_cast<float>(this->Exposure));
  program->SetUniformi("pgiCombineWithVTKLighting", this->CombineWithVTKLighting ? 1 : 0);
  program->SetUniformi("pgiSRGBOutput", this->SRGBOutput ? 1 : 0);
}

bool vtkPGIGIPolyDataMapper::GetPerVertexResults(vtkFloatArray* radiance, vtkFloatArray* visibility)
{
  Internals& g = *this->GPU;
  if (!g.HaveResults || !g.Window || !radiance)
  {
    return false;
  }
  g.Window->MakeCurrent();
  const std::size_t count = static_cast<std::size_t>(g.Points) * g.ResultFloats;
  std::vector<float> data(count);
  glBindBuffer(GL_ARRAY_BUFFER, g.Results->GetHandle());
  glGetBufferSubData(
    GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(count * sizeof(float)), data.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  const int n2 = this->GPU->LightOrder * this->GPU->LightOrder;
  radiance->SetNumberOfComponents(3);
  radiance->SetNumberOfTuples(g.Points);
  if (visibility)
  {
    visibility->SetNumberOfComponents(g.ResultFloats > 4 ? n2 : 1);
    visibility->SetNumberOfTuples(g.ResultFloats > 4 ? g.Points : 0);
  }
  for (vtkIdType i = 0; i < g.Points; ++i)
  {
    const float* row = &data[static_cast<std::size_t>(i) * g.ResultFloats];
    radiance->SetTypedTuple(i, row);
    if (visibility && g.ResultFloats > 4)
    {
      visibility->SetTypedTuple(i, row + 4);
    }
  }
  return glGetError() == GL_NO_ERROR;
}
