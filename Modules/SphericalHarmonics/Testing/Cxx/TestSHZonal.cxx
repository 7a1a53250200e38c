// Zonal harmonics: rotation rule against direct projection, clamped cosine
// and cap coefficients against independent integration, irradiance of
// uniform light (white furnace), windowing.
#include "pgiSHBasis.h"
#include "pgiSHZonal.h"
#include "pgiTesting.h"

#include <random>
#include <vector>

using namespace proxygi::sh;

int TestSHZonal(int, char*[])
{
  // ZH rotation = projection of the rotated circular function. h(t) is a
  // cubic in t = s.d, so exact quadrature makes both sides exact.
  auto h = [](double t) { return 1.0 + 2.0 * t - 3.0 * t * t + 0.5 * t * t * t; };
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  for (int order = 1; order <= MaxOrder; ++order)
  {
    const int n2 = NumCoefficients(order);
    const SphereQuadrature rule = SphereQuadrature::ForDegree(3 + order - 1);
    std::vector<double> full(n2), rotated(n2), direct(n2);
    Project(
      order, [&](double, double, double z) { return h(z); }, rule, full.data());
    std::vector<double> zh(order);
    for (int l = 0; l < order; ++l)
    {
      zh[l] = full[Index(l, 0)];
      for (int m = -l; m <= l; ++m)
      {
        if (m != 0)
        {
          PGI_NEAR(full[Index(l, m)], 0.0, 1e-13); // circular symmetry about z
        }
      }
    }
    double worst = 0.0;
    for (int trial = 0; trial < 20; ++trial)
    {
      double d[3] = { normal(rng), normal(rng), normal(rng) };
      const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      for (double& c : d)
      {
        c /= len;
      }
      RotateZonal(order, zh.data(), d[0], d[1], d[2], rotated.data());
      Project(
        order, [&](double x, double y, double z) { return h(x * d[0] + y * d[1] + z * d[2]); },
        rule, direct.data());
      for (int i = 0; i < n2; ++i)
      {
        worst = std::max(worst, std::fabs(rotated[i] - direct[i]));
      }
    }
    std::printf("order %d: |rotate(zh) - project(rotated)| = %.3g\n", order, worst);
    PGI_BELOW(worst, 1e-6);
    PGI_BELOW(worst, 1e-12);
  }

  // Clamped cosine: known closed forms of the first bands, zero odd bands > 1.
  double cc[MaxOrder];
  ClampedCosineZonal(MaxOrder, cc);
  PGI_NEAR(cc[0], std::sqrt(Pi) / 2.0, 1e-14);
  PGI_NEAR(cc[1], std::sqrt(Pi / 3.0), 1e-14);
  PGI_NEAR(cc[2], std::sqrt(5.0 * Pi) / 8.0, 1e-14);
  PGI_NEAR(cc[3], 0.0, 1e-14);
  PGI_NEAR(cc[4], -std::sqrt(Pi) / 16.0, 1e-14);
  PGI_NEAR(cc[5], 0.0, 1e-14);

  // Caps: the Legendre closed form against Gauss integration of y_l0 on the cap.
  for (int order = 1; order <= MaxOrder; ++order)
  {
    for (double theta = 0.0; theta <= Pi + 1e-9; theta += Pi / 24)
    {
      double zh[MaxOrder], vis[MaxOrder];
      CapZonal(order, theta, zh);
      CapVisibilityZonal(order, theta, vis);
      std::vector<double> nodes, weights;
      GaussLegendre(order + 2, std::cos(theta), 1.0, nodes, weights);
      for (int l = 0; l < order; ++l)
      {
        double ref = 0.0;
        for (std::size_t q = 0; q < nodes.size(); ++q)
        {
          double y[MaxCoefficients];
          const double z = nodes[q];
          EvaluateBasis(order, std::sqrt(std::max(0.0, 1.0 - z * z)), 0.0, z, y);
          ref += weights[q] * 2.0 * Pi * y[Index(l, 0)];
        }
        PGI_NEAR(zh[l], ref, 1e-12);
        PGI_NEAR(vis[l], (l == 0 ? SqrtFourPi : 0.0) - ref, 1e-12);
      }
    }
  }

  // White furnace: uniform radiance 1, albedo 1, nothing blocking -> exit
  // radiance H(N) . L = 1 for every normal, float and double.
  for (int order = 1; order <= MaxOrder; ++order)
  {
    double light[MaxCoefficients], hN[MaxCoefficients];
    float lightF[MaxCoefficients], hNF[MaxCoefficients];
    SetConstant(order, 1.0, light);
    SetConstant(order, 1.0f, lightF);
    for (int trial = 0; trial < 10; ++trial)
    {
      double d[3] = { normal(rng), normal(rng), normal(rng) };
      const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      DiffuseTransfer(order, d[0] / len, d[1] / len, d[2] / len, hN);
      DiffuseTransfer(order, float(d[0] / len), float(d[1] / len), float(d[2] / len), hNF);
      PGI_NEAR(Dot(NumCoefficients(order), hN, light), 1.0, 1e-14);
      PGI_NEAR(Dot(NumCoefficients(order), hNF, lightF), 1.0, 1e-6);
    }
    // Convolution gives irradiance E = pi everywhere.
    ConvolveZonal(order, cc, light);
    PGI_NEAR(Reconstruct(order, light, 0.0, 0.6, 0.8), Pi, 1e-13);
  }

  // Irradiance from a cosine lobe L(s) = max(s.z, 0): E(z) has a closed
  // form (2 pi / 3 at the pole); order 3 captures it to 1%, a known result.
  {
    const int order = 3;
    double light[9], cc3[3];
    Project(
      order, [](double, double, double z) { return std::max(z, 0.0); }, SphereQuadrature(64),
      light);
    ClampedCosineZonal(order, cc3);
    ConvolveZonal(order, cc3, light);
    const double pole = Reconstruct(order, light, 0.0, 0.0, 1.0);
    std::printf("cosine-lobe irradiance at the pole: %.5f (exact %.5f)\n", pole, 2.0 * Pi / 3.0);
    PGI_NEAR(pole, 2.0 * Pi / 3.0, 0.01 * 2.0 * Pi / 3.0);
  }

  // Window: band factors cos(pi/2 l/h), h = 2n by default; it lowers the
  // Gibbs overshoot of a 60-degree cap's visibility.
  {
    const int order = 4;
    double g[16] = { 0 }, w[16], zh[4];
    CapVisibilityZonal(order, Pi / 3, zh);
    for (int l = 0; l < order; ++l)
    {
      g[Index(l, 0)] = zh[l];
    }
    std::copy(g, g + 16, w);
    Window(order, w);
    for (int l = 0; l < order; ++l)
    {
      PGI_NEAR(w[Index(l, 0)], g[Index(l, 0)] * std::cos(0.5 * Pi * l / 8.0), 1e-15);
    }
    double overshootRaw = 0.0, overshootWin = 0.0;
    for (int k = 0; k <= 1000; ++k)
    {
      const double z = -1.0 + 2.0 * k / 1000.0, x = std::sqrt(1.0 - z * z);
      const double a = Reconstruct(order, g, x, 0.0, z), b = Reconstruct(order, w, x, 0.0, z);
      overshootRaw = std::max({ overshootRaw, -a, a - 1.0 });
      overshootWin = std::max({ overshootWin, -b, b - 1.0 });
    }
    std::printf("cap overshoot: raw %.4f, windowed %.4f\n", overshootRaw, overshootWin);
    PGI_CHECK(overshootWin < overshootRaw);
    PGI_NEAR(WindowFactor(0, 8.0), 1.0, 0.0);
    PGI_NEAR(WindowFactor(8, 8.0), 0.0, 0.0);
  }
  return pgitest::Result();
}
