// Basis: orthonormality by exact quadrature, closed form against recurrence,
// known values of the convention, projection/reconstruction round trip.
#include "pgiSHBasis.h"
#include "pgiTesting.h"

#include <random>
#include <vector>

using namespace proxygi::sh;

int TestSHBasis(int, char*[])
{
  // Orthonormality, orders 1..8 (and the recurrence up to 16).
  for (int order = 1; order <= MaxBasisOrder; order = order < 8 ? order + 1 : order * 2)
  {
    const int n2 = NumCoefficients(order);
    const SphereQuadrature rule = SphereQuadrature::ForDegree(2 * (order - 1));
    std::vector<double> basis(rule.Size() * n2);
    for (std::size_t q = 0; q < rule.Size(); ++q)
    {
      EvaluateBasis(order, rule.X[q], rule.Y[q], rule.Z[q], &basis[q * n2]);
    }
    double worst = 0.0;
    for (int i = 0; i < n2; ++i)
    {
      for (int j = 0; j < n2; ++j)
      {
        double s = 0.0;
        for (std::size_t q = 0; q < rule.Size(); ++q)
        {
          s += rule.W[q] * basis[q * n2 + i] * basis[q * n2 + j];
        }
        worst = std::max(worst, std::fabs(s - (i == j ? 1.0 : 0.0)));
      }
    }
    std::printf("order %2d: max |<y_i, y_j> - delta_ij| = %.3g\n", order, worst);
    PGI_BELOW(worst, 1e-6);
    PGI_BELOW(worst, 1e-12); // what double precision actually gives
  }

  // Closed-form polynomials against the recurrence, double and float.
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  double worstPoly = 0.0, worstFloat = 0.0;
  for (int trial = 0; trial < 2000; ++trial)
  {
    double d[3] = { normal(rng), normal(rng), normal(rng) };
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (double& c : d)
    {
      c /= len;
    }
    for (int order = 1; order <= 8; ++order)
    {
      double a[64], b[64];
      float fa[64];
      EvaluateBasisPolynomial(order, d[0], d[1], d[2], a);
      EvaluateBasisRecurrence(order, d[0], d[1], d[2], b);
      EvaluateBasis(order, float(d[0]), float(d[1]), float(d[2]), fa);
      for (int i = 0; i < order * order; ++i)
      {
        worstPoly = std::max(worstPoly, std::fabs(a[i] - b[i]));
        worstFloat = std::max(worstFloat, std::fabs(double(fa[i]) - b[i]));
      }
    }
  }
  std::printf("polynomial vs recurrence: %.3g, float vs double: %.3g\n", worstPoly, worstFloat);
  PGI_BELOW(worstPoly, 1e-12);
  PGI_BELOW(worstFloat, 2e-5);

  // The documented convention: band 1 = sqrt(3/(4 pi)) (y, z, x), no CS phase.
  double y[9];
  const double c1 = std::sqrt(3.0 / (4.0 * Pi));
  EvaluateBasis(3, 0.0, 0.0, 1.0, y);
  PGI_NEAR(y[0], 0.5 / std::sqrt(Pi), 1e-15);
  PGI_NEAR(y[2], c1, 1e-15);
  PGI_NEAR(y[6], std::sqrt(5.0 / (4.0 * Pi)), 1e-15);
  PGI_NEAR(y[1], 0.0, 1e-15);
  PGI_NEAR(y[3], 0.0, 1e-15);
  EvaluateBasis(3, 1.0, 0.0, 0.0, y);
  PGI_NEAR(y[3], c1, 1e-15);
  PGI_NEAR(y[8], 0.5 * std::sqrt(15.0 / (4.0 * Pi)), 1e-15); // xx - yy term
  EvaluateBasis(3, 0.0, 1.0, 0.0, y);
  PGI_NEAR(y[1], c1, 1e-15);
  PGI_NEAR(y[8], -0.5 * std::sqrt(15.0 / (4.0 * Pi)), 1e-15);
  const double s = std::sqrt(0.5);
  EvaluateBasis(3, s, s, 0.0, y);
  PGI_NEAR(y[4], 0.5 * std::sqrt(15.0 / Pi) * 0.5, 1e-15); // xy term

  // Projection of a reconstruction returns the coefficients (exact rule).
  for (int order = 1; order <= MaxOrder; ++order)
  {
    const int n2 = NumCoefficients(order);
    std::vector<double> coeffs(n2), back(n2);
    for (double& c : coeffs)
    {
      c = normal(rng);
    }
    Project(
      order,
      [&](double x, double yy, double z) { return Reconstruct(order, coeffs.data(), x, yy, z); },
      SphereQuadrature::ForDegree(2 * (order - 1)), back.data());
    double worst = 0.0;
    for (int i = 0; i < n2; ++i)
    {
      worst = std::max(worst, std::fabs(back[i] - coeffs[i]));
    }
    PGI_BELOW(worst, 1e-12);
  }
  return pgitest::Result();
}
