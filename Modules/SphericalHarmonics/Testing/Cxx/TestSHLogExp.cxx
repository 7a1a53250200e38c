// SH log and exp: exp(log(g)) = g for cap visibilities over the whole range
// of sphere blockers, and exp of summed cap logs against product-space
// accumulation and the exact visibility for random sets of 1-200 caps.
// Errors are RMS visibility differences over the sphere (visibility units).
#include "pgiSHCapSet.h"
#include "pgiSHExp.h"
#include "pgiSHLog.h"
#include "pgiSHTables.h"
#include "pgiSHZonal.h"
#include "pgiTesting.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace proxygi::sh;

namespace
{
struct Method
{
  std::string Name;
  ExpOptions Options;
};

std::vector<Method> Methods()
{
  std::vector<Method> methods;
  for (int p : { 2, 4, 8 })
  {
    ExpOptions o;
    o.Method = ExpMethod::PS;
    o.Degree = p;
    methods.push_back({ "PS-" + std::to_string(p), o });
  }
  for (int p : { 2, 4 })
  {
    ExpOptions o;
    o.Method = ExpMethod::PSStar;
    o.Degree = p;
    methods.push_back({ "PS*-" + std::to_string(p), o });
  }
  ExpOptions ol;
  ol.Method = ExpMethod::OL;
  methods.push_back({ "OL", ol });
  methods.push_back({ "HYB", ExpOptions() });
  return methods;
}

void CapVector(int order, double theta, double* g)
{
  double zh[MaxOrder];
  CapVisibilityZonal(order, theta, zh);
  Fill(g, NumCoefficients(order), 0.0);
  for (int l = 0; l < order; ++l)
  {
    g[Index(l, 0)] = zh[l];
  }
}
} // namespace

