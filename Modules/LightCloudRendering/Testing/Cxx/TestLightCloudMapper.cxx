// The light cloud relit on the GPU against the CPU filter, in the Cornell
// box (Testing/Data/cornell-box.json), image against image:
//  - diffuse, dense and compressed: the mapper's per-vertex sums drawn
//    against the CPU filter's "LightCloudRadiance" drawn as vertex colours
//    (same light, same visibility and fade: PrepareFrame is shared);
//  - glossy (order 4): per vertex against the CPU filter seen from the
//    camera; per fragment close to per vertex, and not identical;
//  - an unchanged frame reuses the light, a moved light recomputes it, a
//    light outside the cloud adds nothing and the status says why;
//  - bad input: no cloud, receivers that are not the cloud's.
#include "pgiCornellBox.h"
#include "pgiOffscreenWindow.h"
#include "pgiTesting.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILightCloud.h"
#include "vtkPGILightCloudPolyDataMapper.h"
#include "vtkPGILightCloudRelight.h"
#include "vtkPGILightCloudTransfer.h"
#include "vtkPGILighting.h"
#include "vtkPGIMeshOccluder.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
const double Light[3] = { 0.13, -0.41, 1.37 };
const double Camera[3] = { 0.0, -4.6, 1.0 };

std::vector<unsigned char> Grab(vtkRenderWindow* window)
{
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  auto* pixels =
    vtkUnsignedCharArray::SafeDownCast(grab->GetOutput()->GetPointData()->GetScalars());
  return std::vector<unsigned char>(
    pixels->GetPointer(0), pixels->GetPointer(0) + pixels->GetNumberOfValues());
}

struct Difference
{
  double Mean = 0.0;   // over the values, in 1/255
  double P99 = 0.0;    // 99th percentile
  double Bright = 0.0; // mean of the first image
};

Difference Compare(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b)
{
  Difference d;
  std::vector<int> diffs(a.size());
  for (std::size_t k = 0; k < a.size() && k < b.size(); ++k)
  {
    diffs[k] = std::abs(int(a[k]) - int(b[k]));
    d.Mean += diffs[k];
    d.Bright += a[k];
  }
  d.Mean /= std::max<std::size_t>(1, a.size());
  d.Bright /= std::max<std::size_t>(1, a.size());
  std::sort(diffs.begin(), diffs.end());
  d.P99 = diffs.empty() ? 0.0 : diffs[diffs.size() * 99 / 100];
  return d;
}

struct Stage
{
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkActor> Actor;
  vtkNew<vtkPolyDataMapper> PlainMapper;
  vtkNew<vtkPGILightCloudPolyDataMapper> CloudMapper;
  vtkNew<vtkPolyData> Coloured;

  bool Set(vtkRenderWindow* window)
  {
    this->Window = window;
    window->SetSize(160, 160);
    window->AddRenderer(this->Renderer);
    this->Renderer->AddActor(this->Actor);
    this->Renderer->SetBackground(0, 0, 0);
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetPosition(Camera[0], Camera[1], Camera[2]);
    camera->SetFocalPoint(0, 0, 1);
    camera->SetViewUp(0, 0, 1);
    camera->SetViewAngle(40);
    this->Renderer->ResetCameraClippingRange(-1, 1, -1, 1, 0, 2);
    // Colours as they are: ambient 1, diffuse 0, no lighting.
    this->Actor->GetProperty()->SetAmbient(1.0);
    this->Actor->GetProperty()->SetDiffuse(0.0);
    this->Actor->GetProperty()->SetSpecular(0.0);
    this->Actor->GetProperty()->LightingOff();
    this->CloudMapper->SetSRGBOutput(false);
    this->CloudMapper->SetCombineWithVTKLighting(false);
    return true;
  }

  // The CPU filter's radiance, drawn as 8-bit vertex colours.
  std::vector<unsigned char> DrawCPU(vtkPolyData* box, vtkFloatArray* radiance, double exposure)
  {
    this->Coloured->ShallowCopy(box);
    vtkNew<vtkUnsignedCharArray> colours;
    colours->SetName("Colours");
    colours->SetNumberOfComponents(3);
    colours->SetNumberOfTuples(box->GetNumberOfPoints());
    for (vtkIdType k = 0; k < radiance->GetNumberOfValues(); ++k)
    {
      const double v = std::min(1.0, std::max(0.0, exposure * radiance->GetValue(k)));
      colours->SetValue(k, static_cast<unsigned char>(std::lround(255.0 * v)));
    }
    this->Coloured->GetPointData()->SetScalars(colours);
    this->PlainMapper->SetInputData(this->Coloured);
    this->PlainMapper->SetColorModeToDirectScalars();
    this->PlainMapper->ScalarVisibilityOn();
    this->Actor->SetMapper(this->PlainMapper);
    return Grab(this->Window);
  }

