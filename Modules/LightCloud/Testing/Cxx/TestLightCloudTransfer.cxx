// The light cloud as one more effect of the GI filter (Cornell box,
// Testing/Data/cornell-box.json): with a vtkPGILightCloudTransfer and the
// settings' LightCloud on, the lighting's point lights get their indirect
// light from the cloud ("IndirectLocal", the relight filter's light to the
// float), added to Radiance; the plan says what ran and why:
//  - no point lights: no cloud; no cloud given: skipped, with the reason;
//  - LightCloud off: off; a light outside the cloud: a warning, nothing added;
//  - a static light: the cloud's light is reused (not recomputed);
//  - a cloud that carries direct light: skipped with a warning;
//  - receivers that are not the cloud's: an error, and the rest still runs.
#include "pgiCornellBox.h"
#include "pgiTesting.h"
#include "pgiTestingErrors.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILightCloud.h"
#include "vtkPGILightCloudRelight.h"
#include "vtkPGILightCloudTransfer.h"
#include "vtkPGILighting.h"
#include "vtkPGIMeshOccluder.h"

#include "vtkFloatArray.h"
#include "vtkPointData.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace
{
bool PlanSays(vtkPGIGlobalIllumination* gi, const char* text)
{
  for (const std::string& line : gi->GetPlan())
  {
    if (line.find(text) != std::string::npos)
    {
      return true;
    }
  }
  std::printf("plan lacks \"%s\":\n", text);
  for (const std::string& line : gi->GetPlan())
  {
    std::printf("  %s\n", line.c_str());
  }
  return false;
}

vtkFloatArray* Array(vtkAlgorithm* a, const char* name)
{
  return vtkFloatArray::SafeDownCast(
    vtkPolyData::SafeDownCast(a->GetOutputDataObject(0))->GetPointData()->GetArray(name));
}

double LargestAbs(vtkFloatArray* a)
{
  double m = 0.0;
  for (vtkIdType k = 0; k < a->GetNumberOfValues(); ++k)
  {
    m = std::max(m, static_cast<double>(std::fabs(a->GetValue(k))));
  }
  return m;
}
} // namespace

