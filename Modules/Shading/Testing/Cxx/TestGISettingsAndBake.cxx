// One settings type and one precompute for every GI consumer:
// vtkPGIGISettings::Resolve replaces exactly what a backend cannot honour
// and says each replacement; vtkPGIGIBake rebuilds only when one of its
// inputs changed, and the filter reuses it across receiver changes; the
// bake's outputs are the formulas they stand for (response interleave,
// light above the planes, bad proxies refused with the scene kept).
#include "vtkPGIGIBake.h"
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILighting.h"

#include "pgiHardScenes.h"
#include "pgiTesting.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace
{
bool Mentions(const std::vector<std::string>& notes, const std::string& text)
{
  for (const std::string& n : notes)
  {
    if (n.find(text) != std::string::npos)
    {
      return true;
    }
  }
  std::printf("no note mentions \"%s\"; notes:\n", text.c_str());
  for (const std::string& n : notes)
  {
    std::printf("  %s\n", n.c_str());
  }
  return false;
}

void TestResolve()
{
  vtkNew<vtkPGIGISettings> s, e;
  std::vector<std::string> notes;
  // The CPU filter honours everything: nothing replaced, values copied.
  s->SetOrder(8);
  s->SetExpMethod(vtkPGIGISettings::EXP_OL);
  s->SetHierarchyAngle(25);
  PGI_CHECK(s->Resolve(vtkPGIGlobalIllumination::GetSupport(), 1, e, notes));
  PGI_CHECK(notes.empty());
  PGI_CHECK(e->GetOrder() == 8 && e->GetExpMethod() == vtkPGIGISettings::EXP_OL);
  PGI_NEAR(e->GetHierarchyAngle(), 25.0, 0.0);

  // A GPU-like backend: order 2..6, HYB only, no hierarchy, product matrix.
  vtkPGIGISettings::Support gpu;
  gpu.Backend = "test backend";
  gpu.MaxOrder = 6;
  gpu.ExpMethods = 1u << vtkPGIGISettings::EXP_HYB;
  gpu.Hierarchy = false;
  gpu.ShadingPaths = 1u << vtkPGIGISettings::SHADING_PRODUCT_MATRIX;
  gpu.IndirectOperators = 1u << vtkPGIGISettings::INDIRECT_AVERAGED;
  gpu.PlaneBlockings = 1u << vtkPGIGISettings::PLANES_IN_LOG_SPACE;
  gpu.IndirectModes = 1u << vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED;
  notes.clear();
  PGI_CHECK(!s->Resolve(gpu, 0, e, notes));
  PGI_CHECK(e->GetOrder() == 6);
  PGI_CHECK(Mentions(notes, "Order: order 8 is outside 2..6; order 6 runs in the test backend"));
  PGI_CHECK(e->GetExpMethod() == vtkPGIGISettings::EXP_HYB);
  PGI_CHECK(Mentions(notes, "ExpMethod: OL is not available; HYB runs"));
  PGI_CHECK(e->GetHierarchyAngle() == 0.0 && Mentions(notes, "HierarchyAngle"));
  // The table path is the default: replaced by the product matrix unsaid
  // (same L*H(N)); no planes: PlaneBlocking is not said either.
  PGI_CHECK(e->GetShadingPath() == vtkPGIGISettings::SHADING_PRODUCT_MATRIX);
  PGI_CHECK(e->GetPlaneBlocking() == vtkPGIGISettings::PLANES_IN_LOG_SPACE);
  PGI_CHECK(notes.size() == 3);
  // With a plane the planes' mode is said; shadowed bounce -> unshadowed.
  s->SetIndirectModeToShadowed();
  notes.clear();
  s->Resolve(gpu, 1, e, notes);
  PGI_CHECK(Mentions(notes, "PlaneBlocking: planes in the light is not available"));
  PGI_CHECK(Mentions(notes,
    "IndirectMode: shadowed indirect light is not available; "
    "unshadowed runs"));
  PGI_CHECK(e->GetIndirectMode() == vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED);
  // The bounce's own order: said where a shadowed bounce runs without it;
  // at or above Order there is nothing to replace.
  {
    vtkPGIGISettings::Support shadowedGpu = gpu;
    shadowedGpu.IndirectModes = 0x3;
    shadowedGpu.IndirectOrder = false;
    vtkNew<vtkPGIGISettings> r, re;
    r->SetOrder(6);
    r->SetIndirectOrder(4);
    r->SetIndirectModeToShadowed();
    PGI_CHECK(r->GetEffectiveIndirectOrder() == 4);
    std::vector<std::string> said;
    r->Resolve(shadowedGpu, 0, re, said);
    PGI_CHECK(Mentions(said, "IndirectOrder: the bounce runs at the shading order 6"));
    PGI_CHECK(re->GetIndirectOrder() == 0 && re->GetEffectiveIndirectOrder() == 6);
    r->SetIndirectOrder(8);
    said.clear();
    r->Resolve(shadowedGpu, 0, re, said);
    PGI_CHECK(said.empty() && re->GetEffectiveIndirectOrder() == 6);
    r->SetIndirectOrder(4);
    said.clear();
    r->Resolve(vtkPGIGlobalIllumination::GetSupport(), 0, re, said);
    PGI_CHECK(said.empty() && re->GetEffectiveIndirectOrder() == 4);
  }
  // The operator matters for the unshadowed model only.
  s->SetIndirectModeToUnshadowed();
  s->SetIndirectOperator(vtkPGIGISettings::INDIRECT_EXACT);
  notes.clear();
  s->Resolve(gpu, 0, e, notes);
  PGI_CHECK(Mentions(notes, "IndirectOperator: exact is not available; the averaged"));
  s->IndirectOff();
  notes.clear();
  s->Resolve(gpu, 0, e, notes);
  for (const std::string& n : notes)
  {
    PGI_CHECK(n.find("IndirectOperator") == std::string::npos);
  }
  // Resolve into the same effective object again: no MTime change.
  const vtkMTimeType t = e->GetMTime();
  notes.clear();
  s->Resolve(gpu, 0, e, notes);
  PGI_CHECK(e->GetMTime() == t);
  // A backend that ignores receiver albedo says so once it is changed.
  vtkPGIGISettings::Support pass = gpu;
  pass.ReceiverAlbedo = false;
  notes.clear();
  s->Resolve(pass, 0, e, notes);
  for (const std::string& n : notes)
  {
    PGI_CHECK(n.find("DefaultAlbedo") == std::string::npos); // left at its default
  }
  s->SetDefaultAlbedo(0.5, 0.5, 0.5);
  notes.clear();
  s->Resolve(pass, 0, e, notes);
  PGI_CHECK(Mentions(notes, "DefaultAlbedo"));
  // Local lights a backend cannot draw are said only when the scene has some.
  pass.LocalLights = false;
  notes.clear();
  s->Resolve(pass, 0, e, notes);
  for (const std::string& n : notes)
  {
    PGI_CHECK(n.find("LocalLights") == std::string::npos);
  }
  notes.clear();
  s->Resolve(pass, 0, e, notes, 3);
  PGI_CHECK(Mentions(notes, "LocalLights: the 3 local lights are not drawn in the test backend"));
  PGI_CHECK(!e->GetLocalLights());
}

void TestBakeReuse()
{
  vtkNew<vtkPGIGISettings> settings;
  vtkSmartPointer<vtkPolyData> proxies =
    pgitest::HardProxies({ { 0, 0, 1.0, 0.5, 0 }, { 0.8, 0, 1.2, 0.3, 0 } });
  vtkSmartPointer<vtkPGILighting> lighting = pgitest::HardLighting();
  vtkNew<vtkPGIGIBake> bake;
  bake->SetSettings(settings);
  bake->SetProxies(proxies);
  bake->SetLighting(lighting);
  const double origin[3] = { 0, 0, 0 }, up[3] = { 0, 0, 2 }, grey[3] = { 0.5, 0.5, 0.5 };
  bake->AddBlockerPlane(origin, up, grey);
  PGI_CHECK(bake->Update());
  PGI_CHECK(bake->Update());
  PGI_CHECK(bake->GetNumberOfBuilds() == 1);
  const proxygi::BakedScene& b = bake->GetScene();
  const int n2 = b.Order * b.Order;
  PGI_CHECK(b.SceneBlockers.Spheres() == 2 && b.SceneBlockers.Planes() == 1);
  PGI_NEAR(b.SceneBlockers.PlaneNormal[2], 1.0, 1e-7); // normalised
  PGI_CHECK(b.PlanesInLight && b.Light.size() == 3 * static_cast<std::size_t>(n2));
  // The light above the ground misses the sky below it: less DC.
  PGI_CHECK(b.LightAbovePlanes[0] < b.Light[0]);
  // The response interleave is the channel-major response transposed.
  for (int i = 0; i < n2; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      PGI_CHECK(b.InterleavedResponse[3 * i + c] == b.Secondary->Response[c * n2 + i]);
    }
  }
  PGI_CHECK(b.RunShadows && b.RunIndirect && b.RunLocal && b.Locals.Count() == 2);
  PGI_CHECK(b.Kernel.PlanesInLogSpace == false);

  // Each input change rebuilds once; nothing else does. Moving proxies or
  // a kernel knob keeps the projected light (the same values, not re-made);
  // the order, the lighting and the planes project it again.
  PGI_CHECK(bake->GetNumberOfLightProjections() == 1);
  const std::vector<double> lightBefore = b.LightAbovePlanes;
  proxies->GetPoints()->SetPoint(1, 0.9, 0, 1.2);
  proxies->GetPoints()->Modified();
  PGI_CHECK(bake->Update() && bake->Update());
  PGI_CHECK(bake->GetNumberOfBuilds() == 2 && bake->GetNumberOfLightProjections() == 1);
  PGI_CHECK(bake->GetScene().LightAbovePlanes == lightBefore && bake->GetScene().Shading);
  PGI_CHECK(bake->GetScene().Secondary && bake->GetScene().PlanesInLight);
  settings->SetExpMethod(vtkPGIGISettings::EXP_OL);
  PGI_CHECK(bake->Update() && bake->GetNumberOfLightProjections() == 1);
  PGI_CHECK(bake->GetScene().Kernel.Exp.Method == proxygi::sh::ExpMethod::OL);
  settings->SetExpMethod(vtkPGIGISettings::EXP_HYB);
  PGI_CHECK(bake->Update() && bake->GetNumberOfBuilds() == 4);
  settings->SetOrder(3);
  PGI_CHECK(bake->Update() && bake->GetNumberOfBuilds() == 5 && bake->GetScene().Order == 3);
  PGI_CHECK(bake->GetNumberOfLightProjections() == 2);
  lighting->SetUniformRadiance(0.5, 0.5, 0.5);
  PGI_CHECK(bake->Update() && bake->GetNumberOfBuilds() == 6);
  PGI_CHECK(bake->GetNumberOfLightProjections() == 3);
  bake->RemoveAllBlockerPlanes();
  PGI_CHECK(bake->Update() && bake->GetNumberOfBuilds() == 7);
  PGI_CHECK(bake->GetNumberOfLightProjections() == 4);
  PGI_CHECK(!bake->GetScene().PlanesInLight);

  // Shadowed mode: the spherical lights after their first pass.
  settings->SetIndirectModeToShadowed();
  PGI_CHECK(bake->Update() && bake->GetScene().RunShadowed);
  PGI_CHECK(bake->GetScene().Lights.Count() == 2);

  // Bad proxies: refused with the reason, the rest of the scene kept.
  vtkSmartPointer<vtkPolyData> bad = pgitest::HardProxies(
    { { 0, 0, 1.0, 0.5, 0 }, { std::numeric_limits<double>::quiet_NaN(), 0, 1, 0.3, 0 } });
  bake->SetProxies(bad);
  PGI_CHECK(!bake->Update());
  PGI_CHECK(bake->GetProxyError().find("proxy 1 has a NaN") != std::string::npos);
  PGI_CHECK(bake->GetScene().SceneBlockers.Spheres() == 0);
  PGI_CHECK(!bake->GetScene().Light.empty());
}

