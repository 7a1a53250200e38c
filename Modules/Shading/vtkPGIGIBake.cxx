#include "vtkPGIGIBake.h"

#include "pgiEnvironmentMap.h"
#include "pgiMaterial.h"
#include "pgiSHLightTables.h"
#include "pgiSHTables.h"
#include "vtkPGIGISettings.h"
#include "vtkPGILighting.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkSMPTools.h"

#include <cmath>
#include <sstream>

vtkStandardNewMacro(vtkPGIGIBake);
vtkCxxSetObjectMacro(vtkPGIGIBake, Proxies, vtkPolyData);
vtkCxxSetObjectMacro(vtkPGIGIBake, Lighting, vtkPGILighting);

namespace proxygi
{
vtkSmartPointer<vtkDataArray> ReceiverNormals(vtkPolyData* receivers)
{
  vtkSmartPointer<vtkDataArray> normals = receivers->GetPointData()->GetNormals();
  if (normals)
  {
    return normals;
  }
  vtkNew<vtkPolyDataNormals> computer;
  computer->SetInputData(receivers);
  computer->SplittingOff();
  UpdateNormals(computer);
  if (computer->GetOutput()->GetNumberOfPoints() != receivers->GetNumberOfPoints())
  {
    return nullptr;
  }
  return computer->GetOutput()->GetPointData()->GetNormals();
}

void UpdateNormals(vtkPolyDataNormals* filter)
{
  vtkSMPTools::LocalScope(
    vtkSMPTools::Config{ 1, vtkSMPTools::GetBackend(), false }, [filter]() { filter->Update(); });
}
} // namespace proxygi

vtkPGIGIBake::vtkPGIGIBake()
{
  this->Settings = vtkPGIGISettings::New();
}

vtkPGIGIBake::~vtkPGIGIBake()
{
  this->SetProxies(nullptr);
  this->SetLighting(nullptr);
  this->SetSettings(nullptr);
}

void vtkPGIGIBake::SetSettings(vtkPGIGISettings* settings)
{
  if (settings == this->Settings)
  {
    return;
  }
  if (this->Settings)
  {
    this->Settings->UnRegister(this);
  }
  this->Settings = settings;
  if (this->Settings)
  {
    this->Settings->Register(this);
  }
  this->Modified();
}

void vtkPGIGIBake::AddBlockerPlane(
  const double origin[3], const double normal[3], const double albedo[3], const double* halfEdges)
{
  this->Planes.insert(this->Planes.end(), origin, origin + 3);
  this->Planes.insert(this->Planes.end(), normal, normal + 3);
  this->Planes.insert(this->Planes.end(), albedo, albedo + 3);
  const double unbounded[6] = { 0, 0, 0, 0, 0, 0 };
  const double* e = halfEdges ? halfEdges : unbounded;
  this->PlaneExtents.insert(this->PlaneExtents.end(), e, e + 6);
  this->Modified();
}

void vtkPGIGIBake::RemoveAllBlockerPlanes()
{
  if (!this->Planes.empty())
  {
    this->Planes.clear();
    this->PlaneExtents.clear();
    this->Modified();
  }
}

vtkMTimeType vtkPGIGIBake::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  for (vtkObject* o : { static_cast<vtkObject*>(this->Proxies),
         static_cast<vtkObject*>(this->Lighting), static_cast<vtkObject*>(this->Settings) })
  {
    if (o)
    {
      t = std::max(t, o->GetMTime());
    }
  }
  return t;
}

