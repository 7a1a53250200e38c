// Hard cases: exp of log vectors with |f^| from 0 to 1e3 (hundreds of
// overlapping caps, total occlusion) stays finite and bounded; log of
// near-zero or negative visibility stays finite; NaN/Inf are reported;
// the exp is continuous where HYB and PS* change their number of squarings.
#include "pgiSHBasis.h"
#include "pgiSHCapSet.h"
#include "pgiSHExp.h"
#include "pgiSHLog.h"
#include "pgiSHTables.h"
#include "pgiTesting.h"

#include <algorithm>
#include <limits>
#include <vector>

using namespace proxygi::sh;

namespace
{
// Range of the reconstruction on a dense set that differs from the guard's.
template <typename T>
void ReconstructedRange(int order, const T* g, double& lo, double& hi)
{
  static const SphereQuadrature rule(48);
  lo = std::numeric_limits<double>::max();
  hi = -lo;
  for (std::size_t q = 0; q < rule.Size(); ++q)
  {
    const double v = Reconstruct(order, g, T(rule.X[q]), T(rule.Y[q]), T(rule.Z[q]));
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
}

double NormNoDC(int order, const double* f)
{
  double s = 0.0;
  for (int i = 1; i < NumCoefficients(order); ++i)
  {
    s += f[i] * f[i];
  }
  return std::sqrt(s);
}
} // namespace

int TestSHHardCases(int, char*[])
{
  // The guard's tolerance; the exact projection of one cap already reaches
  // [-0.40, 1.33], so bounded means [-0.5, 1.5] plus what lies between the
  // guard's sample directions.
  const double eps = 0.5 + 0.05;
  const ExpMethod methods[] = { ExpMethod::PSStar, ExpMethod::OL, ExpMethod::Hybrid };

  for (int order = 3; order <= 6; ++order)
  {
    const CapTables& tables = CapTables::Get(order);
    double worstLo = 0.0, worstHi = 1.0, maxNorm = 0.0;
    double unguardedLo = 0.0, unguardedHi = 1.0;
    int cases = 0;
    for (int count : { 1, 10, 50, 200, 1000 })
    {
      for (int hemisphere = 0; hemisphere < 2; ++hemisphere)
      {
        std::vector<Cap> caps = RandomCaps(17 + count, count, 0.05, 1.5);
        if (hemisphere)
        {
          for (Cap& c : caps)
          {
            c.Direction[2] = std::fabs(c.Direction[2]); // all overlap on one side
          }
        }
        double f[MaxCoefficients], base[MaxCoefficients];
        AccumulateLog(tables, caps, base);
        // Scale the same log so that |f^| sweeps 0 .. about 1e3.
        for (double scale : { 0.0, 1e-3, 0.1, 1.0, 3.0 })
        {
          for (int i = 0; i < NumCoefficients(order); ++i)
          {
            f[i] = scale * base[i];
          }
          maxNorm = std::max(maxNorm, NormNoDC(order, f));
          for (ExpMethod method : methods)
          {
            for (int guard = 0; guard < 2; ++guard)
            {
              ExpOptions o;
              o.Method = method;
              o.RangeGuard = guard != 0;
              double g[MaxCoefficients];
              const Status s = Exp(order, f, g, o);
              PGI_CHECK(s == Status::Ok);
              PGI_CHECK(AllFinite(g, NumCoefficients(order)));
              double lo, hi;
              ReconstructedRange(order, g, lo, hi);
              if (guard)
              {
                worstLo = std::min(worstLo, lo);
                worstHi = std::max(worstHi, hi);
              }
              else if (method == ExpMethod::Hybrid)
              {
                unguardedLo = std::min(unguardedLo, lo);
                unguardedHi = std::max(unguardedHi, hi);
              }
              ++cases;
            }
            // Float kernels: finite on the same input.
            float ff[MaxCoefficients], gf[MaxCoefficients];
            for (int i = 0; i < NumCoefficients(order); ++i)
            {
              ff[i] = static_cast<float>(f[i]);
            }
            ExpOptions o;
            o.Method = method;
            const Status s = Exp(order, ff, gf, o);
            PGI_CHECK(s == Status::Ok && AllFinite(gf, NumCoefficients(order)));
            double lo, hi;
            ReconstructedRange(order, gf, lo, hi);
            PGI_CHECK(lo >= -eps && hi <= 1.0 + eps);
          }
        }
      }
    }
    std::printf("order %d: %d cases, |f^| up to %.0f: guarded range [%.3f, %.3f], HYB unguarded "
                "[%.3f, %.3f]\n",
      order, cases, maxNorm, worstLo, worstHi, unguardedLo, unguardedHi);
    PGI_CHECK(maxNorm > 1e3);
    PGI_BELOW(-worstLo, eps);
    PGI_BELOW(worstHi, 1.0 + eps);
  }

  // Total occlusion: 1000 large caps all round leave (numerically) nothing.
  {
    const std::vector<Cap> caps = RandomCaps(99, 1000, 1.0, 1.5);
    double f[16], g[16];
    AccumulateLog(CapTables::Get(4), caps, f);
    for (ExpMethod method : methods)
    {
      ExpOptions o;
      o.Method = method;
      PGI_CHECK(Exp(4, f, g, o) == Status::Ok);
      for (double v : g)
      {
        PGI_NEAR(v, 0.0, 1e-9);
      }
    }
  }

  // Log of zero, tiny, negative and wildly ringing visibility stays finite.
  {
    const int order = 4;
    std::vector<std::vector<double>> inputs;
    inputs.push_back(std::vector<double>(16, 0.0));
    std::vector<double> tiny(16, 0.0);
    tiny[0] = 1e-12;
    inputs.push_back(tiny);
    std::vector<double> negative(16, 0.0);
    negative[0] = -SqrtFourPi;
    inputs.push_back(negative);
    std::vector<double> wild(16);
    for (int i = 0; i < 16; ++i)
    {
      wild[i] = (i % 3 == 0 ? -1.0 : 1.0) * (1 + i);
    }
    inputs.push_back(wild);
    for (const auto& g : inputs)
    {
      double f[16], back[16];
      PGI_CHECK(Log(order, g.data(), f) == Status::Ok);
      PGI_CHECK(AllFinite(f, 16));
      PGI_CHECK(Exp(order, f, back) == Status::Ok);
      PGI_CHECK(AllFinite(back, 16));
    }
    // Zero visibility logs to a strongly negative DC: exp gives ~0 back.
    double f[16], back[16];
    Log(order, inputs[0].data(), f);
    PGI_CHECK(f[0] < -10.0);
    Exp(order, f, back);
    PGI_BELOW(std::fabs(back[0]), 1e-3);
  }

  // NaN and Inf are reported, never passed on.
  {
    const int order = 4;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    for (double bad : { nan, inf, -inf })
    {
      for (int where : { 0, 7 })
      {
        double f[16] = { 0 }, g[16];
        f[where] = bad;
        for (ExpMethod method :
          { ExpMethod::PS, ExpMethod::PSStar, ExpMethod::OL, ExpMethod::Hybrid })
        {
          ExpOptions o;
          o.Method = method;
          std::fill(g, g + 16, 123.0);
          PGI_CHECK(Exp(order, f, g, o) == Status::NonFiniteInput);
          PGI_CHECK(std::all_of(g, g + 16, [](double v) { return v == 0.0; }));
        }
        double l[16];
        PGI_CHECK(Log(order, f, l) == Status::NonFiniteInput);
        PGI_CHECK(AllFinite(l, 16));
        float ff[16] = { 0 }, gf[16];
        ff[where] = static_cast<float>(bad);
        PGI_CHECK(Exp(order, ff, gf) == Status::NonFiniteInput);
      }
    }
    // Not a log-visibility at all: a huge positive DC overflows; reported,
    // and g is all zeros (pgiSHExp.h).
    double f[16] = { 1e6 }, g[16];
    std::fill(g, g + 16, 123.0);
    const Status s = Exp(order, f, g);
    PGI_CHECK(s == Status::NonFiniteResult);
    PGI_CHECK(std::all_of(g, g + 16, [](double v) { return v == 0.0; }));
    PGI_CHECK(Exp(0, f, g) == Status::InvalidOrder);
    PGI_CHECK(Exp(MaxOrder + 1, f, g) == Status::InvalidOrder);
    PGI_CHECK(Log(0, f, g) == Status::InvalidOrder);
    std::printf("status strings: %s / %s\n", StatusString(Status::NonFiniteInput),
      StatusString(Status::NonFiniteResult));
  }

  // Continuity in f: sweep t f for a 20-cap log across several changes of
  // the number of squarings; the largest step between neighbours (RMS
  // visibility) stays at the level of the methods' own error.
  {
    const int order = 4;
    const std::vector<Cap> caps = RandomCaps(7, 20, 0.2, 0.9);
    double base[16];
    AccumulateLog(CapTables::Get(order), caps, base);
    for (ExpMethod method : { ExpMethod::PSStar, ExpMethod::Hybrid })
    {
      ExpOptions o;
      o.Method = method;
      double prev[16], g[16], worstJump = 0.0, worstSmooth = 0.0;
      const int steps = 4000;
      for (int k = 0; k <= steps; ++k)
      {
        double f[16];
        const double t = 2.0 * k / steps;
        for (int i = 0; i < 16; ++i)
        {
          f[i] = t * base[i];
        }
        Exp(order, f, g, o);
        if (k > 0)
        {
          worstJump = std::max(worstJump, RmsDifference(order, g, prev));
        }
        std::copy(g, g + 16, prev);
      }
      // A smooth function moves by about |d exp/dt| dt per step: compare.
      worstSmooth = 2.0 / steps * NormNoDC(order, base) / std::sqrt(4 * Pi);
      std::printf("%s: largest step %.4f over a sweep whose smooth step is ~%.4f\n",
        ExpMethodName(method), worstJump, worstSmooth);
      PGI_BELOW(worstJump, 0.005);
      // The sweep moves g at all (a frozen exp has no steps), and no step is
      // far above a smooth function's.
      PGI_CHECK(worstJump > 0.1 * worstSmooth);
      PGI_BELOW(worstJump, 3.0 * worstSmooth);
    }
  }
  return pgitest::Result();
}
