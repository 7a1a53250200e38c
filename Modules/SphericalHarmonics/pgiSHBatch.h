/**
 * @file pgiSHBatch.h
 * @brief SH kernels over a batch of BatchWidth receivers at once, in
 * structure-of-arrays form (coefficient i of lane k at [i * BatchWidth + k]),
 * compiled for several instruction sets (Google Highway) and dispatched at
 * run time to the widest this CPU has (AVX-512, AVX2, SSE4, or baseline).
 *
 * Each kernel is the twin of a scalar one and is tested against it:
 *  - BatchSquare: TripleProduct::Square;
 *  - BatchAddCaps: CapTables::CapLog + RotateScaledZonal, summed;
 *  - BatchExp: Exp (HYB vectorised, including the range guard; the other
 *    methods run the scalar Exp lane by lane);
 *  - BatchIndirectWeights: the averaged bounce's per-proxy cap weight and
 *    AveragedRadiances (IndirectExitRadiance's loop over proxies).
 * Results equal the scalar kernels' bit for bit on every instruction set:
 * no fused multiply-adds (the kernels' files are built with
 * -ffp-contract=off) and each sum in the scalar code's order, since HYB's
 * squarings double any difference per step.
 */
#ifndef pgiSHBatch_h
#define pgiSHBatch_h

#include "pgiSH.h"
#include "pgiSHExp.h"

#include <string>
#include <vector>

namespace proxygi
{
namespace sh
{
class CapTables;
class IndirectTables;

/// Lanes per batch: 16 floats, one AVX-512 register (two AVX2, four SSE).
constexpr int BatchWidth = 16;

/// Whether the batched kernels are in use (default: yes, unless the
/// environment sets PROXYGI_SIMD=0). Callers take their scalar path when not.
PROXYGISPHERICALHARMONICS_EXPORT bool BatchKernelsEnabled();
PROXYGISPHERICALHARMONICS_EXPORT void SetBatchKernelsEnabled(bool enabled);
/// The instruction set the batched kernels dispatch to on this CPU
/// ("AVX3" is AVX-512), or "scalar" when they are disabled.
PROXYGISPHERICALHARMONICS_EXPORT const char* BatchTargetName();
/// The instruction sets compiled in that this CPU runs, best first.
PROXYGISPHERICALHARMONICS_EXPORT std::vector<std::string> BatchTargets();
/// Dispatches every batched kernel to one of BatchTargets() from now on
/// (tests and benchmarks compare them); "" returns to the best. False, and
/// nothing changed, for a name not in the list.
PROXYGISPHERICALHARMONICS_EXPORT bool SetBatchTarget(const std::string& name);

/// out = f * f for BatchWidth lanes (order n in and out); out may not alias f.
PROXYGISPHERICALHARMONICS_EXPORT void BatchSquare(int order, const float* f, float* out);

/**
 * f += sum over blockers b of CapLog(theta_b) (times ratio_b per band, if
 * ratios) rotated to dir_b, for BatchWidth lanes. theta, dirX, dirY, dirZ
 * hold count rows of BatchWidth values; a lane whose theta is negative is
 * skipped for that blocker. ratios: count rows of `order` values, or null.
 * Orders up to 8.
 */
PROXYGISPHERICALHARMONICS_EXPORT void BatchAddCaps(const CapTables& tables, int order, int count,
  const float* theta, const float* dirX, const float* dirY, const float* dirZ, const float* ratios,
  float* f);

/**
 * The averaged bounce's weights of BatchWidth proxies seen from one
 * receiver (theta, dirX, dirY, dirZ: BatchWidth values each; unit
 * directions receiver -> centre): capWeight = h . the cap of half-angle
 * theta about dir (CapTables::CapVisibility turned into the cap, rotated),
 * and for each of `channels` radiance SH (order^2 floats each, one after the
 * other) kappa_c = IndirectTables::AveragedRadiances. h: the receiver's
 * DiffuseTransfer. Lanes with a negative theta get zeros. kappa: channels
 * (at most 3) rows of BatchWidth; channels 0 leaves it alone. With the
 * batched kernels disabled, the scalar twin runs lane by lane.
 */
PROXYGISPHERICALHARMONICS_EXPORT void BatchIndirectWeights(const CapTables& caps,
  const IndirectTables& indirect, int order, const float* theta, const float* dirX,
  const float* dirY, const float* dirZ, const float* h, int channels, const float* radiances,
  float* capWeight, float* kappa);

/**
 * g = exp(f) for BatchWidth lanes, as Exp<float> does per lane; status
 * receives each lane's status. f and g may not alias.
 */
PROXYGISPHERICALHARMONICS_EXPORT void BatchExp(
  int order, const float* f, float* g, const ExpOptions& options, Status* status);

} // namespace sh
} // namespace proxygi

#endif
