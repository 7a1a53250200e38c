// Per-receiver soft-shadow cost: receivers x blockers per second at SH order
// 3-6 (log accumulation with the self-shadow rules, then HYB), scalar and
// batched on every instruction set the CPU runs, next to the machine's float
// multiply-add peak measured in the same run (the widest FMA, one core and
// all cores), so the kernel's efficiency reads off one run. Plan/...: the whole filter with an
// effect the scene does not call for (skipped) against the effect off, and
// against the effect running, to show a skipped effect costs nothing.
// Bake/...: an update that reuses the shared precompute against one that
// rebuilds it. BrightLights/...: taking a map's sun out, and a frame of the
// bunny scene under a sun map with it off, shadowed by the proxies' cones,
// and by rays against the meshes (static, and moving: the Embree scene
// rebuilt every update).
#include "pgiBenchPeak.h"
#include "pgiBrightLights.h"
#include "pgiEnvironmentMap.h"
#include "pgiEnvironmentShading.h"
#include "pgiSHBatch.h"
#include "pgiSoftShadows.h"
#ifdef PROXYGI_BENCH_SCENES
#include "pgiScene.h"
#include "pgiSceneSetup.h"
#endif
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILighting.h"
#include "vtkPGIOccluder.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <thread>
#include <vector>

using namespace proxygi;

