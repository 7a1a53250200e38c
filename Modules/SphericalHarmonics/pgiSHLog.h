/**
 * @file pgiSHLog.h
 * @brief SH logarithm by eigen-inversion of the product matrix (SHEXP paper,
 * section 5): with M_g = R^T D R,
 *   log(g) = R^T q'(D~) R (g - 1),   q'(x) = log(x) / (x - 1),
 * where D~ clips the eigenvalues from below at max(RelativeClip * d_max,
 * AbsoluteFloor). The clipping keeps the log finite for visibility that is
 * near zero or negative; the absolute floor covers all-zero input.
 * Also the naive log by projection of log(max(g(s), eps)) for comparison.
 */
#ifndef pgiSHLog_h
#define pgiSHLog_h

#include "pgiSH.h"

namespace proxygi
{
namespace sh
{

struct LogOptions
{
  /// Eigenvalues below RelativeClip * (largest eigenvalue) are raised to it.
  double RelativeClip = 0.02;
  /// Lower bound of the clip whatever the largest eigenvalue is.
  double AbsoluteFloor = 1e-6;
};

/// f = log(g) at order 1..MaxOrder; zeros and a non-Ok status on bad input.
PROXYGISPHERICALHARMONICS_EXPORT Status Log(
  int order, const double* g, double* f, const LogOptions& options = LogOptions());

/**
 * Log of a zonal function (zh: its order m = 0 coefficients, one per band),
 * the same eigen-inversion as Log: a zonal g's product matrix is block
 * diagonal by m, so the eigenvalues come block by block (the clip's largest
 * among them all) and the result, zonal too, from the m = 0 block alone.
 * Agrees with Log on the full vector to rounding; tens of times cheaper.
 */
PROXYGISPHERICALHARMONICS_EXPORT Status LogZonal(
  int order, const double* zh, double* logZh, const LogOptions& options = LogOptions());

/// Naive log: projects log(max(g(s), epsilon)) (eq. 25), for comparison.
PROXYGISPHERICALHARMONICS_EXPORT Status LogByProjection(
  int order, const double* g, double* f, double epsilon = 0.02);

} // namespace sh
} // namespace proxygi

#endif
