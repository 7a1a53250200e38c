// The plan of vtkPGIGlobalIllumination: static inputs reuse the last result
// (no re-execution until an input, the light or a knob changes); effects a
// scene does not call for are skipped, said so in the plan (GetPlan and the
// "Plan" field array), and skipping changes nothing: the output equals the
// one with the effect switched off, bit for bit, or (blockers below
// MinBlockerAngle, skipped per receiver) stays within the stated bound.
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILighting.h"

#include "pgiHardScenes.h"
#include "pgiTesting.h"

#include "pgiSRGB.h"
#include "vtkCallbackCommand.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include <cstdio>

namespace
{
int Executions = 0;
void CountStart(vtkObject*, unsigned long, void*, void*)
{
  ++Executions;
}

// Largest |a - b| over every component of the named array.
double Difference(vtkPolyData* a, vtkPolyData* b, const char* name)
{
  vtkDataArray* x = a->GetPointData()->GetArray(name);
  vtkDataArray* y = b->GetPointData()->GetArray(name);
  double worst = 0.0;
  for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < x->GetNumberOfComponents(); ++c)
    {
      worst = std::max(worst, std::fabs(x->GetComponent(i, c) - y->GetComponent(i, c)));
    }
  }
  return worst;
}

vtkSmartPointer<vtkPolyData> Copy(vtkPolyData* data)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(data);
  return copy;
}

vtkSmartPointer<vtkPolyData> WithAlbedo(vtkPolyData* proxies, double albedo)
{
  vtkSmartPointer<vtkPolyData> copy = Copy(proxies);
  vtkNew<vtkFloatArray> a;
  a->SetName("Albedo");
  a->SetNumberOfComponents(3);
  a->SetNumberOfTuples(copy->GetNumberOfPoints());
  a->Fill(albedo);
  copy->GetPointData()->AddArray(a);
  return copy;
}
} // namespace

