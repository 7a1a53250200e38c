/**
 * @file pgiSHRotation.h
 * @brief Rotation of a full SH vector (not only a ZH) by a 3x3 rotation,
 * and orthonormal frames about an axis. The exact indirect operator M(theta)
 * needs it: the proxy's radiance is turned into the proxy's canonical frame
 * and the result turned back.
 */
#ifndef pgiSHRotation_h
#define pgiSHRotation_h

#include "pgiSH.h"

namespace proxygi
{
namespace sh
{

/**
 * Rotates an SH function: out(s) = in(R^T s), so a feature at direction x
 * moves to R x. R is a row-major orthonormal 3x3 matrix. Computed by
 * projecting the rotated function with a quadrature exact for degree
 * 2 (order - 1), hence exact (to rounding) for every order-n input.
 * in and out must not alias; order in 1..MaxOrder.
 */
template <typename T>
PROXYGISPHERICALHARMONICS_EXPORT void RotateSH(int order, const double R[9], const T* in, T* out);

/**
 * Row-major rotation whose third column is the unit axis d (so R maps +z to
 * d) and whose first two columns complete a right-handed orthonormal frame.
 * Any such frame serves for z-symmetric operators.
 */
PROXYGISPHERICALHARMONICS_EXPORT void FrameFromAxis(double dx, double dy, double dz, double R[9]);

} // namespace sh
} // namespace proxygi

#endif
