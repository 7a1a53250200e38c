#include "vtkPGIGlobalIllumination.h"

#include "pgiEnvironmentMap.h"
#include "pgiEnvironmentShading.h"
#include "pgiIndirectLight.h"
#include "pgiMaterial.h"
#include "pgiSHLightTables.h"
#include "pgiSHSphericalLight.h"
#include "pgiSHZonal.h"
#include "pgiSoftShadows.h"
#include "pgiSphericalLights.h"
#include "vtkPGILighting.h"

#include "vtkDataArray.h"
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
#include "vtkStringArray.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>

vtkStandardNewMacro(vtkPGIGlobalIllumination);

namespace
{
/**
 * The spherical lights of one cluster's cut (hierarchy indices `cut` into
 * `nodes`), each parent with the reflection ratio (Guerrero 2008, eq. 25)
 * that scales its share at the cluster's central receiver (p, n) to the sum
 * of its leaves' shares there.
 */
void CutSphericalLights(const proxygi::SphericalLights& nodes,
  const proxygi::SphericalLights& leaves, const std::map<std::size_t, int>& leafOfNode,
  const proxygi::ProxyHierarchy& hierarchy, const std::vector<int>& cut,
  const proxygi::Blockers& planes, const proxygi::ShadowedIndirect& kernel, const float p[3],
  const float n[3], proxygi::SphericalLights& out)
{
  const std::size_t n2 = static_cast<std::size_t>(nodes.Order * nodes.Order);
  out = proxygi::SphericalLights();
  out.Order = nodes.Order;
  for (int node : cut)
  {
    out.Add(nodes.X[node], nodes.Y[node], nodes.Z[node], nodes.R[node], nodes.Object[node]);
    out.Radiance.insert(out.Radiance.end(), nodes.Radiance.begin() + node * 3 * n2,
      nodes.Radiance.begin() + (node + 1) * 3 * n2);
  }
  out.Finish();
  proxygi::SphericalLightScratch scratch;
  std::vector<float> leafShare(leaves.Count()), cutShare(out.Count());
  float rgb[3];
  kernel.ExitRadiance(leaves, true, nullptr, &planes, p, n, rgb, scratch, leafShare.data());
  kernel.ExitRadiance(out, true, nullptr, &planes, p, n, rgb, scratch, cutShare.data());
  out.ReflectionRatio.assign(out.Count(), 1.0f);
  for (std::size_t k = 0; k < cut.size(); ++k)
  {
    if (hierarchy.Children[cut[k]].empty())
    {
      continue; // a leaf: ratio 1
    }
    float sum = 0.0f;
    std::vector<int> below(hierarchy.Children[cut[k]]);
    while (!below.empty())
    {
      const int j = below.back();
      below.pop_back();
      if (!hierarchy.Children[j].empty())
      {
        below.insert(below.end(), hierarchy.Children[j].begin(), hierarchy.Children[j].end());
        continue;
      }
      const auto leaf = leafOfNode.find(static_cast<std::size_t>(j));
      sum += leaf != leafOfNode.end() ? leafShare[leaf->second] : 0.0f;
    }
    // Nothing to scale where the parent is hidden or unlit at the centre: 1.
    out.ReflectionRatio[k] = cutShare[k] > 1e-12f ? std::min(4.0f, sum / cutShare[k]) : 1.0f;
  }
}
} // namespace
vtkCxxSetObjectMacro(vtkPGIGlobalIllumination, Lighting, vtkPGILighting);

vtkPGIGlobalIllumination::vtkPGIGlobalIllumination()
{
  this->SetNumberOfInputPorts(2);
  this->SetAlbedoArrayName("Albedo");
}

vtkPGIGlobalIllumination::~vtkPGIGlobalIllumination()
{
  this->SetLighting(nullptr);
  this->SetAlbedoArrayName(nullptr);
}

vtkMTimeType vtkPGIGlobalIllumination::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->Lighting)
  {
    t = std::max(t, this->Lighting->GetMTime());
  }
  return t;
}

void vtkPGIGlobalIllumination::AddBlockerPlane(const double origin[3], const double normal[3])
{
  const double black[3] = { 0, 0, 0 };
  this->AddBlockerPlane(origin, normal, black);
}

