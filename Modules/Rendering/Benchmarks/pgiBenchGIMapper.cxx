// Frame times of the GI mapper against VTK's own mapper, offscreen: a plane
// of R x R quads plus a sphere, N sphere proxies, SH order n, the camera
// orbiting. Three ways to draw: VTK's vtkOpenGLPolyDataMapper (its lighting),
// the GI mapper with cached GI (only the camera moves), and the GI mapper
// recomputing GI every frame (moving proxies). Also the CPU filter's time
// for the same per-vertex GI. Prints a Markdown table.
//
//   ProxyGIBenchGIMapper [--size 512] [--budget 2] [--quick] [--effects]
//
// --effects: instead, the GI pass run every frame with each effect added in
// turn (a ground blocker plane carried by the light or in log space, the
// one-bounce indirect light, three local lights, the shadowed bounce per
// sphere and per object), one scene.
#include "pgiOffscreenWindow.h"
#include "vtkPGIGIPolyDataMapper.h"
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
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
  ball->SetThetaResolution(64);
  ball->SetPhiResolution(32);
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

// Milliseconds per frame: renders (orbiting) until `budget` seconds or 30 frames.
double FrameTime(vtkRenderWindow* window, vtkRenderer* renderer, double budget)
{
  for (int i = 0; i < 2; ++i) // warm-up: shaders, buffers, first GI pass
  {
    window->Render();
  }
  window->WaitForCompletion();
  int frames = 0;
  const auto start = Clock::now();
  double elapsed = 0.0;
  while (frames < 30 && (frames < 3 || elapsed < budget))
  {
    renderer->GetActiveCamera()->Azimuth(3.0);
    window->Render();
    window->WaitForCompletion();
    ++frames;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  }
  return 1000.0 * elapsed / frames;
}
// GI every frame with the effects added one by one (order 4).
int Effects(vtkRenderWindow* window, int resolution, int proxyCount, double budget)
{
  vtkSmartPointer<vtkPolyData> mesh = Scene(resolution);
  vtkSmartPointer<vtkPolyData> proxies = Proxies(proxyCount);
  vtkNew<vtkPGILighting> sky, lights;
  const double c1[3] = { 2, -1, 2.5 }, e1[3] = { 6, 5, 4 }, c2[3] = { -1.5, 1.5, 1.2 },
               e2[3] = { 0.5, 0.8, 1.5 }, c3[3] = { 0.5, -2, 0.8 }, e3[3] = { 4, 3, 2 };
  lights->AddSphereLight(c1, 0.05, e1);
  lights->AddSphereLight(c2, 0.6, e2);
  lights->AddPointLight(c3, e3);
  std::printf("%lld vertices, %d proxies, order 4, GI pass every frame\n\n| effects | frame ms |\n"
              "|---|---|\n",
    static_cast<long long>(mesh->GetNumberOfPoints()), proxyCount);
  const char* names[] = { "shadows", "+ ground plane (in the light)", "+ ground plane (log space)",
    "+ plane, indirect (PlaneBounceShadows off)", "+ plane, indirect",
    "+ plane, indirect, 3 local lights", "+ plane, shadowed indirect (spherical lights)",
    "+ plane, shadowed indirect, per object" };
  for (int variant = 0; variant < 8; ++variant)
  {
    vtkNew<vtkRenderer> renderer;
    vtkNew<vtkActor> actor;
    vtkNew<vtkPGIGIPolyDataMapper> gi;
    gi->GetSettings()->IndirectOff(); // the GPU default before the shared settings
    gi->SetProxies(proxies);
    gi->SetLighting(variant == 5 ? lights.Get() : sky.Get());
    gi->GetSettings()->SetOrder(4);
    gi->AlwaysRecomputeOn();
    if (variant > 0)
    {
      const double origin[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 }, grey[3] = { 0.5, 0.5, 0.5 };
      gi->AddBlockerPlane(origin, up, grey);
    }
    gi->GetSettings()->SetPlaneBlocking(
      variant == 2 ? vtkPGIGISettings::PLANES_IN_LOG_SPACE : vtkPGIGISettings::PLANES_IN_LIGHT);
    gi->GetSettings()->SetIndirect(variant >= 3);
    gi->GetSettings()->SetIndirectMode(variant >= 6 ? vtkPGIGISettings::INDIRECT_MODE_SHADOWED
                                                    : vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED);
    gi->GetSettings()->SetSphericalLightBlocking(
      variant == 7 ? vtkPGIGISettings::BLOCKING_PER_OBJECT : vtkPGIGISettings::BLOCKING_PER_SPHERE);
    gi->GetSettings()->SetPlaneBounceShadows(variant != 3);
    gi->SetInputData(mesh);
    actor->SetMapper(gi);
    renderer->AddActor(actor);
    window->AddRenderer(renderer);
    renderer->GetActiveCamera()->SetPosition(0, -9, 6);
    renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0.5);
    renderer->GetActiveCamera()->SetViewUp(0, 0, 1);
    renderer->ResetCameraClippingRange();
    std::printf("| %s | %.1f |\n", names[variant], FrameTime(window, renderer, budget));
    std::fflush(stdout);
    window->RemoveRenderer(renderer);
  }
  return 0;
}
} // namespace