bool vtkPGIGIBake::Update()
{
  if (this->NumberOfBuilds > 0 && this->BuiltProxies == this->Proxies &&
    this->BuiltLighting == this->Lighting && this->GetMTime() <= this->BuildTime.GetMTime())
  {
    return this->BuiltOk;
  }
  if (!this->Settings)
  {
    vtkNew<vtkPGIGISettings> defaults;
    this->SetSettings(defaults);
  }
  this->Error.clear();
  this->ProxyError.clear();
  proxygi::BakedScene previous = std::move(this->Scene);
  this->Scene = proxygi::BakedScene();
  this->Scene.Order = this->Settings->GetOrder();
  this->Scene.IndirectOrder = this->Settings->GetEffectiveIndirectOrder();
  // Without a lighting: one default kept across builds, so its projection is too.
  if (!this->Lighting && !this->DefaultLighting)
  {
    this->DefaultLighting = vtkSmartPointer<vtkPGILighting>::New();
  }
  vtkPGILighting* lighting = this->Lighting ? this->Lighting : this->DefaultLighting.Get();
  bool ok = this->ReadBlockers() && this->ProjectLight(lighting, previous);
  if (ok)
  {
    this->PlanEffects(lighting);
    this->PrepareLocalLights(lighting);
    ok = this->PrepareSphericalLights();
  }
  ok = ok && this->ProxyError.empty();
  if (!ok && this->Error.empty())
  {
    this->Error = this->ProxyError;
  }
  this->BuiltOk = ok;
  this->BuiltProxies = this->Proxies;
  this->BuiltLighting = this->Lighting;
  ++this->NumberOfBuilds;
  this->BuildTime.Modified();
  return ok;
}

bool vtkPGIGIBake::UpdateFor(vtkObject* owner, vtkPGIGISettings* requested,
  const vtkPGIGISettings::Support& support, std::vector<std::string>& said)
{
  std::vector<std::string> notes;
  const int lights = this->Lighting ? static_cast<int>(this->Lighting->GetSphereLights().size() +
                                        this->Lighting->GetPointLights().size())
                                    : 0;
  requested->Resolve(support, this->GetNumberOfBlockerPlanes(), this->Settings, notes, lights);
  if (notes != said)
  {
    for (const std::string& note : notes)
    {
      vtkWarningWithObjectMacro(owner, << "Not honoured: " << note << ".");
    }
    said = notes;
  }
  const int builds = this->NumberOfBuilds;
  const bool ok = this->Update();
  const bool rebuilt = this->NumberOfBuilds != builds;
  if (!ok && this->ProxyError.empty())
  {
    if (rebuilt)
    {
      vtkErrorWithObjectMacro(owner, << this->Error);
    }
    return false;
  }
  if (rebuilt && !this->ProxyError.empty())
  {
    vtkErrorWithObjectMacro(owner, << "Proxies ignored: " << this->ProxyError << ".");
  }
  return true;
}

