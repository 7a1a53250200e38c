// SH exponential and blocker accumulation: time per call (Google Benchmark)
// and, as counters measured in the same run, the RMS visibility error of
// each method against the exact visibility of the same cap sets.
//
// Workload per order: 64 random cap sets, 1 to 200 caps (log-uniform), cap
// radii shrinking with the count so the sets range from one large blocker
// to many small overlapping ones. Kernels run in float, as the shading does.
#include "pgiSHCapSet.h"
#include "pgiSHExp.h"
#include "pgiSHLog.h"
#include "pgiSHTables.h"
#include "pgiSHTripleProduct.h"
#include "pgiSHZonal.h"

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

using namespace proxygi::sh;

namespace
{
constexpr int SetCount = 64;

struct Workload
{
  std::vector<std::vector<Cap>> Sets;
  std::vector<std::array<float, MaxCoefficients>> Logs;
  std::vector<std::array<double, MaxCoefficients>> Exact;
  double ProductError = 0.0; // product-space accumulation vs exact
  double MeanNorm = 0.0;     // mean |f^| of the logs
};

const Workload& GetWorkload(int order)
{
  static std::map<int, std::unique_ptr<Workload>> cache;
  auto& w = cache[order];
  if (w)
  {
    return *w;
  }
  w.reset(new Workload);
  const CapTables& tables = CapTables::Get(order);
  const int n2 = NumCoefficients(order);
  for (int s = 0; s < SetCount; ++s)
  {
    const int count = static_cast<int>(std::lround(std::pow(200.0, s / double(SetCount - 1))));
    const double maxAngle = 0.05 + 1.2 / std::sqrt(double(count));
    w->Sets.push_back(RandomCaps(1234 + s, count, 0.02, maxAngle));
    std::array<float, MaxCoefficients> f{};
    std::array<double, MaxCoefficients> exact{}, product{};
    AccumulateLog(tables, w->Sets.back(), f.data());
    ProjectExactVisibility(order, w->Sets.back(), exact.data(), 128);
    AccumulateProduct(order, w->Sets.back(), product.data());
    w->ProductError += RmsDifference(order, product.data(), exact.data()) / SetCount;
    double norm = 0.0;
    for (int i = 1; i < n2; ++i)
    {
      norm += double(f[i]) * f[i];
    }
    w->MeanNorm += std::sqrt(norm) / SetCount;
    w->Logs.push_back(f);
    w->Exact.push_back(exact);
  }
  return *w;
}

double ExpError(int order, const ExpOptions& options)
{
  const Workload& w = GetWorkload(order);
  double err = 0.0;
  for (int s = 0; s < SetCount; ++s)
  {
    float g[MaxCoefficients];
    Exp(order, w.Logs[s].data(), g, options);
    double gd[MaxCoefficients];
    for (int i = 0; i < NumCoefficients(order); ++i)
    {
      gd[i] = g[i];
    }
    err += RmsDifference(order, gd, w.Exact[s].data()) / SetCount;
  }
  return err;
}

void BenchExp(benchmark::State& state, int order, ExpOptions options)
{
  const Workload& w = GetWorkload(order);
  TripleProduct::Get(order);
  CapTables::Get(order);
  float g[MaxCoefficients];
  std::size_t k = 0;
  for (auto _ : state)
  {
    Exp(order, w.Logs[k].data(), g, options);
    benchmark::DoNotOptimize(g);
    k = (k + 1) % SetCount;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["rms_err"] = ExpError(order, options);
  state.counters["mean_norm"] = w.MeanNorm;
}

// Per-blocker cost of log-space accumulation: table lookup, ZH rotation, sum.
void BenchAccumulateLog(benchmark::State& state, int order)
{
  const CapTables& tables = CapTables::Get(order);
  const std::vector<Cap> caps = RandomCaps(9, 256, 0.02, 0.6);
  const int n2 = NumCoefficients(order);
  float sum[MaxCoefficients], zh[MaxOrder], v[MaxCoefficients];
  for (auto _ : state)
  {
    Fill(sum, n2, 0.0f);
    for (const Cap& c : caps)
    {
      tables.CapLog(static_cast<float>(c.HalfAngle), zh);
      RotateScaledZonal(
        order, zh, float(c.Direction[0]), float(c.Direction[1]), float(c.Direction[2]), v);
      for (int i = 0; i < n2; ++i)
      {
        sum[i] += v[i];
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * caps.size());
}

// Per-blocker cost of product-space accumulation (one SH product per blocker).
void BenchAccumulateProduct(benchmark::State& state, int order)
{
  const CapTables& tables = CapTables::Get(order);
  const TripleProduct& tp = TripleProduct::Get(order);
  const std::vector<Cap> caps = RandomCaps(9, 256, 0.02, 0.6);
  const int n2 = NumCoefficients(order);
  float acc[MaxCoefficients], tmp[MaxCoefficients], zh[MaxOrder], v[MaxCoefficients];
  for (auto _ : state)
  {
    SetConstant(order, 1.0f, acc);
    for (const Cap& c : caps)
    {
      tables.CapVisibility(static_cast<float>(c.HalfAngle), zh);
      RotateScaledZonal(
        order, zh, float(c.Direction[0]), float(c.Direction[1]), float(c.Direction[2]), v);
      tp.Product(acc, v, tmp);
      std::copy(tmp, tmp + n2, acc);
    }
    benchmark::DoNotOptimize(acc);
  }
  state.SetItemsProcessed(state.iterations() * caps.size());
  state.counters["rms_err"] = GetWorkload(order).ProductError;
}

// Eigen-inversion log of a cap (precomputation cost of the tables).
void BenchLog(benchmark::State& state, int order)
{
  const int n2 = NumCoefficients(order);
  std::vector<double> g(n2, 0.0), f(n2);
  double zh[MaxOrder];
  CapVisibilityZonal(order, 0.6, zh);
  for (int l = 0; l < order; ++l)
  {
    g[Index(l, 0)] = zh[l];
  }
  for (auto _ : state)
  {
    Log(order, g.data(), f.data());
    benchmark::DoNotOptimize(f.data());
  }
  state.SetItemsProcessed(state.iterations());
}

struct Variant
{
  std::string Name;
  ExpOptions Options;
};

std::vector<Variant> Variants()
{
  std::vector<Variant> v;
  auto add = [&v](const std::string& name, ExpMethod m, int degree, double limit, bool guard)
  {
    ExpOptions o;
    o.Method = m;
    o.Degree = degree;
    o.HybridMaxNorm = limit;
    o.RangeGuard = guard;
    v.push_back({ name, o });
  };
  add("PS-2", ExpMethod::PS, 2, 0, true);
  add("PS-4", ExpMethod::PS, 4, 0, true);
  add("PS-8", ExpMethod::PS, 8, 0, true);
  add("PS*-2", ExpMethod::PSStar, 2, 0, true);
  add("PS*-4", ExpMethod::PSStar, 4, 0, true);
  add("OL", ExpMethod::OL, 0, 0, true);
  add("HYB", ExpMethod::Hybrid, 0, 0, true);
  add("HYB-noguard", ExpMethod::Hybrid, 0, 0, false);
  add("HYB-limit0.25", ExpMethod::Hybrid, 0, 0.25, true);
  add("HYB-limit1", ExpMethod::Hybrid, 0, 1.0, true);
  add("HYB-limit2", ExpMethod::Hybrid, 0, 2.0, true);
  return v;
}
} // namespace

int main(int argc, char** argv)
{
  for (int order = 3; order <= 6; ++order)
  {
    for (const Variant& v : Variants())
    {
      benchmark::RegisterBenchmark(
        ("Exp/" + v.Name + "/order:" + std::to_string(order)).c_str(), BenchExp, order, v.Options);
    }
    benchmark::RegisterBenchmark(
      ("AccumulateLog/order:" + std::to_string(order)).c_str(), BenchAccumulateLog, order);
    benchmark::RegisterBenchmark(
      ("AccumulateProduct/order:" + std::to_string(order)).c_str(), BenchAccumulateProduct, order);
    benchmark::RegisterBenchmark(("Log/order:" + std::to_string(order)).c_str(), BenchLog, order);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv))
  {
    return 1;
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
