// proxygi cloud: builds a scene's light cloud (Kristensen 2005) on Embree,
// moves a user light along a path through it and renders each step: the
// cloud's indirect light plus the light's direct light; prints the
// precompute, the relighting time per frame, the largest per-step change
// and, at a few steps, the error against Embree.
#include "proxygiBackends.h"
#include "proxygiCommands.h"
#include "proxygiCornellBox.h"
#include "proxygiImage.h"
#include "proxygiProgress.h"

#include "pgiOffscreenWindow.h"
#include "pgiSRGB.h"
#include "pgiScene.h"
#include "vtkPGILightCloud.h"
#include "vtkPGILightCloudPrecompute.h"
#include "vtkPGILightCloudRelight.h"
#include "vtkPGILighting.h"
#include "vtkPGIMeshOccluder.h"
#include "vtkPGIReferenceIllumination.h"

#include <vtkAppendPolyData.h>
#include <vtkCamera.h>
#include <vtkFloatArray.h>
#include <vtkLogger.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkWindowToImageFilter.h>
#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace proxygi
{
namespace cli
{
namespace
{
const char* Usage = R"(usage: proxygi cloud [SCENE.json] [options]

Builds the light cloud of a scene (default: the Cornell box) on Embree,
moves a point light along the scene's light path ("light_cloud": "path" in
the scene file; default a diagonal of the cloud's region) and renders each
step: the cloud's indirect light plus the light's direct light (Embree
shadow rays, one per vertex; the light is a point). Prints the precompute,
the relighting time per frame, the largest per-step change of the cloud's
light and, at --check steps, the error against Embree's path tracer.

  --grid N            cloud lights across the region's shortest axis, the
                      other axes in proportion (cubic cells; default 5)
  --samples N         gather rays per receiver (default 64)
  --compress          zones, clustered lights and CPCA (default: dense)
  --vectors V         PCA vectors per receiver when compressed (default 12)
  --specular KS       glossy receivers: Phong ks (default 0: diffuse); the
                      cloud's light is order-4 SH seen from the camera (the
                      direct light stays diffuse; no Embree checks, whose
                      reference is diffuse)
  --phong E           the Phong exponent of --specular (default 12)
  --steps N           steps along the path (default 24)
  --fps F             frames per second: the fade's clock (default 30)
  --frames PREFIX     write PREFIX-000.png ... (default proxygi-cloud)
  --no-frames         render nothing, only measure
  --check K           steps compared with Embree, spread along the path
                      (default 3; 0: none)
  --reference-spp N   Embree's samples per vertex (default 1024)
  --cache DIR         where the cloud is kept and resumed from
                      (default proxygi-cache)
)";

using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

// `steps` points evenly spaced by arc length along the polyline.
std::vector<double> Resample(const std::vector<double>& path, int steps)
{
  std::vector<double> length(1, 0.0);
  for (std::size_t i = 3; i < path.size(); i += 3)
  {
    const double d = std::sqrt(vtkMath::Distance2BetweenPoints(&path[i - 3], &path[i]));
    length.push_back(length.back() + d);
  }
  std::vector<double> out;
  out.reserve(3 * steps);
  std::size_t segment = 0;
  for (int s = 0; s < steps; ++s)
  {
    const double at = steps > 1 ? length.back() * s / (steps - 1) : 0.0;
    while (segment + 2 < length.size() && length[segment + 1] < at)
    {
      ++segment;
    }
    const double span = length[segment + 1] - length[segment];
    const double t = span > 0.0 ? std::min(1.0, (at - length[segment]) / span) : 0.0;
    for (int a = 0; a < 3; ++a)
    {
      out.push_back((1 - t) * path[3 * segment + a] + t * path[3 * segment + 3 + a]);
    }
  }
  return out;
}

// Embree's light of the scene lit by one point light: direct (one shadow
// ray per vertex when samples is 1 and bounces 0) and one bounce.
vtkSmartPointer<vtkPolyData> EmbreeLight(
  vtkPolyData* receivers, const double* p, const double* intensity, int samples, int bounces)
{
  vtkNew<vtkPGILighting> lighting;
  lighting->SetUniformRadiance(0.0, 0.0, 0.0);
  lighting->AddPointLight(p[0], p[1], p[2], intensity[0], intensity[1], intensity[2]);
  vtkNew<vtkPGIReferenceIllumination> reference;
  reference->SetInputData(receivers);
  reference->SetLighting(lighting);
  reference->SetSamples(samples);
  reference->SetMaxBounces(bounces);
  reference->Update();
  return reference->GetOutput();
}

// Relative RMSE of a against b over all components.
double RelativeRMSE(vtkDataArray* a, vtkDataArray* b, vtkDataArray* scale)
{
  double e2 = 0.0, t2 = 0.0;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double d = a->GetComponent(i, c) - b->GetComponent(i, c);
      e2 += d * d;
      t2 += scale->GetComponent(i, c) * scale->GetComponent(i, c);
    }
  }
  return t2 > 0.0 ? std::sqrt(e2 / t2) : 0.0;
}
} // namespace

