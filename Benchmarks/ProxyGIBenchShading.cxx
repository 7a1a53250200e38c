// Per-receiver soft-shadow cost: receivers x blockers per second at SH order
// 3-6 (log accumulation with the self-shadow rules, then HYB), next to the
// machine's measured single-core float multiply-add peak, so the kernel's
// efficiency can be read off one run. Plan/...: the whole filter with an
// effect the scene does not call for (skipped) against the effect off, and
// against the effect running, to show a skipped effect costs nothing.
// Bake/...: an update that reuses the shared precompute against one that
// rebuilds it.
#include "pgiSoftShadows.h"
#include "vtkPGIGISettings.h"
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILighting.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

using namespace proxygi;

namespace
{
// Independent multiply-adds the compiler vectorises (the build's ISA).
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

void BenchVisibility(benchmark::State& state, int order, int count)
{
  SoftShadowSettings settings;
  settings.Order = order;
  const SoftShadows shadows(settings);
  Blockers blockers;
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int k = 0; k < count; ++k)
  {
    blockers.AddSphere(3 * u(rng), 3 * u(rng), 1.5f + u(rng), 0.2f + 0.1f * u(rng));
  }
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
  state.SetItemsProcessed(state.iterations());
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
} // namespace

int main(int argc, char** argv)
{
  const char* plans[] = { "Plan/shadows only (baseline)", "Plan/bounce on, albedo 0 (skipped)",
    "Plan/bounce on, albedo 0.8 (runs)", "Plan/shadowed bounce on, albedo 0 (skipped)",
    "Plan/shadowed bounce on, albedo 0.8 (runs)", "Plan/local lights on, none (skipped)",
    "Plan/one far tiny blocker (skipped per receiver)", "Plan/no proxies" };
  for (int variant = 0; variant < 8; ++variant)
  {
    benchmark::RegisterBenchmark(plans[variant], BenchPlan, variant)->Unit(benchmark::kMillisecond);
  }
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
  benchmark::RegisterBenchmark("FloatPeak", BenchFloatPeak);
  for (int order = 3; order <= 6; ++order)
  {
    for (int count : { 16, 64, 256 })
    {
      benchmark::RegisterBenchmark(
        ("Visibility/order:" + std::to_string(order) + "/blockers:" + std::to_string(count))
          .c_str(),
        BenchVisibility, order, count);
    }
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
