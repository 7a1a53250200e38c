// Per-pass times of the image-space GI pass (vtkPGIImageSpaceGIPass, with
// indirect light) at each receiver scale, bilateral and bilinear, and its
// frame time with shadows only against per-vertex GI on the GPU
// (vtkPGIGIPolyDataMapper, shadows only, recomputing every frame) of the
// same scene: a plane of R x R quads plus a sphere, N sphere proxies,
// order 4, offscreen.
// Pass times come from glFinish + wall clock around each pass, averaged over
// the frames; on llvmpipe only the ratios mean anything. Prints Markdown.
//
//   ProxyGIBenchImageSpace [--size 512] [--resolution 256] [--budget 1] [--quick]
//                          [--nearest-fallback]
#include "pgiOffscreenWindow.h"
#include "vtkPGIGIPolyDataMapper.h"
#include "vtkPGIImageSpaceGIPass.h"
#include "vtkPGILighting.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;

vtkSmartPointer<vtkPolyData> Scene(int resolution)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-4, -4, 0);
  plane->SetPoint1(4, -4, 0);
  plane->SetPoint2(-4, 4, 0);
  plane->SetResolution(resolution, resolution);
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(0, 0, 1.5);
  ball->SetThetaResolution(128);
  ball->SetPhiResolution(64);
  vtkNew<vtkAppendPolyData> all;
  all->AddInputConnection(plane->GetOutputPort());
  all->AddInputConnection(ball->GetOutputPort());
  all->Update();
  return all->GetOutput();
}

// The ball plus count - 1 random spheres above the plane.
vtkSmartPointer<vtkPolyData> Proxies(int count)
{
  auto proxies = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("Radius");
  points->InsertNextPoint(0, 0, 1.5);
  radius->InsertNextValue(1.0);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 1; i < count; ++i)
  {
    points->InsertNextPoint(3.5 * u(rng), 3.5 * u(rng), 1.0 + 0.6 * u(rng));
    radius->InsertNextValue(0.35 + 0.15 * u(rng));
  }
  proxies->SetPoints(points);
  proxies->GetPointData()->AddArray(radius);
  return proxies;
}

struct Timing
{
  double Frame = 0.0; // ms
  double Pass[vtkPGIImageSpaceGIPass::NumberOfPasses] = {};
};

// Renders (orbiting) until `budget` seconds or 20 frames, at least 3.
Timing Measure(
  vtkRenderWindow* window, vtkRenderer* renderer, vtkPGIImageSpaceGIPass* pass, double budget)
{
  for (int i = 0; i < 2; ++i) // warm-up: shaders, targets
  {
    window->Render();
  }
  window->WaitForCompletion();
  Timing t;
  int frames = 0;
  const auto start = Clock::now();
  double elapsed = 0.0;
  while (frames < 20 && (frames < 3 || elapsed < budget))
  {
    renderer->GetActiveCamera()->Azimuth(3.0);
    window->Render();
    window->WaitForCompletion();
    ++frames;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    for (int p = 0; pass && p < vtkPGIImageSpaceGIPass::NumberOfPasses; ++p)
    {
      t.Pass[p] += 1000.0 * pass->GetPassTime(p);
    }
  }
  t.Frame = 1000.0 * elapsed / frames;
  for (double& p : t.Pass)
  {
    p /= frames;
  }
  return t;
}
} // namespace