void TestFilterReusesBake()
{
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(0, 0, 0);
  ball->SetRadius(0.2);
  vtkNew<vtkPGIGlobalIllumination> gi;
  gi->SetInputConnection(ball->GetOutputPort());
  gi->SetProxiesData(pgitest::HardProxies({ { 0, 0, 1.0, 0.5, 0 } }));
  gi->Update();
  ball->SetThetaResolution(24); // receivers change, the scene does not
  gi->Update();
  PGI_CHECK(gi->GetBake()->GetNumberOfBuilds() == 1);
  gi->GetSettings()->SetOrder(5);
  gi->Update();
  PGI_CHECK(gi->GetBake()->GetNumberOfBuilds() == 2);
  PGI_CHECK(gi->GetOutput()->GetPointData()->GetArray("Visibility")->GetNumberOfComponents() == 25);
  // One settings object shared by two filters drives both.
  vtkNew<vtkPGIGlobalIllumination> other;
  other->SetInputConnection(ball->GetOutputPort());
  other->SetSettings(gi->GetSettings());
  other->GetSettings()->SetOrder(3);
  other->Update();
  gi->Update();
  PGI_CHECK(gi->GetOutput()->GetPointData()->GetArray("Visibility")->GetNumberOfComponents() == 9);
}

std::string PlanLine(vtkPolyData* output, const std::string& start)
{
  auto* plan = vtkStringArray::SafeDownCast(output->GetFieldData()->GetAbstractArray("Plan"));
  for (vtkIdType i = 0; plan && i < plan->GetNumberOfValues(); ++i)
  {
    if (plan->GetValue(i).rfind(start, 0) == 0)
    {
      return plan->GetValue(i);
    }
  }
  return std::string();
}