int TestSHLogExp(int, char*[])
{
  const std::vector<Method> methods = Methods();

  // 1. Round trip over theta in [0, 90] degrees.
  for (int order = 3; order <= 6; ++order)
  {
    double worstSmall = 0.0, worstAll = 0.0, worstHybSmall = 0.0, worstHybAll = 0.0;
    for (int deg = 0; deg <= 90; deg += 3)
    {
      const double theta = deg * Pi / 180.0;
      double g[MaxCoefficients], f[MaxCoefficients], e[MaxCoefficients];
      CapVector(order, theta, g);
      PGI_CHECK(Log(order, g, f) == Status::Ok);
      ExpOptions accurate;
      accurate.Method = ExpMethod::PSStar;
      accurate.Degree = 8;
      PGI_CHECK(Exp(order, f, e, accurate) == Status::Ok);
      const double err = RmsDifference(order, e, g);
      Exp(order, f, e);
      const double errHyb = RmsDifference(order, e, g);
      worstAll = std::max(worstAll, err);
      worstHybAll = std::max(worstHybAll, errHyb);
      if (deg <= 30)
      {
        worstSmall = std::max(worstSmall, err);
        worstHybSmall = std::max(worstHybSmall, errHyb);
      }
    }
    std::printf("order %d exp(log(cap)) RMS error: PS*-8 %.5f (theta<=30) %.5f (all); "
                "HYB %.5f / %.5f\n",
      order, worstSmall, worstAll, worstHybSmall, worstHybAll);
    PGI_BELOW(worstSmall, 2e-3);
    PGI_BELOW(worstAll, 0.06);
    PGI_BELOW(worstHybSmall, 5e-3);
    PGI_BELOW(worstHybAll, 0.1);
  }

  // Eigen-inversion beats the naive projected log (SHEXP section 5).
  {
    const int order = 4;
    double g[16], f[16], fn[16], e[16], en[16];
    CapVector(order, 40.0 * Pi / 180.0, g);
    Log(order, g, f);
    LogByProjection(order, g, fn);
    ExpOptions accurate;
    accurate.Method = ExpMethod::PSStar;
    accurate.Degree = 8;
    Exp(order, f, e, accurate);
    Exp(order, fn, en, accurate);
    const double eig = RmsDifference(order, e, g), naive = RmsDifference(order, en, g);
    std::printf(
      "40-degree cap round trip: eigen-inversion %.5f, naive projection %.5f\n", eig, naive);
    PGI_CHECK(eig < 0.5 * naive);
  }

  // 2. Random cap sets: log-space methods against product space and truth.
  struct Set
  {
    int Count;
    double MinAngle, MaxAngle;
  };
  const Set sets[] = { { 1, 0.05, 0.8 }, { 5, 0.05, 0.6 }, { 20, 0.05, 0.4 }, { 50, 0.02, 0.3 },
    { 200, 0.02, 0.2 }, { 200, 0.1, 0.6 } };
  const int order = 4, trials = 4;
  const CapTables& tables = CapTables::Get(order);
  std::printf("order 4, mean RMS visibility error against the exact visibility\n");
  std::printf("%-16s %8s %8s", "set", "|f^|", "product");
  for (const Method& m : methods)
  {
    std::printf(" %8s", m.Name.c_str());
  }
  std::printf("\n");
  for (const Set& set : sets)
  {
    std::vector<double> err(methods.size(), 0.0);
    double productErr = 0.0, norm = 0.0;
    for (int t = 0; t < trials; ++t)
    {
      const std::vector<Cap> caps =
        RandomCaps(1000 * set.Count + t, set.Count, set.MinAngle, set.MaxAngle);
      double exact[16], product[16], f[16], g[16];
      ProjectExactVisibility(order, caps, exact, 160);
      AccumulateProduct(order, caps, product);
      AccumulateLog(tables, caps, f);
      double n = 0.0;
      for (int i = 1; i < 16; ++i)
      {
        n += f[i] * f[i];
      }
      norm += std::sqrt(n) / trials;
      productErr += RmsDifference(order, product, exact) / trials;
      for (std::size_t k = 0; k < methods.size(); ++k)
      {
        const Status s = Exp(order, f, g, methods[k].Options);
        PGI_CHECK(s == Status::Ok);
        PGI_CHECK(AllFinite(g, 16));
        err[k] += RmsDifference(order, g, exact) / trials;
      }
    }
    char label[64];
    std::snprintf(label, sizeof(label), "%d caps %.2f-%.2f", set.Count, set.MinAngle, set.MaxAngle);
    std::printf("%-16s %8.2f %8.4f", label, norm, productErr);
    for (double e : err)
    {
      std::printf(" %8.4f", e);
    }
    std::printf("\n");
    // What the methods must achieve (measured values are well inside).
    const double psStar2 = err[3], ol = err[5], hyb = err[6];
    PGI_BELOW(psStar2, productErr + 0.03);
    PGI_BELOW(hyb, productErr + 0.04);
    PGI_BELOW(ol, productErr + 0.06); // measured excess at most 0.0399 (5 caps)
    // A higher series degree must help, so an ignored Degree fails: PS-4
    // beats PS-2 everywhere (measured 0.0211 vs 0.1197 ... 0.5192 vs 0.9248),
    // PS-8 is never worse than PS-4 (measured; 1e-4 covers the 4-digit
    // print) and clearly better for large logs (measured 0.0006 vs
    // 0.0211 at |f^| 1.40, 0.4632 vs 0.5192 at |f^| 8.65).
    PGI_CHECK(err[1] < 0.8 * err[0]);
    PGI_BELOW(err[2], err[1] + 1e-4);
    if (norm > 1.3)
    {
      PGI_CHECK(err[2] < 0.95 * err[1]);
    }
    // PS*-4 matches PS*-2 (measured equal to 4 digits) and stays near the
    // product (measured excess at most 0.0048).
    PGI_BELOW(err[4], err[3] + 0.005);
    PGI_BELOW(err[4], productErr + 0.01);
    if (norm < 2.0)
    {
      PGI_BELOW(err[2], productErr + 0.01); // measured excess at most 0.0048
    }
    if (norm > 2.0)
    {
      PGI_CHECK(psStar2 < err[0]);      // DC isolation + scaling beat the plain series
      PGI_CHECK(err[4] < 0.1 * err[1]); // measured 0.0022 vs 0.5192
    }
  }

  // LogZonal (block by block) against Log of the full vector: caps over the
  // whole range at every order, through the clip's kinks, and other clips.
  {
    double worst = 0.0;
    for (int o = 1; o <= MaxOrder; ++o)
    {
      for (double clip : { 0.02, 0.0, 0.2 })
      {
        LogOptions options;
        options.RelativeClip = clip;
        for (int i = 0; i <= 200; ++i)
        {
          const double theta = 0.5 * Pi * i / 200;
          double zh[MaxOrder], g[MaxCoefficients], full[MaxCoefficients], zonal[MaxOrder];
          CapVisibilityZonal(o, theta, zh);
          CapVector(o, theta, g);
          PGI_CHECK(Log(o, g, full, options) == Status::Ok);
          PGI_CHECK(LogZonal(o, zh, zonal, options) == Status::Ok);
          for (int l = 0; l < o; ++l)
          {
            worst = std::max(worst, std::fabs(zonal[l] - full[Index(l, 0)]));
            for (int m = -l; m <= l; ++m)
            {
              worst = m != 0 ? std::max(worst, std::fabs(full[Index(l, m)])) : worst;
            }
          }
        }
      }
    }
    std::printf("LogZonal against Log: largest difference %.3g\n", worst);
    PGI_BELOW(worst, 1e-9);
    double zh[MaxOrder] = { 1.0, std::nan("") }, out[MaxOrder];
    PGI_CHECK(LogZonal(2, zh, out, LogOptions()) == Status::NonFiniteInput);
    PGI_CHECK(LogZonal(0, zh, out, LogOptions()) == Status::InvalidOrder);
  }

  // The exact-visibility reference is converged well below those errors.
  {
    const std::vector<Cap> caps = RandomCaps(5, 20, 0.05, 0.5);
    double a[16], b[16];
    ProjectExactVisibility(order, caps, a, 160);
    ProjectExactVisibility(order, caps, b, 640);
    std::printf("reference convergence (160 vs 640 nodes): %.2g\n", RmsDifference(order, a, b));
    PGI_BELOW(RmsDifference(order, a, b), 1e-3);
  }
  return pgitest::Result();
}
