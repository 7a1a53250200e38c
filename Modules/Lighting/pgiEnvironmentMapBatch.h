/**
 * @file pgiEnvironmentMapBatch.h
 * @brief EnvironmentMap::ProjectSH's sums over one row of texels, the
 * coefficients side by side in vectors; compiled per instruction set and
 * dispatched at run time (Google Highway) like the SH kernels.
 */
#ifndef pgiEnvironmentMapBatch_h
#define pgiEnvironmentMapBatch_h

namespace proxygi
{
namespace detail
{
/// The stride RowSums' column integrals and sums use for `order` terms: a
/// whole number of the widest vector of doubles.
constexpr int RowSumsStride(int order)
{
  return (order + 7) / 8 * 8;
}

/**
 * For c < 3 and m < stride (RowSumsStride):
 *   rowCos[c * stride + m] = sum over i < width of rgb[3 i + c] cosInt[i * stride + m],
 *   rowSin the same with sinInt,
 * each sum in the order of i, a multiplication and an addition per term
 * (as the scalar loop rounds them), so the sums equal it bit for bit.
 */
void RowSums(const float* rgb, int width, const double* cosInt, const double* sinInt, int stride,
  double* rowCos, double* rowSin);
} // namespace detail
} // namespace proxygi

#endif
