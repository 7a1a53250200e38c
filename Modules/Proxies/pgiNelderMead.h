/**
 * @file pgiNelderMead.h
 * @brief Derivative-free minimisation in 3-D (Nelder-Mead simplex), used where
 * the papers use Powell's method: sphere centres minimising outside volume or
 * bounding radius. Private to the Proxies module.
 */
#ifndef pgiNelderMead_h
#define pgiNelderMead_h

#include <algorithm>
#include <cmath>

namespace proxygi
{
/**
 * Minimises f over R^3 from x with initial simplex edge `step`; stops after
 * maxEvaluations or when the simplex is smaller than `minStep`. Writes the
 * best point to x and returns its value.
 */
template <typename F>
double MinimizeNelderMead3(F&& f, double x[3], double step, double minStep, int maxEvaluations)
{
  double p[4][3];
  double v[4];
  for (int i = 0; i < 4; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      p[i][k] = x[k] + (i == k + 1 ? step : 0.0);
    }
    v[i] = f(p[i]);
  }
  int evaluations = 4;
  int order[4] = { 0, 1, 2, 3 };
  while (evaluations < maxEvaluations)
  {
    std::sort(order, order + 4, [&](int a, int b) { return v[a] < v[b]; });
    const int best = order[0], worst = order[3], second = order[2];
    double size = 0.0;
    for (int i = 1; i < 4; ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        size = std::max(size, std::fabs(p[order[i]][k] - p[best][k]));
      }
    }
    if (size < minStep)
    {
      break;
    }
    double centroid[3] = { 0, 0, 0 };
    for (int i = 0; i < 3; ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        centroid[k] += p[order[i]][k] / 3.0;
      }
    }
    auto along = [&](double t, double out[3])
    {
      for (int k = 0; k < 3; ++k)
      {
        out[k] = centroid[k] + t * (p[worst][k] - centroid[k]);
      }
    };
    double r[3];
    along(-1.0, r);
    const double vr = f(r);
    ++evaluations;
    if (vr < v[best])
    {
      double e[3];
      along(-2.0, e);
      const double ve = f(e);
      ++evaluations;
      if (ve < vr)
      {
        std::copy(e, e + 3, p[worst]);
        v[worst] = ve;
      }
      else
      {
        std::copy(r, r + 3, p[worst]);
        v[worst] = vr;
      }
      continue;
    }
    if (vr < v[second])
    {
      std::copy(r, r + 3, p[worst]);
      v[worst] = vr;
      continue;
    }
    double c[3];
    along(vr < v[worst] ? -0.5 : 0.5, c);
    const double vc = f(c);
    ++evaluations;
    if (vc < std::min(vr, v[worst]))
    {
      std::copy(c, c + 3, p[worst]);
      v[worst] = vc;
      continue;
    }
    // Shrink towards the best vertex.
    for (int i = 1; i < 4; ++i)
    {
      const int j = order[i];
      for (int k = 0; k < 3; ++k)
      {
        p[j][k] = p[best][k] + 0.5 * (p[j][k] - p[best][k]);
      }
      v[j] = f(p[j]);
      ++evaluations;
    }
  }
  int best = 0;
  for (int i = 1; i < 4; ++i)
  {
    if (v[i] < v[best])
    {
      best = i;
    }
  }
  std::copy(p[best], p[best] + 3, x);
  return v[best];
}
} // namespace proxygi

#endif