namespace
{
// Flops per receiver-blocker pair the report counts (basis, rotation, sum,
// rules, asin), for the GFLOP/s counters.
constexpr double FlopsPerPair = 110.0;

// One core's peak, measured once per process (the kernels' counters use it).
double OneCorePeak()
{
  static const double peak = []()
  {
    float sink;
    proxygi::bench::FmaPeak(1 << 22, &sink); // warm up the clock
    const auto start = std::chrono::steady_clock::now();
    const double flops = proxygi::bench::FmaPeak(1 << 26, &sink);
    return flops / std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }();
  return peak;
}

void BenchWidestPeak(benchmark::State& state, int threads)
{
  double flops = 0.0;
  for (auto _ : state)
  {
    const long iterations = 1 << 24;
    std::vector<std::thread> pool;
    pool.reserve(threads);
    std::vector<float> sink(threads);
    for (int t = 0; t < threads; ++t)
    {
      pool.emplace_back([&, t]() { proxygi::bench::FmaPeak(iterations, &sink[t]); });
    }
    for (std::thread& t : pool)
    {
      t.join();
    }
    benchmark::DoNotOptimize(sink.data());
    flops += threads * 2.0 * 12.0 * proxygi::bench::FmaPeakLanes() * iterations;
  }
  state.counters["GFLOPS"] = benchmark::Counter(flops / 1e9, benchmark::Counter::kIsRate);
  state.counters["lanes"] = proxygi::bench::FmaPeakLanes();
  state.counters["threads"] = threads;
}

// Independent multiply-adds the compiler vectorises for the build's ISA
// (baseline x86-64: SSE2, no FMA): what the scalar kernels can reach.
void BenchFloatPeak(benchmark::State& state)
{
  constexpr int Lanes = 64;
  alignas(64) float a[Lanes], b[Lanes], c[Lanes];
  for (int i = 0; i < Lanes; ++i)
  {
    a[i] = 1.0f + 1e-7f * i;
    b[i] = 0.999999f;
    c[i] = 1e-7f;
  }
  const int inner = 1000;
  for (auto _ : state)
  {
    for (int k = 0; k < inner; ++k)
    {
      for (int i = 0; i < Lanes; ++i)
      {
        a[i] = a[i] * b[i] + c[i];
      }
    }
    benchmark::DoNotOptimize(a);
  }
  // 2 flops per multiply-add.
  state.counters["GFLOPS"] =
    benchmark::Counter(2.0 * Lanes * inner * state.iterations() / 1e9, benchmark::Counter::kIsRate);
}

// `count` random spheres above the receivers' plane z = 0.
Blockers RandomBlockers(int count, std::mt19937& rng)
{
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Blockers blockers;
  for (int k = 0; k < count; ++k)
  {
    blockers.AddSphere(3 * u(rng), 3 * u(rng), 1.5f + u(rng), 0.2f + 0.1f * u(rng));
  }
  return blockers;
}

void BenchVisibility(benchmark::State& state, int order, int count)
{
  SoftShadowSettings settings;
  settings.Order = order;
  const SoftShadows shadows(settings);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const Blockers blockers = RandomBlockers(count, rng);
  std::vector<float> receivers(3 * 256);
  for (float& v : receivers)
  {
    v = u(rng);
  }
  const float up[3] = { 0, 0, 1 };
  float g[sh::MaxCoefficients];
  std::size_t r = 0;
  for (auto _ : state)
  {
    float p[3] = { receivers[3 * r], receivers[3 * r + 1], 0.0f };
    sh::Status status;
    shadows.Visibility(p, up, blockers, g, status);
    benchmark::DoNotOptimize(g);
    r = (r + 1) % 256;
  }
  state.counters["receivers_x_blockers"] =
    benchmark::Counter(double(count) * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["GFLOPS"] = benchmark::Counter(
    FlopsPerPair * count * state.iterations() / 1e9, benchmark::Counter::kIsRate);
  state.SetItemsProcessed(state.iterations());
}

// The same receivers and blockers through VisibilityBatch on one target.
// neighbours: each batch of 16 receivers a 4 x 4 patch 0.02 apart around a
// random point, as the filter batches them (its receivers grouped by their
// hierarchy cluster); otherwise every receiver anywhere in the square.
void BenchVisibilityBatch(
  benchmark::State& state, int order, int count, const std::string& target, bool neighbours)
{
  if (!proxygi::sh::SetBatchTarget(target))
  {
    state.SkipWithError("target not available");
    return;
  }
  SoftShadowSettings settings;
  settings.Order = order;
  const SoftShadows shadows(settings);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const Blockers blockers = RandomBlockers(count, rng);
  constexpr int Receivers = 256;
  std::vector<float> p(3 * Receivers), n(3 * Receivers);
  float centre[2] = { 0.0f, 0.0f };
  for (int r = 0; r < Receivers; ++r)
  {
    const int k = r % sh::BatchWidth;
    if (neighbours && k == 0)
    {
      centre[0] = u(rng);
      centre[1] = u(rng);
    }
    const int column = k % 4, row = k / 4; // in the 4 x 4 patch
    p[3 * r] = neighbours ? centre[0] + 0.02f * static_cast<float>(column) : u(rng);
    p[3 * r + 1] = neighbours ? centre[1] + 0.02f * static_cast<float>(row) : u(rng);
    p[3 * r + 2] = 0.0f;
    n[3 * r] = n[3 * r + 1] = 0.0f;
    n[3 * r + 2] = 1.0f;
  }
  std::vector<float> g(Receivers * order * order);
  std::vector<sh::Status> status(Receivers);
  std::vector<int> used(Receivers);
  for (auto _ : state)
  {
    shadows.VisibilityBatch(
      Receivers, p.data(), n.data(), blockers, g.data(), status.data(), used.data());
    benchmark::DoNotOptimize(g.data());
  }
  proxygi::sh::SetBatchTarget("");
  const double pairs = double(count) * Receivers * state.iterations();
  state.counters["receivers_x_blockers"] = benchmark::Counter(pairs, benchmark::Counter::kIsRate);
  state.counters["GFLOPS"] =
    benchmark::Counter(FlopsPerPair * pairs / 1e9, benchmark::Counter::kIsRate);
  state.counters["peak_GFLOPS"] = OneCorePeak() / 1e9;
  state.SetItemsProcessed(state.iterations() * Receivers);
}
// A grid of (n + 1)^2 receivers on z = 0 facing up, quads as polygons.
vtkSmartPointer<vtkPolyData> Grid(int n)
{
  auto grid = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  vtkNew<vtkCellArray> quads;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      points->InsertNextPoint(-3.0 + 6.0 * i / n, -3.0 + 6.0 * j / n, 0.0);
      normals->InsertNextTuple3(0, 0, 1);
      if (i < n && j < n)
      {
        const vtkIdType a = j * (n + 1) + i, quad[4] = { a, a + 1, a + n + 2, a + n + 1 };
        quads->InsertNextCell(4, quad);
      }
    }
  }
  grid->SetPoints(points);
  grid->SetPolys(quads);
  grid->GetPointData()->SetNormals(normals);
  return grid;
}

