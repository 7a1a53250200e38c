// Accuracy against time for every knob of the per-vertex GI filter, on the
// default scene (the bunny over a plane under the forest map), measured in
// one run against the Embree reference; Embree itself at several sample
// counts for comparison, and the speed-up over it at equal error. Then the
// baseline settings on every scene given (per effect, with the proxy-mode
// split of the ground's error). Writes a Markdown table, a CSV and a PNG plot
// (VTK charts; needs a display or xvfb-run).
//
//   ProxyGISweepGI [--reference-spp N] [--cache DIR] [--out PREFIX] [--quick]
//                  [scene.json ...]
#include "proxygiProgress.h"

#include "pgiScene.h"
#include "pgiSceneSetup.h"
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILighting.h"
#include "vtkPGIOccluder.h"

#include "pgiBenchPlot.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkSMPTools.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <sys/stat.h>
#include <vector>

using namespace proxygi;
using proxygi::cli::InterruptedExitCode;
using proxygi::cli::SetupProgress;

namespace
{
using Clock = std::chrono::steady_clock;

struct Row
{
  std::string Knob, Setting;
  double Seconds, ErrorTotal, ErrorDirect, ErrorIndirect;
};

double Seconds(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}
// The one-bounce light whichever mode made it (the other array is zeros).
void AddIndirectSum(const std::vector<vtkSmartPointer<vtkPolyData>>& shaded)
{
  for (auto& s : shaded)
  {
    vtkDataArray* a = s->GetPointData()->GetArray("IndirectProxy");
    vtkDataArray* b = s->GetPointData()->GetArray("IndirectShadowed");
    vtkDataArray* own = s->GetPointData()->GetArray("IndirectSelf");
    vtkNew<vtkDoubleArray> sum;
    sum->SetName("IndirectAny");
    sum->SetNumberOfComponents(3);
    sum->SetNumberOfTuples(a->GetNumberOfTuples());
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        sum->SetComponent(i, c,
          a->GetComponent(i, c) + (b ? b->GetComponent(i, c) : 0.0) +
            (own ? own->GetComponent(i, c) : 0.0));
      }
    }
    s->GetPointData()->AddArray(sum);
  }
}
} // namespace