int TestLightCloudTransfer(int, char*[])
{
  vtkNew<vtkPGIMeshOccluder> occluder;
  vtkSmartPointer<vtkPolyData> box =
    pgitest::LoadCornellBox(PROXYGI_TEST_DATA_DIR "/cornell-box.json", occluder);
  if (!PGI_CHECK(box))
  {
    return pgitest::Result();
  }
  vtkSmartPointer<vtkPGILightCloud> cloud = pgitest::CornellCloud(box, 3, false);

  const double light[3] = { 0.13, -0.41, 1.37 }, intensity[3] = { 1.0, 0.8, 0.6 };
  vtkNew<vtkPGILighting> lighting;
  lighting->SetUniformRadiance(0.0, 0.0, 0.0);
  vtkSmartPointer<vtkPGIGlobalIllumination> gi = pgitest::CloudGI(box, cloud, lighting, occluder);
  vtkSmartPointer<vtkPGILightCloudTransfer> transfer =
    vtkPGILightCloudTransfer::SafeDownCast(gi->GetLocalLightTransfer());

  // 1. No point lights: no cloud.
  gi->Update();
  PGI_CHECK(PlanSays(gi, "light cloud: skipped (no point lights in the lighting)"));
  PGI_CHECK(Array(gi, "IndirectLocal") && LargestAbs(Array(gi, "IndirectLocal")) == 0.0);

  // 2. A point light: IndirectLocal is the relight filter's light, in Radiance.
  lighting->AddPointLight(light, intensity);
  gi->Update();
  vtkNew<vtkPGILightCloudRelight> relight;
  relight->SetInputData(box);
  relight->SetCloudData(cloud);
  relight->SetOccluder(occluder);
  relight->AddLight(light[0], light[1], light[2], intensity[0], intensity[1], intensity[2]);
  relight->Update();
  vtkFloatArray* cloudLight = Array(gi, "IndirectLocal");
  vtkFloatArray* expected = Array(relight, "LightCloudRadiance");
  vtkFloatArray* total = Array(gi, "Radiance");
  vtkFloatArray* local = Array(gi, "LocalLights");
  double worst = 0.0, sumWorst = 0.0;
  for (vtkIdType k = 0; k < expected->GetNumberOfValues(); ++k)
  {
    worst = std::max(worst, std::fabs(double(cloudLight->GetValue(k)) - expected->GetValue(k)));
    sumWorst = std::max(sumWorst,
      std::fabs(double(total->GetValue(k)) - local->GetValue(k) - cloudLight->GetValue(k)));
  }
  std::printf("IndirectLocal vs the relight filter: largest difference %.3g (largest value "
              "%.3g); Radiance - LocalLights - IndirectLocal: %.3g\n",
    worst, LargestAbs(expected), sumWorst);
  PGI_CHECK(LargestAbs(expected) > 1e-3);
  PGI_BELOW(worst, 1e-6 * LargestAbs(expected));
  PGI_BELOW(sumWorst, 1e-5 * LargestAbs(total));
  PGI_CHECK(PlanSays(gi, "light cloud: 26 cloud lights, indirect light only"));
  PGI_CHECK(PlanSays(gi, "light cloud: recomputed"));
  PGI_CHECK(transfer->GetNumberOfRelights() == 1);

  // 3. A static light: something else changes, the cloud's light is reused.
  gi->GetSettings()->SetOrder(3);
  gi->Update();
  PGI_CHECK(PlanSays(gi, "light cloud: reused (the point lights did not move)"));
  PGI_CHECK(transfer->GetNumberOfRelights() == 1);

  // 4. Off in the settings.
  gi->GetSettings()->LightCloudOff();
  gi->Update();
  PGI_CHECK(PlanSays(gi, "light cloud: off (switched off)"));
  PGI_CHECK(LargestAbs(Array(gi, "IndirectLocal")) == 0.0);
  gi->GetSettings()->LightCloudOn();

  // 5. A light outside the cloud: a warning, nothing added, the plan says why.
  lighting->RemoveAllPointLights();
  lighting->AddPointLight(5.0, 0.0, 1.0, 1.0, 1.0, 1.0);
  vtkNew<vtkTest::ErrorObserver> warnings;
  transfer->GetRelight()->AddObserver(vtkCommand::WarningEvent, warnings);
  gi->Update();
  PGI_CHECK(warnings->GetWarning() &&
    warnings->GetWarningMessage().find("outside the light cloud") != std::string::npos);
  PGI_CHECK(PlanSays(gi, "outside the cloud: skipped"));
  PGI_CHECK(LargestAbs(Array(gi, "IndirectLocal")) == 0.0);

  // 6. No cloud given: skipped, with the reason.
  gi->SetLocalLightTransfer(nullptr);
  gi->Update();
  PGI_CHECK(PlanSays(gi, "light cloud: skipped (no cloud given"));
  gi->SetLocalLightTransfer(transfer);

  // 7. A cloud that carries direct light: skipped with a warning.
  {
    vtkNew<vtkPGILightCloud> direct;
    direct->DeepCopy(cloud);
    direct->SetContents(vtkPGILightCloud::DirectAndIndirect);
    transfer->SetCloud(direct);
    PGI_CHECK(pgitest::WarnsSaying(gi, "carries direct light too"));
    PGI_CHECK(PlanSays(gi, "it carries direct light too"));
    transfer->SetCloud(cloud);
  }

  // 8. Receivers that are not the cloud's: an error, the rest still runs.
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->Update();
    gi->SetInputData(sphere->GetOutput());
    PGI_CHECK(pgitest::FailsSaying(gi, "are not the ones the cloud was computed for"));
    PGI_CHECK(PlanSays(gi, "light cloud: failed"));
    PGI_CHECK(Array(gi, "Radiance") &&
      Array(gi, "Radiance")->GetNumberOfTuples() == sphere->GetOutput()->GetNumberOfPoints());
  }
  return pgitest::Result();
}