// Proxies: `count` spheres over the grid (or one far, tiny one), albedo a.
vtkSmartPointer<vtkPolyData> Proxies(int count, double albedo, bool farTiny)
{
  auto proxies = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> radius, colour;
  radius->SetName("Radius");
  colour->SetName("Albedo");
  colour->SetNumberOfComponents(3);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < count; ++k)
  {
    points->InsertNextPoint(
      farTiny ? 0.0 : 2 * u(rng), farTiny ? 0.0 : 2 * u(rng), farTiny ? 1e4 : 1.0 + 0.5 * u(rng));
    radius->InsertNextValue(farTiny ? 1.0 : 0.4 + 0.2 * u(rng));
    colour->InsertNextTuple3(albedo, albedo, albedo);
  }
  proxies->SetPoints(points);
  proxies->GetPointData()->AddArray(radius);
  proxies->GetPointData()->AddArray(colour);
  return proxies;
}

// The filter over 65^2 receivers, 8 proxies, a ground, one effect varied.
void BenchPlan(benchmark::State& state, int variant)
{
  vtkSmartPointer<vtkPolyData> grid = Grid(64);
  vtkNew<vtkPGILighting> lighting;
  vtkNew<vtkPGIGlobalIllumination> gi;
  gi->SetInputData(grid);
  const bool dark = variant == 1 || variant == 3;
  gi->SetProxiesData(Proxies(variant == 6 ? 1 : 8, dark ? 0.0 : 0.8, variant == 6));
  gi->SetLighting(lighting);
  gi->GetSettings()->SetIndirect(variant >= 1 && variant <= 4);
  gi->GetSettings()->SetIndirectMode(variant == 3 || variant == 4
      ? vtkPGIGISettings::INDIRECT_MODE_SHADOWED
      : vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED);
  gi->GetSettings()->SetLocalLights(variant == 5);
  if (variant == 7)
  {
    gi->SetProxiesData(nullptr);
  }
  for (auto _ : state)
  {
    gi->Modified();
    gi->Update();
  }
  state.SetItemsProcessed(state.iterations() * grid->GetNumberOfPoints());
}
// The filter re-executed on the shadowed bounce over 65^2 receivers and
// `count` proxies: after a receiver change (the bake is reused) and after a
// proxy change (the bake rebuilds: blockers, light, spherical lights' first
// pass), so the precompute's share of an update reads off one run.
void BenchBake(benchmark::State& state, int count, bool proxiesChange)
{
  vtkSmartPointer<vtkPolyData> grid = Grid(64);
  vtkSmartPointer<vtkPolyData> proxies = Proxies(count, 0.8, false);
  vtkNew<vtkPGILighting> lighting;
  vtkNew<vtkPGIGlobalIllumination> gi;
  gi->SetInputData(grid);
  gi->SetProxiesData(proxies);
  gi->SetLighting(lighting);
  gi->GetSettings()->SetIndirectModeToShadowed();
  gi->Update();
  const int builds = gi->GetBake()->GetNumberOfBuilds();
  for (auto _ : state)
  {
    (proxiesChange ? static_cast<vtkObject*>(proxies) : static_cast<vtkObject*>(grid))->Modified();
    gi->Update();
  }
  state.counters["BakeBuilds"] =
    static_cast<double>(gi->GetBake()->GetNumberOfBuilds() - builds) / state.iterations();
  state.SetItemsProcessed(state.iterations() * grid->GetNumberOfPoints());
}
#ifdef PROXYGI_BENCH_SCENES
// The scene and its 64-sphere proxies (cached); false (the benchmark
// skipped with the reason) when either fails.
bool LoadWithProxies(benchmark::State& state, const SceneDescription& scene, LoadedScene& loaded,
  SceneProxies& proxies)
{
  std::string error;
  if (!BuildScene(scene, loaded, error) ||
    !BuildSceneProxies(scene, loaded, 64, PROXYGI_BENCH_CACHE, proxies, error))
  {
    state.SkipWithError(error.c_str());
    return false;
  }
  return true;
}