bool vtkPGIGIBake::ReadBlockers()
{
  proxygi::BakedScene& b = this->Scene;
  vtkPolyData* proxies = this->Proxies;
  if (proxies && proxies->GetNumberOfPoints() > 0)
  {
    vtkDataArray* radius = proxies->GetPointData()->GetArray("Radius");
    vtkDataArray* level = proxies->GetPointData()->GetArray("Level");
    vtkDataArray* parent = proxies->GetPointData()->GetArray("Parent");
    vtkDataArray* objectIds = proxies->GetPointData()->GetArray("ObjectId");
    b.UseHierarchy = this->Settings->GetHierarchyAngle() > 0.0 && level && parent;
    if (!radius)
    {
      this->ProxyError = "the proxies need a \"Radius\" point array";
    }
    const double* fallback = this->Settings->GetDefaultProxyAlbedo();
    const char* albedoArray = this->Settings->GetAlbedoArrayName();
    for (vtkIdType i = 0; radius && i < proxies->GetNumberOfPoints(); ++i)
    {
      double c[3], albedo[3];
      proxies->GetPoint(i, c);
      const double r = radius->GetTuple1(i);
      if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]) ||
        !std::isfinite(r) || r < 0.0)
      {
        std::ostringstream m;
        m << "proxy " << i << " has a NaN, Inf or negative centre or radius";
        this->ProxyError = m.str();
        break;
      }
      proxygi::AlbedoOf(proxies, albedoArray, i, fallback, albedo);
      const float a[3] = { float(albedo[0]), float(albedo[1]), float(albedo[2]) };
      const int object = objectIds ? static_cast<int>(objectIds->GetTuple1(i)) : -1;
      if (b.UseHierarchy)
      {
        b.Hierarchy.Object.push_back(object);
        b.Hierarchy.Albedo.insert(b.Hierarchy.Albedo.end(), a, a + 3);
        b.Hierarchy.X.push_back(float(c[0]));
        b.Hierarchy.Y.push_back(float(c[1]));
        b.Hierarchy.Z.push_back(float(c[2]));
        b.Hierarchy.R.push_back(float(r));
        b.Hierarchy.Level.push_back(static_cast<int>(level->GetTuple1(i)));
        b.Hierarchy.Parent.push_back(static_cast<int>(parent->GetTuple1(i)));
      }
      // Only leaves block; parents (Level > 0) are for hierarchy cuts.
      if (level && level->GetTuple1(i) != 0.0)
      {
        continue;
      }
      b.SceneBlockers.AddSphere(float(c[0]), float(c[1]), float(c[2]), float(r), a, object);
      b.LeafIds.push_back(i);
    }
    if (!this->ProxyError.empty())
    {
      b.SceneBlockers = proxygi::Blockers();
      b.LeafIds.clear();
      b.Hierarchy = proxygi::ProxyHierarchy();
      b.UseHierarchy = false;
    }
    else if (b.UseHierarchy && !b.Hierarchy.Finish())
    {
      this->ProxyError = "the proxies' Parent array does not form a hierarchy (a parent must "
                         "have a higher Level than its child)";
      b.UseHierarchy = false;
    }
  }
  for (std::size_t k = 0; k + 8 < this->Planes.size(); k += 9)
  {
    float v[15];
    for (int q = 0; q < 9; ++q)
    {
      v[q] = static_cast<float>(this->Planes[k + q]);
    }
    for (int q = 0; q < 6; ++q)
    {
      v[9 + q] = static_cast<float>(this->PlaneExtents[k / 9 * 6 + q]);
    }
    b.SceneBlockers.AddPlane(v, v + 3, v + 6, v + 9);
  }
  return true;
}

bool vtkPGIGIBake::ProjectLight(vtkPGILighting* lighting, proxygi::BakedScene& previous)
{
  proxygi::BakedScene& b = this->Scene;
  const proxygi::EnvironmentMap* environment = nullptr;
  std::string error;
  if (!lighting->GetEnvironment(environment, error))
  {
    this->Error = "Bad environment: " + error;
    this->LastLight = LightKey();
    return false;
  }
  const int order = b.Order;
  b.Environment = environment;
  LightKey key;
  key.Environment = environment;
  key.Time = lighting->GetMTime();
  if (lighting->GetEnvironmentImage())
  {
    key.Time = std::max(key.Time, lighting->GetEnvironmentImage()->GetMTime());
  }
  key.Order = order;
  key.IndirectOrder = b.IndirectOrder;
  key.Path = this->Settings->GetShadingPath();
  key.PlaneBlocking = this->Settings->GetPlaneBlocking();
  key.Planes = this->Planes;
  key.Bright = { this->Settings->GetBrightLights() ? 1.0 : 0.0,
    this->Settings->GetBrightLightFraction(),
    static_cast<double>(this->Settings->GetBrightLightCount()) };
  if (key == this->LastLight && previous.Shading)
  {
    // Only the proxies or the kernel's knobs changed: the light stands.
    b.Light = std::move(previous.Light);
    b.OpenShading = std::move(previous.OpenShading);
    b.PlanesInLight = previous.PlanesInLight;
    b.LightAbovePlanes = std::move(previous.LightAbovePlanes);
    b.PlaneVisibility = std::move(previous.PlaneVisibility);
    b.Shading = std::move(previous.Shading);
    b.IndirectShading = std::move(previous.IndirectShading);
    b.BrightLights = std::move(previous.BrightLights);
    b.BrightestFraction = previous.BrightestFraction;
    b.BrightFraction = previous.BrightFraction;
    b.Secondary = std::move(previous.Secondary);
    b.InterleavedResponse = std::move(previous.InterleavedResponse);
    b.Dark = previous.Dark;
  }
  else
  {
    this->ProjectEnvironment(*environment);
    this->LastLight = key;
    ++this->NumberOfLightProjections;
  }
  this->SetKernel();
  return true;
}

