#include "pgiSHCapSet.h"

#include "pgiSHBasis.h"
#include "pgiSHTables.h"
#include "pgiSHTripleProduct.h"
#include "pgiSHZonal.h"

#include <algorithm>
#include <random>

namespace proxygi
{
namespace sh
{

template <typename T>
void AccumulateLog(const CapTables& tables, const std::vector<Cap>& caps, T* logSum)
{
  const int order = tables.GetOrder();
  const int n2 = NumCoefficients(order);
  Fill(logSum, n2, T(0));
  T zh[MaxOrder], v[MaxCoefficients];
  for (const Cap& cap : caps)
  {
    tables.CapLog(static_cast<T>(cap.HalfAngle), zh);
    RotateScaledZonal(order, zh, static_cast<T>(cap.Direction[0]), static_cast<T>(cap.Direction[1]),
      static_cast<T>(cap.Direction[2]), v);
    for (int i = 0; i < n2; ++i)
    {
      logSum[i] += v[i];
    }
  }
}

void AccumulateProduct(int order, const std::vector<Cap>& caps, double* visibility)
{
  const int n2 = NumCoefficients(order);
  const TripleProduct& tp = TripleProduct::Get(order);
  SetConstant(order, 1.0, visibility);
  double zh[MaxOrder], v[MaxCoefficients], tmp[MaxCoefficients];
  for (const Cap& cap : caps)
  {
    CapVisibilityZonal(order, cap.HalfAngle, zh);
    RotateZonal(order, zh, cap.Direction[0], cap.Direction[1], cap.Direction[2], v);
    tp.Product(visibility, v, tmp);
    std::copy(tmp, tmp + n2, visibility);
  }
}

void ProjectExactVisibility(int order, const std::vector<Cap>& caps, double* visibility, int zNodes)
{
  std::vector<double> cosines(caps.size());
  for (std::size_t i = 0; i < caps.size(); ++i)
  {
    cosines[i] = std::cos(caps[i].HalfAngle);
  }
  Project(
    order,
    [&](double x, double y, double z)
    {
      for (std::size_t i = 0; i < caps.size(); ++i)
      {
        const double* d = caps[i].Direction;
        if (x * d[0] + y * d[1] + z * d[2] >= cosines[i])
        {
          return 0.0;
        }
      }
      return 1.0;
    },
    SphereQuadrature(zNodes), visibility);
}

double RmsDifference(int order, const double* a, const double* b)
{
  // Orthonormal basis: the L2 norm of the function is the coefficient norm.
  double s = 0.0;
  for (int i = 0; i < NumCoefficients(order); ++i)
  {
    s += (a[i] - b[i]) * (a[i] - b[i]);
  }
  return std::sqrt(s / (4.0 * Pi));
}

std::vector<Cap> RandomCaps(std::uint32_t seed, int count, double minAngle, double maxAngle)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> angle(minAngle, maxAngle);
  std::vector<Cap> caps(count);
  for (Cap& cap : caps)
  {
    double len = 0.0;
    do
    {
      for (double& c : cap.Direction)
      {
        c = normal(rng);
      }
      len = std::sqrt(cap.Direction[0] * cap.Direction[0] + cap.Direction[1] * cap.Direction[1] +
        cap.Direction[2] * cap.Direction[2]);
    } while (len < 1e-9);
    for (double& c : cap.Direction)
    {
      c /= len;
    }
    cap.HalfAngle = angle(rng);
  }
  return caps;
}

template PROXYGISPHERICALHARMONICS_EXPORT void AccumulateLog<float>(
  const CapTables&, const std::vector<Cap>&, float*);
template PROXYGISPHERICALHARMONICS_EXPORT void AccumulateLog<double>(
  const CapTables&, const std::vector<Cap>&, double*);

} // namespace sh
} // namespace proxygi