// Moves every proxy by `step` along x, and the next call back.
void NudgeProxies(vtkPolyData* spheres, double& step)
{
  vtkPoints* centres = spheres->GetPoints();
  for (vtkIdType i = 0; i < centres->GetNumberOfPoints(); ++i)
  {
    double c[3];
    centres->GetPoint(i, c);
    c[0] += step;
    centres->SetPoint(i, c);
  }
  step = -step;
  centres->Modified();
  spheres->Modified();
}

// The update: the default scene's bunny proxies (64 asked, with the
// hierarchy) over a 128 x 128 ground grid (16,384 receivers), order 4, HYB,
// shadows only, the ground plane carried by the light; every update moves
// the proxies by a small step (the precompute rebuilds, the receivers'
// clusters stand), on all cores.
void BenchBunnyOverGround(benchmark::State& state, double hierarchy)
{
  const SceneDescription scene = DefaultScene();
  LoadedScene loaded;
  SceneProxies proxies;
  if (!LoadWithProxies(state, scene, loaded, proxies))
  {
    return;
  }
  const auto receivers = SceneReceivers(loaded);
  double bounds[6];
  receivers.back()->GetBounds(bounds); // the ground
  vtkSmartPointer<vtkPolyData> ground = Grid(127);
  vtkPoints* points = ground->GetPoints();
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double x[3];
    points->GetPoint(i, x);
    points->SetPoint(i, bounds[0] + (x[0] + 3.0) / 6.0 * (bounds[1] - bounds[0]),
      bounds[2] + (x[1] + 3.0) / 6.0 * (bounds[3] - bounds[2]), bounds[4]);
  }
  vtkNew<vtkPGIGlobalIllumination> gi;
  gi->SetInputData(ground);
  ConfigureGlobalIllumination(gi, scene, loaded, proxies);
  vtkPGIGISettings* settings = gi->GetSettings();
  settings->SetOrder(4);
  settings->SetExpMethod(vtkPGIGISettings::EXP_HYB);
  settings->SetIndirect(false);
  settings->SetLocalLights(false);
  // The SH kernels alone, as section 15 of the report measures them (the
  // forest's sun taken out costs its own pass: BrightLights/...).
  settings->SetBrightLights(false);
  settings->SetHierarchyAngle(hierarchy);
  gi->Update();
  double step = 1e-4;
  for (auto _ : state)
  {
    NudgeProxies(proxies.Spheres, step);
    gi->Update();
  }
  state.counters["updates_per_second"] =
    benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["receivers"] = static_cast<double>(ground->GetNumberOfPoints());
  state.counters["leaves"] = static_cast<double>(proxies.Leaves);
  state.counters["threads"] = vtkSMPTools::GetEstimatedNumberOfThreads();
  state.counters["bake_builds"] = gi->GetBake()->GetNumberOfBuilds();
  // The last update's per-stage profile, for the report.
  if (auto* plan =
        vtkStringArray::SafeDownCast(gi->GetOutput()->GetFieldData()->GetAbstractArray("Plan")))
  {
    for (vtkIdType i = 0; i < plan->GetNumberOfValues(); ++i)
    {
      if (plan->GetValue(i).rfind("stages", 0) == 0)
      {
        std::fprintf(stderr, "%s\n", plan->GetValue(i).c_str());
      }
    }
  }
}