void vtkPGIGIBake::ProjectEnvironment(const proxygi::EnvironmentMap& map)
{
  proxygi::BakedScene& b = this->Scene;
  // The peaks are looked for even when switched off: the plan says what the
  // SH then carries.
  proxygi::BrightLightOptions options;
  options.MaxLights = std::max(1, this->Settings->GetBrightLightCount());
  options.MinFraction = this->Settings->GetBrightLightFraction();
  proxygi::BrightLightResult bright;
  proxygi::ExtractBrightLights(map, options, bright);
  b.BrightestFraction = bright.BrightestFraction;
  const bool takeOut = this->Settings->GetBrightLights() &&
    this->Settings->GetBrightLightCount() > 0 && !bright.Lights.empty();
  if (takeOut)
  {
    b.BrightLights = bright.Lights;
    b.BrightFraction = bright.ExtractedFraction;
  }
  const proxygi::EnvironmentMap* environment = takeOut ? &bright.Residual : &map;
  const int order = b.Order, n2 = order * order;
  // With planes in the light, each map is projected once at the planes'
  // product order; its first order^2 coefficients are the order-n ones.
  b.PlanesInLight = this->Settings->GetPlaneBlocking() == vtkPGIGISettings::PLANES_IN_LIGHT &&
    b.SceneBlockers.Planes() > 0;
  const int high = proxygi::LightAbovePlanesOrder(order), h2 = high * high;
  const auto project = [&](const proxygi::EnvironmentMap& from, std::vector<double>& out,
                         std::vector<double>& projected)
  {
    out.assign(3 * static_cast<std::size_t>(n2), 0.0);
    if (!b.PlanesInLight)
    {
      from.ProjectSH(order, &out[0], &out[n2], &out[2 * n2]);
      return;
    }
    projected.assign(3 * static_cast<std::size_t>(h2), 0.0);
    from.ProjectSH(high, &projected[0], &projected[h2], &projected[2 * h2]);
    for (int c = 0; c < 3; ++c)
    {
      std::copy_n(&projected[c * static_cast<std::size_t>(h2)], n2, &out[c * n2]);
    }
  };
  std::vector<double> projected;
  project(*environment, b.Light, projected);
  const auto path = this->Settings->GetShadingPath() == vtkPGIGISettings::SHADING_TABLE
    ? proxygi::EnvironmentShading::Path::Table
    : proxygi::EnvironmentShading::Path::ProductMatrix;
  b.OpenShading = std::make_shared<proxygi::EnvironmentShading>(
    order, &b.Light[0], &b.Light[n2], &b.Light[2 * n2], path);
  // With planes in the light, receivers above every plane get L times the
  // planes' steps; the others keep L and the planes in log space.
  b.LightAbovePlanes = b.Light;
  b.PlaneVisibility.assign(n2, 0.0);
  double* above = b.LightAbovePlanes.data();
  if (b.PlanesInLight)
  {
    proxygi::LightAbovePlanes(projected, order, b.SceneBlockers.PlaneNormal.data(),
      static_cast<int>(b.SceneBlockers.Planes()), above, above + n2, above + 2 * n2,
      b.PlaneVisibility.data());
  }
  b.Shading =
    std::make_shared<proxygi::EnvironmentShading>(order, above, above + n2, above + 2 * n2, path);
  std::vector<double> bounceAbove;
  if (takeOut)
  {
    // The bounce sees the whole map (its coefficients; a table only where
    // the bounce's shading reads one, below).
    project(map, bounceAbove, projected);
    if (b.PlanesInLight)
    {
      std::vector<double> unused(n2);
      proxygi::LightAbovePlanes(projected, order, b.SceneBlockers.PlaneNormal.data(),
        static_cast<int>(b.SceneBlockers.Planes()), &bounceAbove[0], &bounceAbove[n2],
        &bounceAbove[2 * n2], unused.data());
    }
    above = bounceAbove.data();
  }
  if (b.IndirectOrder == order)
  {
    b.IndirectShading = takeOut ? std::make_shared<proxygi::EnvironmentShading>(
                                    order, above, above + n2, above + 2 * n2, path)
                                : b.Shading;
  }
  else
  {
    // The first k^2 coefficients of each channel: the order-n product with
    // the planes' steps, truncated, is closer than one taken at order k.
    const int k2 = b.IndirectOrder * b.IndirectOrder;
    std::vector<double> low(3 * static_cast<std::size_t>(k2));
    for (int c = 0; c < 3; ++c)
    {
      std::copy(above + c * n2, above + c * n2 + k2, low.begin() + c * k2);
    }
    b.IndirectShading = std::make_shared<proxygi::EnvironmentShading>(
      b.IndirectOrder, &low[0], &low[k2], &low[2 * k2], path);
  }
  b.Secondary = std::make_shared<proxygi::SecondaryLights>(
    order, above, above + n2, above + 2 * n2, b.PlanesInLight ? nullptr : &b.SceneBlockers);
  b.InterleavedResponse.resize(3 * static_cast<std::size_t>(n2));
  for (int i = 0; i < n2; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      b.InterleavedResponse[3 * i + c] = b.Secondary->Response[c * n2 + i];
    }
  }
  b.Dark = above[0] <= 0.0 && above[n2] <= 0.0 && above[2 * n2] <= 0.0;
}

