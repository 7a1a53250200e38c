/**
 * @file pgiSHExp.h
 * @brief SH exponential g = exp*(f) (SHEXP paper, section 4), four methods:
 *
 * | method  | what it does                                              | products |
 * |---------|-----------------------------------------------------------|----------|
 * | PS      | product series 1 + f + f^2/2 + ... + f^p/p! (PS-p)        | p - 1    |
 * | PSStar  | DC isolation, scaling by 2^-s with s = max(0, floor(log2 |f^| + 3)), even/odd
 * factored degree-p series, s squarings (PS*-p) | about p/2 + s | | OL      | DC isolation, a(|f^|)
 * 1 + b(|f^|) f^ from the CapTables fit | 0      | | Hybrid  | OL after scaling |f^| below
 * HybridMaxNorm, then squarings (HYB) | s  |
 *
 * f^ is f with its DC coefficient removed; exp(f_0 / sqrt(4 pi)) is applied
 * analytically. Order 1..MaxOrder; float and double.
 *
 * Range guard (on by default): for inputs far outside the range the OL and
 * series were fitted on (hundreds of overlapping blockers), truncation error
 * amplified by many squarings can push the reconstruction out of [0, 1]. The
 * guard samples the result on a fixed direction set only when a cheap
 * per-band Cauchy-Schwarz bound says it might leave [-tol, 1 + tol], and then
 * remaps it affinely into that interval. The remap is the identity whenever
 * the result is already in range, so results stay continuous in f. The
 * default tolerance 0.5 leaves legitimate ringing alone: the exact order-n
 * projection of a single cap's visibility already spans [-0.40, 1.33].
 *
 * Errors: NaN/Inf in f gives Status::NonFiniteInput, an overflowing result
 * Status::NonFiniteResult; g is then all zeros.
 */
#ifndef pgiSHExp_h
#define pgiSHExp_h

#include "pgiSH.h"

namespace proxygi
{
namespace sh
{

enum class ExpMethod
{
  PS,
  PSStar,
  OL,
  Hybrid
};

PROXYGISPHERICALHARMONICS_EXPORT const char* ExpMethodName(ExpMethod method);

struct ExpOptions
{
  ExpMethod Method = ExpMethod::Hybrid;
  /// Series degree p of PS and PS*.
  int Degree = 2;
  /// HYB: halve f^ until |f^| <= this; <= 0 means DefaultHybridMaxNorm(order).
  double HybridMaxNorm = 0.0;
  bool RangeGuard = true;
  /// The guard keeps the reconstruction within [-RangeTolerance, 1 + RangeTolerance].
  double RangeTolerance = 0.5;
};

/// The HYB threshold used when ExpOptions::HybridMaxNorm <= 0.
PROXYGISPHERICALHARMONICS_EXPORT double DefaultHybridMaxNorm(int order);

/// Number of scaling/squaring steps PS* uses for |f^| (eq. 21's p).
PROXYGISPHERICALHARMONICS_EXPORT int ScalingSteps(double normFHat);

template <typename T>
PROXYGISPHERICALHARMONICS_EXPORT Status Exp(
  int order, const T* f, T* g, const ExpOptions& options = ExpOptions());

/// Remaps g affinely so its reconstruction on the guard directions lies in
/// [-tolerance, 1 + tolerance]; returns true when it changed g.
template <typename T>
PROXYGISPHERICALHARMONICS_EXPORT bool GuardRange(int order, T* g, double tolerance);

/// HYB's schedule at |f^| = norm: `steps` squarings, blended with weight w
/// towards one more (see HybridExp in the .cxx).
PROXYGISPHERICALHARMONICS_EXPORT void HybridSchedule(
  int order, double norm, const ExpOptions& options, int& steps, double& w);

/// GuardRange in parts, for the batched exp: the cheap per-band bound
/// (true: g is in range, nothing to do), the guard's sample directions
/// (count rows of order^2 basis values), and the remap from the sampled
/// extremes.
template <typename T>
PROXYGISPHERICALHARMONICS_EXPORT bool GuardInBounds(int order, const T* g, double tolerance);
PROXYGISPHERICALHARMONICS_EXPORT const float* GuardBasis(int order, int& count);
template <typename T>
PROXYGISPHERICALHARMONICS_EXPORT bool GuardRemap(
  int order, T* g, double vmin, double vmax, double tolerance);

/// Reference exp: projects exp(f(s)) with a dense quadrature (slow; tests).
PROXYGISPHERICALHARMONICS_EXPORT void ExpByProjection(int order, const double* f, double* g);

} // namespace sh
} // namespace proxygi

#endif
