/**
 * @file pgiSHZonal.h
 * @brief Zonal harmonics (ZH): functions symmetric about an axis, stored as
 * n coefficients z_l (the m = 0 coefficients about +z). Rotation rule,
 * convolution, the clamped-cosine kernel, circular caps, windowing.
 */
#ifndef pgiSHZonal_h
#define pgiSHZonal_h

#include "pgiSH.h"

namespace proxygi
{
namespace sh
{

/// sqrt(4 pi / (2l + 1)): the factor of the ZH rotation rule.
inline double ZonalScale(int l)
{
  return std::sqrt(4.0 * Pi / (2 * l + 1));
}

/**
 * Rotates a ZH function from +z to the unit axis d (rotation rule):
 * out_lm = sqrt(4 pi / (2l+1)) zh_l y_lm(d). zh holds `order` values.
 */
template <typename T>
PROXYGISPHERICALHARMONICS_EXPORT void RotateZonal(int order, const T* zh, T dx, T dy, T dz, T* out);

/// Same, with zh already multiplied by ZonalScale(l) (what tables store).
template <typename T>
PROXYGISPHERICALHARMONICS_EXPORT void RotateScaledZonal(
  int order, const T* scaledZh, T dx, T dy, T dz, T* out);

/**
 * Convolves f in place with the ZH kernel k (Funk-Hecke):
 * f_lm *= sqrt(4 pi / (2l+1)) k_l.
 */
PROXYGISPHERICALHARMONICS_EXPORT void ConvolveZonal(int order, const double* kernelZh, double* f);

/// ZH coefficients of max(cos theta, 0), exact.
PROXYGISPHERICALHARMONICS_EXPORT void ClampedCosineZonal(int order, double* zh);

/**
 * H(N) of the SHEXP paper, eq. (9): (1/pi) int max(s.N, 0) y(s) ds, so that
 * H(N) . (L * g) is the exit radiance of a white diffuse receiver.
 */
template <typename T>
PROXYGISPHERICALHARMONICS_EXPORT void DiffuseTransfer(int order, T nx, T ny, T nz, T* out);

/// ZH of the indicator of the cap {s : s.z >= cos(halfAngle)}, exact.
PROXYGISPHERICALHARMONICS_EXPORT void CapZonal(int order, double halfAngle, double* zh);

/// ZH of the visibility 1 - cap (what a blocker of that angular radius leaves).
PROXYGISPHERICALHARMONICS_EXPORT void CapVisibilityZonal(int order, double halfAngle, double* zh);

/// Cosine window of band l: cos(pi/2 * l/h) for l < h, 0 beyond.
inline double WindowFactor(int l, double h)
{
  if (h <= 0.0)
  {
    return 1.0;
  }
  const double t = l / h;
  return t >= 1.0 ? 0.0 : std::cos(0.5 * Pi * t);
}

/// Applies the cosine window in place; h <= 0 means h = 2 * order (the default).
template <typename T>
PROXYGISPHERICALHARMONICS_EXPORT void Window(int order, T* f, double h = 0.0);

} // namespace sh
} // namespace proxygi

#endif