// A frame of the bunny scene under the sunrise map with every effect the CLI
// runs (shadowed bounce, cuts at 25 degrees, self-visibility off here):
// each update moves the proxies by a small step; variant 0 keeps the sun in
// the SH, 1 shadows it by the proxies' cones, 2 by rays against the meshes,
// 3 the same with the meshes marked changed (the Embree scene rebuilt).
void BenchBrightUpdate(benchmark::State& state, int variant, int planeDirections)
{
  SceneDescription scene = DefaultScene();
  scene.EnvironmentMap = "environments/sunrise.exr";
  scene.Name = "default scene, sunrise map";
  LoadedScene loaded;
  SceneProxies proxies;
  if (!LoadWithProxies(state, scene, loaded, proxies))
  {
    return;
  }
  const auto receivers = SceneReceivers(loaded);
  vtkSmartPointer<vtkPGIOccluder> occluder = variant >= 2 ? SceneOccluder(receivers) : nullptr;
  std::vector<vtkSmartPointer<vtkPGIGlobalIllumination>> filters;
  for (const auto& r : receivers)
  {
    auto gi = vtkSmartPointer<vtkPGIGlobalIllumination>::New();
    gi->SetInputData(r);
    ConfigureGlobalIllumination(gi, scene, loaded, proxies);
    gi->GetSettings()->SetIndirectMode(vtkPGIGISettings::INDIRECT_MODE_SHADOWED);
    gi->GetSettings()->SetHierarchyAngle(25.0);
    gi->GetSettings()->SetBrightLights(variant > 0);
    gi->GetSettings()->SetPlaneBounceDirections(planeDirections);
    gi->SetOccluder(occluder);
    gi->Update();
    filters.push_back(gi);
  }
  double step = 1e-4;
  for (auto _ : state)
  {
    NudgeProxies(proxies.Spheres, step);
    if (variant == 3)
    {
      receivers.front()->Modified();
    }
    for (auto& gi : filters)
    {
      gi->Update();
    }
  }
  state.counters["receivers"] = static_cast<double>(
    receivers.front()->GetNumberOfPoints() + receivers.back()->GetNumberOfPoints());
}

// A first update of a scene as `proxygi render --mode vertex` runs it:
// fitted proxies, the meshes' own visibility traced (256 rays, cached),
// the shadowed bounce, cuts at 25 degrees, the sun taken out and shadowed
// by rays. `scene` 0: the default scene; 1: cow, dino and armadillo on a
// plane under the forest. One filter per object, each building its own
// bake, or one filter shading the objects in turn (one bake); the bounce
// at `indirectOrder` (0: the shading order).
void BenchFirstUpdate(
  benchmark::State& state, int which, int order, int indirectOrder, bool oneFilter)
{
  SceneDescription scene = DefaultScene();
  LoadedScene loaded;
  SceneProxies proxies;
  std::string error;
  double seconds = 0.0;
  std::vector<vtkSmartPointer<vtkPolyData>> receivers;
  const bool ok = (which == 0 || LoadScene(PROXYGI_BENCH_OBJECTS_SCENE, scene, error)) &&
    BuildScene(scene, loaded, error) &&
    BuildSceneProxies(
      scene, loaded, 64, PROXYGI_BENCH_CACHE, proxies, error, nullptr, ProxyFit::Occlusion) &&
    ((receivers = SceneReceivers(loaded)),
      AddSelfVisibility(scene, receivers, order, 256, PROXYGI_BENCH_CACHE, seconds, error));
  if (!ok)
  {
    state.SkipWithError(error.c_str());
    return;
  }
  vtkSmartPointer<vtkPGIOccluder> occluder = SceneOccluder(receivers);
  auto configure = [&](vtkPGIGlobalIllumination* gi)
  {
    ConfigureGlobalIllumination(gi, scene, loaded, proxies);
    gi->GetSettings()->SetOrder(order);
    gi->GetSettings()->SetIndirectOrder(indirectOrder);
    gi->GetSettings()->SetIndirectModeToShadowed();
    gi->GetSettings()->SetHierarchyAngle(25.0);
    gi->SetOccluder(occluder);
  };
  for (auto _ : state)
  {
    if (oneFilter)
    {
      vtkNew<vtkPGIGlobalIllumination> gi;
      configure(gi);
      for (const auto& r : receivers)
      {
        gi->SetInputData(r);
        gi->Update();
      }
    }
    else
    {
      for (const auto& r : receivers)
      {
        vtkNew<vtkPGIGlobalIllumination> gi;
        configure(gi);
        gi->SetInputData(r);
        gi->Update();
      }
    }
  }
  vtkIdType count = 0;
  for (const auto& r : receivers)
  {
    count += r->GetNumberOfPoints();
  }
  state.counters["receivers"] = static_cast<double>(count);
}
#endif