  std::vector<unsigned char> DrawGPU(vtkPolyData* box, vtkPGILightCloud* cloud, double exposure)
  {
    this->CloudMapper->SetInputData(box);
    this->CloudMapper->SetCloud(cloud);
    this->CloudMapper->SetExposure(exposure);
    this->CloudMapper->ScalarVisibilityOff();
    this->Actor->SetMapper(this->CloudMapper);
    return Grab(this->Window);
  }
};

vtkFloatArray* CPURadiance(
  vtkPGILightCloudRelight* relight, vtkPolyData* box, vtkPGILightCloud* cloud, bool view)
{
  relight->SetInputData(box);
  relight->SetCloudData(cloud);
  if (view)
  {
    relight->SetViewPoint(Camera);
  }
  relight->Update();
  return vtkFloatArray::SafeDownCast(
    relight->GetOutput()->GetPointData()->GetArray("LightCloudRadiance"));
}

double Brightest(vtkFloatArray* a)
{
  double m = 0.0;
  for (vtkIdType k = 0; k < a->GetNumberOfValues(); ++k)
  {
    m = std::max(m, static_cast<double>(a->GetValue(k)));
  }
  return m;
}

bool Says(const std::string& status, const char* text)
{
  if (status.find(text) != std::string::npos)
  {
    return true;
  }
  std::printf("status lacks \"%s\": %s\n", text, status.c_str());
  return false;
}

void SetUp(vtkPGILightCloudRelight* relight, vtkPGIMeshOccluder* occluder)
{
  relight->RemoveAllLights();
  relight->AddLight(Light[0], Light[1], Light[2], 1.0, 0.8, 0.6);
  relight->SetOccluder(occluder);
}
} // namespace