void vtkPGIGIBake::SetKernel()
{
  proxygi::BakedScene& b = this->Scene;
  proxygi::SoftShadowSettings& k = b.Kernel;
  vtkPGIGISettings* s = this->Settings;
  k.Order = b.Order;
  k.AccumulationOrder = s->GetAccumulationOrder();
  k.Exp.Method = static_cast<proxygi::sh::ExpMethod>(s->GetExpMethod());
  k.Exp.Degree = s->GetExpDegree();
  k.Exp.HybridMaxNorm = s->GetHybridMaxNorm();
  k.Exp.RangeGuard = s->GetRangeTolerance() >= 0.0;
  k.Exp.RangeTolerance = std::max(0.0, s->GetRangeTolerance());
  k.WindowH = s->GetWindowSize();
  k.MinAngle = static_cast<float>(s->GetMinBlockerAngle());
  k.SelfShadowRules = s->GetSelfShadowRules();
  k.PlanesInLogSpace = !b.PlanesInLight;
  b.IndirectKernel = k;
  b.IndirectKernel.Order = b.IndirectOrder;
}

void vtkPGIGIBake::PlanEffects(vtkPGILighting* lighting)
{
  proxygi::BakedScene& b = this->Scene;
  vtkPGIGISettings* s = this->Settings;
  const proxygi::Blockers& blockers = b.SceneBlockers;
  b.AnyBlockers = blockers.Spheres() > 0 || blockers.Planes() > 0;
  b.RunShadows = s->GetShadows() && b.AnyBlockers;
  for (float a : blockers.Albedo)
  {
    b.AnyAlbedo = b.AnyAlbedo || a > 0.0f;
  }
  for (float a : blockers.PlaneAlbedo)
  {
    b.PlanesReflect = b.PlanesReflect || a > 0.0f;
  }
  b.AnyAlbedo = b.AnyAlbedo || b.PlanesReflect;
  const bool indirect = s->GetIndirect();
  const bool shadowedMode =
    indirect && s->GetIndirectMode() == vtkPGIGISettings::INDIRECT_MODE_SHADOWED;
  b.RunIndirect = indirect && !shadowedMode && b.AnyBlockers && b.AnyAlbedo && !b.Dark;
  // The shadowed model's lights are the spheres; planes still reflect.
  b.RunPlaneBounce = shadowedMode && b.PlanesReflect && !b.Dark;
  const bool hasLights =
    !lighting->GetSphereLights().empty() || !lighting->GetPointLights().empty();
  b.RunLocal = s->GetLocalLights() && hasLights;

  std::ostringstream env;
  env << "environment light: SH order " << b.Order << ", "
      << (s->GetShadingPath() == vtkPGIGISettings::SHADING_TABLE ? "tabulated L*H(N)"
                                                                 : "product matrix M_L");
  b.Plan.push_back(env.str());
  b.RunBrightLights = !b.BrightLights.empty() && !b.Dark;
  {
    std::ostringstream line;
    line.precision(3);
    const double min = s->GetBrightLightFraction();
    if (b.RunBrightLights)
    {
      line << "bright lights: " << b.BrightLights.size() << " taken out of the map ("
           << 100.0 * b.BrightFraction << "% of its power; half-angles";
      for (const proxygi::DistantLight& l : b.BrightLights)
      {
        line << " " << l.HalfAngle * 180.0 / 3.14159265358979323846 << " deg";
      }
      line << "), each with its own shadows; the SH carries the rest, the bounce the whole map";
    }
    else if (!s->GetBrightLights() || s->GetBrightLightCount() == 0)
    {
      line << "bright lights: off; the map's brightest compact peak holds "
           << 100.0 * b.BrightestFraction << "% of its power, carried by the SH";
    }
    else
    {
      line << "bright lights: none (the brightest compact peak holds "
           << 100.0 * b.BrightestFraction << "% of the map's power, under " << 100.0 * min << "%)";
    }
    b.Plan.push_back(line.str());
  }
  if (!s->GetShadows())
  {
    b.Plan.push_back("shadows: off (switched off)");
  }
  else if (!b.RunShadows)
  {
    b.Plan.push_back("shadows: skipped (no proxies and no blocker planes)");
  }
  if (!indirect)
  {
    b.Plan.push_back("indirect light: off (switched off)");
  }
  else if (shadowedMode)
  {
    // Planned in PrepareSphericalLights, once the lights are built.
  }
  else if (!b.RunIndirect)
  {
    b.Plan.push_back(!b.AnyBlockers ? "indirect light: skipped (no proxies or planes to reflect)"
        : b.Dark                    ? "indirect light: skipped (the environment is black)"
                 : "indirect light: skipped (every proxy and plane has albedo 0)");
  }
  else
  {
    b.Plan.push_back(std::string("indirect light: one bounce from the proxies and planes, ") +
      proxygi::IndirectOperatorName(
        static_cast<proxygi::IndirectOperator>(s->GetIndirectOperator())) +
      " operator, overlap normalisation xi");
  }
  if (!s->GetLocalLights())
  {
    b.Plan.push_back(hasLights ? "local lights: off (switched off)"
                               : "local lights: off (switched off; none in the lighting)");
  }
  else if (!b.RunLocal)
  {
    b.Plan.push_back("local lights: skipped (none in the lighting)");
  }
  else
  {
    std::ostringstream line;
    line << "local lights: " << lighting->GetSphereLights().size() << " spherical, "
         << lighting->GetPointLights().size()
         << " point (analytic L_H lobes, shadowed by the proxies' visibility)";
    b.Plan.push_back(line.str());
  }
  b.NeedVisibility =
    b.AnyBlockers && (b.RunShadows || b.RunIndirect || b.RunPlaneBounce || b.RunLocal);
  // The bounce's tables, built here (each in parallel) rather than first in
  // a parallel loop (one thread building while the others wait).
  if (b.RunIndirect || b.RunPlaneBounce)
  {
    proxygi::sh::IndirectTables::Get(b.Order);
  }
  if (this->Settings->GetIndirect() &&
    this->Settings->GetIndirectMode() == vtkPGIGISettings::INDIRECT_MODE_SHADOWED)
  {
    proxygi::sh::IndirectTables::Get(b.IndirectOrder);
    proxygi::sh::CapTables::Get(b.IndirectOrder);
  }
}

