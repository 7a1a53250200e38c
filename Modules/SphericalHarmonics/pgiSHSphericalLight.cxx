#include "pgiSHSphericalLight.h"

#include "pgiSHBasis.h"

#include <array>
#include <cmath>
#include <map>

namespace proxygi
{
namespace sh
{

std::vector<double> GeodesicDirections(int frequency)
{
  frequency = frequency < 1 ? 1 : frequency;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const double v[12][3] = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 }, { 0, -1, t },
    { 0, 1, t }, { 0, -1, -t }, { 0, 1, -t }, { t, 0, -1 }, { t, 0, 1 }, { -t, 0, -1 },
    { -t, 0, 1 } };
  const int faces[20][3] = { { 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 }, { 0, 7, 10 }, { 0, 10, 11 },
    { 1, 5, 9 }, { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 }, { 3, 9, 4 }, { 3, 4, 2 },
    { 3, 2, 6 }, { 3, 6, 8 }, { 3, 8, 9 }, { 4, 9, 5 }, { 2, 4, 11 }, { 6, 2, 10 }, { 8, 6, 7 },
    { 9, 8, 1 } };
  // Points of the subdivided faces, deduplicated by their rounded position
  // (shared edges and corners are generated more than once).
  std::map<std::array<long long, 3>, int> seen;
  std::vector<double> out;
  for (const auto& f : faces)
  {
    for (int i = 0; i <= frequency; ++i)
    {
      for (int j = 0; i + j <= frequency; ++j)
      {
        const double a = double(frequency - i - j) / frequency, b = double(i) / frequency,
                     c = double(j) / frequency;
        double p[3];
        for (int k = 0; k < 3; ++k)
        {
          p[k] = a * v[f[0]][k] + b * v[f[1]][k] + c * v[f[2]][k];
        }
        const double len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        std::array<long long, 3> key;
        for (int k = 0; k < 3; ++k)
        {
          p[k] /= len;
          key[k] = std::llround(p[k] * 1e9);
        }
        if (seen.emplace(key, static_cast<int>(out.size() / 3)).second)
        {
          out.insert(out.end(), p, p + 3);
        }
      }
    }
  }
  return out;
}

std::vector<double> VoronoiBasisSums(int order, const std::vector<double>& w, int zNodes)
{
  const int n2 = NumCoefficients(order);
  const std::size_t m = w.size() / 3;
  std::vector<double> sums(m * n2, 0.0);
  if (m == 0)
  {
    return sums;
  }
  const SphereQuadrature rule(zNodes);
  double y[MaxCoefficients];
  for (std::size_t q = 0; q < rule.Size(); ++q)
  {
    std::size_t best = 0;
    double bestDot = -2.0;
    for (std::size_t j = 0; j < m; ++j)
    {
      const double d = rule.X[q] * w[3 * j] + rule.Y[q] * w[3 * j + 1] + rule.Z[q] * w[3 * j + 2];
      if (d > bestDot)
      {
        bestDot = d;
        best = j;
      }
    }
    EvaluateBasis(order, rule.X[q], rule.Y[q], rule.Z[q], y);
    for (int i = 0; i < n2; ++i)
    {
      sums[best * n2 + i] += rule.W[q] * y[i];
    }
  }
  return sums;
}

} // namespace sh
} // namespace proxygi
