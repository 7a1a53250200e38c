/**
 * @file pgiSH.h
 * @brief Conventions shared by every spherical-harmonics routine of ProxyGI.
 *
 * Order n means n bands (l = 0 .. n-1) and n^2 coefficients, as in the
 * papers. Coefficient (l, m) sits at index i = l^2 + l + m.
 *
 * Real SH without the Condon-Shortley phase:
 *   y_l0  = K_l0 P_l(z),
 *   y_lm  = sqrt(2) K_lm P_l^m(z) cos(m phi)   (m > 0),
 *   y_l-m = sqrt(2) K_lm P_l^m(z) sin(m phi)   (m > 0),
 * with K_lm = sqrt((2l+1)/(4 pi) (l-m)!/(l+m)!) and
 * P_l^m(z) = (1 - z^2)^(m/2) d^m P_l(z)/dz^m. Band 1 is
 * sqrt(3/(4 pi)) (y, z, x). The GLSL code uses the same convention.
 *
 * The constant function 1 projects to (sqrt(4 pi), 0, ..., 0).
 *
 * Errors: routines that can meet bad numbers return a Status; on anything but
 * Status::Ok their outputs are filled with zeros, never with NaN or Inf.
 */
#ifndef pgiSH_h
#define pgiSH_h

#include "ProxyGISphericalHarmonicsModule.h"

#include <cmath>
#include <cstddef>

namespace proxygi
{
namespace sh
{

constexpr double Pi = 3.14159265358979323846;
/// sqrt(4 pi): the DC coefficient of the constant function 1.
constexpr double SqrtFourPi = 3.5449077018110320546;

/// Largest order the cached tables and tensors are built for.
constexpr int MaxOrder = 8;
/// Largest order the basis evaluation supports (recurrence).
constexpr int MaxBasisOrder = 16;
constexpr int MaxCoefficients = MaxOrder * MaxOrder;

constexpr int NumCoefficients(int order)
{
  return order * order;
}
constexpr int Index(int l, int m)
{
  return l * l + l + m;
}
/// Band l of coefficient index i.
inline int BandOf(int i)
{
  int l = static_cast<int>(std::sqrt(static_cast<double>(i)));
  while (l * l > i)
  {
    --l;
  }
  while ((l + 1) * (l + 1) <= i)
  {
    ++l;
  }
  return l;
}

enum class Status
{
  Ok = 0,
  /// An input held NaN or Inf.
  NonFiniteInput,
  /// The computation itself overflowed (input far outside the valid range).
  NonFiniteResult,
  /// Order outside 1..MaxOrder (or the routine's own limit).
  InvalidOrder,
  /// Another argument was out of range.
  InvalidArgument
};

PROXYGISPHERICALHARMONICS_EXPORT const char* StatusString(Status status);

template <typename T>
inline bool AllFinite(const T* v, int count)
{
  for (int i = 0; i < count; ++i)
  {
    if (!std::isfinite(v[i]))
    {
      return false;
    }
  }
  return true;
}

template <typename T>
inline void Fill(T* v, int count, T value)
{
  for (int i = 0; i < count; ++i)
  {
    v[i] = value;
  }
}

/// Sets v to the SH vector of the constant function `value`.
template <typename T>
inline void SetConstant(int order, T value, T* v)
{
  Fill(v, NumCoefficients(order), T(0));
  v[0] = static_cast<T>(value * SqrtFourPi);
}

template <typename T>
inline T Dot(int count, const T* a, const T* b)
{
  T s = T(0);
  for (int i = 0; i < count; ++i)
  {
    s += a[i] * b[i];
  }
  return s;
}

} // namespace sh
} // namespace proxygi

#endif