int main(int argc, char* argv[])
{
  int size = 512, resolution = 256;
  double budget = 1.0;
  bool quick = false;
  int fallback = vtkPGIImageSpaceGIPass::ExactFallback;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--size") && i + 1 < argc)
    {
      size = std::atoi(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--resolution") && i + 1 < argc)
    {
      resolution = std::atoi(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--budget") && i + 1 < argc)
    {
      budget = std::atof(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--quick"))
    {
      quick = true;
    }
    else if (!std::strcmp(argv[i], "--nearest-fallback"))
    {
      fallback = vtkPGIImageSpaceGIPass::NearestSampleFallback;
    }
    else
    {
      std::fprintf(stderr,
        "usage: %s [--size 512] [--resolution 256] [--budget seconds] [--quick] "
        "[--nearest-fallback]\n",
        argv[0]);
      return 2;
    }
  }
  std::string description;
  vtkSmartPointer<vtkRenderWindow> window = proxygi::NewOffscreenRenderWindow(&description);
  if (!window)
  {
    std::fprintf(stderr, "no offscreen window: %s\n", description.c_str());
    return 1;
  }
  window->SetSize(size, size);
  std::printf("window: %s, %dx%d, %s fallback\n\n", description.c_str(), size, size,
    fallback == vtkPGIImageSpaceGIPass::ExactFallback ? "exact" : "nearest-sample");

  vtkNew<vtkPGILighting> lighting;
  vtkSmartPointer<vtkPolyData> mesh = Scene(resolution);
  std::vector<int> proxyCounts = { 8, 32 };
  if (quick)
  {
    proxyCounts = { 8 };
  }
  for (int count : proxyCounts)
  {
    vtkSmartPointer<vtkPolyData> proxies = Proxies(count);
    auto setCamera = [](vtkRenderer* renderer)
    {
      renderer->GetActiveCamera()->SetPosition(0, -9, 6);
      renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0.5);
      renderer->GetActiveCamera()->SetViewUp(0, 0, 1);
      renderer->ResetCameraClippingRange();
    };
    // Per-vertex GI every frame (as if the proxies moved).
    double perVertex = 0.0;
    {
      vtkNew<vtkRenderer> renderer;
      vtkNew<vtkPGIGIPolyDataMapper> mapper;
      mapper->GetSettings()->IndirectOff(); // the GPU default before the shared settings
      mapper->SetInputData(mesh);
      mapper->SetProxies(proxies);
      mapper->SetLighting(lighting);
      mapper->GetSettings()->SetOrder(4);
      mapper->AlwaysRecomputeOn();
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      renderer->AddActor(actor);
      window->AddRenderer(renderer);
      setCamera(renderer);
      perVertex = Measure(window, renderer, nullptr, budget).Frame;
      window->RemoveRenderer(renderer);
    }
    std::printf("%lld vertices, %d proxies, order 4, %dx%d: per-vertex GI (shadows) every frame "
                "%.1f ms\n\n",
      static_cast<long long>(mesh->GetNumberOfPoints()), count, size, size, perVertex);
    std::printf("| scale | upsampling | receiver setup ms | splatting ms | exponentiation ms | "
                "indirect ms | upsampling ms | frame ms | frame vs 1/1 | bilateral / bilinear | "
                "shadows-only frame ms | shadows-only image-space / per-vertex |\n"
                "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    double frameAtOne[2] = { 0.0, 0.0 };
    for (int scale : { 1, 2, 4, 8 })
    {
      double bilinearFrame = 0.0;
      for (int mode : { vtkPGIImageSpaceGIPass::Bilinear, vtkPGIImageSpaceGIPass::Bilateral })
      {
        vtkNew<vtkRenderer> renderer;
        vtkNew<vtkPolyDataMapper> mapper;
        mapper->SetInputData(mesh);
        vtkNew<vtkActor> actor;
        actor->SetMapper(mapper);
        actor->GetProperty()->SetColor(0.8, 0.8, 0.8);
        renderer->AddActor(actor);
        vtkNew<vtkPGIImageSpaceGIPass> pass;
        pass->GetSettings()->IndirectOff(); // the GPU default before the shared settings
        pass->SetProxies(proxies);
        pass->SetLighting(lighting);
        pass->SetReceiverScale(scale);
        pass->SetUpsampling(mode);
        pass->SetFallback(fallback);
        pass->MeasurePassTimesOn();
        pass->GetSettings()->IndirectOn();
        renderer->SetPass(pass);
        window->AddRenderer(renderer);
        setCamera(renderer);
        const Timing t = Measure(window, renderer, pass, budget);
        pass->GetSettings()->IndirectOff();
        pass->MeasurePassTimesOff();
        const double shadowsOnly = Measure(window, renderer, pass, budget).Frame;
        window->RemoveRenderer(renderer);
        if (scale == 1)
        {
          frameAtOne[mode] = t.Frame;
        }
        if (mode == vtkPGIImageSpaceGIPass::Bilinear)
        {
          bilinearFrame = t.Frame;
        }
        char ratio[32] = "";
        if (mode == vtkPGIImageSpaceGIPass::Bilateral)
        {
          std::snprintf(ratio, sizeof(ratio), "%.2f", t.Frame / bilinearFrame);
        }
        std::printf(
          "| 1/%d | %s | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.2f | %s | %.1f | %.2f |\n",
          scale, mode == vtkPGIImageSpaceGIPass::Bilateral ? "bilateral" : "bilinear",
          t.Pass[vtkPGIImageSpaceGIPass::ReceiverSetupPass],
          t.Pass[vtkPGIImageSpaceGIPass::SplattingPass],
          t.Pass[vtkPGIImageSpaceGIPass::ExponentiationPass],
          t.Pass[vtkPGIImageSpaceGIPass::IndirectPass],
          t.Pass[vtkPGIImageSpaceGIPass::UpsamplingPass], t.Frame, t.Frame / frameAtOne[mode],
          ratio, shadowsOnly, shadowsOnly / perVertex);
        std::fflush(stdout);
      }
    }
    std::printf("\n");
  }
  return 0;
}