void vtkPGIGlobalIllumination::AddBlockerPlane(
  const double origin[3], const double normal[3], const double albedo[3])
{
  this->BlockerPlanes.insert(this->BlockerPlanes.end(), origin, origin + 3);
  this->BlockerPlanes.insert(this->BlockerPlanes.end(), normal, normal + 3);
  this->BlockerPlanes.insert(this->BlockerPlanes.end(), albedo, albedo + 3);
  this->Modified();
}

void vtkPGIGlobalIllumination::RemoveAllBlockerPlanes()
{
  this->BlockerPlanes.clear();
  this->Modified();
}

void vtkPGIGlobalIllumination::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Lighting: " << this->Lighting << "\n";
  os << indent << "Order: " << this->Order << "\n";
  os << indent << "ExpMethod: " << this->ExpMethod << " (degree " << this->ExpDegree << ")\n";
  os << indent << "AccumulationOrder: " << this->AccumulationOrder << "\n";
  os << indent << "WindowSize: " << this->WindowSize << "\n";
  os << indent << "SelfShadowRules: " << this->SelfShadowRules << "\n";
  os << indent << "MinBlockerAngle: " << this->MinBlockerAngle << "\n";
  os << indent << "ShadingPath: " << this->ShadingPath << "\n";
  os << indent << "Shadows: " << this->Shadows << "\n";
  os << indent << "Indirect: " << this->Indirect << " (operator " << this->IndirectOperator
     << ")\n";
  os << indent << "IndirectMode: "
     << (this->IndirectMode == INDIRECT_MODE_UNSHADOWED    ? "Unshadowed"
            : this->IndirectMode == INDIRECT_MODE_SHADOWED ? "Shadowed"
                                                           : "Off")
     << "\n";
  os << indent << "SphericalLightBlocking: "
     << (this->SphericalLightBlocking == BLOCKING_PER_OBJECT ? "PerObject" : "PerSphere") << "\n";
  os << indent << "PlaneBounceShadows: " << this->PlaneBounceShadows << "\n";
  os << indent
     << "PlaneBlocking: " << (this->PlaneBlocking == PLANES_IN_LIGHT ? "InLight" : "InLogSpace")
     << "\n";
  os << indent << "LocalLights: " << this->LocalLights << "\n";
  os << indent << "HierarchyAngle: " << this->HierarchyAngle << "\n";
  os << indent << "ReceiversPerCluster: " << this->ReceiversPerCluster << "\n";
  os << indent << "BlockerPlanes: " << this->BlockerPlanes.size() / 9 << "\n";
  os << indent << "DefaultAlbedo: " << this->DefaultAlbedo[0] << " " << this->DefaultAlbedo[1]
     << " " << this->DefaultAlbedo[2] << "\n";
  os << indent << "AlbedoArrayName: " << (this->AlbedoArrayName ? this->AlbedoArrayName : "(none)")
     << "\n";
}

int vtkPGIGlobalIllumination::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

