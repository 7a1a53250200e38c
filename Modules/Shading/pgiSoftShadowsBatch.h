/**
 * @file pgiSoftShadowsBatch.h
 * @brief The blocker selection of SoftShadows::Visibility (the replacement
 * rules, the MinAngle cut, the angular radius and direction) for
 * sh::BatchWidth receivers at once, and the planes' light maps' products
 * of a visibility with the basis at sh::BatchWidth directions; compiled per
 * instruction set and dispatched at run time like the kernels in
 * pgiSHBatch.h.
 */
#ifndef pgiSoftShadowsBatch_h
#define pgiSoftShadowsBatch_h

#include <cstddef>

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

/// For each block b of `blocks` (count of them) and k < sh::BatchWidth,
/// with j = b * sh::BatchWidth + k: v[j] = sum_i g[i] basis[i * stride + j],
/// each sum in the order of i, rounded as the scalar loop rounds it (bit for
/// bit on every target; the scalar loop itself with the batched kernels
/// disabled). The other entries of v are left alone.
void DotBlocks(int coefficients, const float* g, const float* basis, std::size_t stride,
  const int* blocks, int count, float* v);
} // namespace detail
} // namespace proxygi

#endif