int RunCloud(const Args& args)
{
  if (Flag(args, "--help"))
  {
    std::fputs(Usage, stdout);
    return 0;
  }
  bool ok = true;
  const int grid = static_cast<int>(NumberOption(args, "--grid", 5, ok));
  const int samples = static_cast<int>(NumberOption(args, "--samples", 64, ok));
  const double vectors = NumberOption(args, "--vectors", 12, ok);
  const double specular = NumberOption(args, "--specular", 0, ok);
  const double phong = NumberOption(args, "--phong", 12, ok);
  const int steps = static_cast<int>(NumberOption(args, "--steps", 24, ok));
  const double fps = NumberOption(args, "--fps", 30, ok);
  const int checks = static_cast<int>(NumberOption(args, "--check", 3, ok));
  const int referenceSpp = static_cast<int>(NumberOption(args, "--reference-spp", 1024, ok));
  const std::string frames = Option(args, "--frames", "proxygi-cloud");
  const std::string cacheDir = Option(args, "--cache", "proxygi-cache");
  const bool compress = Flag(args, "--compress");
  const bool noFrames = Flag(args, "--no-frames");
  const std::string scenePath = Positional(args, { "--compress", "--no-frames", "--help" });
  if (!ok)
  {
    return 2;
  }
  if (grid < 1 || grid > 64 || samples < 1 || steps < 2 || steps > 100000 || !(fps > 0.0) ||
    checks < 0 || referenceSpp < 1 || !(vectors >= 0.0) || !(specular >= 0.0 && specular <= 1.0) ||
    !(phong >= 0.0 && phong <= 1e4))
  {
    vtkLogF(ERROR,
      "proxygi cloud: --grid 1..64, --samples >= 1, --steps >= 2, --fps > 0, --check >= 0, "
      "--reference-spp >= 1, --vectors >= 0, --specular 0..1, --phong 0..10000");
    return 2;
  }

  SceneDescription scene;
  std::string error;
  const bool parsed = scenePath.empty() ? ParseScene(CornellBoxJSON, "", scene, error)
                                        : LoadScene(scenePath, scene, error);
  LoadedScene loaded;
  if (!parsed || !BuildScene(scene, loaded, error))
  {
    vtkLogF(ERROR, "proxygi cloud: %s", error.c_str());
    return 1;
  }
  vtkNew<vtkAppendPolyData> append;
  vtkNew<vtkPGIMeshOccluder> occluder;
  for (auto& object : loaded.Objects)
  {
    append->AddInputData(object);
    occluder->AddMesh(object);
  }
  append->Update();
  vtkPolyData* receivers = append->GetOutput();
  double region[6];
  receivers->GetBounds(region);
  if (scene.HasCloudRegion)
  {
    std::copy(scene.CloudRegion, scene.CloudRegion + 6, region);
  }
  std::vector<double> path = scene.LightPath;
  if (path.empty())
  {
    for (double f : { 0.2, 0.8 })
    {
      for (int a = 0; a < 3; ++a)
      {
        path.push_back(region[2 * a] + f * (region[2 * a + 1] - region[2 * a]));
      }
    }
  }
  // The scene's first point light sets the intensity (else 1 W/sr).
  double intensity[3] = { 1, 1, 1 };
  for (const SceneLight& light : scene.Lights)
  {
    if (!light.Sphere)
    {
      std::copy(light.Value, light.Value + 3, intensity);
      break;
    }
  }
  std::printf("scene: %s, %lld receivers\n", scene.Name.c_str(),
    static_cast<long long>(receivers->GetNumberOfPoints()));

  // The cloud, cached per scene file.
  vtksys::SystemTools::MakeDirectory(cacheDir);
  const std::string stem = scenePath.empty()
    ? std::string("cornell-box")
    : vtksys::SystemTools::GetFilenameWithoutLastExtension(scenePath);
  const std::string cacheFile = cacheDir + "/light-cloud-" + stem + ".pgilc";
  vtkNew<vtkPGILightCloudPrecompute> precompute;
  precompute->SetInputData(receivers);
  precompute->SetRegionOfInterest(region);
  const double shortest =
    std::min({ region[1] - region[0], region[3] - region[2], region[5] - region[4] });
  int cells[3];
  for (int a = 0; a < 3; ++a)
  {
    const double extent = region[2 * a + 1] - region[2 * a];
    cells[a] = shortest > 0.0
      ? std::max(1, std::min(4 * grid, static_cast<int>(std::lround(grid * extent / shortest))))
      : 1;
  }
  precompute->SetGridResolution(cells);
  precompute->SetSamples(samples);
  precompute->SetCompress(compress);
  precompute->SetVectorsPerReceiver(vectors);
  precompute->SetSpecularAlbedo(specular);
  precompute->SetPhongExponent(phong);
  precompute->SetCacheFileName(cacheFile.c_str());
  const auto t0 = Clock::now();
  {
    Progress progress(precompute, "light cloud");
    precompute->Update();
    if (progress.Interrupted())
    {
      return InterruptedExitCode;
    }
  }
  const auto t1 = Clock::now();
  vtkPGILightCloud* cloud = precompute->GetOutput();
  if (precompute->GetErrorCode() || cloud->GetNumberOfLights() == 0)
  {
    vtkLogF(ERROR, "proxygi cloud: the precompute failed (see above)");
    return 1;
  }
  std::printf("cloud: %lld lights (%dx%dx%d grid, %lld left out inside solids, %lld moved off "
              "surfaces), %d gather rays per receiver; %lld traced, %lld from %s; %.2f s\n",
    static_cast<long long>(precompute->GetLightsTraced() + precompute->GetLightsFromCache()),
    cells[0], cells[1], cells[2], static_cast<long long>(precompute->GetLightsDropped()),
    static_cast<long long>(precompute->GetLightsMoved()), samples,
    static_cast<long long>(precompute->GetLightsTraced()),
    static_cast<long long>(precompute->GetLightsFromCache()), cacheFile.c_str(), Seconds(t0, t1));
  if (compress)
  {
    std::printf("compressed: %d zones, %.1f lights after clustering, %.1f coefficients per "
                "receiver, PCA error %.2f%%, %.2f s\n",
      static_cast<int>(cloud->GetNumberOfZones()), precompute->GetCompressedLights(),
      cloud->GetCoefficientsPerReceiver(), 100 * precompute->GetPCARelativeError(),
      precompute->GetCompressionSeconds());
  }
  else
  {
    std::printf("dense: %.1f coefficients per receiver\n", cloud->GetCoefficientsPerReceiver());
  }
  std::printf("memory: %.2f MB\n", cloud->GetActualMemorySize() / 1024.0);

  vtkNew<vtkPGILightCloudRelight> relight;
  relight->SetInputData(receivers);
  relight->SetCloudData(cloud);
  relight->SetOccluder(occluder);
  const std::vector<double> at = Resample(path, steps);
  relight->AddLight(at[0], at[1], at[2], intensity[0], intensity[1], intensity[2]);
  if (specular > 0.0)
  {
    relight->SetViewPoint(loaded.Camera->GetPosition());
    std::printf("glossy receivers: Phong ks %.2f, exponent %.0f, %d SH coefficients per colour, "
                "seen from the camera\n",
      specular, phong, cloud->GetCoefficients());
  }

  // The picture: vertex colours, no VTK lighting, the scene's camera.
  vtkSmartPointer<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  if (!noFrames)
  {
    renderer->SetBackground(0.05, 0.05, 0.06);
    renderer->SetActiveCamera(loaded.Camera);
    std::string windowPath;
    window = NewOffscreenRenderWindow(&windowPath);
    if (!window)
    {
      vtkLogF(ERROR, "proxygi cloud: no offscreen OpenGL: %s", windowPath.c_str());
      return 1;
    }
    window->SetSize(scene.Size[0], scene.Size[1]);
    window->AddRenderer(renderer);
    std::printf("window: %s\n", windowPath.c_str());
  }

  // Embree's reference is diffuse: no checks for glossy receivers.
  const int checkCount = specular > 0.0 ? 0 : std::min(checks, steps);
  if (specular > 0.0 && checks > 0)
  {
    std::printf("checks: none (glossy receivers; Embree's reference is diffuse)\n");
  }
  std::vector<int> checked;
  checked.reserve(checkCount);
  for (int k = 0; k < checkCount; ++k)
  {
    checked.push_back(checkCount == 1 ? steps / 2 : k * (steps - 1) / (checkCount - 1));
  }
  // The first relighting builds the locators: timed apart.
  double firstRelight = 0.0, relightSeconds = 0.0, directSeconds = 0.0, drawSeconds = 0.0;
  double exposure = 0.0;
  double largestStep = 0.0, brightest = 0.0;
  int outside = 0;
  vtkNew<vtkFloatArray> previous, total;
  total->SetNumberOfComponents(3);
  total->SetName("Radiance");
  vtkNew<vtkPolyData> shaded; // the receivers with the total as "Radiance"
  shaded->ShallowCopy(receivers);
  shaded->GetPointData()->AddArray(total);
  std::vector<vtkSmartPointer<vtkPolyData>> displayed;
  std::printf("\n| step | light at | cloud lights used | indirect error | total error |\n"
              "|---|---|---|---|---|\n");
  for (int s = 0; s < steps; ++s)
  {
    const double* p = &at[3 * s];
    relight->SetLightPosition(0, p[0], p[1], p[2]);
    relight->SetTime(s / fps);
    const auto r0 = Clock::now();
    relight->Update();
    const auto r1 = Clock::now();
    (s == 0 ? firstRelight : relightSeconds) += Seconds(r0, r1);
    outside += relight->GetLightsOutside();
    vtkDataArray* indirect = relight->GetOutput()->GetPointData()->GetArray("LightCloudRadiance");
    if (!indirect)
    {
      vtkLogF(ERROR, "proxygi cloud: relighting failed at step %d (see above)", s);
      return 1;
    }
    // The largest change of any vertex's cloud light between two steps.
    for (vtkIdType i = 0; i < indirect->GetNumberOfValues(); ++i)
    {
      const double v = indirect->GetComponent(i / 3, i % 3);
      brightest = std::max(brightest, v);
      if (s > 0)
      {
        largestStep = std::max(largestStep, std::abs(v - previous->GetValue(i)));
      }
    }
    previous->DeepCopy(indirect);

    const auto d0 = Clock::now();
    vtkSmartPointer<vtkPolyData> direct = EmbreeLight(receivers, p, intensity, 1, 0);
    const auto d1 = Clock::now();
    directSeconds += Seconds(d0, d1);
    vtkDataArray* directArray = direct->GetPointData()->GetArray("DirectShadowed");
    total->SetNumberOfTuples(indirect->GetNumberOfTuples());
    std::vector<double> luminance;
    luminance.reserve(total->GetNumberOfTuples());
    for (vtkIdType i = 0; i < total->GetNumberOfTuples(); ++i)
    {
      double rgb[3];
      for (int c = 0; c < 3; ++c)
      {
        rgb[c] = indirect->GetComponent(i, c) + directArray->GetComponent(i, c);
        total->SetComponent(i, c, rgb[c]);
      }
      luminance.push_back(Luminance(rgb[0], rgb[1], rgb[2]));
    }
    if (s == 0)
    {
      exposure = AutoExposure(luminance); // one exposure for the whole path
    }

    std::string indirectError = "", totalError = "";
    if (std::find(checked.begin(), checked.end(), s) != checked.end())
    {
      vtkSmartPointer<vtkPolyData> truth = EmbreeLight(receivers, p, intensity, referenceSpp, 1);
      vtkDataArray* truthIndirect = truth->GetPointData()->GetArray("IndirectOneBounce");
      vtkDataArray* truthTotal = truth->GetPointData()->GetArray("Radiance");
      char text[64];
      std::snprintf(
        text, sizeof(text), "%.1f%%", 100 * RelativeRMSE(indirect, truthIndirect, truthIndirect));
      indirectError = text;
      std::snprintf(
        text, sizeof(text), "%.1f%%", 100 * RelativeRMSE(total, truthTotal, truthTotal));
      totalError = text;
    }
    std::printf("| %d | (%.3f, %.3f, %.3f) | %d | %s | %s |\n", s, p[0], p[1], p[2],
      relight->GetCloudLightsUsed(), indirectError.c_str(), totalError.c_str());

    if (!noFrames)
    {
      if (displayed.empty())
      {
        displayed = AddVertexColourActors(renderer, { shaded }, exposure);
      }
      else
      {
        ColourByRadiance(shaded, exposure, displayed[0]);
      }
      const auto g0 = Clock::now();
      window->Render();
      window->WaitForCompletion();
      drawSeconds += Seconds(g0, Clock::now());
      vtkNew<vtkWindowToImageFilter> grab;
      grab->SetInput(window);
      grab->SetInputBufferTypeToRGB();
      grab->ReadFrontBufferOff();
      grab->Update();
      char name[32];
      std::snprintf(name, sizeof(name), "-%03d.png", s);
      if (!WritePNG(grab->GetOutput(), frames + name))
      {
        vtkLogF(ERROR, "proxygi cloud: cannot write %s%s", frames.c_str(), name);
        return 1;
      }
    }
  }
  std::printf("\nper frame: relighting %.2f ms (CPU filter, %lld receivers; the first frame "
              "%.2f ms, building the locators), direct light %.2f ms (Embree shadow rays), "
              "drawing %.2f ms\n",
    1e3 * relightSeconds / (steps - 1), static_cast<long long>(receivers->GetNumberOfPoints()),
    1e3 * firstRelight, 1e3 * directSeconds / steps, noFrames ? 0.0 : 1e3 * drawSeconds / steps);
  std::printf("largest per-step change of the cloud's light: %.4f of its brightest value "
              "(%d steps, %.3f apart)\n",
    brightest > 0.0 ? largestStep / brightest : 0.0, steps,
    std::sqrt(vtkMath::Distance2BetweenPoints(&at[0], &at[3])));
  if (outside > 0)
  {
    std::printf("%d steps had the light outside the cloud: direct light only there\n", outside);
  }
  if (!noFrames)
  {
    std::printf("wrote %s-000.png .. %s-%03d.png\n", frames.c_str(), frames.c_str(), steps - 1);
  }
  return 0;
}
} // namespace cli
} // namespace proxygi
