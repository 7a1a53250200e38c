/**
 * @file pgiSoftShadowsBatch.h
 * @brief The blocker selection of SoftShadows::Visibility (the replacement
 * rules, the MinAngle cut, the angular radius and direction) for
 * sh::BatchWidth receivers at once; compiled per instruction set and
 * dispatched at run time like the kernels in pgiSHBatch.h.
 */
#ifndef pgiSoftShadowsBatch_h
#define pgiSoftShadowsBatch_h

namespace proxygi
{
namespace detail
{
/**
 * lanes: the receivers' px, py, pz, nx, ny, nz, BatchWidth values each.
 * For sphere s < rows (centre X[s], Y[s], Z[s], radius R[s]) writes row s of
 * theta (negative: the lane skips it) and of the unit direction dx, dy, dz.
 */
void BlockerLanes(const float* lanes, const float* X, const float* Y, const float* Z,
  const float* R, int rows, float sinMin, bool rules, float* theta, float* dx, float* dy,
  float* dz);

/// asin for the blockers' angular radius, as BlockerLanes computes it (one
/// polynomial for the scalar and the batched paths; |x| <= 1).
float BlockerAsin(float x);
} // namespace detail
} // namespace proxygi

#endif
