#include "pgiSHZonal.h"

#include "pgiSHBasis.h"

#include <array>
#include <vector>

namespace proxygi
{
namespace sh
{

namespace
{
// Legendre polynomials P_0..P_{count-1} at t.
void Legendre(int count, double t, double* p)
{
  p[0] = 1.0;
  if (count > 1)
  {
    p[1] = t;
  }
  for (int l = 2; l < count; ++l)
  {
    p[l] = ((2 * l - 1) * t * p[l - 1] - (l - 1) * p[l - 2]) / l;
  }
}
} // namespace

template <typename T>
void RotateScaledZonal(int order, const T* scaledZh, T dx, T dy, T dz, T* out)
{
  EvaluateBasis(order, dx, dy, dz, out);
  for (int l = 0; l < order; ++l)
  {
    const T s = scaledZh[l];
    for (int i = l * l; i < (l + 1) * (l + 1); ++i)
    {
      out[i] *= s;
    }
  }
}

template <typename T>
void RotateZonal(int order, const T* zh, T dx, T dy, T dz, T* out)
{
  T scaled[MaxBasisOrder];
  for (int l = 0; l < order; ++l)
  {
    scaled[l] = static_cast<T>(zh[l] * ZonalScale(l));
  }
  RotateScaledZonal(order, scaled, dx, dy, dz, out);
}

void ConvolveZonal(int order, const double* kernelZh, double* f)
{
  for (int l = 0; l < order; ++l)
  {
    const double s = ZonalScale(l) * kernelZh[l];
    for (int i = l * l; i < (l + 1) * (l + 1); ++i)
    {
      f[i] *= s;
    }
  }
}

void ClampedCosineZonal(int order, double* zh)
{
  // z_l = 2 pi K_l0 int_0^1 P_l(t) t dt; Gauss-Legendre is exact for this degree.
  std::vector<double> nodes, weights;
  GaussLegendre(order + 1, 0.0, 1.0, nodes, weights);
  std::vector<double> p(order);
  for (int l = 0; l < order; ++l)
  {
    zh[l] = 0.0;
  }
  for (std::size_t q = 0; q < nodes.size(); ++q)
  {
    Legendre(order, nodes[q], p.data());
    for (int l = 0; l < order; ++l)
    {
      zh[l] += weights[q] * p[l] * nodes[q];
    }
  }
  for (int l = 0; l < order; ++l)
  {
    zh[l] *= 2 * Pi * BasisNormalization(l, 0);
  }
}

namespace
{
// Scaled clamped-cosine ZH over pi, per band: the same for every order, so
// computed once (DiffuseTransfer runs per receiver).
const std::array<double, MaxBasisOrder>& DiffuseTransferZonal()
{
  static const std::array<double, MaxBasisOrder> table = []()
  {
    std::array<double, MaxBasisOrder> zh{};
    ClampedCosineZonal(MaxBasisOrder, zh.data());
    for (int l = 0; l < MaxBasisOrder; ++l)
    {
      zh[l] *= ZonalScale(l) / Pi;
    }
    return zh;
  }();
  return table;
}
} // namespace

template <typename T>
void DiffuseTransfer(int order, T nx, T ny, T nz, T* out)
{
  const auto& zh = DiffuseTransferZonal();
  T scaled[MaxBasisOrder];
  for (int l = 0; l < order; ++l)
  {
    scaled[l] = static_cast<T>(zh[l]);
  }
  RotateScaledZonal(order, scaled, nx, ny, nz, out);
}

void CapZonal(int order, double halfAngle, double* zh)
{
  // int_t^1 P_l = (P_{l-1}(t) - P_{l+1}(t)) / (2l + 1) for l >= 1.
  const double t = std::cos(halfAngle);
  std::vector<double> p(order + 1);
  Legendre(order + 1, t, p.data());
  for (int l = 0; l < order; ++l)
  {
    const double integral = l == 0 ? 1.0 - t : (p[l - 1] - p[l + 1]) / (2 * l + 1);
    zh[l] = 2 * Pi * BasisNormalization(l, 0) * integral;
  }
}

void CapVisibilityZonal(int order, double halfAngle, double* zh)
{
  CapZonal(order, halfAngle, zh);
  for (int l = 0; l < order; ++l)
  {
    zh[l] = -zh[l];
  }
  zh[0] += SqrtFourPi;
}

template <typename T>
void Window(int order, T* f, double h)
{
  if (h <= 0.0)
  {
    h = 2.0 * order;
  }
  for (int l = 1; l < order; ++l)
  {
    const T s = static_cast<T>(WindowFactor(l, h));
    for (int i = l * l; i < (l + 1) * (l + 1); ++i)
    {
      f[i] *= s;
    }
  }
}

// T is a type here: it cannot take the parentheses the check asks for.
// NOLINTBEGIN(bugprone-macro-parentheses)
#define PGI_INSTANTIATE(T)                                                                         \
  template PROXYGISPHERICALHARMONICS_EXPORT void RotateZonal<T>(int, const T*, T, T, T, T*);       \
  template PROXYGISPHERICALHARMONICS_EXPORT void RotateScaledZonal<T>(int, const T*, T, T, T, T*); \
  template PROXYGISPHERICALHARMONICS_EXPORT void DiffuseTransfer<T>(int, T, T, T, T*);             \
  template PROXYGISPHERICALHARMONICS_EXPORT void Window<T>(int, T*, double);
PGI_INSTANTIATE(float)
PGI_INSTANTIATE(double)
#undef PGI_INSTANTIATE
// NOLINTEND(bugprone-macro-parentheses)

} // namespace sh
} // namespace proxygi