int main(int argc, char* argv[])
{
  int size = 512;
  double budget = 2.0;
  bool quick = false;
  bool effects = false;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--size") && i + 1 < argc)
    {
      size = std::atoi(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--budget") && i + 1 < argc)
    {
      budget = std::atof(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--effects"))
    {
      effects = true;
    }
    else if (!std::strcmp(argv[i], "--quick"))
    {
      quick = true;
    }
    else
    {
      std::fprintf(
        stderr, "usage: %s [--size 512] [--budget seconds] [--quick] [--effects]\n", argv[0]);
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
  std::printf("window: %s, %dx%d\n\n", description.c_str(), size, size);
  if (effects)
  {
    return Effects(window, quick ? 64 : 128, quick ? 8 : 32, budget);
  }
  std::printf("| vertices | proxies | order | VTK mapper ms | GI cached ms (x) | GI every frame ms "
              "(x) | GI pass ms | CPU filter ms |\n|---|---|---|---|---|---|---|---|\n");

  vtkNew<vtkPGILighting> lighting;
  struct Config
  {
    int Resolution, Proxies, Order;
  };
  std::vector<Config> configs = { { 64, 1, 4 }, { 64, 8, 4 }, { 64, 32, 4 }, { 128, 1, 4 },
    { 128, 8, 4 }, { 128, 32, 3 }, { 128, 32, 4 }, { 128, 128, 4 }, { 256, 8, 4 }, { 256, 32, 4 } };
  if (quick)
  {
    configs = { { 64, 8, 4 } };
  }
  for (const Config& c : configs)
  {
    vtkSmartPointer<vtkPolyData> mesh = Scene(c.Resolution);
    vtkSmartPointer<vtkPolyData> proxies = Proxies(c.Proxies);
    double ms[3];
    for (int mode = 0; mode < 3; ++mode)
    {
      vtkNew<vtkRenderer> renderer;
      vtkNew<vtkActor> actor;
      vtkSmartPointer<vtkPolyDataMapper> mapper;
      if (mode == 0)
      {
        mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
      }
      else
      {
        auto gi = vtkSmartPointer<vtkPGIGIPolyDataMapper>::New();
        gi->GetSettings()->IndirectOff(); // the GPU default before the shared settings
        gi->SetProxies(proxies);
        gi->SetLighting(lighting);
        gi->GetSettings()->SetOrder(c.Order);
        gi->SetAlwaysRecompute(mode == 2);
        mapper = gi;
      }
      mapper->SetInputData(mesh);
      actor->SetMapper(mapper);
      renderer->AddActor(actor);
      window->AddRenderer(renderer);
      renderer->GetActiveCamera()->SetPosition(0, -9, 6);
      renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0.5);
      renderer->GetActiveCamera()->SetViewUp(0, 0, 1);
      renderer->ResetCameraClippingRange();
      ms[mode] = FrameTime(window, renderer, budget);
      window->RemoveRenderer(renderer);
    }
    const auto start = Clock::now();
    vtkNew<vtkPGIGlobalIllumination> cpu;
    cpu->SetInputData(mesh);
    cpu->SetProxiesData(proxies);
    cpu->SetLighting(lighting);
    cpu->GetSettings()->SetOrder(c.Order);
    cpu->GetSettings()->IndirectOff();
    cpu->GetSettings()->LocalLightsOff();
    cpu->Update();
    const double cpuMs = 1000.0 * std::chrono::duration<double>(Clock::now() - start).count();
    std::printf("| %lld | %d | %d | %.1f | %.1f (%.2f) | %.1f (%.2f) | %.1f | %.0f |\n",
      static_cast<long long>(mesh->GetNumberOfPoints()), c.Proxies, c.Order, ms[0], ms[1],
      ms[1] / ms[0], ms[2], ms[2] / ms[0], ms[2] - ms[1], cpuMs);
    std::fflush(stdout);
  }
  return 0;
}
