// Shading tables: lookups against direct computation on and between grid
// points, float against double, rotation of tabulated logs against the log
// of the rotated visibility, and the OL curves.
#include "pgiSHCapSet.h"
#include "pgiSHExp.h"
#include "pgiSHLog.h"
#include "pgiSHTables.h"
#include "pgiSHZonal.h"
#include "pgiTesting.h"

#include <cmath>
#include <vector>

using namespace proxygi::sh;

namespace
{
void CapLogDirect(int order, double theta, double* scaledZh)
{
  double zh[MaxOrder], g[MaxCoefficients], f[MaxCoefficients];
  CapVisibilityZonal(order, theta, zh);
  Fill(g, NumCoefficients(order), 0.0);
  for (int l = 0; l < order; ++l)
  {
    g[Index(l, 0)] = zh[l];
  }
  Log(order, g, f);
  for (int l = 0; l < order; ++l)
  {
    scaledZh[l] = f[Index(l, 0)] * ZonalScale(l);
  }
}
} // namespace

int TestSHTables(int, char*[])
{
  for (int order = 1; order <= MaxOrder; ++order)
  {
    const CapTables& tables = CapTables::Get(order);
    PGI_CHECK(tables.GetResolution() == 256);
    PGI_CHECK(AllFinite(tables.GetLogTable().data(), 256 * order));
    PGI_CHECK(AllFinite(tables.GetVisibilityTable().data(), 256 * order));
    // The optimal-linear curves, order 1 included (one fitted sample there:
    // AddressSanitizer found the fit reading past it).
    PGI_CHECK(AllFinite(tables.GetOptimalLinearA().data(), 256));
    PGI_CHECK(AllFinite(tables.GetOptimalLinearB().data(), 256));
    double olA = -1.0, olB = -1.0;
    tables.OptimalLinear(0.5 * tables.GetOptimalLinearMaxNorm(), olA, olB);
    PGI_CHECK(std::isfinite(olA) && std::isfinite(olB));
    double worstGrid = 0.0, worstMid = 0.0, worstFloat = 0.0, worstVisMid = 0.0;
    for (int i = 0; i < 255; i += 5)
    {
      for (double frac : { 0.0, 0.5 })
      {
        const double theta = CapTables::MaxAngle * (i + frac) / 255.0;
        double looked[MaxOrder], direct[MaxOrder], vis[MaxOrder], visDirect[MaxOrder];
        float lookedF[MaxOrder];
        tables.CapLog(theta, looked);
        tables.CapLog(float(theta), lookedF);
        CapLogDirect(order, theta, direct);
        tables.CapVisibility(theta, vis);
        CapVisibilityZonal(order, theta, visDirect);
        double scale = 1.0; // relative to the vector's size (logs reach -20)
        for (int l = 0; l < order; ++l)
        {
          scale = std::max(scale, std::fabs(direct[l]));
        }
        for (int l = 0; l < order; ++l)
        {
          const double d = std::fabs(looked[l] - direct[l]) / scale;
          (frac == 0.0 ? worstGrid : worstMid) = std::max(frac == 0.0 ? worstGrid : worstMid, d);
          worstFloat = std::max(worstFloat, std::fabs(double(lookedF[l]) - looked[l]) / scale);
          worstVisMid = std::max(worstVisMid, std::fabs(vis[l] - visDirect[l] * ZonalScale(l)));
        }
      }
    }
    std::printf("order %d: relative log table error on grid %.2g, between grid points %.2g "
                "(visibility %.2g), float %.2g\n",
      order, worstGrid, worstMid, worstVisMid, worstFloat);
    PGI_BELOW(worstGrid, 1e-10);
    // The clipped log has a kink where an eigenvalue meets the clip (near 49
    // degrees at order 4); linear interpolation is worst there.
    PGI_BELOW(worstMid, 1e-2);
    PGI_BELOW(worstVisMid, 1e-4);
    PGI_BELOW(worstFloat, 1e-5);

    // OL curves start at the two-term series and stay finite and positive.
    double a, b;
    tables.OptimalLinear(0.0, a, b);
    PGI_NEAR(a, 1.0, 1e-12);
    PGI_NEAR(b, 1.0, 1e-12);
    for (double x = 0.0; x < 2.0 * tables.GetOptimalLinearMaxNorm(); x += 0.05)
    {
      tables.OptimalLinear(x, a, b);
      PGI_CHECK(std::isfinite(a) && std::isfinite(b) && a > 0.0 && b > 0.0);
    }
  }

  // Rotating a tabulated log equals the log of the rotated visibility: the
  // eigen-inversion log commutes with rotation.
  {
    const int order = 5;
    const Cap cap = { { 0.48, -0.6, 0.64 }, 0.7 };
    double viaTable[25], g[25], f[25], zh[5];
    AccumulateLog(CapTables::Get(order), { cap }, viaTable);
    CapVisibilityZonal(order, cap.HalfAngle, zh);
    RotateZonal(order, zh, cap.Direction[0], cap.Direction[1], cap.Direction[2], g);
    Log(order, g, f);
    double worst = 0.0;
    for (int i = 0; i < 25; ++i)
    {
      worst = std::max(worst, std::fabs(viaTable[i] - f[i]));
    }
    std::printf("tabulated-and-rotated log vs log of rotated visibility: %.2g\n", worst);
    PGI_BELOW(worst, 5e-3);
  }

  // OL reproduces the exp of a single cap log where the fit is exact (eq. 24).
  {
    const int order = 4;
    double f[16], g[16], exact[16], zh[4];
    const double theta = 0.35;
    AccumulateLog(CapTables::Get(order), { Cap{ { 0.0, 0.0, 1.0 }, theta } }, f);
    ExpOptions ol;
    ol.Method = ExpMethod::OL;
    Exp(order, f, g, ol);
    CapVisibilityZonal(order, theta, zh);
    Fill(exact, 16, 0.0);
    for (int l = 0; l < order; ++l)
    {
      exact[Index(l, 0)] = zh[l];
    }
    PGI_BELOW(RmsDifference(order, g, exact), 5e-3);
  }

  // A finer table interpolates better (the resolution knob does something).
  {
    const CapTables coarse(4, 32), fine(4, 256);
    double worstCoarse = 0.0, worstFine = 0.0;
    for (int k = 1; k < 200; ++k)
    {
      const double theta = CapTables::MaxAngle * (k + 0.37) / 200.0;
      double c[4], f[4], d[4];
      coarse.CapLog(theta, c);
      fine.CapLog(theta, f);
      CapLogDirect(4, theta, d);
      for (int l = 0; l < 4; ++l)
      {
        worstCoarse = std::max(worstCoarse, std::fabs(c[l] - d[l]));
        worstFine = std::max(worstFine, std::fabs(f[l] - d[l]));
      }
    }
    std::printf("interpolation error: 32 entries %.2g, 256 entries %.2g\n", worstCoarse, worstFine);
    PGI_CHECK(worstFine < 0.2 * worstCoarse);
  }
  return pgitest::Result();
}
