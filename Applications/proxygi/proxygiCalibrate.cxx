// proxygi calibrate: the accuracy budget's model measured on this machine.
// Every candidate of the knob grid shades every scene given; its time (one
// filter update over all receivers, best of --repeats) and its error against
// the cached Embree reference are the measurements the model is fitted on.
#include "proxygiBackends.h"
#include "proxygiCommands.h"
#include "proxygiProgress.h"

#include "pgiAccuracyBudget.h"
#include "pgiScene.h"
#include "pgiSceneSetup.h"
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILighting.h"
#include "vtkPGIOccluder.h"

#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <sys/utsname.h>

namespace proxygi
{
namespace cli
{
namespace
{
const char* Usage = R"(usage: proxygi calibrate [scene.json ...] [options]

Measures the accuracy budget's candidates (SH order 3, 4, 6, 8; 16 or 64
spheres; traced self-visibility or the self-shadow rules; shadowed or
unshadowed bounce) on each scene ('default' or none: the built-in bunny
scene) against the Embree reference, fits the cost and error model and
writes it. Give the file to 'proxygi render --budget-model FILE' or to the
filter's and the GPU mappers' SetBudgetModelFileName; without one they use
the model that ships. The times are this machine's, with all its threads.

  --routes R[,R]      filter (default), mapper, or both: the GPU mapper's
                      candidates (16 or 64 spheres, shadowed or unshadowed
                      bounce, --mapper-orders), each timed as a frame that
                      recomputes GI on this machine's GL renderer, which the
                      model records
  --grid G[,G]        the filter's candidates: default (the 32 above),
                      variations (exp OL and PS*, hierarchy angle 0 and 45,
                      per-object blocking, 4 and 64 rays per bright light,
                      each alone around the order 4 and 6 candidates with
                      traced self-visibility: 52), trades (of those, the
                      45-degree cuts and the 4 rays: 16), or several; with
                      --fit, only these candidates' runs are fitted (no
                      --grid: every run)
  --mapper-orders L   the mapper's orders (default 3,4; 6 is its most: on
                      llvmpipe one of its frames takes 2-9 s)
  --mapper-renderer N with --fit: the GL renderer the mapper's runs were
                      timed on (the model's record of it)
  -o FILE             the model (default proxygi-budget-model.txt)
  --measurements CSV  also write every run (scene, features, knobs, time, error)
  --fit CSV[,CSV...]  no measuring: fit the model from measurements written
                      before (the times stay those of the machine that ran them)
  --embree CSV        also time Embree at 16, 64 and 256 samples per vertex
                      against the reference (the curve a budget is compared to)
  --cache DIR         proxies, self-visibility and references (proxygi-cache)
  --reference-spp N   samples per vertex of the reference (default 1024)
  --repeats N         runs per candidate, the fastest kept (default 2)
  --quick             orders 4 and 6 only, one repeat (a smoke run)
)";

using Clock = std::chrono::steady_clock;
// Samples per vertex of the Embree run a budget's check compares with.
constexpr int CheckSpp = 16;

std::string MachineName()
{
  struct utsname u;
  std::string cpu;
  std::ifstream info("/proc/cpuinfo");
  std::string line;
  while (std::getline(info, line))
  {
    if (line.rfind("model name", 0) == 0)
    {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  std::ostringstream s;
  s << (cpu.empty() ? std::string(uname(&u) == 0 ? u.machine : "unknown") : cpu) << ", "
    << vtkSMPTools::GetEstimatedNumberOfThreads() << " threads";
  return s.str();
}

bool SplitList(const std::string& text, std::vector<std::string>& out)
{
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ','))
  {
    if (!item.empty())
    {
      out.push_back(item);
    }
  }
  return !out.empty();
}
} // namespace

bool SceneBudgetFeatures(const SceneDescription& scene, const LoadedScene& loaded,
  budget::SceneFeatures& features, std::string& error)
{
  features = budget::SceneFeatures();
  // The receivers are the objects' points (SceneReceivers adds arrays only).
  for (const auto& object : loaded.Objects)
  {
    features.Receivers += static_cast<double>(object->GetNumberOfPoints());
  }
  double meshes = 0.0;
  for (const SceneObject& o : scene.Objects)
  {
    meshes += o.Type == SceneObject::Kind::Mesh ? 1.0 : 0.0;
  }
  features.Objects = std::max(1.0, meshes);
  return features.SetLight(loaded.Lighting, error);
}

