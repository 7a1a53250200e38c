// Triple-product tensor: sparsity counts, symmetry, and the SH product
// against the projection of the product of reconstructions.
#include "pgiSHBasis.h"
#include "pgiSHTripleProduct.h"
#include "pgiTesting.h"

#include <random>
#include <vector>

using namespace proxygi::sh;

int TestSHTripleProduct(int, char*[])
{
  // Ordered triples allowed by the selection rules, and those actually nonzero.
  const std::size_t allowed[8] = { 1, 10, 83, 359, 1164, 2961, 6586, 13018 };
  const std::size_t nonzero[8] = { 1, 10, 83, 353, 1158, 2907, 6460, 12868 };
  for (int order = 1; order <= 8; ++order)
  {
    const TripleProduct& tp = TripleProduct::Get(order);
    const std::size_t a = TripleProduct::CountAllowed(order);
    std::printf("order %d: allowed %zu, nonzero %zu, stored terms %zu\n", order, a,
      tp.CountNonzero(), tp.Terms().size());
    PGI_CHECK(a == allowed[order - 1]);
    PGI_CHECK(tp.CountNonzero() == nonzero[order - 1]);
    for (const auto& t : tp.Terms())
    {
      PGI_CHECK(std::fabs(t.Value) > 1e-12);
      PGI_CHECK(TripleProduct::Allowed(t.I, t.J, t.K));
    }
  }

  // Symmetry and the identity row: Gamma_0jk = delta_jk / sqrt(4 pi).
  const TripleProduct& t4 = TripleProduct::Get(4);
  for (int i = 0; i < 16; ++i)
  {
    for (int j = 0; j < 16; ++j)
    {
      PGI_NEAR(t4.Value(0, i, j), i == j ? 1.0 / SqrtFourPi : 0.0, 1e-14);
      for (int k = 0; k < 16; ++k)
      {
        const double v = t4.Value(i, j, k);
        PGI_NEAR(t4.Value(j, i, k), v, 1e-14);
        PGI_NEAR(t4.Value(k, j, i), v, 1e-14);
      }
    }
  }

  // f * g equals the truncated projection of f(s) g(s) (exact quadrature).
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  for (int order = 1; order <= 8; ++order)
  {
    const int n2 = NumCoefficients(order);
    const TripleProduct& tp = TripleProduct::Get(order);
    std::vector<double> f(n2), g(n2), fg(n2), ref(n2), sq(n2), mg(n2), m(n2 * n2);
    for (int i = 0; i < n2; ++i)
    {
      f[i] = normal(rng);
      g[i] = normal(rng);
    }
    tp.Product(f.data(), g.data(), fg.data());
    Project(
      order,
      [&](double x, double y, double z)
      { return Reconstruct(order, f.data(), x, y, z) * Reconstruct(order, g.data(), x, y, z); },
      SphereQuadrature::ForDegree(3 * (order - 1)), ref.data());
    tp.Square(f.data(), sq.data());
    std::vector<double> ff(n2);
    tp.Product(f.data(), f.data(), ff.data());
    tp.ProductMatrix(f.data(), m.data());
    double worst = 0.0, worstSq = 0.0, worstM = 0.0;
    for (int i = 0; i < n2; ++i)
    {
      double s = 0.0;
      for (int j = 0; j < n2; ++j)
      {
        s += m[i * n2 + j] * g[j];
        PGI_NEAR(m[i * n2 + j], m[j * n2 + i], 1e-13); // M_f is symmetric
      }
      worst = std::max(worst, std::fabs(fg[i] - ref[i]));
      worstSq = std::max(worstSq, std::fabs(sq[i] - ff[i]));
      worstM = std::max(worstM, std::fabs(s - fg[i]));
    }
    std::printf("order %d: |f*g - proj(fg)| = %.3g, |square - f*f| = %.3g, |M_f g - f*g| = %.3g\n",
      order, worst, worstSq, worstM);
    PGI_BELOW(worst, 1e-6);
    PGI_BELOW(worst, 1e-11);
    PGI_BELOW(worstSq, 1e-11);
    PGI_BELOW(worstM, 1e-11);

    // The float path agrees with double to float precision.
    std::vector<float> ffl(f.begin(), f.end()), gfl(g.begin(), g.end()), outf(n2);
    tp.Product(ffl.data(), gfl.data(), outf.data());
    double worstF = 0.0, scale = 0.0;
    for (int i = 0; i < n2; ++i)
    {
      worstF = std::max(worstF, std::fabs(double(outf[i]) - fg[i]));
      scale = std::max(scale, std::fabs(fg[i]));
    }
    PGI_BELOW(worstF, 1e-5 * (1.0 + scale));
  }

  // The product is commutative but not associative (truncation): show it.
  {
    const int n2 = 16;
    std::vector<double> a(n2), b(n2), c(n2), ab(n2), bc(n2), l(n2), r(n2);
    for (int i = 0; i < n2; ++i)
    {
      a[i] = normal(rng);
      b[i] = normal(rng);
      c[i] = normal(rng);
    }
    t4.Product(a.data(), b.data(), ab.data());
    t4.Product(ab.data(), c.data(), l.data());
    t4.Product(b.data(), c.data(), bc.data());
    t4.Product(a.data(), bc.data(), r.data());
    double diff = 0.0;
    for (int i = 0; i < n2; ++i)
    {
      diff = std::max(diff, std::fabs(l[i] - r[i]));
    }
    PGI_CHECK(diff > 1e-3);
  }
  return pgitest::Result();
}