int TestGlobalIlluminationPlan(int, char*[])
{
  const pgitest::HardScene scene = pgitest::HardScenes()[3]; // a ground under 4 spheres
  vtkNew<vtkPGILighting> sky;
  const double origin[3] = { 0, 0, -1.5 }, up[3] = { 0, 0, 1 }, black[3] = { 0, 0, 0 };

  // Reuse: Update without a change does not execute again; each input, the
  // light and a knob make it execute once.
  {
    vtkNew<vtkPGIGlobalIllumination> gi;
    vtkNew<vtkCallbackCommand> counter;
    counter->SetCallback(CountStart);
    gi->AddObserver(vtkCommand::StartEvent, counter);
    gi->SetInputData(scene.Receivers);
    gi->SetProxiesData(scene.Proxies);
    gi->SetLighting(sky);
    gi->Update();
    gi->Update();
    gi->Update();
    const int once = Executions;
    vtkStringArray* plan =
      vtkStringArray::SafeDownCast(gi->GetOutput()->GetFieldData()->GetAbstractArray("Plan"));
    std::printf("three updates, nothing changed: %d execution(s); the Plan field array has %lld "
                "lines\n",
      once, plan ? static_cast<long long>(plan->GetNumberOfValues()) : -1LL);
    PGI_CHECK(once == 1);
    PGI_CHECK(plan && plan->GetNumberOfValues() == static_cast<vtkIdType>(gi->GetPlan().size()));
    gi->GetSettings()->SetOrder(3);
    gi->Update();
    PGI_CHECK(Executions == 2); // a knob
    sky->SetUniformRadiance(0.5, 0.5, 0.5);
    gi->Update();
    PGI_CHECK(Executions == 3); // the light
    scene.Proxies->Modified();
    gi->Update();
    PGI_CHECK(Executions == 4); // the proxies
    scene.Receivers->Modified();
    gi->Update();
    gi->Update();
    PGI_CHECK(Executions == 5); // the receivers, once
    sky->SetUniformRadiance(1, 1, 1);
  }

  // Skipped effects change nothing: each run equals the one with the effect
  // switched off, every output array, bit for bit.
  const auto run = [&](vtkPolyData* proxies, vtkPGILighting* lighting, bool indirect, int mode,
                     bool local, vtkSmartPointer<vtkPGIGlobalIllumination>* keep = nullptr)
  {
    auto gi = vtkSmartPointer<vtkPGIGlobalIllumination>::New();
    gi->SetInputData(scene.Receivers);
    gi->SetProxiesData(proxies);
    gi->SetLighting(lighting);
    gi->AddBlockerPlane(origin, up, black);
    gi->GetSettings()->SetIndirect(indirect);
    gi->GetSettings()->SetIndirectMode(mode);
    gi->GetSettings()->SetLocalLights(local);
    gi->Update();
    if (keep)
    {
      *keep = gi;
    }
    return Copy(gi->GetOutput());
  };
  const char* arrays[] = { "DirectShadowed", "IndirectProxy", "IndirectShadowed", "LocalLights",
    "Radiance", "Visibility" };
  const auto same = [&](vtkPolyData* a, vtkPolyData* b, const char* what)
  {
    double worst = 0.0;
    for (const char* name : arrays)
    {
      worst = std::max(worst, Difference(a, b, name));
    }
    std::printf("%s: largest difference to the effect switched off %.3g\n", what, worst);
    PGI_CHECK(worst == 0.0);
  };
  const int unshadowed = vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED;
  const int shadowed = vtkPGIGISettings::INDIRECT_MODE_SHADOWED;
  vtkSmartPointer<vtkPolyData> dark = WithAlbedo(scene.Proxies, 0.0);
  vtkSmartPointer<vtkPolyData> off = run(dark, sky, false, unshadowed, false);
  vtkSmartPointer<vtkPGIGlobalIllumination> gi;

  vtkSmartPointer<vtkPolyData> skipped = run(dark, sky, true, unshadowed, false, &gi);
  PGI_CHECK(pgitest::Says(
    gi->GetPlan(), "indirect light: skipped (every proxy and plane has albedo 0)", true));
  same(skipped, off, "unshadowed bounce, albedo 0 (skipped)");

  skipped = run(dark, sky, true, shadowed, false, &gi);
  PGI_CHECK(pgitest::Says(gi->GetPlan(),
    "indirect light (shadowed): skipped (every spherical light has albedo 0)", true));
  same(skipped, off, "shadowed bounce, albedo 0 (skipped)");

  skipped = run(dark, sky, false, unshadowed, true, &gi);
  PGI_CHECK(pgitest::Says(gi->GetPlan(), "local lights: skipped (none in the lighting)", true));
  same(skipped, off, "local lights, none in the lighting (skipped)");

  vtkNew<vtkPGILighting> night;
  night->SetUniformRadiance(0, 0, 0);
  vtkSmartPointer<vtkPolyData> lit = WithAlbedo(scene.Proxies, 0.8);
  skipped = run(lit, night, true, unshadowed, false, &gi);
  PGI_CHECK(
    pgitest::Says(gi->GetPlan(), "indirect light: skipped (the environment is black)", true));
  same(skipped, run(lit, night, false, unshadowed, false), "bounce under a black sky (skipped)");

  // Where an effect runs, it shows: the test above could not pass by
  // leaving the bounce out everywhere.
  vtkSmartPointer<vtkPolyData> bounce = run(lit, sky, true, unshadowed, false, &gi);
  PGI_CHECK(pgitest::Says(gi->GetPlan(), "indirect light: one bounce", true));
  const double added = Difference(bounce, run(lit, sky, false, unshadowed, false), "Radiance");
  std::printf("unshadowed bounce, albedo 0.8 (runs): adds up to %.3f\n", added);
  PGI_CHECK(added > 0.01);

  // Per receiver: blockers subtending less than MinBlockerAngle (0.002 rad)
  // are skipped. A blocker of angular radius 0.0015 rad changes the
  // irradiance by at most sin^2(0.0015) = 2.3e-6 of the sky's: skipping it
  // stays within 1e-5 of the peak.
  {
    vtkSmartPointer<vtkPolyData> tiny =
      pgitest::HardProxies({ { 0.0, 0.0, 1000.0, 1000.0 * std::sin(0.0015), 0 } });
    vtkNew<vtkPGIGlobalIllumination> exact, fast;
    for (vtkPGIGlobalIllumination* f : { exact.Get(), fast.Get() })
    {
      f->SetInputData(scene.Receivers);
      f->SetProxiesData(tiny);
      f->SetLighting(sky);
    }
    exact->GetSettings()->SetMinBlockerAngle(0.0);
    exact->Update();
    fast->Update();
    PGI_CHECK(pgitest::Says(fast->GetPlan(), " 0 of ", true));
    PGI_CHECK(!pgitest::Says(exact->GetPlan(), " 0 of "));
    const double difference = Difference(exact->GetOutput(), fast->GetOutput(), "Radiance");
    const double peak = pgitest::HardPeak(exact->GetOutput()->GetPointData()->GetArray("Radiance"));
    std::printf("a 0.0015 rad blocker skipped by MinBlockerAngle: largest radiance difference "
                "%.2e (peak %.3f, bound 1e-5 of it)\n",
      difference, peak);
    PGI_CHECK(difference > 0.0);
    PGI_BELOW(difference, 1e-5 * peak);

    // RadianceSRGB: the display bytes of ColorExposure x Radiance (pgiSRGB.h).
    fast->SetColorExposure(0.5);
    fast->Update();
    vtkDataArray* radiance = fast->GetOutput()->GetPointData()->GetArray("Radiance");
    auto* colors = vtkUnsignedCharArray::SafeDownCast(
      fast->GetOutput()->GetPointData()->GetArray("RadianceSRGB"));
    PGI_CHECK(colors && colors->GetNumberOfComponents() == 3 &&
      colors->GetNumberOfTuples() == radiance->GetNumberOfTuples());
    int wrong = 0;
    for (vtkIdType i = 0; colors && i < colors->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        wrong +=
          colors->GetTypedComponent(i, c) != proxygi::ToSRGB8(0.5 * radiance->GetComponent(i, c));
      }
    }
    std::printf("RadianceSRGB at ColorExposure 0.5: %d of %lld bytes differ from ToSRGB8\n", wrong,
      static_cast<long long>(colors ? 3 * colors->GetNumberOfTuples() : 0));
    PGI_CHECK(wrong == 0);
  }
  return pgitest::Result();
}