// An update that only moves proxies reuses the receivers' clusters, the
// projected light and the output arrays (unless someone holds them), and
// gives what a fresh filter gives.
void TestFilterReusesBuffers()
{
  vtkSmartPointer<vtkPolyData> ground = pgitest::HardPlane(2.0, 0.0, 40);
  vtkSmartPointer<vtkPolyData> proxies = pgitest::HardProxies(
    { { -0.3, 0, 0.6, 0.25, 0 }, { 0.3, 0, 0.6, 0.25, 0 }, { 0, 0, 0.6, 0.6, 0 } });
  vtkNew<vtkIntArray> level, parent;
  level->SetName("Level");
  parent->SetName("Parent");
  for (int v : { 0, 0, 1 })
  {
    level->InsertNextValue(v);
  }
  for (int v : { 2, 2, -1 })
  {
    parent->InsertNextValue(v);
  }
  proxies->GetPointData()->AddArray(level);
  proxies->GetPointData()->AddArray(parent);
  vtkNew<vtkPGIGlobalIllumination> gi;
  gi->SetInputData(ground);
  gi->SetProxiesData(proxies);
  gi->GetSettings()->SetIndirect(false);
  gi->GetSettings()->SetHierarchyAngle(25.0);
  gi->Update();
  PGI_CHECK(PlanLine(gi->GetOutput(), "hierarchy:").find("reused") == std::string::npos);
  vtkDataArray* first = gi->GetOutput()->GetPointData()->GetArray("Radiance");
  const double before = first->GetComponent(820, 0);
  proxies->GetPoints()->SetPoint(0, -0.2, 0.1, 0.6);
  proxies->GetPoints()->Modified();
  gi->Update();
  PGI_CHECK(PlanLine(gi->GetOutput(), "hierarchy:").find("reused") != std::string::npos);
  PGI_CHECK(gi->GetBake()->GetNumberOfBuilds() == 2);
  PGI_CHECK(gi->GetBake()->GetNumberOfLightProjections() == 1);
  vtkSmartPointer<vtkDataArray> held = gi->GetOutput()->GetPointData()->GetArray("Radiance");
  PGI_CHECK(held.Get() == first); // the same memory, new values
  // Someone holds the array: the next update leaves it alone.
  std::vector<double> kept(held->GetNumberOfTuples());
  for (vtkIdType i = 0; i < held->GetNumberOfTuples(); ++i)
  {
    kept[i] = held->GetComponent(i, 0);
  }
  PGI_CHECK(kept[820] != before);
  proxies->GetPoints()->SetPoint(0, -0.3, 0, 0.6);
  proxies->GetPoints()->Modified();
  gi->Update();
  vtkDataArray* latest = gi->GetOutput()->GetPointData()->GetArray("Radiance");
  PGI_CHECK(latest != held.Get());
  bool unchanged = true;
  for (vtkIdType i = 0; i < held->GetNumberOfTuples(); ++i)
  {
    unchanged = unchanged && held->GetComponent(i, 0) == kept[i];
  }
  PGI_CHECK(unchanged);
  // Back where it started: what the first update (and a fresh filter) gave.
  PGI_NEAR(latest->GetComponent(820, 0), before, 0.0);
  vtkNew<vtkPGIGlobalIllumination> fresh;
  fresh->SetInputData(ground);
  fresh->SetProxiesData(proxies);
  fresh->GetSettings()->SetIndirect(false);
  fresh->GetSettings()->SetHierarchyAngle(25.0);
  fresh->Update();
  vtkDataArray* reference = fresh->GetOutput()->GetPointData()->GetArray("Radiance");
  double worst = 0.0;
  for (vtkIdType i = 0; i < reference->GetNumberOfTuples(); ++i)
  {
    worst = std::max(worst, std::fabs(reference->GetComponent(i, 0) - latest->GetComponent(i, 0)));
  }
  PGI_CHECK(worst == 0.0);
}
} // namespace

int TestGISettingsAndBake(int, char*[])
{
  TestResolve();
  TestBakeReuse();
  TestFilterReusesBake();
  TestFilterReusesBuffers();
  return pgitest::Result();
}