int main(int argc, char* argv[])
{
  int referenceSpp = 2048;
  std::string cache = "proxygi-cache", out = "gi-sweep";
  bool quick = false;
  std::vector<std::string> sceneFiles;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--reference-spp") && i + 1 < argc)
    {
      referenceSpp = std::atoi(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--cache") && i + 1 < argc)
    {
      cache = argv[++i];
    }
    else if (!std::strcmp(argv[i], "--out") && i + 1 < argc)
    {
      out = argv[++i];
    }
    else if (!std::strcmp(argv[i], "--quick"))
    {
      quick = true;
    }
    else
    {
      sceneFiles.push_back(argv[i]);
    }
  }
  vtkSMPTools::SetBackend("STDThread");
  const int repeats = quick ? 1 : 3;
  // The long set-up work (references, proxies) shows its progress; Ctrl-C
  // stops it and caches nothing (the timed runs below show none).
  SetupProgress progress("ProxyGISweepGI");
  std::string error;
  const SceneDescription scene = DefaultScene();
  LoadedScene loaded;
  if (!BuildScene(scene, loaded, error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  const auto receivers = SceneReceivers(loaded);
  // The same receivers with each mesh's own visibility traced (cached).
  auto receiversTraced = receivers, receiversTraced6 = receivers;
  double selfSeconds = 0.0;
  if (!AddSelfVisibility(scene, receiversTraced, 4, 256, cache, selfSeconds, error, &progress) ||
    !AddSelfVisibility(scene, receiversTraced6, 6, 256, cache, selfSeconds, error, &progress))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return progress.Interrupted() ? InterruptedExitCode : 1;
  }
  double refSeconds = 0.0;
  std::printf("reference: %d samples per vertex...\n", referenceSpp);
  const auto truth = SceneReference(
    scene, loaded, receivers, referenceSpp, cache, nullptr, refSeconds, error, 1, true, &progress);
  if (truth.empty())
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return progress.Interrupted() ? InterruptedExitCode : 1;
  }
  const double referenceNoise = RelativeRMS(truth, "RadianceStdErr", "Radiance");
  std::printf("reference noise (relative RMS standard error): %.3f%%, %.1f s\n",
    100 * referenceNoise, refSeconds);

  // Proxies per sphere count (cached), with the hierarchy above them.
  std::map<int, SceneProxies> proxies;
  const std::vector<int> counts =
    quick ? std::vector<int>{ 32, 64 } : std::vector<int>{ 16, 32, 64, 128 };
  for (int count : counts)
  {
    if (!BuildSceneProxies(scene, loaded, count, cache, proxies[count], error, &progress))
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      return progress.Interrupted() ? InterruptedExitCode : 1;
    }
    std::printf("proxies: %d asked, %lld leaves, %.1f s%s\n", count,
      static_cast<long long>(proxies[count].Leaves), proxies[count].Seconds,
      proxies[count].Cached ? " (cached)" : "");
  }
  // The 64 spheres' radii fitted for occlusion (vtkPGIOcclusionFit).
  SceneProxies fitted;
  if (!BuildSceneProxies(scene, loaded, 64, cache, fitted, error, &progress, ProxyFit::Occlusion))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return progress.Interrupted() ? InterruptedExitCode : 1;
  }

  struct Config
  {
    std::string Knob, Setting;
    int Order = 4, Method = vtkPGIGISettings::EXP_HYB, Spheres = 64;
    double Hierarchy = 0.0;
    int Operator = vtkPGIGISettings::INDIRECT_AVERAGED;
    bool Shadows = true;
    int Planes = vtkPGIGISettings::PLANES_IN_LIGHT;
    bool PlaneBounceShadows = true;
    int PlaneDirections = 64; // the planes' light map's look-ups (0: one point)
    int Mode = vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED;
    int Blocking = vtkPGIGISettings::BLOCKING_PER_SPHERE;
    bool SelfVisibility = false;
    bool Fitted = false;   // the spheres' radii fitted for occlusion
    int Bright = 0;        // bright lights: 0 off (the map in SH), 1 proxies' cones, 2 rays
    int IndirectOrder = 0; // the shadowed bounce's order (0: Order)
  };
  std::vector<Config> configs;
  configs.push_back({ "baseline", "order 4, HYB, 64 spheres, averaged" });
  for (int order : { 3, 5, 6 })
  {
    Config c{ "SH order", std::to_string(order) };
    c.Order = order;
    configs.push_back(c);
  }
  const char* methodNames[] = { "PS-2", "PS*-2", "OL", "HYB" };
  for (int m :
    { vtkPGIGISettings::EXP_PS, vtkPGIGISettings::EXP_PS_STAR, vtkPGIGISettings::EXP_OL })
  {
    Config c{ "exp method", methodNames[m] };
    c.Method = m;
    configs.push_back(c);
  }
  for (int count : counts)
  {
    if (count == 64)
    {
      continue;
    }
    Config c{ "spheres", std::to_string(count) };
    c.Spheres = count;
    configs.push_back(c);
  }
  for (double angle : { 10.0, 20.0, 30.0 })
  {
    Config c{ "hierarchy angle", std::to_string(static_cast<int>(angle)) + " deg" };
    c.Hierarchy = angle;
    configs.push_back(c);
  }
  const char* operatorNames[] = { "point-sampled", "averaged", "exact" };
  for (int op : { vtkPGIGISettings::INDIRECT_POINT_SAMPLED, vtkPGIGISettings::INDIRECT_EXACT })
  {
    Config c{ "indirect operator", operatorNames[op] };
    c.Operator = op;
    configs.push_back(c);
  }
  {
    Config c{ "plane blocking", "log-space cap (the image-space pass's way)" };
    c.Planes = vtkPGIGISettings::PLANES_IN_LOG_SPACE;
    configs.push_back(c);
  }
  {
    Config c{ "plane bounce", "plane uniformly lit (no proxy shadow on it)" };
    c.PlaneBounceShadows = false;
    configs.push_back(c);
  }
  for (int directions : { 0, 16, 256 })
  {
    Config c{ "plane bounce",
      directions == 0 ? std::string("one plane point per receiver (the GPU's way)")
                      : "light map, " + std::to_string(directions) + " directions" };
    c.PlaneDirections = directions;
    configs.push_back(c);
  }
  {
    Config c{ "indirect model", "shadowed spherical lights, per-sphere blocking" };
    c.Mode = vtkPGIGISettings::INDIRECT_MODE_SHADOWED;
    configs.push_back(c);
    c.Setting = "shadowed spherical lights, per-object blocking";
    c.Blocking = vtkPGIGISettings::BLOCKING_PER_OBJECT;
    configs.push_back(c);
    c.Setting = "shadowed, per sphere, hierarchy 25 deg";
    c.Blocking = vtkPGIGISettings::BLOCKING_PER_SPHERE;
    c.Hierarchy = 25.0;
    configs.push_back(c);
  }
  {
    Config c{ "self-visibility", "traced once, 256 rays (vtkPGISelfVisibility)" };
    c.SelfVisibility = true;
    configs.push_back(c);
    c.Setting = "traced, shadowed bounce, hierarchy 25 deg";
    c.Mode = vtkPGIGISettings::INDIRECT_MODE_SHADOWED;
    c.Hierarchy = 25.0;
    configs.push_back(c);
  }
  {
    Config c{ "bright lights", "taken out, shadowed by the proxies' cones" };
    c.Bright = 1;
    configs.push_back(c);
    c.Setting = "taken out, 16 rays per light against the meshes";
    c.Bright = 2;
    configs.push_back(c);
    c.Knob = "proxy fit";
    c.Setting = "proxygi render's default with bounding radii";
    c.SelfVisibility = true;
    c.Mode = vtkPGIGISettings::INDIRECT_MODE_SHADOWED;
    c.Hierarchy = 25.0;
    configs.push_back(c);
    c.Knob = "proxygi render";
    c.Setting = "its default before: order 4, fitted radii, traced self, bright rays, shadowed, "
                "hierarchy 25";
    c.Fitted = true;
    configs.push_back(c);
    // The shadowed bounce's own order under order-6 shadows.
    c.Knob = "indirect order";
    c.Order = 6;
    for (int k : { 6, 3 })
    {
      c.IndirectOrder = k;
      c.Setting = "order 6, the bounce at " + std::to_string(k) + " (proxygi render otherwise)";
      configs.push_back(c);
    }
    c.Knob = "proxygi render";
    c.IndirectOrder = 4;
    c.Setting = "its default: order 6, the bounce at 4, fitted radii, traced self, bright rays, "
                "shadowed, hierarchy 25";
    configs.push_back(c);
  }
  // The meshes for the bright lights' rays (its Embree scene built here).
  vtkSmartPointer<vtkPGIOccluder> occluder = SceneOccluder(receivers);
  if (!occluder->Prepare(error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  {
    Config c{ "no shadows", "unshadowed environment (what shadows buy)" };
    c.Shadows = false;
    configs.push_back(c);
  }

  // One untimed run: the SH tables are built on first use.
  for (auto& r : receivers)
  {
    vtkNew<vtkPGIGlobalIllumination> gi;
    gi->SetInputData(r);
    ConfigureGlobalIllumination(gi, scene, loaded, proxies.at(64));
    gi->Update();
  }
  std::vector<Row> rows;
  for (const Config& c : configs)
  {
    double best = 1e300;
    std::vector<vtkSmartPointer<vtkPolyData>> shaded;
    for (int repeat = 0; repeat < repeats; ++repeat)
    {
      const auto t0 = Clock::now();
      // One filter shades every object, as proxygi render does (one bake).
      vtkNew<vtkPGIGlobalIllumination> gi;
      ConfigureGlobalIllumination(gi, scene, loaded, c.Fitted ? fitted : proxies.at(c.Spheres));
      vtkPGIGISettings* settings = gi->GetSettings();
      settings->SetOrder(c.Order);
      settings->SetExpMethod(c.Method);
      settings->SetHierarchyAngle(c.Hierarchy);
      settings->SetIndirectOperator(c.Operator);
      settings->SetShadows(c.Shadows);
      settings->SetPlaneBlocking(c.Planes);
      settings->SetPlaneBounceShadows(c.PlaneBounceShadows);
      settings->SetPlaneBounceDirections(c.PlaneDirections);
      settings->SetIndirectMode(c.Mode);
      settings->SetSphericalLightBlocking(c.Blocking);
      settings->SetBrightLights(c.Bright > 0);
      settings->SetIndirectOrder(c.IndirectOrder);
      gi->SetOccluder(c.Bright == 2 ? occluder.Get() : nullptr);
      shaded = ShadeEach(
        gi, c.SelfVisibility ? (c.Order == 6 ? receiversTraced6 : receiversTraced) : receivers);
      best = std::min(best, Seconds(t0));
    }
    AddIndirectSum(shaded);
    rows.push_back({ c.Knob, c.Setting, best, RelativeRMSE(shaded, "Radiance", truth, "Radiance"),
      RelativeRMSE(shaded, "DirectShadowed", truth, "DirectShadowed"),
      RelativeRMSE(shaded, "IndirectAny", truth, "IndirectOneBounce") });
    std::printf("%-18s %-36s %8.3f s  total %6.2f%%  direct %6.2f%%\n", c.Knob.c_str(),
      c.Setting.c_str(), best, 100 * rows.back().ErrorTotal, 100 * rows.back().ErrorDirect);
  }
  // Embree at lower sample counts against the same reference, with another
  // seed (the same one would correlate them with the truth).
  for (int spp : quick ? std::vector<int>{ 8, 32 } : std::vector<int>{ 4, 16, 64, 256 })
  {
    double seconds = 0.0;
    // Traced anew (not cached): its time belongs to this run, like ours.
    const auto r =
      SceneReference(scene, loaded, receivers, spp, std::string(), nullptr, seconds, error, 7);
    rows.push_back({ "Embree reference", std::to_string(spp) + " samples", seconds,
      RelativeRMSE(r, "Radiance", truth, "Radiance"),
      RelativeRMSE(r, "DirectShadowed", truth, "DirectShadowed"),
      RelativeRMSE(r, "IndirectOneBounce", truth, "IndirectOneBounce") });
    std::printf("%-18s %-36s %8.3f s  total %6.2f%%  direct %6.2f%%\n", "Embree",
      rows.back().Setting.c_str(), seconds, 100 * rows.back().ErrorTotal,
      100 * rows.back().ErrorDirect);
  }
  // Embree's time at the baseline's error: Monte Carlo error falls as
  // 1/sqrt(time), fitted through the Embree rows (log-log least squares).
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int m = 0;
  for (const Row& r : rows)
  {
    if (r.Knob == "Embree reference")
    {
      const double x = std::log(r.Seconds), y = std::log(r.ErrorTotal);
      sx += x, sy += y, sxx += x * x, sxy += x * y, ++m;
    }
  }
  const double slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  const double intercept = (sy - slope * sx) / m;
  const double embreeAtBaseline = std::exp((std::log(rows[0].ErrorTotal) - intercept) / slope);
  std::printf("Embree at the baseline's error %.2f%%: %.3f s (fit slope %.2f), %.0fx the "
              "baseline's %.3f s\n",
    100 * rows[0].ErrorTotal, embreeAtBaseline, slope, embreeAtBaseline / rows[0].Seconds,
    rows[0].Seconds);

  // Table and CSV.
  std::ofstream md(out + ".md"), csv(out + ".csv");
  md << "Default scene (bunny " << receivers[0]->GetNumberOfPoints() << " vertices + plane "
     << receivers[1]->GetNumberOfPoints() << " vertices), "
     << vtkSMPTools::GetEstimatedNumberOfThreads() << " threads. Ground truth: Embree, "
     << referenceSpp << " samples per vertex, one bounce (its own noise "
     << std::round(1000 * referenceNoise) / 10
     << "% relative RMS). Error: relative RMSE of per-vertex radiance; time: best of " << repeats
     << " runs of the filter over all receivers.\n\n";
  md << "| knob | setting | time (s) | time / baseline | error, total | direct | indirect |\n";
  md << "|---|---|---:|---:|---:|---:|---:|\n";
  const double base = rows[0].Seconds;
  csv << "knob,setting,seconds,error_total,error_direct,error_indirect\n";
  for (const Row& r : rows)
  {
    char line[512];
    std::snprintf(line, sizeof(line), "| %s | %s | %.3f | %.2f | %.2f%% | %.2f%% | %.1f%% |\n",
      r.Knob.c_str(), r.Setting.c_str(), r.Seconds, r.Seconds / base, 100 * r.ErrorTotal,
      100 * r.ErrorDirect, 100 * r.ErrorIndirect);
    md << line;
    csv << r.Knob << "," << r.Setting << "," << r.Seconds << "," << r.ErrorTotal << ","
        << r.ErrorDirect << "," << r.ErrorIndirect << "\n";
  }
  {
    char line[512];
    std::snprintf(line, sizeof(line),
      "\nEmbree needs %.2f s to reach the baseline's %.2f%% (error ~ time^%.2f fitted through "
      "its rows): the SH filter is %.0fx faster at equal error.\n",
      embreeAtBaseline, 100 * rows[0].ErrorTotal, slope, embreeAtBaseline / base);
    md << line;
  }

  // Every scene at the baseline settings: error per effect, and for the
  // planes the split into SH error (against the reference with the other
  // objects replaced by their proxies) and proxy-geometry error.
  std::vector<std::string> scenes = { "" };
  scenes.insert(scenes.end(), sceneFiles.begin(), sceneFiles.end());
  md << "\n| scene | indirect model | receivers | SH filter (s) | Embree " << referenceSpp / 2
     << " spp (s) | its noise | direct | indirect | total | planes: total | planes: SH "
        "only |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  const int sceneSpp = referenceSpp / 2;
  for (const std::string& file : scenes)
  {
    SceneDescription sd = DefaultScene();
    LoadedScene ld;
    if ((!file.empty() && !LoadScene(file, sd, error)) || !BuildScene(sd, ld, error))
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      return 1;
    }
    SceneProxies sp, spFitted;
    if (!BuildSceneProxies(sd, ld, 64, cache, sp, error, &progress) ||
      !BuildSceneProxies(sd, ld, 64, cache, spFitted, error, &progress, ProxyFit::Occlusion))
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      return progress.Interrupted() ? InterruptedExitCode : 1;
    }
    const auto rc = SceneReceivers(ld);
    auto rcTraced = rc, rcTraced6 = rc;
    double selfTracing = 0.0;
    if (!AddSelfVisibility(sd, rcTraced, 4, 256, cache, selfTracing, error, &progress) ||
      !AddSelfVisibility(sd, rcTraced6, 6, 256, cache, selfTracing, error, &progress))
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      return progress.Interrupted() ? InterruptedExitCode : 1;
    }
    double tracing = 0.0, tracingProxies = 0.0;
    const auto ref =
      SceneReference(sd, ld, rc, sceneSpp, cache, nullptr, tracing, error, 1, true, &progress);
    const auto refProxies = ref.empty()
      ? ref
      : SceneReference(sd, ld, rc, sceneSpp, cache, &sp, tracingProxies, error, 1, true, &progress);
    const auto refFitted = refProxies.empty()
      ? refProxies
      : SceneReference(
          sd, ld, rc, sceneSpp, cache, &spFitted, tracingProxies, error, 1, true, &progress);
    if (ref.empty() || refProxies.empty() || refFitted.empty())
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      return progress.Interrupted() ? InterruptedExitCode : 1;
    }
    std::vector<std::size_t> planes;
    for (std::size_t k = 0; k < sd.Objects.size(); ++k)
    {
      if (sd.Objects[k].Type == SceneObject::Kind::Plane)
      {
        planes.push_back(k);
      }
    }
    vtkSmartPointer<vtkPGIOccluder> meshes = SceneOccluder(rc);
    if (!meshes->Prepare(error))
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      return 1;
    }
    // Unshadowed, shadowed, both traced; then shadowed and traced with the
    // bright lights taken out (proxies' cones, rays against the meshes); last
    // the rays with the planes' light sampled at one point per receiver (the
    // GPU's way, and the filter's before the planes' light maps); then the
    // rays with the light maps and the radii fitted for occlusion (the CLI's
    // default before), and the same with order-6 shadows and an order-4
    // bounce (its default now).
    for (int variant = 0; variant < 9; ++variant)
    {
      const bool fitted = variant >= 7;
      const bool order6 = variant == 8;
      const int mode = variant % 2 || variant >= 4 ? vtkPGIGISettings::INDIRECT_MODE_SHADOWED
                                                   : vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED;
      const bool traced = variant >= 2;
      const int bright = variant >= 6 ? 2 : (variant >= 4 ? variant - 3 : 0);
      const bool onePoint = variant == 6;
      std::vector<vtkSmartPointer<vtkPolyData>> shaded;
      vtkIdType count = 0;
      double best = 1e300;
      for (int repeat = 0; repeat < repeats; ++repeat)
      {
        const auto t0 = Clock::now();
        // One filter shades every object (one bake), as proxygi render does.
        vtkNew<vtkPGIGlobalIllumination> gi;
        ConfigureGlobalIllumination(gi, sd, ld, fitted ? spFitted : sp);
        gi->GetSettings()->SetIndirectMode(mode);
        gi->GetSettings()->SetBrightLights(bright > 0);
        gi->GetSettings()->SetPlaneBounceDirections(onePoint ? 0 : 64);
        gi->GetSettings()->SetOrder(order6 ? 6 : 4);
        gi->GetSettings()->SetIndirectOrder(order6 ? 4 : 0);
        gi->SetOccluder(bright == 2 ? meshes.Get() : nullptr);
        shaded = ShadeEach(gi, order6 ? rcTraced6 : (traced ? rcTraced : rc));
        best = std::min(best, Seconds(t0));
      }
      for (const auto& r : shaded)
      {
        count += r->GetNumberOfPoints();
      }
      AddIndirectSum(shaded);
      char line[1024];
      std::snprintf(line, sizeof(line),
        "| %s | %s | %lld | %.3f | %.1f | %.1f%% | %.1f%% | %.1f%% | %.1f%% | %.1f%% | %.1f%% |\n",
        sd.Name.c_str(),
        order6          ? "proxygi render: fitted radii, order-6 shadows, order-4 bounce"
          : fitted      ? "shadowed, traced, bright rays, radii fitted for occlusion"
          : onePoint    ? "shadowed, traced, bright rays, planes' light at one point"
          : bright == 2 ? "shadowed, traced, bright lights (rays)"
          : bright == 1 ? "shadowed, traced, bright lights (proxies)"
          : mode == vtkPGIGISettings::INDIRECT_MODE_SHADOWED
          ? (traced ? "shadowed, self-visibility traced" : "shadowed")
          : (traced ? "unshadowed, self-visibility traced" : "unshadowed"),
        static_cast<long long>(count), best, tracing,
        100 * RelativeRMS(ref, "RadianceStdErr", "Radiance"),
        100 * RelativeRMSE(shaded, "DirectShadowed", ref, "DirectShadowed"),
        100 * RelativeRMSE(shaded, "IndirectAny", ref, "IndirectOneBounce"),
        100 * RelativeRMSE(shaded, "Radiance", ref, "Radiance"),
        100 * RelativeRMSE(shaded, "Radiance", ref, "Radiance", planes),
        100 *
          RelativeRMSE(shaded, "Radiance", fitted ? refFitted : refProxies, "Radiance", planes));
      md << line;
      std::printf("%s", line);
    }
  }

  // Plot: error against time, one series per knob (log-log).
  std::vector<std::string> knobs;
  for (const Row& r : rows)
  {
    if (std::find(knobs.begin(), knobs.end(), r.Knob) == knobs.end())
    {
      knobs.push_back(r.Knob);
    }
  }
  std::vector<pgibench::Series> series;
  for (const std::string& knob : knobs)
  {
    pgibench::Series s;
    s.Name = knob;
    s.Line = knob == "Embree reference";
    for (const Row& r : rows)
    {
      if (r.Knob == knob || (r.Knob == "baseline" && knob != "Embree reference"))
      {
        s.X.push_back(r.Seconds);
        s.Y.push_back(100 * r.ErrorTotal);
      }
    }
    series.push_back(s);
  }
  pgibench::WritePlot(out + ".png",
    { "ProxyGI per-vertex GI: accuracy against time (default scene)", "time (s)",
      "relative RMSE of radiance (%)" },
    series);
  std::printf("wrote %s.md, %s.csv, %s.png\n", out.c_str(), out.c_str(), out.c_str());
  return 0;
}
