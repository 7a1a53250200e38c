// proxygi sh: look at what the SphericalHarmonics module computes.
#include "proxygiCommands.h"

#include "pgiSHBasis.h"
#include "pgiSHCapSet.h"
#include "pgiSHExp.h"
#include "pgiSHLog.h"
#include "pgiSHTables.h"
#include "pgiSHZonal.h"

#include <vtkLogger.h>

#include <cstdio>
#include <vector>

namespace proxygi
{
namespace cli
{
using namespace proxygi::sh;

namespace
{
const char* Usage = R"(usage: proxygi sh [--order N] [--cap DEG] [--function NAME]

  --order N        SH order, 1..8 (n bands, n^2 coefficients); default 4
  --cap DEG        a blocker of angular radius DEG (0..90) seen along +z: prints
                   its visibility and log-visibility (eigen-inversion log) and
                   the RMS error of exp(log) for each exp method; default 30
  --function NAME  instead, project a function by quadrature and print its
                   coefficients: constant | cosine (max(z,0)) | cap (uses --cap)
)";

void PrintVector(const char* title, int order, const double* v)
{
  std::printf("%s\n", title);
  for (int l = 0; l < order; ++l)
  {
    std::printf("  l=%d:", l);
    for (int m = -l; m <= l; ++m)
    {
      std::printf(" %+.6f", v[Index(l, m)]);
    }
    std::printf("\n");
  }
}
} // namespace

int RunSH(const Args& args)
{
  if (Flag(args, "--help"))
  {
    std::fputs(Usage, stdout);
    return 0;
  }
  bool ok = true;
  const int order = static_cast<int>(NumberOption(args, "--order", 4, ok));
  const double degrees = NumberOption(args, "--cap", 30, ok);
  if (!ok)
  {
    return 2;
  }
  if (order < 1 || order > MaxOrder)
  {
    vtkLogF(ERROR, "proxygi sh: --order must lie in 1..%d", MaxOrder);
    return 2;
  }
  if (!(degrees >= 0.0 && degrees <= 90.0))
  {
    vtkLogF(ERROR, "proxygi sh: --cap must lie in 0..90 degrees");
    return 2;
  }
  const double theta = degrees * Pi / 180.0;
  const int n2 = NumCoefficients(order);
  std::vector<double> g(n2), f(n2), e(n2);

  const std::string function = Option(args, "--function", "");
  if (!function.empty())
  {
    SphericalFunction fn;
    if (function == "constant")
    {
      fn = [](double, double, double) { return 1.0; };
    }
    else if (function == "cosine")
    {
      fn = [](double, double, double z) { return z > 0.0 ? z : 0.0; };
    }
    else if (function == "cap")
    {
      const double c = std::cos(theta);
      fn = [c](double, double, double z) { return z >= c ? 1.0 : 0.0; };
    }
    else
    {
      vtkLogF(ERROR, "proxygi sh: unknown function '%s'", function.c_str());
      return 2;
    }
    Project(order, fn, SphereQuadrature(256), g.data());
    PrintVector(("projection of " + function + " (256 x 512 Gauss rule)").c_str(), order, g.data());
    return 0;
  }

  double zh[MaxOrder];
  CapVisibilityZonal(order, theta, zh);
  for (int l = 0; l < order; ++l)
  {
    g[Index(l, 0)] = zh[l];
  }
  const Status s = Log(order, g.data(), f.data());
  if (s != Status::Ok)
  {
    vtkLogF(ERROR, "proxygi sh: log failed: %s", StatusString(s));
    return 1;
  }
  std::printf("order %d, blocker of angular radius %.2f degrees along +z\n", order, degrees);
  PrintVector("visibility g (exact projection)", order, g.data());
  PrintVector("log-visibility f = log(g) (eigen-inversion, clip 0.02)", order, f.data());
  std::printf("exp(f) against g, RMS visibility error:\n");
  struct
  {
    const char* Name;
    ExpMethod Method;
    int Degree;
  } methods[] = { { "PS-2", ExpMethod::PS, 2 }, { "PS-4", ExpMethod::PS, 4 },
    { "PS*-2", ExpMethod::PSStar, 2 }, { "OL", ExpMethod::OL, 0 },
    { "HYB", ExpMethod::Hybrid, 0 } };
  for (const auto& m : methods)
  {
    ExpOptions o;
    o.Method = m.Method;
    o.Degree = m.Degree;
    Exp(order, f.data(), e.data(), o);
    std::printf("  %-6s %.6f\n", m.Name, RmsDifference(order, e.data(), g.data()));
  }
  return 0;
}

} // namespace cli
} // namespace proxygi