// The environment's L*H(N) table (the Table shading path), built once per
// light (every row; Shade fills only the rows it reads): a uniform sky's
// order-n SH, the default 64 x 128 grid.
void BenchShadingTable(benchmark::State& state, int order)
{
  std::vector<double> light(3 * static_cast<std::size_t>(order) * order, 0.0);
  for (std::size_t i = 0; i < light.size(); ++i)
  {
    light[i] = 1.0 / (1.0 + static_cast<double>(i % (order * order)));
  }
  const int n2 = order * order;
  for (auto _ : state)
  {
    EnvironmentShading table(order, &light[0], &light[n2], &light[2 * n2]);
    table.BuildTable();
    benchmark::DoNotOptimize(&table);
  }
}

// Taking the sun out of the sunrise map (1024 x 512).
void BenchExtractBrightLights(benchmark::State& state)
{
  proxygi::EnvironmentMap map;
  vtkNew<vtkPGILighting> lighting;
  lighting->SetEnvironmentFileName(PROXYGI_BENCH_DATA "/environments/sunrise.exr");
  const proxygi::EnvironmentMap* loaded = nullptr;
  std::string error;
  if (!lighting->GetEnvironment(loaded, error))
  {
    state.SkipWithError(error.c_str());
    return;
  }
  proxygi::BrightLightResult result;
  for (auto _ : state)
  {
    proxygi::ExtractBrightLights(*loaded, proxygi::BrightLightOptions(), result);
    benchmark::DoNotOptimize(result.Lights.data());
  }
  state.counters["lights"] = static_cast<double>(result.Lights.size());
}
} // namespace