int TestLightCloudMapper(int, char*[])
{
  std::string description;
  vtkSmartPointer<vtkRenderWindow> window = proxygi::NewOffscreenRenderWindow(&description);
  if (!window)
  {
    std::printf("no offscreen window: %s\n", description.c_str());
    return EXIT_FAILURE;
  }
  std::printf("window: %s\n", description.c_str());
  vtkNew<vtkPGIMeshOccluder> occluder;
  vtkSmartPointer<vtkPolyData> box =
    pgitest::LoadCornellBox(PROXYGI_TEST_DATA_DIR "/cornell-box.json", occluder);
  if (!PGI_CHECK(box))
  {
    return pgitest::Result();
  }
  Stage stage;
  stage.Set(window);
  vtkPGILightCloudPolyDataMapper* mapper = stage.CloudMapper;
  SetUp(mapper->GetRelight(), occluder);

  // 1. Diffuse, dense and compressed: the GPU's sums are the CPU's.
  for (bool compress : { false, true })
  {
    auto cloud = pgitest::CornellCloud(box, 3, compress, 0.0);
    vtkNew<vtkPGILightCloudRelight> cpu;
    SetUp(cpu, occluder);
    vtkFloatArray* radiance = CPURadiance(cpu, box, cloud, false);
    const double exposure = 0.9 / std::max(1e-12, Brightest(radiance));
    const auto reference = stage.DrawCPU(box, radiance, exposure);
    const auto gpu = stage.DrawGPU(box, cloud, exposure);
    const Difference d = Compare(reference, gpu);
    std::printf("diffuse %s: CPU image mean %.1f/255; GPU - CPU: mean %.3f/255, p99 %.0f/255\n"
                "  status: %s\n",
      compress ? "compressed" : "dense", d.Bright, d.Mean, d.P99, mapper->GetStatus().c_str());
    PGI_CHECK(d.Bright > 10.0);
    PGI_BELOW(d.Mean, 0.5);
    PGI_BELOW(d.P99, 3.0);
    PGI_CHECK(Says(mapper->GetStatus(), compress ? "compressed" : "dense"));
    PGI_CHECK(Says(mapper->GetStatus(), "recomputed"));
  }

  // 2. An unchanged frame reuses the light; a moved light recomputes it and
  //    the image changes; the light back where it was gives the image back.
  {
    const int updates = mapper->GetNumberOfLightUpdates();
    const auto before = Grab(window);
    PGI_CHECK(mapper->GetNumberOfLightUpdates() == updates);
    PGI_CHECK(Says(mapper->GetStatus(), "reused (nothing changed)"));
    mapper->GetRelight()->SetLightPosition(0, -0.5, 0.3, 1.7);
    mapper->GetRelight()->ResetFade();
    const auto moved = Grab(window);
    PGI_CHECK(mapper->GetNumberOfLightUpdates() == updates + 1);
    PGI_CHECK(Says(mapper->GetStatus(), "recomputed (lights)"));
    const Difference d = Compare(before, moved);
    std::printf("light moved: mean change %.2f/255\n", d.Mean);
    PGI_CHECK(d.Mean > 1.0);
    mapper->GetRelight()->SetLightPosition(0, Light[0], Light[1], Light[2]);
    mapper->GetRelight()->ResetFade();
    const Difference back = Compare(before, Grab(window));
    PGI_BELOW(back.Mean, 1e-9);
  }

  // 3. Glossy (ks 0.5, exponent 12, order 4): per vertex it is the CPU
  //    filter seen from the camera; per fragment close to it, not the same.
  {
    auto cloud = pgitest::CornellCloud(box, 3, false, 0.5);
    vtkNew<vtkPGILightCloudRelight> cpu;
    SetUp(cpu, occluder);
    vtkFloatArray* radiance = CPURadiance(cpu, box, cloud, true);
    const double exposure = 0.9 / std::max(1e-12, Brightest(radiance));
    const auto reference = stage.DrawCPU(box, radiance, exposure);
    mapper->GlossyPerFragmentOff();
    const auto perVertex = stage.DrawGPU(box, cloud, exposure);
    PGI_CHECK(Says(mapper->GetStatus(), "glossy SH of order 4 per vertex (GlossyPerFragment off)"));
    mapper->GlossyPerFragmentOn();
    const auto perFragment = Grab(window);
    PGI_CHECK(Says(mapper->GetStatus(), "glossy SH of order 4 per fragment"));
    const Difference v = Compare(reference, perVertex), f = Compare(perVertex, perFragment);
    std::printf("glossy: CPU image mean %.1f/255; per vertex - CPU: mean %.3f/255, p99 %.0f/255; "
                "per fragment - per vertex: mean %.3f/255, p99 %.0f/255\n",
      v.Bright, v.Mean, v.P99, f.Mean, f.P99);
    PGI_CHECK(v.Bright > 10.0);
    PGI_BELOW(v.Mean, 0.5);
    PGI_BELOW(v.P99, 3.0);
    PGI_BELOW(f.Mean, 4.0);
    PGI_CHECK(f.Mean > 0.01);

    // Compressed glossy: the GPU's reconstruction is the CPU's.
    auto compressed = pgitest::CornellCloud(box, 3, true, 0.5);
    vtkNew<vtkPGILightCloudRelight> cpuCompressed;
    SetUp(cpuCompressed, occluder);
    vtkFloatArray* r2 = CPURadiance(cpuCompressed, box, compressed, true);
    const auto reference2 = stage.DrawCPU(box, r2, exposure);
    mapper->GlossyPerFragmentOff();
    const Difference c = Compare(reference2, stage.DrawGPU(box, compressed, exposure));
    std::printf(
      "glossy compressed: per vertex - CPU: mean %.3f/255, p99 %.0f/255\n", c.Mean, c.P99);
    PGI_BELOW(c.Mean, 0.5);
    PGI_BELOW(c.P99, 3.0);
    mapper->GlossyPerFragmentOn();
  }

  // 4. A light outside the cloud adds nothing (a warning, and the status says it).
  {
    vtkNew<vtkTest::ErrorObserver> warnings;
    mapper->GetRelight()->AddObserver(vtkCommand::WarningEvent, warnings);
    mapper->GetRelight()->SetLightPosition(0, 5.0, 0.0, 1.0);
    const auto outside = Grab(window);
    PGI_CHECK(warnings->GetWarning());
    PGI_CHECK(Says(mapper->GetStatus(), "outside the cloud"));
    double sum = 0.0;
    for (unsigned char v : outside)
    {
      sum += v;
    }
    PGI_BELOW(sum, 1e-9);
    mapper->GetRelight()->SetLightPosition(0, Light[0], Light[1], Light[2]);
  }

  // 5. Bad input: no cloud; receivers that are not the cloud's.
  {
    vtkNew<vtkTest::ErrorObserver> errors, relightErrors;
    mapper->AddObserver(vtkCommand::ErrorEvent, errors);
    mapper->GetRelight()->AddObserver(vtkCommand::ErrorEvent, relightErrors);
    vtkSmartPointer<vtkPGILightCloud> cloud = mapper->GetCloud();
    mapper->SetCloud(nullptr);
    Grab(window);
    PGI_CHECK(errors->GetError());
    PGI_CHECK(Says(mapper->GetStatus(), "no cloud"));
    errors->Clear();
    vtkNew<vtkSphereSource> sphere;
    sphere->Update();
    mapper->SetCloud(cloud);
    mapper->SetInputData(sphere->GetOutput());
    Grab(window);
    PGI_CHECK(errors->GetError());
    PGI_CHECK(relightErrors->GetError());
    PGI_CHECK(Says(mapper->GetStatus(), "refused"));
  }

  // 6. Under the GI (GlobalIllumination on): the lighting's point light is
  //    the user light, its direct light the GI mapper's, its indirect light
  //    the cloud's; the image is the CPU GI filter's with the cloud as its
  //    transfer (Radiance = LocalLights + IndirectLocal).
  {
    auto cloud = pgitest::CornellCloud(box, 3, true, 0.0);
    vtkNew<vtkPGILighting> lighting;
    lighting->SetUniformRadiance(0.0, 0.0, 0.0);
    lighting->AddPointLight(Light[0], Light[1], Light[2], 1.0, 0.8, 0.6);
    vtkSmartPointer<vtkPGIGlobalIllumination> gi = pgitest::CloudGI(box, cloud, lighting, occluder);
    gi->Update();
    auto* radiance =
      vtkFloatArray::SafeDownCast(gi->GetOutput()->GetPointData()->GetArray("Radiance"));
    auto* indirect =
      vtkFloatArray::SafeDownCast(gi->GetOutput()->GetPointData()->GetArray("IndirectLocal"));
    const double exposure = 0.9 / std::max(1e-12, Brightest(radiance));
    const auto reference = stage.DrawCPU(box, radiance, exposure);
    const auto cpuDirect = [&]
    {
      vtkNew<vtkFloatArray> direct;
      direct->DeepCopy(radiance);
      for (vtkIdType k = 0; k < direct->GetNumberOfValues(); ++k)
      {
        direct->SetValue(k, direct->GetValue(k) - indirect->GetValue(k));
      }
      return stage.DrawCPU(box, direct, exposure);
    }();
    mapper->GetRelight()->RemoveAllLights();
    mapper->SetLighting(lighting);
    mapper->GlobalIlluminationOn();
    mapper->SetCombineWithVTKLighting(false);
    const auto gpu = stage.DrawGPU(box, cloud, exposure);
    const Difference d = Compare(reference, gpu), direct = Compare(cpuDirect, reference);
    std::printf("under the GI: CPU image mean %.1f/255 (direct light alone %.1f); GPU - CPU: mean "
                "%.3f/255, p99 %.0f/255\n  GI: %s\n  cloud: %s\n",
      d.Bright, direct.Bright, d.Mean, d.P99, mapper->GetGIStatus().c_str(),
      mapper->GetStatus().c_str());
    PGI_CHECK(mapper->GetRelight()->GetNumberOfLights() == 1);
    PGI_CHECK(Says(mapper->GetGIStatus(), "1 local lights"));
    PGI_CHECK(Says(mapper->GetStatus(), "compressed"));
    PGI_CHECK(d.Bright > direct.Bright + 1.0);
    PGI_BELOW(d.Mean, 1.0);
    PGI_BELOW(d.P99, 4.0);
    // The lighting's light moves: the cloud follows.
    lighting->RemoveAllPointLights();
    lighting->AddPointLight(-0.5, 0.3, 1.7, 1.0, 0.8, 0.6);
    Grab(window);
    PGI_CHECK(Says(mapper->GetStatus(), "recomputed (lights)"));
    PGI_NEAR(mapper->GetRelight()->GetLightPosition(0)[2], 1.7, 1e-12);
  }
  return pgitest::Result();
}