int vtkPGIGlobalIllumination::RequestData(
  vtkInformation*, vtkInformationVector** in, vtkInformationVector* out)
{
  this->Plan.clear();
  vtkPolyData* receivers = vtkPolyData::GetData(in[0]);
  vtkPolyData* output = vtkPolyData::GetData(out);
  if (!receivers || receivers->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro("No receivers: input 0 is empty.");
    return 0;
  }
  const vtkIdType n = receivers->GetNumberOfPoints();
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    receivers->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      vtkErrorMacro("Receiver " << i << " has a NaN or Inf coordinate.");
      return 0;
    }
  }

  // Blockers: proxies (checked) and planes; the hierarchy when asked for.
  proxygi::Blockers blockers;
  proxygi::ProxyHierarchy hierarchy;
  bool useHierarchy = false;
  std::vector<vtkIdType> leafIds; // proxies that are blockers (and spherical lights)
  vtkPolyData* proxies =
    this->GetNumberOfInputConnections(1) ? vtkPolyData::GetData(in[1]) : nullptr;
  if (proxies && proxies->GetNumberOfPoints() > 0)
  {
    vtkDataArray* radius = proxies->GetPointData()->GetArray("Radius");
    if (!radius)
    {
      vtkErrorMacro("The proxies (input 1) need a \"Radius\" point array.");
      return 0;
    }
    // Only leaves block; parents (Level > 0) are for hierarchy cuts.
    vtkDataArray* level = proxies->GetPointData()->GetArray("Level");
    vtkDataArray* parent = proxies->GetPointData()->GetArray("Parent");
    double proxyAlbedo[3];
    useHierarchy = this->HierarchyAngle > 0.0 && level && parent;
    for (vtkIdType i = 0; i < proxies->GetNumberOfPoints(); ++i)
    {
      double c[3];
      proxies->GetPoint(i, c);
      const double r = radius->GetTuple1(i);
      if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]) ||
        !std::isfinite(r) || r < 0.0)
      {
        vtkErrorMacro("Proxy " << i << " has a NaN, Inf or negative centre or radius.");
        return 0;
      }
      proxygi::AlbedoOf(proxies, this->AlbedoArrayName, i, this->DefaultAlbedo, proxyAlbedo);
      const float albedoF[3] = { float(proxyAlbedo[0]), float(proxyAlbedo[1]),
        float(proxyAlbedo[2]) };
      if (useHierarchy)
      {
        hierarchy.Albedo.insert(hierarchy.Albedo.end(), albedoF, albedoF + 3);
        hierarchy.X.push_back(float(c[0]));
        hierarchy.Y.push_back(float(c[1]));
        hierarchy.Z.push_back(float(c[2]));
        hierarchy.R.push_back(float(r));
        hierarchy.Level.push_back(static_cast<int>(level->GetTuple1(i)));
        hierarchy.Parent.push_back(static_cast<int>(parent->GetTuple1(i)));
      }
      if (level && level->GetTuple1(i) != 0.0)
      {
        continue;
      }
      blockers.AddSphere(float(c[0]), float(c[1]), float(c[2]), float(r), albedoF);
      leafIds.push_back(i);
    }
  }
  if (useHierarchy && !hierarchy.Finish())
  {
    vtkErrorMacro("The proxies' Parent array does not form a hierarchy (a parent must have a "
                  "higher Level than its child).");
    return 0;
  }
  for (std::size_t k = 0; k + 8 < this->BlockerPlanes.size(); k += 9)
  {
    float v[9];
    for (int q = 0; q < 9; ++q)
    {
      v[q] = static_cast<float>(this->BlockerPlanes[k + q]);
    }
    blockers.AddPlane(v, v + 3, v + 6);
  }

  // Light: the environment projected to SH at the shading order.
  vtkNew<vtkPGILighting> defaultLighting;
  vtkPGILighting* lighting = this->Lighting ? this->Lighting : defaultLighting.Get();
  const proxygi::EnvironmentMap* environment = nullptr;
  std::string error;
  if (!lighting->GetEnvironment(environment, error))
  {
    vtkErrorMacro("Bad environment: " << error);
    return 0;
  }
  const int order = this->Order, n2 = order * order;
  std::vector<double> lr(n2), lg(n2), lb(n2);
  environment->ProjectSH(order, lr.data(), lg.data(), lb.data());
  const auto shadingPath = this->ShadingPath == SHADING_TABLE
    ? proxygi::EnvironmentShading::Path::Table
    : proxygi::EnvironmentShading::Path::ProductMatrix;
  // The open light serves receivers without shadows or below a plane; with
  // planes in the light, those above every plane get L times their steps.
  const proxygi::EnvironmentShading openShading(
    order, lr.data(), lg.data(), lb.data(), shadingPath);
  const bool planesInLight = this->PlaneBlocking == PLANES_IN_LIGHT && blockers.Planes() > 0;
  std::vector<double> planeVisibility(n2, 0.0);
  if (planesInLight)
  {
    proxygi::LightAbovePlanes(*environment, order, blockers.PlaneNormal.data(),
      static_cast<int>(blockers.Planes()), lr.data(), lg.data(), lb.data(), planeVisibility.data());
  }
  const proxygi::EnvironmentShading shading(order, lr.data(), lg.data(), lb.data(), shadingPath);

  // The plan: what this scene needs.
  const proxygi::SecondaryLights secondary(
    order, lr.data(), lg.data(), lb.data(), planesInLight ? nullptr : &blockers);
  const bool anyBlockers = blockers.Spheres() > 0 || blockers.Planes() > 0;
  const bool runShadows = this->Shadows && anyBlockers;
  bool anyAlbedo = false;
  for (float a : blockers.Albedo)
  {
    anyAlbedo = anyAlbedo || a > 0.0f;
  }
  for (float a : blockers.PlaneAlbedo)
  {
    anyAlbedo = anyAlbedo || a > 0.0f;
  }
  const bool dark = lr[0] <= 0.0 && lg[0] <= 0.0 && lb[0] <= 0.0;
  const int indirectMode = this->Indirect ? this->IndirectMode : INDIRECT_MODE_OFF;
  const bool runIndirect =
    indirectMode == INDIRECT_MODE_UNSHADOWED && anyBlockers && anyAlbedo && !dark;
  // The shadowed model's lights are the spheres; planes still reflect.
  bool planesReflect = false;
  for (float a : blockers.PlaneAlbedo)
  {
    planesReflect = planesReflect || a > 0.0f;
  }
  const bool runPlaneBounce = indirectMode == INDIRECT_MODE_SHADOWED && planesReflect && !dark;
  const bool hasLights =
    !lighting->GetSphereLights().empty() || !lighting->GetPointLights().empty();
  const bool runLocal = this->LocalLights && hasLights;
  {
    std::ostringstream line;
    line << "environment light: SH order " << order << ", "
         << (this->ShadingPath == SHADING_TABLE ? "tabulated L*H(N)" : "product matrix M_L");
    this->Plan.push_back(line.str());
  }
  if (!this->Shadows)
  {
    this->Plan.push_back("shadows: off (switched off)");
  }
  else if (!runShadows)
  {
    this->Plan.push_back("shadows: skipped (no proxies and no blocker planes)");
  }
  if (indirectMode == INDIRECT_MODE_OFF)
  {
    this->Plan.push_back("indirect light: off (switched off)");
  }
  else if (indirectMode == INDIRECT_MODE_SHADOWED)
  {
    // Planned below, once the spherical lights are built.
  }
  else if (!runIndirect)
  {
    this->Plan.push_back(!anyBlockers ? "indirect light: skipped (no proxies or planes to reflect)"
        : dark                        ? "indirect light: skipped (the environment is black)"
               : "indirect light: skipped (every proxy and plane has albedo 0)");
  }
  else
  {
    this->Plan.push_back(std::string("indirect light: one bounce from the proxies and planes, ") +
      proxygi::IndirectOperatorName(
        static_cast<proxygi::IndirectOperator>(this->IndirectOperator)) +
      " operator, overlap normalisation xi");
  }
  if (!this->LocalLights)
  {
    this->Plan.push_back("local lights: off (switched off)");
  }
  else
  {
    std::ostringstream line;
    line << (runLocal ? "local lights: " : "local lights: skipped (none in the lighting)");
    if (runLocal)
    {
      line << lighting->GetSphereLights().size() << " spherical, "
           << lighting->GetPointLights().size()
           << " point (analytic L_H lobes, shadowed by the proxies' visibility)";
    }
    this->Plan.push_back(line.str());
  }
  const bool needVisibility =
    anyBlockers && (runShadows || runIndirect || runPlaneBounce || runLocal);
  // Local lights as spheres: point lights are tiny spheres of equal power.
  proxygi::LocalEmitters locals;
  if (runLocal)
  {
    locals.AddLights(*lighting);
  }
  const proxygi::sh::AnalyticLightTables* lightTables =
    runLocal ? &proxygi::sh::AnalyticLightTables::Get(order) : nullptr;
  if (runIndirect)
  {
    proxygi::sh::IndirectTables::Get(order); // build before the parallel loops
  }

  // Shadowed one bounce (Guerrero 2008): the leaf proxies as spherical lights.
  proxygi::SoftShadowSettings settings;
  settings.Order = order;
  settings.AccumulationOrder = this->AccumulationOrder;
  settings.Exp.Method = static_cast<proxygi::sh::ExpMethod>(this->ExpMethod);
  settings.Exp.Degree = this->ExpDegree;
  settings.WindowH = this->WindowSize;
  settings.MinAngle = static_cast<float>(this->MinBlockerAngle);
  settings.SelfShadowRules = this->SelfShadowRules;
  settings.PlanesInLogSpace = !planesInLight;
  const proxygi::ShadowedIndirect shadowedIndirect(settings,
    this->SphericalLightBlocking == BLOCKING_PER_OBJECT
      ? proxygi::SphericalLightBlocking::PerObject
      : proxygi::SphericalLightBlocking::PerSphere);
  proxygi::SphericalLights spheres, leafLights;
  std::map<std::size_t, int> leafOfNode; // hierarchy node -> index in leafLights
  bool runShadowed = false;
  if (indirectMode == INDIRECT_MODE_SHADOWED)
  {
    std::string summary, bad;
    // With a hierarchy every node is a spherical light (parents for the cuts).
    std::vector<vtkIdType> allIds;
    if (useHierarchy)
    {
      for (vtkIdType i = 0; i < proxies->GetNumberOfPoints(); ++i)
      {
        allIds.push_back(i);
      }
    }
    const std::string why = PrepareSphericalLights(proxies, useHierarchy ? allIds : leafIds,
      useHierarchy ? proxies->GetPointData()->GetArray("Level") : nullptr, order,
      this->AlbedoArrayName, this->DefaultAlbedo, shading, dark, blockers,
      locals.Count() ? &locals : nullptr, shadowedIndirect, spheres, summary, bad);
    if (!bad.empty())
    {
      vtkErrorMacro(<< bad);
      return 0;
    }
    runShadowed = why.empty();
    this->Plan.push_back(runShadowed ? "indirect light (shadowed): " + summary
                                     : "indirect light (shadowed): skipped (" + why + ")");
    if (runPlaneBounce)
    {
      this->Plan.push_back("indirect light (shadowed): the blocker planes reflect as uniform "
                           "lights, dimmed where the proxies shadow them");
    }
    if (runShadowed && useHierarchy)
    {
      // The leaves alone: what receivers use without a cut, and the ratios' reference.
      for (std::size_t i = 0; i < spheres.Count(); ++i)
      {
        if (spheres.Level[i] != 0)
        {
          continue;
        }
        leafOfNode[i] = static_cast<int>(leafLights.Count());
        leafLights.Add(spheres.X[i], spheres.Y[i], spheres.Z[i], spheres.R[i], spheres.Object[i]);
        const std::size_t n2s = static_cast<std::size_t>(3 * n2);
        leafLights.Radiance.insert(leafLights.Radiance.end(), spheres.Radiance.begin() + i * n2s,
          spheres.Radiance.begin() + (i + 1) * n2s);
      }
      leafLights.Order = order;
      leafLights.Finish();
    }
  }
  const proxygi::SphericalLights& shadowedLeaves = useHierarchy ? leafLights : spheres;
  std::vector<proxygi::SphericalLights> clusterLights;

  vtkSmartPointer<vtkDataArray> normals = receivers->GetPointData()->GetNormals();
  if (!normals)
  {
    vtkNew<vtkPolyDataNormals> computer;
    computer->SetInputData(receivers);
    computer->SplittingOff();
    computer->Update();
    if (computer->GetOutput()->GetNumberOfPoints() != n ||
      !computer->GetOutput()->GetPointData()->GetNormals())
    {
      vtkErrorMacro("Could not compute receiver normals (no polygons?); give point normals.");
      return 0;
    }
    normals = computer->GetOutput()->GetPointData()->GetNormals();
  }

  const proxygi::SoftShadows shadows(settings);
  // Receivers on or below a plane keep the planes in log space (they see
  // under the ones they are below, and skip those).
  proxygi::SoftShadowSettings logSettings = settings;
  logSettings.PlanesInLogSpace = true;
  const proxygi::SoftShadows shadowsLog(logSettings);

  vtkNew<vtkFloatArray> direct, indirect, indirectShadowed, local, total, visibility;
  direct->SetName("DirectShadowed");
  indirect->SetName("IndirectProxy");
  indirectShadowed->SetName("IndirectShadowed");
  local->SetName("LocalLights");
  total->SetName("Radiance");
  visibility->SetName("Visibility");
  for (vtkFloatArray* a :
    { direct.Get(), indirect.Get(), indirectShadowed.Get(), local.Get(), total.Get() })
  {
    a->SetNumberOfComponents(3);
    a->SetNumberOfTuples(n);
  }
  visibility->SetNumberOfComponents(n2);
  visibility->SetNumberOfTuples(n);

  // Receiver clusters and their hierarchy cuts (one blocker list each).
  std::vector<int> clusterOf;
  std::vector<proxygi::Blockers> clusterBlockers;
  if (needVisibility && useHierarchy)
  {
    const int clusters = static_cast<int>(
      std::max<vtkIdType>(1, (n + this->ReceiversPerCluster - 1) / this->ReceiversPerCluster));
    std::vector<double> centres(3 * clusters);
    for (int k = 0; k < clusters; ++k)
    {
      receivers->GetPoint(n * k / clusters, &centres[3 * k]);
    }
    clusterOf.assign(n, 0);
    for (int iteration = 0; iteration < 4; ++iteration) // Lloyd
    {
      vtkSMPTools::For(0, n,
        [&](vtkIdType first, vtkIdType last)
        {
          for (vtkIdType i = first; i < last; ++i)
          {
            double x[3];
            receivers->GetPoint(i, x);
            double best = VTK_DOUBLE_MAX;
            for (int k = 0; k < clusters; ++k)
            {
              const double d = vtkMath::Distance2BetweenPoints(x, &centres[3 * k]);
              if (d < best)
              {
                best = d;
                clusterOf[i] = k;
              }
            }
          }
        });
      std::vector<double> sum(3 * clusters, 0.0);
      std::vector<vtkIdType> count(clusters, 0);
      for (vtkIdType i = 0; i < n; ++i)
      {
        double x[3];
        receivers->GetPoint(i, x);
        for (int c = 0; c < 3; ++c)
        {
          sum[3 * clusterOf[i] + c] += x[c];
        }
        ++count[clusterOf[i]];
      }
      for (int k = 0; k < clusters; ++k)
      {
        for (int c = 0; count[k] && c < 3; ++c)
        {
          centres[3 * k + c] = sum[3 * k + c] / count[k];
        }
      }
    }
    // Per cluster: bounding sphere, central receiver, cut.
    std::vector<double> radius(clusters, 0.0);
    std::vector<vtkIdType> central(clusters, -1);
    std::vector<double> centralDistance(clusters, VTK_DOUBLE_MAX);
    for (vtkIdType i = 0; i < n; ++i)
    {
      double x[3];
      receivers->GetPoint(i, x);
      const int k = clusterOf[i];
      const double d2 = vtkMath::Distance2BetweenPoints(x, &centres[3 * k]);
      radius[k] = std::max(radius[k], std::sqrt(d2));
      if (d2 < centralDistance[k])
      {
        centralDistance[k] = d2;
        central[k] = i;
      }
    }
    clusterBlockers.resize(clusters);
    const float maxAngle = static_cast<float>(vtkMath::RadiansFromDegrees(this->HierarchyAngle));
    std::size_t cutTotal = 0;
    int used = 0;
    for (int k = 0; k < clusters; ++k)
    {
      if (central[k] < 0)
      {
        continue;
      }
      double pc[3], nc[3];
      receivers->GetPoint(central[k], pc);
      normals->GetTuple(central[k], nc);
      vtkMath::Normalize(nc);
      const float pR[3] = { float(centres[3 * k]), float(centres[3 * k + 1]),
        float(centres[3 * k + 2]) };
      const float pf[3] = { float(pc[0]), float(pc[1]), float(pc[2]) };
      const float nf[3] = { float(nc[0]), float(nc[1]), float(nc[2]) };
      std::vector<int> nodes;
      clusterBlockers[k] = proxygi::CutHierarchy(hierarchy, pR, float(radius[k]), pf, nf, maxAngle,
        order, this->SelfShadowRules, runShadowed ? &nodes : nullptr);
      if (runShadowed)
      {
        clusterLights.resize(clusters);
        CutSphericalLights(spheres, leafLights, leafOfNode, hierarchy, nodes, blockers,
          shadowedIndirect, pf, nf, clusterLights[k]);
      }
      clusterBlockers[k].PlaneOrigin = blockers.PlaneOrigin;
      clusterBlockers[k].PlaneNormal = blockers.PlaneNormal;
      clusterBlockers[k].PlaneAlbedo = blockers.PlaneAlbedo;
      cutTotal += clusterBlockers[k].Spheres();
      ++used;
    }
    std::ostringstream line;
    line << "hierarchy: " << used << " receiver clusters, cuts of "
         << (used ? static_cast<double>(cutTotal) / used : 0.0) << " spheres on average (of "
         << blockers.Spheres() << " leaves) at " << this->HierarchyAngle << " degrees"
         << (runShadowed ? "; spherical lights cut alike, with reflection ratios" : "");
    this->Plan.push_back(line.str());
  }
  else if (this->HierarchyAngle > 0.0)
  {
    this->Plan.push_back("hierarchy: not used (the proxies have no Level/Parent arrays)");
  }

  std::atomic<vtkIdType> shadowed(0), failures(0), shadowedFailures(0);
  std::atomic<long long> secondPassNs(0);
  const vtkIdType blocks = std::min<vtkIdType>(50, n);
  for (vtkIdType b = 0; b < blocks && !this->GetAbortExecute(); ++b)
  {
    vtkSMPTools::For(n * b / blocks, n * (b + 1) / blocks,
      [&](vtkIdType first, vtkIdType last)
      {
        float g[proxygi::sh::MaxCoefficients], unshadowed[proxygi::sh::MaxCoefficients];
        proxygi::sh::SetConstant(order, 1.0f, unshadowed);
        std::vector<proxygi::SeenBlocker> seen;
        proxygi::SphericalLightScratch scratch;
        vtkIdType localShadowed = 0, localFailures = 0, localShadowedFailures = 0;
        long long localSecondPassNs = 0;
        for (vtkIdType i = first; i < last; ++i)
        {
          double pd[3], nd[3], albedo[3];
          receivers->GetPoint(i, pd);
          normals->GetTuple(i, nd);
          if (!(vtkMath::Normalize(nd) > 0.0))
          {
            nd[0] = nd[1] = 0.0;
            nd[2] = 1.0;
          }
          const float p[3] = { float(pd[0]), float(pd[1]), float(pd[2]) };
          const float nf[3] = { float(nd[0]), float(nd[1]), float(nd[2]) };
          float rgb[3], bounce[3] = { 0, 0, 0 }, lit[3] = { 0, 0, 0 },
                        bounceShadowed[3] = { 0, 0, 0 };
          const proxygi::Blockers& mine =
            clusterOf.empty() ? blockers : clusterBlockers[clusterOf[i]];
          const bool lightCarriesPlanes = planesInLight && blockers.AboveEveryPlane(p);
          seen.clear();
          if (needVisibility)
          {
            proxygi::sh::Status status;
            const proxygi::SoftShadows& kernel = lightCarriesPlanes ? shadows : shadowsLog;
            if (kernel.Visibility(
                  p, nf, mine, g, status, runIndirect || runPlaneBounce ? &seen : nullptr) > 0)
            {
              ++localShadowed;
            }
            if (status != proxygi::sh::Status::Ok)
            {
              ++localFailures;
              proxygi::sh::SetConstant(order, 1.0f, g);
              seen.clear();
            }
          }
          else
          {
            proxygi::sh::SetConstant(order, 1.0f, g);
          }
          if (runShadows)
          {
            (lightCarriesPlanes ? shading : openShading).Shade(nf, g, rgb);
          }
          else
          {
            openShading.ShadeUnshadowed(nf, rgb);
          }
          float planeBounce[3] = { 0, 0, 0 };
          if (runIndirect || runPlaneBounce)
          {
            // xi needs the coverage of everything seen, planes included.
            float dc = g[0];
            if (lightCarriesPlanes)
            {
              double sum = 0.0;
              for (int k = 0; k < n2; ++k)
              {
                sum += g[k] * planeVisibility[k];
              }
              dc = static_cast<float>(sum / proxygi::sh::SqrtFourPi);
            }
            // Planes reflect less where the proxies shadow them.
            float planeScale[3 * 8];
            const bool scalePlanes =
              this->PlaneBounceShadows && mine.Planes() > 0 && mine.Planes() <= 8;
            for (std::size_t k = 0; scalePlanes && k < mine.Planes(); ++k)
            {
              proxygi::PlaneShadowScale(
                shadows, openShading, mine, static_cast<int>(k), p, nf, &planeScale[3 * k]);
            }
            proxygi::IndirectExitRadiance(
              static_cast<proxygi::IndirectOperator>(this->IndirectOperator), secondary, mine, seen,
              dc, nf, runIndirect ? bounce : planeBounce, scalePlanes ? planeScale : nullptr,
              !runIndirect);
          }
          const proxygi::SphericalLights& myLights =
            clusterLights.empty() ? shadowedLeaves : clusterLights[clusterOf[i]];
          if (runShadowed)
          {
            const auto start = std::chrono::steady_clock::now();
            if (!shadowedIndirect.ExitRadiance(
                  myLights, true, nullptr, &blockers, p, nf, bounceShadowed, scratch))
            {
              ++localShadowedFailures;
            }
            localSecondPassNs += std::chrono::duration_cast<std::chrono::nanoseconds>(
              std::chrono::steady_clock::now() - start)
                                   .count();
          }
          for (int c = 0; c < 3; ++c)
          {
            bounceShadowed[c] += planeBounce[c];
          }
          if (lightTables)
          {
            proxygi::LocalLightsRadiance(
              locals, *lightTables, pd, nf, this->Shadows ? g : unshadowed, lit);
          }
          proxygi::AlbedoOf(receivers, this->AlbedoArrayName, i, this->DefaultAlbedo, albedo);
          float sum[3];
          for (int k = 0; k < 3; ++k)
          {
            rgb[k] = static_cast<float>(rgb[k] * albedo[k]);
            bounce[k] = static_cast<float>(bounce[k] * albedo[k]);
            bounceShadowed[k] = static_cast<float>(bounceShadowed[k] * albedo[k]);
            lit[k] = static_cast<float>(lit[k] * albedo[k]);
            sum[k] = rgb[k] + bounce[k] + bounceShadowed[k] + lit[k]; // one of the two is 0
          }
          direct->SetTypedTuple(i, rgb);
          indirect->SetTypedTuple(i, bounce);
          indirectShadowed->SetTypedTuple(i, bounceShadowed);
          local->SetTypedTuple(i, lit);
          total->SetTypedTuple(i, sum);
          visibility->SetTypedTuple(i, g);
        }
        shadowed += localShadowed;
        failures += localFailures;
        shadowedFailures += localShadowedFailures;
        secondPassNs += localSecondPassNs;
      });
    this->UpdateProgress(static_cast<double>(b + 1) / blocks);
  }
  if (runShadowed)
  {
    const double seconds = 1e-9 * static_cast<double>(secondPassNs.load());
    std::ostringstream line;
    line << "indirect light (shadowed): second pass over " << n << " receivers, "
         << (this->SphericalLightBlocking == BLOCKING_PER_OBJECT ? "per-object" : "per-sphere")
         << " blocking, " << seconds << " s summed over threads ("
         << 1e6 * seconds / static_cast<double>(n) << " us per receiver)";
    this->Plan.push_back(line.str());
  }
  if (shadowedFailures > 0)
  {
    vtkWarningMacro(<< shadowedFailures
                    << " receivers met non-finite SH values in the shadowed indirect light; "
                       "those spherical lights were left out.");
  }
  if (failures > 0)
  {
    vtkWarningMacro(<< failures
                    << " receivers met non-finite SH values; they were left unshadowed.");
  }
  if (needVisibility)
  {
    std::ostringstream line;
    line << (runShadows ? "shadows: " : "visibility (for indirect/local lights): ")
         << blockers.Spheres() << " proxy spheres, " << blockers.Planes()
         << (planesInLight ? " planes (carried by the light)" : " planes (log space)") << ", exp "
         << proxygi::sh::ExpMethodName(settings.Exp.Method) << "; " << shadowed.load() << " of "
         << n << " receivers had blockers in view (the others skipped the exp)";
    this->Plan.push_back(line.str());
  }

  output->ShallowCopy(receivers);
  output->GetPointData()->AddArray(direct);
  output->GetPointData()->AddArray(indirect);
  output->GetPointData()->AddArray(indirectShadowed);
  output->GetPointData()->AddArray(local);
  output->GetPointData()->AddArray(total);
  output->GetPointData()->AddArray(visibility);
  if (!receivers->GetPointData()->GetNormals())
  {
    output->GetPointData()->SetNormals(normals);
  }
  vtkNew<vtkStringArray> plan;
  plan->SetName("Plan");
  for (const std::string& line : this->Plan)
  {
    plan->InsertNextValue(line);
  }
  output->GetFieldData()->AddArray(plan);
  return 1;
}