int main(int argc, char** argv)
{
  vtkSMPTools::SetBackend("STDThread");
  const char* plans[] = { "Plan/shadows only (baseline)", "Plan/bounce on, albedo 0 (skipped)",
    "Plan/bounce on, albedo 0.8 (runs)", "Plan/shadowed bounce on, albedo 0 (skipped)",
    "Plan/shadowed bounce on, albedo 0.8 (runs)", "Plan/local lights on, none (skipped)",
    "Plan/one far tiny blocker (skipped per receiver)", "Plan/no proxies" };
  for (int variant = 0; variant < 8; ++variant)
  {
    benchmark::RegisterBenchmark(plans[variant], BenchPlan, variant)->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("BrightLights/extract, sunrise 1024x512", BenchExtractBrightLights)
    ->Unit(benchmark::kMillisecond);
  for (int order = 4; order <= 8; order += 2)
  {
    benchmark::RegisterBenchmark(
      ("ShadingTable/L*H(N), order:" + std::to_string(order)).c_str(), BenchShadingTable, order)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  }
#ifdef PROXYGI_BENCH_SCENES
  // (order, bounce order, one filter): before and after sharing the bake,
  // and the bounce at order 4 under order-6 shadows.
  const int firstUpdates[5][3] = { { 4, 0, 0 }, { 4, 0, 1 }, { 6, 0, 0 }, { 6, 0, 1 },
    { 6, 4, 1 } };
  for (int which : { 0, 1 })
  {
    for (const auto& f : firstUpdates)
    {
      const std::string name = std::string("FirstUpdate/") +
        (which == 0 ? "default scene" : "cow, dino, armadillo, forest") +
        ", order:" + std::to_string(f[0]) +
        (f[1] ? ", bounce order:" + std::to_string(f[1]) : std::string()) +
        (f[2] ? ", one filter" : ", a filter per object");
      benchmark::RegisterBenchmark(name.c_str(), BenchFirstUpdate, which, f[0], f[1], f[2] == 1)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    }
  }
#endif
#ifdef PROXYGI_BENCH_SCENES
  const char* bright[] = { "BrightLights/frame, sun in the SH",
    "BrightLights/frame, proxies' cones", "BrightLights/frame, rays, meshes static",
    "BrightLights/frame, rays, meshes moving" };
  for (int variant = 0; variant < 4; ++variant)
  {
    benchmark::RegisterBenchmark(bright[variant], BenchBrightUpdate, variant, 64)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  }
  // The ground's bounce: one plane point per receiver against the planes'
  // light map (rebuilt every update, as the proxies move).
  for (int directions : { 0, 16, 64, 256 })
  {
    const std::string name = directions == 0
      ? std::string("PlaneBounce/frame, rays, one plane point")
      : "PlaneBounce/frame, rays, light map, " + std::to_string(directions) + " directions";
    benchmark::RegisterBenchmark(name.c_str(), BenchBrightUpdate, 2, directions)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  }
#endif
  for (int count : { 8, 64 })
  {
    const std::string proxies = "/proxies:" + std::to_string(count);
    benchmark::RegisterBenchmark(
      ("Bake/receivers changed (reused)" + proxies).c_str(), BenchBake, count, false)
      ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(
      ("Bake/proxies changed (rebuilt)" + proxies).c_str(), BenchBake, count, true)
      ->Unit(benchmark::kMillisecond);
  }
#ifdef PROXYGI_BENCH_SCENES
  benchmark::RegisterBenchmark(
    "Update/bunny proxies over a 128x128 ground, shadows only, cuts at 25 degrees",
    BenchBunnyOverGround, 25.0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
  benchmark::RegisterBenchmark(
    "Update/bunny proxies over a 128x128 ground, shadows only, every leaf", BenchBunnyOverGround,
    0.0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
#endif
  benchmark::RegisterBenchmark("FloatPeak/compiler-vectorised, build ISA", BenchFloatPeak);
  benchmark::RegisterBenchmark("FloatPeak/widest FMA, one core", BenchWidestPeak, 1)->UseRealTime();
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  benchmark::RegisterBenchmark("FloatPeak/widest FMA, all cores", BenchWidestPeak, cores)
    ->UseRealTime();
  for (const std::string& target : proxygi::sh::BatchTargets())
  {
    for (int order = 3; order <= 8; ++order)
    {
      for (int count : { 16, 64, 256 })
      {
        if (order != 4 && target != proxygi::sh::BatchTargets()[0])
        {
          continue; // every target at order 4, the best one at every order
        }
        benchmark::RegisterBenchmark(("VisibilityBatch/" + target + "/order:" +
                                       std::to_string(order) + "/blockers:" + std::to_string(count))
                                       .c_str(),
          BenchVisibilityBatch, order, count, target, false);
      }
    }
  }
  // Neighbouring receivers, as the filter batches them: the best target.
  for (int order : { 4, 6 })
  {
    benchmark::RegisterBenchmark(("VisibilityBatch/" + proxygi::sh::BatchTargets()[0] +
                                   "/order:" + std::to_string(order) + "/blockers:256/neighbours")
                                   .c_str(),
      BenchVisibilityBatch, order, 256, proxygi::sh::BatchTargets()[0], true);
  }
  for (int order = 3; order <= 8; ++order)
  {
    for (int count : { 16, 64, 256 })
    {
      benchmark::RegisterBenchmark(
        ("Visibility/scalar/order:" + std::to_string(order) + "/blockers:" + std::to_string(count))
          .c_str(),
        BenchVisibility, order, count);
    }
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
