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

/// What PlaneLightMap::Scale reads per look-up direction (arrays padded to
/// whole blocks of sh::BatchWidth) and per receiver.
struct PlaneLookUps
{
  const float* Cosines = nullptr; ///< n . w (0 past the last direction)
  const float* V = nullptr;       ///< the visibility at w, or null (V = 1)
  const float* StepU = nullptr;   ///< the steps on the plane per unit height
  const float* StepV = nullptr;
  float X = 0, Y = 0, H = 0;    ///< the receiver's foot and height (plane units)
  float FU = 0, FV = 0, HU = 0; ///< the same in grid cells
  bool Bounded = false;
  float Dual1[2] = { 0, 0 }, Dual2[2] = { 0, 0 };
  const float* Grid = nullptr; ///< s, RGB per grid point; null: s = 1
  int Columns = 0, Rows = 0;
};

/// Per direction j of the blocks listed (as DotBlocks): weights[j] = n . w
/// where it is positive, else 0; terms[c * stride + j] = that cosine times
/// V clamped to [0, 1] times s's channel c (bilinear; 1 off the grid) where
/// the direction meets the plane on its extent, else 0: Scale's terms, each
/// rounded as Scale's scalar loop rounds it.
void PlaneTerms(const PlaneLookUps& in, const int* blocks, int count, float* weights, float* terms,
  std::size_t stride);

/**
 * PlaneLightMap::SkyPastEdges' stretches for `bins` azimuth bins (a
 * multiple of sh::BatchWidth): axes holds per bin cos, sin, and the steps
 * along the extent's two coordinates, each a row of `bins`; normal the
 * receiver's normal in the plane's frame, a1 a2 its foot in extent
 * coordinates, h its height. Per bin, the heights' first stretch
 * [from[b], to[b]] and second [from[bins + b], to[bins + b]]; a stretch
 * with to <= from is none. Each operation is the scalar loop's, in order.
 */
void SkyStretches(const float* axes, int bins, const float normal[3], float a1, float a2, float h,
  float* from, float* to);
} // namespace detail
} // namespace proxygi

#endif
