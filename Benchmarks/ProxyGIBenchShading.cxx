// Per-receiver soft-shadow cost: receivers x blockers per second at SH order
// 3-6 (log accumulation with the self-shadow rules, then HYB), next to the
// machine's measured single-core float multiply-add peak, so the kernel's
// efficiency can be read off one run.
#include "pgiSoftShadows.h"

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
} // namespace

int main(int argc, char** argv)
{
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