void vtkPGIGIBake::PrepareLocalLights(vtkPGILighting* lighting)
{
  // Point lights are tiny spheres of equal power.
  if (this->Scene.RunLocal)
  {
    this->Scene.Locals.AddLights(*lighting);
    proxygi::sh::AnalyticLightTables::Get(this->Scene.Order);
  }
}

bool vtkPGIGIBake::PrepareSphericalLights()
{
  proxygi::BakedScene& b = this->Scene;
  vtkPGIGISettings* s = this->Settings;
  if (!s->GetIndirect() || s->GetIndirectMode() != vtkPGIGISettings::INDIRECT_MODE_SHADOWED)
  {
    return true;
  }
  const proxygi::ShadowedIndirect kernel(b.IndirectKernel,
    s->GetSphericalLightBlocking() == vtkPGIGISettings::BLOCKING_PER_OBJECT
      ? proxygi::SphericalLightBlocking::PerObject
      : proxygi::SphericalLightBlocking::PerSphere);
  // With a hierarchy every node is a spherical light (parents for the cuts).
  std::vector<vtkIdType> allIds;
  if (b.UseHierarchy)
  {
    for (vtkIdType i = 0; i < this->Proxies->GetNumberOfPoints(); ++i)
    {
      allIds.push_back(i);
    }
  }
  std::string summary, bad;
  const std::string why =
    proxygi::PrepareSphericalLights(this->Proxies, b.UseHierarchy ? allIds : b.LeafIds,
      b.UseHierarchy ? this->Proxies->GetPointData()->GetArray("Level") : nullptr, b.IndirectOrder,
      s->GetAlbedoArrayName(), s->GetDefaultProxyAlbedo(), *b.IndirectShading, b.Dark,
      b.SceneBlockers, b.Locals.Count() ? &b.Locals : nullptr, kernel, b.Lights, summary, bad);
  if (!bad.empty())
  {
    this->Error = bad;
    return false;
  }
  b.RunShadowed = why.empty();
  b.SphericalLightsSummary = b.RunShadowed ? summary : "skipped: " + why;
  const std::string order = b.IndirectOrder == b.Order ? std::string()
                                                       : ", the bounce at SH order " +
      std::to_string(b.IndirectOrder) + " (shadows at " + std::to_string(b.Order) + ")";
  b.Plan.push_back(b.RunShadowed ? "indirect light (shadowed): " + summary + order
                                 : "indirect light (shadowed): skipped (" + why + ")");
  if (b.RunPlaneBounce)
  {
    b.Plan.push_back("indirect light (shadowed): the blocker planes reflect as uniform "
                     "lights, dimmed where the proxies shadow them");
  }
  if (b.RunShadowed && b.UseHierarchy)
  {
    // The leaves alone: what receivers use without a cut, and the ratios' reference.
    const std::size_t n2s = 3 * static_cast<std::size_t>(b.IndirectOrder) * b.IndirectOrder;
    for (std::size_t i = 0; i < b.Lights.Count(); ++i)
    {
      if (b.Lights.Level[i] != 0)
      {
        continue;
      }
      b.LeafOfNode[i] = static_cast<int>(b.LeafLights.Count());
      b.LeafLights.Add(
        b.Lights.X[i], b.Lights.Y[i], b.Lights.Z[i], b.Lights.R[i], b.Lights.Object[i]);
      b.LeafLights.Radiance.insert(b.LeafLights.Radiance.end(), b.Lights.Radiance.begin() + i * n2s,
        b.Lights.Radiance.begin() + (i + 1) * n2s);
    }
    b.LeafLights.Order = b.IndirectOrder;
    b.LeafLights.Finish();
  }
  return true;
}

void vtkPGIGIBake::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Proxies: " << this->Proxies << "\n";
  os << indent << "Lighting: " << this->Lighting << "\n";
  os << indent << "Settings: " << this->Settings << "\n";
  os << indent << "BlockerPlanes: " << this->GetNumberOfBlockerPlanes() << "\n";
  os << indent << "NumberOfBuilds: " << this->NumberOfBuilds << "\n";
  os << indent << "NumberOfLightProjections: " << this->NumberOfLightProjections << "\n";
  os << indent << "Error: " << (this->Error.empty() ? "(none)" : this->Error) << "\n";
}