int RunCalibrate(const Args& args)
{
  if (Flag(args, "--help"))
  {
    std::fputs(Usage, stdout);
    return 0;
  }
  bool ok = true;
  const std::string output = Option(args, "-o", "proxygi-budget-model.txt");
  const std::string measurementsPath = Option(args, "--measurements", "");
  const std::string fitFrom = Option(args, "--fit", "");
  const std::string embreePath = Option(args, "--embree", "");
  const std::string cache = Option(args, "--cache", "proxygi-cache");
  const int spp = static_cast<int>(NumberOption(args, "--reference-spp", 1024, ok));
  const bool quick = Flag(args, "--quick");
  std::vector<std::string> routes;
  SplitList(Option(args, "--routes", "filter"), routes);
  const bool filterRoute = std::find(routes.begin(), routes.end(),
                             budget::RouteName(budget::Route::Filter)) != routes.end();
  const bool mapperRoute = std::find(routes.begin(), routes.end(),
                             budget::RouteName(budget::Route::Mapper)) != routes.end();
  std::string mapperRenderer = Option(args, "--mapper-renderer", "");
  // With --fit, --grid keeps only its candidates' runs (none given: all).
  const std::string gridNames = Option(args, "--grid", "");
  std::vector<std::string> grids;
  SplitList(gridNames.empty() ? std::string("default") : gridNames, grids);
  std::vector<budget::Knobs> filterGrid;
  std::string gridError;
  if (!budget::NamedGrids(grids, filterGrid, gridError))
  {
    vtkLogF(ERROR, "proxygi calibrate: --grid: %s", gridError.c_str());
    return 2;
  }
  if (!(filterRoute || mapperRoute) ||
    std::any_of(routes.begin(), routes.end(),
      [](const std::string& r) { return r != "filter" && r != "mapper"; }))
  {
    vtkLogF(ERROR, "proxygi calibrate: --routes takes filter, mapper or filter,mapper");
    return 2;
  }
  const int repeats = static_cast<int>(NumberOption(args, "--repeats", quick ? 1 : 2, ok));
  if (!ok || spp < 16 || repeats < 1)
  {
    vtkLogF(ERROR, "proxygi calibrate: need --reference-spp >= 16, --repeats >= 1");
    return 2;
  }
  std::vector<budget::Measurement> rows;
  std::string error;
  if (!fitFrom.empty())
  {
    std::vector<std::string> files;
    SplitList(fitFrom, files);
    if (!budget::ReadMeasurementFiles(files, rows, error))
    {
      vtkLogF(ERROR, "proxygi calibrate: %s", error.c_str());
      return 1;
    }
    if (!gridNames.empty())
    {
      const std::size_t measured = rows.size();
      rows = budget::InGrid(rows, filterGrid);
      std::printf(
        "fit: %zu of %zu runs in the grid %s\n", rows.size(), measured, gridNames.c_str());
    }
  }
  else
  {
    // Scenes: every positional argument (the default scene when none).
    std::vector<std::string> scenes;
    for (std::size_t i = 0; i < args.size(); ++i)
    {
      const std::string& a = args[i];
      if (a.rfind('-', 0) == 0)
      {
        i += (a == "--quick") ? 0 : 1;
        continue;
      }
      scenes.push_back(a);
    }
    if (scenes.empty())
    {
      scenes.push_back(std::string());
    }
    std::vector<budget::Knobs> grid, mapperGrid;
    if (filterRoute)
    {
      grid = filterGrid;
    }
    if (mapperRoute)
    {
      std::vector<std::string> orders;
      SplitList(Option(args, "--mapper-orders", "3,4"), orders);
      for (const budget::Knobs& k : budget::MapperGrid())
      {
        if (std::find(orders.begin(), orders.end(), std::to_string(k.Order)) != orders.end())
        {
          mapperGrid.push_back(k);
        }
      }
      if (mapperGrid.empty())
      {
        vtkLogF(ERROR, "proxygi calibrate: --mapper-orders takes orders of 3, 4, 6");
        return 2;
      }
    }
    if (quick)
    {
      for (auto* g : { &grid, &mapperGrid })
      {
        g->erase(std::remove_if(g->begin(), g->end(),
                   [](const budget::Knobs& k) { return k.Order != 4 && k.Order != 6; }),
          g->end());
      }
    }
    std::vector<budget::Knobs> all = grid;
    all.insert(all.end(), mapperGrid.begin(), mapperGrid.end());
    std::ofstream embree;
    if (!embreePath.empty())
    {
      embree.open(embreePath);
      embree << "scene,spp,seconds,error\n";
    }
    SetupProgress progress("proxygi calibrate");
    for (const std::string& file : scenes)
    {
      SceneDescription scene = DefaultScene();
      LoadedScene loaded;
      const bool builtIn = file.empty() || file == "default";
      if ((!builtIn && !LoadScene(file, scene, error)) || !BuildScene(scene, loaded, error))
      {
        vtkLogF(ERROR, "proxygi calibrate: %s: %s", file.c_str(), error.c_str());
        return 1;
      }
      std::printf("scene: %s\n", scene.Name.c_str());
      std::map<int, SceneProxies> proxies;
      std::map<int, std::vector<vtkSmartPointer<vtkPolyData>>> traced;
      const auto plain = SceneReceivers(loaded);
      for (const budget::Knobs& k : all)
      {
        if (!proxies.count(k.Spheres) &&
          !BuildSceneProxies(scene, loaded, k.Spheres, cache, proxies[k.Spheres], error, &progress,
            ProxyFit::Occlusion))
        {
          vtkLogF(ERROR, "proxygi calibrate: %s", error.c_str());
          return progress.Interrupted() ? InterruptedExitCode : 1;
        }
        double seconds = 0.0;
        if (k.SelfVisibility > 0 && !traced.count(k.Order))
        {
          traced[k.Order] = SceneReceivers(loaded);
          if (!AddSelfVisibility(scene, traced[k.Order], k.Order, k.SelfVisibility, cache, seconds,
                error, &progress))
          {
            vtkLogF(ERROR, "proxygi calibrate: %s", error.c_str());
            return progress.Interrupted() ? InterruptedExitCode : 1;
          }
        }
      }
      double tracing = 0.0;
      const auto truth = SceneReference(
        scene, loaded, plain, spp, cache, nullptr, tracing, error, 1, true, &progress);
      if (truth.empty())
      {
        vtkLogF(ERROR, "proxygi calibrate: reference: %s", error.c_str());
        return progress.Interrupted() ? InterruptedExitCode : 1;
      }
      // What a budget's check would see: Embree at 16 samples, other seed.
      double cheapSeconds = 0.0;
      const auto cheap = SceneReference(
        scene, loaded, plain, CheckSpp, std::string(), nullptr, cheapSeconds, error, 7);
      vtkSmartPointer<vtkPGIOccluder> occluder = SceneOccluder(plain);
      budget::SceneFeatures features;
      if (!SceneBudgetFeatures(scene, loaded, features, error))
      {
        vtkLogF(ERROR, "proxygi calibrate: %s", error.c_str());
        return 1;
      }
      const auto record = [&](const budget::Knobs& k, double best, double err, double checkErr)
      {
        budget::Measurement m;
        m.Scene = scene.Name;
        m.Features = features;
        m.Features.Spheres = static_cast<double>(proxies[k.Spheres].Leaves);
        m.Settings = k;
        m.Seconds = best;
        m.Error = err;
        m.CheckError = checkErr;
        rows.push_back(m);
        std::printf("  %-70s %7.3f s %6.2f%% (check %.2f%%)\n", k.Describe().c_str(), best,
          100.0 * err, 100.0 * checkErr);
      };
      for (const budget::Knobs& k : grid)
      {
        const auto& receivers = k.SelfVisibility > 0 ? traced[k.Order] : plain;
        double best = 1e300, err = 0.0, checkErr = -1.0;
        for (int r = 0; r < repeats; ++r)
        {
          // A fresh filter: the time of a frame that changes the settings.
          vtkNew<vtkPGIGISettings> settings;
          ConfigureSettings(settings, scene);
          k.Apply(settings);
          vtkNew<vtkPGIGlobalIllumination> gi;
          ConfigureGlobalIllumination(gi, scene, loaded, proxies[k.Spheres]);
          gi->SetSettings(settings);
          gi->SetOccluder(occluder);
          const auto t0 = Clock::now();
          const auto shaded = ShadeEach(gi, receivers);
          best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
          err = RelativeRMSE(shaded, "Radiance", truth, "Radiance");
          checkErr = cheap.empty() ? -1.0 : EstimatedRelativeRMSE(shaded, cheap, CheckSpp, spp);
        }
        record(k, best, err, checkErr);
      }
      // The GPU mapper: a fresh window per run; its first frame builds the
      // shaders and tables, the timed one recomputes GI (as a frame that
      // changes the scene does).
      for (const budget::Knobs& k : mapperGrid)
      {
        double best = 1e300, err = 0.0, checkErr = -1.0;
        bool cutShort = false;
        for (int r = 0; r < repeats && !cutShort; ++r)
        {
          vtkNew<vtkPGIGISettings> settings;
          ConfigureSettings(settings, scene);
          k.Apply(settings);
          SetBackendPlaneDefaults(settings, "gpu");
          std::vector<vtkSmartPointer<vtkPolyData>> shaded;
          double frame = 0.0;
          if (!ShadeOnGPU(plain, settings, loaded, proxies[k.Spheres], scene.Size, shaded, frame,
                cutShort, mapperRenderer, error))
          {
            vtkLogF(ERROR, "proxygi calibrate: %s", error.c_str());
            return 1;
          }
          err = RelativeRMSE(shaded, "Radiance", truth, "Radiance");
          checkErr = cheap.empty() ? -1.0 : EstimatedRelativeRMSE(shaded, cheap, CheckSpp, spp);
          best = std::min(best, frame);
        }
        // Past llvmpipe's loop limit the GI pass is cut short: its error
        // would be llvmpipe's, not the route's.
        if (cutShort)
        {
          std::printf("  %-70s not measured: llvmpipe's loop limit cuts its GI pass short\n",
            k.Describe().c_str());
          continue;
        }
        record(k, best, err, checkErr);
      }
      if (embree.is_open())
      {
        for (int s : { 16, 64, 256 })
        {
          double seconds = 0.0;
          const auto r =
            SceneReference(scene, loaded, plain, s, std::string(), nullptr, seconds, error, 7);
          const double e = RelativeRMSE(r, "Radiance", truth, "Radiance");
          std::string name = scene.Name;
          std::replace(name.begin(), name.end(), ',', ';');
          embree << name << "," << s << "," << seconds << "," << e << "\n";
          std::printf("  %-70s %7.3f s %6.2f%%\n", ("Embree " + std::to_string(s) + " spp").c_str(),
            seconds, 100.0 * e);
        }
      }
    }
    if (!measurementsPath.empty())
    {
      std::ofstream out(measurementsPath);
      out << budget::WriteMeasurements(rows);
      if (!out)
      {
        vtkLogF(ERROR, "proxygi calibrate: cannot write %s", measurementsPath.c_str());
        return 1;
      }
      std::printf("wrote %s (%zu runs)\n", measurementsPath.c_str(), rows.size());
    }
  }
  budget::Model model;
  if (!model.Fit(rows, error))
  {
    vtkLogF(ERROR, "proxygi calibrate: %s", error.c_str());
    return 1;
  }
  model.Machine = MachineName();
  if (model.HasRoute(budget::Route::Mapper))
  {
    if (mapperRenderer.empty())
    {
      vtkLogF(ERROR,
        "proxygi calibrate: the measurements hold GPU-mapper runs: give --mapper-renderer, the "
        "GL renderer they were timed on");
      return 2;
    }
    model.MapperRenderer = mapperRenderer;
  }
  if (!model.Save(output, error))
  {
    vtkLogF(ERROR, "proxygi calibrate: %s", error.c_str());
    return 1;
  }
  std::printf("model: %zu candidates, %d scenes, error spread x%.2f (log RMS %.3f), on %s\n",
    model.Candidates.size(), model.Scenes, std::exp(model.ErrorSpread), model.ErrorSpread,
    model.Machine.c_str());
  if (!model.MapperRenderer.empty())
  {
    std::printf("model: the GPU mapper's times on %s\n", model.MapperRenderer.c_str());
  }
  std::printf("wrote %s\n", output.c_str());
  return 0;
}

} // namespace cli
} // namespace proxygi
